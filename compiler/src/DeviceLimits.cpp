#include "tidepool/DeviceLimits.h"

#include "tidepool/TextFile.h"
#include "tidepool/base/EditDistance.h"

#include <algorithm>
#include <charconv>
#include <limits>
#include <set>

#include "BuiltInResources.h"
#include <fmt/format.h>

namespace tidepool {
namespace {

struct Word {
    std::string_view text;
    int column = 0;
};

// The words of one line, comments (`#` or `//` to the end of the line) left out.
std::vector<Word> WordsOf(std::string_view line) {
    std::vector<Word> words;
    std::size_t i = 0;
    while (i < line.size()) {
        if (line[i] == '#' || line.compare(i, 2, "//") == 0) {
            break;
        }
        if (line[i] == ' ' || line[i] == '\t' || line[i] == '\r') {
            ++i;
            continue;
        }
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r' &&
               line[i] != '#' && line.compare(i, 2, "//") != 0) {
            ++i;
        }
        words.push_back(Word{line.substr(start, i - start), static_cast<int>(start) + 1});
    }
    return words;
}

}  // namespace

std::string DeviceLimits::Text() const {
    std::string text;
    for (const auto& [name, value] : values) {
        text += fmt::format("{} {}\n", name, value);
    }
    return text;
}

DeviceLimitsRead ParseDeviceLimits(std::string_view text, const std::string& path) {
    DeviceLimitsRead read;
    read.limits.path = path;
    std::set<std::string> seen;
    int line_number = 0;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        const std::string_view line = text.substr(start, end - start);
        start = end + 1;
        ++line_number;
        const std::vector<Word> words = WordsOf(line);
        if (words.empty()) {
            continue;
        }
        auto error = [&](const Word& at, std::string message) {
            read.diagnostics.push_back(MakeError(path, line_number, at.column, std::move(message)));
        };
        if (words.size() != 2) {
            error(words.front(), fmt::format("expected one limit as 'Name value' (as in "
                                             "'MaxVertexUniformVectors 256'), found {} words",
                                             words.size()));
            continue;
        }
        const std::string name(words[0].text);
        const std::vector<std::string>& known = ResourceLimitNames();
        if (std::find(known.begin(), known.end(), name) == known.end()) {
            // A word far longer than any name is no misspelling of one: it gets no suggestion
            // (the distance to every name costs its length times theirs) and is shown cut.
            constexpr std::size_t kLongestShown = 64;
            if (name.size() > kLongestShown) {
                error(words[0],
                      fmt::format("unknown limit '{}...' ({} characters, longer than any limit "
                                  "name; the names are glslang's: `glslangValidator -c` prints "
                                  "them all)",
                                  name.substr(0, kLongestShown), name.size()));
                continue;
            }
            error(words[0], fmt::format("unknown limit '{}'; did you mean '{}'? (the names are "
                                        "glslang's: `glslangValidator -c` prints them all)",
                                        name, base::ClosestName(name, ResourceLimitNames())));
            continue;
        }
        if (!seen.insert(name).second) {
            error(words[0], fmt::format("limit '{}' is given twice; keep one line", name));
            continue;
        }
        int value = 0;
        const std::string_view digits = words[1].text;
        const auto [end_of_number, status] =
                std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (status != std::errc() || end_of_number != digits.data() + digits.size()) {
            // Only the Min... limits may be negative (below); the range says so.
            const bool signed_limit = name.rfind("Min", 0) == 0;
            error(words[1], fmt::format("the value of '{}' must be a whole number from {} to {}, "
                                        "not '{}'",
                                        name, signed_limit ? std::numeric_limits<int>::min() : 0,
                                        std::numeric_limits<int>::max(), digits));
            continue;
        }
        if (IsResourceSwitch(name) && value != 0 && value != 1) {
            error(words[1],
                  fmt::format("'{}' is a switch: its value must be 0 or 1, not {}", name, value));
            continue;
        }
        if (value < 0 && name.rfind("Min", 0) != 0) {
            error(words[1], fmt::format("'{}' cannot be negative ({}); only the Min... limits "
                                        "can",
                                        name, value));
            continue;
        }
        read.limits.values.emplace_back(name, value);
    }
    read.ok = !HasErrors(read.diagnostics);
    return read;
}

DeviceLimitsRead ReadDeviceLimits(const std::string& path) {
    TextFileRead file = ReadTextFile(path);
    DropByteOrderMark(&file.text);
    if (!file.ok) {
        DeviceLimitsRead read;
        read.diagnostics.push_back(
                MakeError(path, 0, 0, fmt::format("cannot read the limits file: {}", file.error)));
        return read;
    }
    return ParseDeviceLimits(file.text, path);
}

}  // namespace tidepool
