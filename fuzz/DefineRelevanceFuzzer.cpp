// libFuzzer target: a define list and a shader text → DefineRelevance, the walk `validate` runs
// in its own process (not in a worker) over every shader file it reads. Any crash, hang, leak or
// sanitizer report is a bug; no answer (nullopt) is the expected outcome of junk. The input's
// first line is the defines, separated by spaces; the rest is the shader. Seeded with the shipped
// shaders under a few define lists (scripts/fuzz.sh).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "DefineRelevance.h"

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
    static_cast<void>(relevance.Relevant(defines));
    static_cast<void>(relevance.Relevant({}));
    return 0;
}
