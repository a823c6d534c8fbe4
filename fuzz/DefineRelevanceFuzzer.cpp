// libFuzzer target: a define list and a shader text → DefineRelevance, the walk `validate` runs
// in its own process (not in a worker) over every shader file it reads, and the blanking of the
// lines it finds skipped. Any crash, hang, leak or sanitizer report is a bug, and so is a skipped
// line outside the text or out of order, or a blanking that moves a line; no answer (nullopt) is
// the expected outcome of junk. The input's
// first line is the defines, separated by spaces; the rest is the shader. Seeded with the shipped
// shaders under a few define lists (scripts/fuzz.sh).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "DefineRelevance.h"
#include "GlslangSession.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    const std::size_t end = input.find('\n');
    std::vector<std::string> defines;
    std::istringstream words(input.substr(0, end));
    for (std::string word; words >> word;) {
        defines.push_back(word);
    }
    const std::string text = end == std::string::npos ? std::string() : input.substr(end + 1);
    const tidepool::DefineRelevance relevance(text);
    std::vector<tidepool::LineSpan> skipped;
    static_cast<void>(relevance.Relevant(defines, &skipped));
    static_cast<void>(relevance.Relevant({}));
    // The skipped lines are the text's, in order and apart; blanking them keeps every line.
    const std::vector<bool> quiet = tidepool::QuietWhenSkippedLines(text);
    int after = 0;
    for (const tidepool::LineSpan& span : skipped) {
        if (span.first <= after || span.last < span.first ||
            span.last > static_cast<int>(quiet.size())) {
            __builtin_trap();
        }
        after = span.last;
    }
    const std::string blanked = tidepool::WithSkippedLinesBlanked(text, skipped, quiet);
    if (std::count(blanked.begin(), blanked.end(), '\n') !=
        std::count(text.begin(), text.end(), '\n')) {
        __builtin_trap();
    }
    return 0;
}
