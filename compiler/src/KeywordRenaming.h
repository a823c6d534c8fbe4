// Words that glslang 12 refuses in a `#version 100` shader although GLSL ES 1.00 allows them as
// identifiers, and the stand-in names glslang is given instead. Private to the compiler library.
#pragma once

#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tidepool {

/// The words GLSL ES 1.00 (rev 17) §3.7 neither uses as keywords nor reserves, but glslang 12
/// rejects in a `#version 100` shader: it treats `case` as a keyword in every version, reserves
/// `active`, `common`, `filter` and `partition` (GLSL 1.30 and ES 3.00 reserve them, ES 1.00
/// does not) and reserves the cube-map-array sampler types (keywords of ES 3.20 only). Found by
/// declaring each of glslang 12's keywords and reserved words as a global `float` in a
/// `#version 100` shader and comparing the errors with the two lists of §3.7.
const std::vector<std::string>& Es100IdentifiersGlslangRejects();

/// The start of the name glslang is given for a word of Es100IdentifiersGlslangRejects().
inline constexpr std::string_view kEs100StandInPrefix = "tp_es100_";

/// The name glslang is given for a struct or block member named `length` (see
/// PlanLengthMemberRenaming).
inline constexpr std::string_view kLengthMemberStandIn = "tp_member_length";

/// Each word of Es100IdentifiersGlslangRejects() that a shader uses, renamed for glslang, and
/// members named `length`.
struct KeywordRenaming {
    /// {stand-in, word as the user wrote it}, in the order of Es100IdentifiersGlslangRejects().
    std::vector<std::pair<std::string, std::string>> names;
    /// Whether members named `length` are given to glslang as kLengthMemberStandIn.
    bool length_members = false;

    /// `text` with every whole-word use of a renamed word replaced by its stand-in, and, when
    /// `length_members`, every `length` that names a member (declared in a struct or uniform
    /// block body, or selected after a `.` and not called) replaced by kLengthMemberStandIn.
    std::string Apply(std::string_view text) const;
    /// `text` (a glslang message) with every stand-in replaced by the user's word again.
    std::string Restore(std::string_view text) const;
};

/// True when `texts` declare a struct or uniform block member named `length` and none spells
/// kLengthMemberStandIn. `length` is no keyword (GLSL ES 1.00 §3.7, 3.00 §3.7) and a structure's
/// members have a name space of their own (1.00 §4.1.8, 3.00 §4.1.8), but glslang 12 takes every
/// `.length` for the array method `length()` and refuses `s.length` on a struct. Renaming the
/// member lets glslang check everything else; `.length()` calls are left alone. Never fails.
bool PlanLengthMemberRenaming(const std::vector<std::string_view>& texts);

/// Plans the renaming of a `#version 100` stage whose text (file and preamble) is `texts`: each
/// word of Es100IdentifiersGlslangRejects() that appears as a whole token gets the stand-in
/// `tp_es100_<word>`, which is the same in every stage so that a varying or uniform named `filter`
/// still links. A word whose stand-in the user's text already spells is not renamed, so that two
/// of the user's names never become one: glslang then reports the word, which is stricter than
/// the specification, never more lenient. Never fails.
KeywordRenaming PlanEs100Renaming(const std::vector<std::string_view>& texts);

/// What the two plans above need to know of one text; a text's scan depends on nothing else, so
/// a caller that gives glslang the same text many times may keep it.
struct RenamingScan {
    /// The tokens that are a word of Es100IdentifiersGlslangRejects() or start with
    /// kEs100StandInPrefix.
    std::set<std::string, std::less<>> es100_tokens;
    bool spells_length_stand_in = false;  // kLengthMemberStandIn is a token
    bool declares_length_member = false;  // a struct or block member named `length`
};

/// The scan of `text`. Never fails.
RenamingScan ScanForRenaming(std::string_view text);

/// The renaming of a stage made of the scanned texts: PlanEs100Renaming's names when `es100`
/// (none otherwise) and PlanLengthMemberRenaming's verdict. Never fails.
KeywordRenaming PlanRenaming(const std::vector<RenamingScan>& scans, bool es100);

}  // namespace tidepool
