// libFuzzer target: scenes/*.yaml text → ParseSceneDescription. Any crash, hang, leak or
// sanitizer report is a bug; diagnostics are the expected outcome of junk. Seeded with the
// shipped scenes (scripts/fuzz.sh).
#include "tidepool/SceneDescription.h"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    static_cast<void>(tidepool::ParseSceneDescription(text, "fuzz.yaml"));
    return 0;
}
