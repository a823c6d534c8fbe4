#include "KeywordRenaming.h"

#include <algorithm>
#include <cctype>
#include <functional>
#include <set>

namespace tidepool {
namespace {

bool IsIdentifierChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

// Calls `visit(start, length)` for every identifier token of `text`; a run of identifier
// characters that starts with a digit is a number (1e5, 0xcafe), not an identifier.
void ForEachIdentifier(std::string_view text,
                       const std::function<void(std::size_t, std::size_t)>& visit) {
    std::size_t i = 0;
    while (i < text.size()) {
        if (!IsIdentifierChar(text[i])) {
            ++i;
            continue;
        }
        const std::size_t start = i;
        while (i < text.size() && IsIdentifierChar(text[i])) {
            ++i;
        }
        if (std::isdigit(static_cast<unsigned char>(text[start])) == 0) {
            visit(start, i - start);
        }
    }
}

// `text` with each whole-word use of one side of `names` ({stand-in, word}) replaced by the
// other side: words by stand-ins when `to_stand_in`, else stand-ins by words.
std::string Replace(std::string_view text,
                    const std::vector<std::pair<std::string, std::string>>& names,
                    bool to_stand_in) {
    if (names.empty()) {
        return std::string(text);
    }
    std::string out;
    out.reserve(text.size());
    std::size_t copied = 0;
    ForEachIdentifier(text, [&](std::size_t start, std::size_t length) {
        const std::string_view token = text.substr(start, length);
        const auto it = std::find_if(names.begin(), names.end(), [&](const auto& name) {
            return (to_stand_in ? name.second : name.first) == token;
        });
        if (it == names.end()) {
            return;
        }
        out.append(text.substr(copied, start - copied));
        out.append(to_stand_in ? it->first : it->second);
        copied = start + length;
    });
    out.append(text.substr(copied));
    return out;
}

}  // namespace

const std::vector<std::string>& Es100IdentifiersGlslangRejects() {
    static const std::vector<std::string> words = {
            "active",
            "case",
            "common",
            "filter",
            "partition",
            "samplerCubeArray",
            "samplerCubeArrayShadow",
            "isamplerCubeArray",
            "usamplerCubeArray",
    };
    return words;
}

std::string KeywordRenaming::Apply(std::string_view text) const {
    return Replace(text, names, /*to_stand_in=*/true);
}

std::string KeywordRenaming::Restore(std::string_view text) const {
    return Replace(text, names, /*to_stand_in=*/false);
}

KeywordRenaming PlanEs100Renaming(const std::vector<std::string_view>& texts) {
    std::set<std::string_view> used;
    for (std::string_view text : texts) {
        ForEachIdentifier(text, [&](std::size_t start, std::size_t length) {
            used.insert(text.substr(start, length));
        });
    }
    KeywordRenaming renaming;
    for (const std::string& word : Es100IdentifiersGlslangRejects()) {
        const std::string stand_in = "tp_es100_" + word;
        if (used.count(word) != 0 && used.count(stand_in) == 0) {
            renaming.names.emplace_back(stand_in, word);
        }
    }
    return renaming;
}

}  // namespace tidepool
