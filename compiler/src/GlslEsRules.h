// GLSL ES rules that glslang 12 does not enforce, and the resource bounds that keep a hostile
// shader from exhausting the validator, in one place. Each check cites the section of the
// GLSL ES specification (1.00 rev 17, 3.00 rev 6) it implements, or the measurement behind its
// bound. A later conformance (dEQP) effort should add its checks here. Private to the compiler
// library.
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/SourceAssembler.h"

#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

struct TBuiltInResource;

namespace glslang {
class TIntermediate;
class TIntermSymbol;
struct TSourceLoc;
}  // namespace glslang

namespace tidepool {

/// One preprocessing token of a source text: an identifier-character run (identifier: it starts
/// with a letter or `_`) or a single other character, with its 1-based line and column.
struct SourceToken {
    std::string_view text;
    int line = 0;
    int column = 0;
    bool identifier = false;
};

/// Splits text into SourceTokens, one vector per logical line (comments dropped, a
/// backslash-newline joins lines as GLSL ES 3.00 §3.2 allows). Numbers come out in pieces
/// (`1.5e3` is `1`, `.`, `5e3`): the macro-size estimate and the WebGL token checks need only
/// the identifiers exact.
std::vector<std::vector<SourceToken>> SourceTokenLines(std::string_view text);

/// A shader may expand, through its macros, to at most this many tokens. glslang 12 needs about
/// 1.5 KB and 9 µs per expanded token (2^20 tokens took 9 s and 1.5 GB), so this bound keeps one
/// stage under about 0.2 s and 200 MB; the largest shipped shader expands to a few thousand.
inline constexpr long long kMaxExpandedTokens = 1LL << 17;
/// What the error for a shader past kMaxExpandedTokens tells its author to do.
inline constexpr const char* kTooLargeFix =
        "write repeated code as functions and loops rather than macros, or split the shader";

/// Checks the source text before glslang sees it: a NUL byte (not in the character set of
/// GLSL ES 1.00 §3.1 / 3.00 §3.1; glslang would silently stop reading there) and macros whose
/// expansion exceeds kMaxExpandedTokens (a "macro bomb"). `preamble` holds the defines given
/// on the command line or by the variant, which expand like the file's own.
std::vector<Diagnostic> CheckSourceText(std::string_view text, std::string_view preamble,
                                        const std::string& file);

/// One declaration (a variable, a parameter, a struct member, counted through arrays of structs
/// and every dimension of an array) may hold at most this many array elements.
/// No GPU gives one shader invocation that much memory (64 Ki vec4s are 1 MiB per vertex or
/// fragment, and llvmpipe puts local arrays on its threads' stacks), while the shipped shaders
/// and the dEQP ES 2.0 corpus write no array size above 4.
inline constexpr long long kMaxArrayElements = 1LL << 16;

/// Checks one parsed stage: every array declaration the stage keeps (globals, and whatever the
/// code uses: locals, parameters) holds at most kMaxArrayElements elements; and no uniform
/// declaration may need more vectors than the stage has
/// (GLSL ES 1.00 Appendix A §7 and §7.4, gl_MaxVertexUniformVectors and
/// gl_MaxFragmentUniformVectors; GLSL ES 3.00 §4.3.5 and §7.3). `source` is the user's text,
/// where the offending declaration is found for its line and column.
std::vector<Diagnostic> CheckStageRules(const glslang::TIntermediate& stage,
                                        const TBuiltInResource& resources, const std::string& file,
                                        std::string_view source);

/// The declarations glslang keeps for the linker: every global the stage declares.
std::vector<glslang::TIntermSymbol*> LinkerObjects(const glslang::TIntermediate& stage);

/// The variables the stage's code reads or writes (a declaration alone is no use), each with
/// the place of its first use.
std::map<std::string, glslang::TSourceLoc> StaticallyUsed(const glslang::TIntermediate& stage);

/// Line and column of the first whole-word mention of `name` in `source` ({0, 0} when none):
/// glslang 12 keeps no position on its linker objects, and in GLSL ES a declaration comes before
/// any use.
std::pair<int, int> FirstMention(std::string_view source, std::string_view name);

/// Checks a vertex and a fragment stage that are linked together: both declare the same
/// language version (GLSL ES 3.00 §3.3: 1.00 and 3.00 shaders cannot be linked), and every
/// varying (1.00 §4.3.5) or input (3.00 §4.3.4) the fragment stage statically uses is declared
/// by the vertex stage.
std::vector<Diagnostic> CheckLinkRules(const glslang::TIntermediate& vertex,
                                       const std::string& vertex_file,
                                       const glslang::TIntermediate& fragment,
                                       const std::string& fragment_file);

}  // namespace tidepool
