// libFuzzer target: variants.yaml text → ParseVariantConfig (and, when it loads, a small
// expansion). Any crash, hang, leak or sanitizer report is a bug; diagnostics are the expected
// outcome of junk. Seeded with the shipped variants.yaml (scripts/fuzz.sh).
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    // The source root, so that the shipped file's shader paths resolve as they do for a user.
    const tidepool::ConfigResult result =
            tidepool::ParseVariantConfig(text, "fuzz.yaml", TIDEPOOL_SOURCE_ROOT);
    if (result.config) {
        // The expansion's own size guard is another target's business; a small cap keeps each
        // input fast so the fuzzer explores the loader.
        tidepool::ExpansionOptions options;
        options.max_variants = 256;
        static_cast<void>(tidepool::ExpandVariants(*result.config, options));
    }
    return 0;
}
