// The rules the WebGL specifications add to GLSL ES, as browsers' shader translators (ANGLE)
// apply them before a driver sees the shader. Each check cites its section of WebGL 1.0 or 2.0
// (the Khronos editor's drafts). Private to the compiler library.
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/VariantConfig.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

struct TBuiltInResource;

namespace glslang {
class TIntermediate;
}  // namespace glslang

namespace tidepool {

/// The longest token a WebGL target accepts: 256 characters for WebGL 1 (WebGL 1.0 §6.20
/// "Maximum GLSL Token Size"), 1024 for WebGL 2 (WebGL 2.0 follows GLSL ES 3.00 §3.8, which
/// limits identifiers to 1024 characters).
int MaxWebGlTokenLength(GlslTarget target);

/// A GLSL ES 1.00 text as WebGL reads it: a backslash at the end of a line joins the next line
/// to it, as in GLSL ES 3.00 §3.1 (GLSL ES 1.00 has no line continuation, but WebGL supports the
/// character in every shader since KhronosGroup/WebGL#3212, 2021, as ANGLE's preprocessor always
/// did). The joined lines' newlines go after the logical line, so every later line keeps its
/// number. Lines ending in `\r\n` are joined too. A text without a continuation comes back as is.
std::string JoinContinuedLines(std::string_view text);

/// Checks the user's text (comments left out, every line, preprocessor directives and inactive
/// blocks included) for a token longer than MaxWebGlTokenLength and for an identifier that starts
/// with `webgl_` or `_webgl_` (WebGL 1.0 §6.17 "GLSL Constructs": reserved for use by WebGL).
std::vector<Diagnostic> CheckWebGlTokens(std::string_view text, GlslTarget target,
                                         const std::string& file);

/// Checks glslang's preprocessed text of a stage (comments and inactive blocks gone, lines kept)
/// for a character outside the GLSL ES source character set (GLSL ES 1.00 §3.1, 3.00 §3.1),
/// which WebGL makes a compile error (WebGL 1.0 §6.21 "Characters Outside the GLSL Source
/// Character Set"). Columns are found on the same line of `source`, the user's text.
std::vector<Diagnostic> CheckWebGlCharacters(std::string_view preprocessed, std::string_view source,
                                             const std::string& file);

/// Checks glslang's preprocessed text of a `#version 300 es` stage (comments and inactive blocks
/// gone, lines kept) for a `shared` or `packed` layout qualifier: WebGL 2 supports only the
/// std140 layout for uniform blocks, and a shader asking for another is refused (WebGL 2.0 "Only
/// std140 layout supported in uniform blocks"). Columns are found on the same line of `source`.
std::vector<Diagnostic> CheckWebGl2BlockLayouts(std::string_view preprocessed,
                                                std::string_view source, const std::string& file);

/// The deepest nesting of structures WebGL accepts (WebGL 1.0 §6.22 "Maximum Nesting of
/// Structures", kept by WebGL 2.0): a structure whose members are no structures is nested 1
/// level deep, one holding such a structure (or an array of them) 2 levels, and so on.
inline constexpr int kMaxWebGlStructNesting = 4;

/// Checks one parsed stage for a structure nested more than kMaxWebGlStructNesting levels deep,
/// among the types of every variable, parameter, constructor and function the stage keeps (a
/// structure type that nothing declared or used leaves no trace in glslang's tree). Reported at
/// the first mention of the structure's name in `source`, the text glslang parsed.
std::vector<Diagnostic> CheckWebGlStructNesting(const glslang::TIntermediate& stage,
                                                const std::string& file, std::string_view source);

/// Checks the initializers of the global variables of a `#version 100` stage for a WebGL 1
/// target. GLSL ES 1.00 §4.3 wants constant expressions there; WebGL 1.0 §6.33 "GLSL ES Global
/// Variable Initialization" also allows non-const user-defined globals and uniforms, and
/// operators, constructors and built-in functions over them, but not texture lookups,
/// user-defined functions, attributes, varyings, built-in variables (other than constant
/// expressions) or assignments (`=`, `+=`, `++`, ...). Each use of one of those is an error at
/// its place; glslang (in relaxed mode) has already checked everything else.
std::vector<Diagnostic> CheckWebGlGlobalInitializers(const glslang::TIntermediate& stage,
                                                     const std::string& file);

/// One variable as GLSL ES 1.00 Appendix A §7 packs it: `elements` array elements (1 when it is
/// no array), each `rows` rows of `columns` components (a vec3 is 1 row of 3, a mat3 3 rows of
/// 3, a mat2 2 full rows of 4).
struct PackingVariable {
    std::string name;
    int rows = 1;
    int columns = 1;
    long long elements = 1;
};

/// Packs `variables` into a grid of `rows` rows of 4 components by the algorithm of GLSL ES 1.00
/// Appendix A §7 (sorted by type: mat4, mat2, vec4, mat3, vec3, vec2, scalars, larger arrays
/// first; 4-component rows from the top, 3-component rows below them, 2-component ones in
/// columns 0-1 from there down or columns 2-3 from the bottom up, scalars into the column with
/// the smallest gap that holds them). Returns the name of the first variable that finds no room,
/// or nothing when all fit.
std::optional<std::string> FirstUnpackedVariable(std::vector<PackingVariable> variables, int rows);

/// WebGL 1.0 §6.26 "Packing Restrictions for Uniforms and Varyings": the uniforms a stage
/// statically uses (GLSL ES 1.00 §4.3.4: declared but unused ones do not count; samplers are
/// not packed here) must pack into its gl_MaxVertexUniformVectors or
/// gl_MaxFragmentUniformVectors rows, structures counted member by member. Reported at the
/// declaration (first mention in `source`) of the first uniform with no room.
std::vector<Diagnostic> CheckWebGlUniformPacking(const glslang::TIntermediate& stage,
                                                 const TBuiltInResource& resources,
                                                 const std::string& file, std::string_view source);

/// WebGL 1.0 §6.26 for a program: the varyings the fragment stage statically uses must pack into
/// gl_MaxVaryingVectors rows. Reported at the fragment stage's declaration of the first varying
/// with no room.
std::vector<Diagnostic> CheckWebGlVaryingPacking(const glslang::TIntermediate& fragment,
                                                 const TBuiltInResource& resources,
                                                 const std::string& file, std::string_view source);

/// Checks a WebGL 2 stage for the operator forms WebGL 2.0 §5.26 "Disallowed variants of GLSL ES
/// 3.00 operators" forbids: the sequence operator `,` with an operand that is void, an array or
/// a structure containing an array, and the ternary operator `?:` whose result is void, an array
/// or such a structure. Reported at the operator. glslang keeps a `?:` of void operands as an
/// if-statement, told apart by the `?` at its place in `source`, the text glslang parsed (one
/// that a macro wrote is not seen).
std::vector<Diagnostic> CheckWebGl2Operators(const glslang::TIntermediate& stage,
                                             const std::string& file, std::string_view source);

}  // namespace tidepool
