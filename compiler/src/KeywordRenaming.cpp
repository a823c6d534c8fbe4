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

struct Token {
    std::size_t start = 0;
    std::string_view text;
};

// The tokens of `text` for the member scan: identifier runs and single other characters, with
// comments and blanks left out.
std::vector<Token> MemberScanTokens(std::string_view text) {
    std::vector<Token> tokens;
    std::size_t i = 0;
    while (i < text.size()) {
        if (text.compare(i, 2, "//") == 0) {
            i = text.find('\n', i);
            i = i == std::string_view::npos ? text.size() : i;
        } else if (text.compare(i, 2, "/*") == 0) {
            const std::size_t end = text.find("*/", i + 2);
            i = end == std::string_view::npos ? text.size() : end + 2;
        } else if (std::isspace(static_cast<unsigned char>(text[i])) != 0) {
            ++i;
        } else if (IsIdentifierChar(text[i])) {
            const std::size_t start = i;
            while (i < text.size() && IsIdentifierChar(text[i])) {
                ++i;
            }
            tokens.push_back(Token{start, text.substr(start, i - start)});
        } else {
            tokens.push_back(Token{i, text.substr(i, 1)});
            ++i;
        }
    }
    return tokens;
}

// A `length` token that names a member: declared inside the body of a struct
// (`struct [Name] {`) or a uniform block (`uniform Name {`), or selected after a `.`. A `length`
// followed by `(` is a call (the built-in function, or the array method) and is left alone.
struct LengthMember {
    std::size_t offset = 0;
    bool declared = false;  // in a body, rather than selected
};

std::vector<LengthMember> LengthMembers(std::string_view text) {
    const std::vector<Token> tokens = MemberScanTokens(text);
    auto text_at = [&](std::size_t i) {
        return i < tokens.size() ? tokens[i].text : std::string_view();
    };
    std::vector<LengthMember> members;
    int body_depth = 0;  // braces opened since the outermost struct or block body began
    for (std::size_t i = 0; i < tokens.size(); ++i) {
        const std::string_view t = tokens[i].text;
        if (t == "{") {
            const bool opens_body =
                    (i >= 1 && text_at(i - 1) == "struct") ||
                    (i >= 2 && (text_at(i - 2) == "struct" || text_at(i - 2) == "uniform"));
            if (body_depth > 0 || opens_body) {
                ++body_depth;
            }
        } else if (t == "}") {
            body_depth = body_depth > 0 ? body_depth - 1 : 0;
        } else if (t == "length" && text_at(i + 1) != "(") {
            const bool selected = i >= 1 && text_at(i - 1) == ".";
            if (body_depth > 0 || selected) {
                members.push_back(LengthMember{tokens[i].start, !selected});
            }
        }
    }
    return members;
}

}  // namespace

bool PlanLengthMemberRenaming(const std::vector<std::string_view>& texts) {
    std::vector<RenamingScan> scans;
    scans.reserve(texts.size());
    for (std::string_view text : texts) {
        scans.push_back(ScanForRenaming(text));
    }
    return PlanRenaming(scans, /*es100=*/false).length_members;
}

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
    if (!length_members) {
        return Replace(text, names, /*to_stand_in=*/true);
    }
    std::string members;
    std::size_t copied = 0;
    for (const LengthMember& member : LengthMembers(text)) {
        members.append(text.substr(copied, member.offset - copied));
        members.append(kLengthMemberStandIn);
        copied = member.offset + std::string_view("length").size();
    }
    members.append(text.substr(copied));
    return Replace(members, names, /*to_stand_in=*/true);
}

std::string KeywordRenaming::Restore(std::string_view text) const {
    std::string restored = Replace(text, names, /*to_stand_in=*/false);
    if (length_members) {
        restored = Replace(restored, {{std::string(kLengthMemberStandIn), "length"}},
                           /*to_stand_in=*/false);
    }
    return restored;
}

RenamingScan ScanForRenaming(std::string_view text) {
    RenamingScan scan;
    // Substring tests first: a word can only be a token of a text that contains it, and most
    // shaders contain none of them. A set of every token of every text, built for each stage
    // glslang was given, was a fifth of a cold validation of the default matrix.
    std::vector<std::string_view> candidates;
    for (const std::string& word : Es100IdentifiersGlslangRejects()) {
        if (text.find(word) != std::string_view::npos) {
            candidates.push_back(word);
        }
    }
    if (!candidates.empty()) {
        ForEachIdentifier(text, [&](std::size_t start, std::size_t length) {
            const std::string_view token = text.substr(start, length);
            if (token.substr(0, kEs100StandInPrefix.size()) == kEs100StandInPrefix ||
                std::find(candidates.begin(), candidates.end(), token) != candidates.end()) {
                scan.es100_tokens.emplace(token);
            }
        });
    }
    // Most shaders mention neither word, so they skip the token scans.
    if (text.find(kLengthMemberStandIn) != std::string_view::npos) {
        ForEachIdentifier(text, [&](std::size_t start, std::size_t length) {
            scan.spells_length_stand_in = scan.spells_length_stand_in ||
                                          text.substr(start, length) == kLengthMemberStandIn;
        });
    }
    if (!scan.spells_length_stand_in && text.find("length") != std::string_view::npos) {
        for (const LengthMember& member : LengthMembers(text)) {
            scan.declares_length_member = scan.declares_length_member || member.declared;
        }
    }
    return scan;
}

KeywordRenaming PlanRenaming(const std::vector<RenamingScan>& scans, bool es100) {
    KeywordRenaming renaming;
    auto used = [&](const std::string& token) {
        return std::any_of(scans.begin(), scans.end(), [&](const RenamingScan& scan) {
            return scan.es100_tokens.count(token) != 0;
        });
    };
    if (es100) {
        for (const std::string& word : Es100IdentifiersGlslangRejects()) {
            const std::string stand_in = std::string(kEs100StandInPrefix) + word;
            if (used(word) && !used(stand_in)) {
                renaming.names.emplace_back(stand_in, word);
            }
        }
    }
    renaming.length_members =
            std::none_of(scans.begin(), scans.end(),
                         [](const RenamingScan& scan) { return scan.spells_length_stand_in; }) &&
            std::any_of(scans.begin(), scans.end(),
                        [](const RenamingScan& scan) { return scan.declares_length_member; });
    return renaming;
}

KeywordRenaming PlanEs100Renaming(const std::vector<std::string_view>& texts) {
    std::vector<RenamingScan> scans;
    scans.reserve(texts.size());
    for (std::string_view text : texts) {
        scans.push_back(ScanForRenaming(text));
    }
    KeywordRenaming renaming = PlanRenaming(scans, /*es100=*/true);
    renaming.length_members = false;  // planned by PlanLengthMemberRenaming
    return renaming;
}

}  // namespace tidepool
