// GLSL ES rules that glslang 12 gets wrong or checks too late, found by the dEQP conformance
// corpus (issue 13): each check or relaxation cites the section of the GLSL ES specification
// (1.00 rev 17, 3.00 rev 6) it implements. Kept apart from GlslEsRules.h, which holds the
// resource bounds, so that the two grow without touching each other. Private to the compiler
// library.
#pragma once

#include "tidepool/Diagnostic.h"

#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace glslang {
class TIntermediate;
}  // namespace glslang

namespace tidepool {

/// Checks one parsed stage for errors glslang 12 reports only at link time, although the
/// specification makes them compile errors: static recursion (GLSL ES 1.00 §6.1, 3.00 §6.1:
/// the call graph of a shader may have no cycle, even through functions never called) and a
/// fragment shader that statically writes both gl_FragColor and gl_FragData (1.00 §7.2).
std::vector<Diagnostic> CheckStageConformance(const glslang::TIntermediate& stage,
                                              const std::string& file);

/// A built-in variable a stage redeclares `invariant` (`invariant gl_Position;`, GLSL ES 1.00
/// §4.6.1), where the user wrote it. glslang 12 keeps no trace of such a redeclaration unless the
/// variable is also used.
struct InvariantBuiltIn {
    std::string name;
    int line = 0;
    int column = 0;
};

/// A cheap over-estimate: true when `source` mentions `invariant` at all. Only then does
/// FindInvarianceDeclarations need the preprocessed text.
bool MayRedeclareInvariant(std::string_view source);

/// What a stage's text says about invariance beyond glslang's qualifiers.
struct InvarianceDeclarations {
    /// Built-ins redeclared `invariant`.
    std::vector<InvariantBuiltIn> builtins;
    /// `#pragma STDGL invariant(all)` (GLSL ES 1.00 §4.6.1): glslang 12 accepts it but marks
    /// nothing invariant.
    bool all = false;
};

/// The invariance declarations in glslang's preprocessed text of a stage (comments and inactive
/// blocks gone, lines kept): `invariant` followed by a list of names starting with `gl_` and a
/// `;`, and the pragma. Columns are found on the same line of `source`, the user's text.
InvarianceDeclarations FindInvarianceDeclarations(std::string_view preprocessed,
                                                  std::string_view source);

/// In a `#version 100` fragment shader, redeclaring gl_FrontFacing `invariant` is an error
/// (GLSL ES 1.00 §4.6.4: its invariance is that of gl_Position); glslang 12 accepts it.
std::vector<Diagnostic> CheckInvariantBuiltIns(const glslang::TIntermediate& stage,
                                               const InvarianceDeclarations& invariance,
                                               const std::string& file);

/// What CheckLinkConformance needs to know of a stage besides its tree.
struct LinkedStage {
    const glslang::TIntermediate& intermediate;
    const std::string& file;
    std::string_view source;  // the text glslang parsed, line for line the user's
    const InvarianceDeclarations& invariance;
};

/// Checks a linked vertex and fragment stage for mismatches, each at the fragment stage's
/// declaration. glslang 12's own link reports some of them too, but with no line and in pieces
/// ("Types must match:"): a uniform declared in both stages whose type (members included) or
/// top-level precision differs (GLSL ES 1.00 §4.5.3, 3.00 §4.3.5), and an output and input of the
/// same name whose types differ (1.00 §4.3.5, 3.00 §4.3.4). The rest glslang 12 lets through: a
/// uniform declared in both stages whose struct or block members differ in precision (glslang
/// compares the precision of the top-level declaration only), an output and input of the same name
/// with different interpolation qualifiers (3.00 §4.3.9), and, in `#version 100`, a varying
/// declared in both stages that is `invariant` in one only (the vertex shader's `#pragma STDGL
/// invariant(all)` makes all its varyings invariant), or gl_FragCoord (gl_PointCoord) redeclared
/// `invariant` while gl_Position (gl_PointSize) is not (1.00 §4.6.4).
std::vector<Diagnostic> CheckLinkConformance(const LinkedStage& vertex,
                                             const LinkedStage& fragment);

/// True when `source` spells, outside comments, one of the words GLSL ES 3.00 §3.7 reserves for
/// future use (inactive blocks included, so an over-estimate). Only then does
/// CheckEs300ReservedWords need the preprocessed text.
bool MayUseEs300ReservedWord(std::string_view source);

/// Checks glslang's preprocessed text of a GLSL ES 3.00 stage (inactive blocks and comments
/// gone, lines kept) for the words §3.7 reserves for future use ("Using them will result in an
/// error"). Each use is an error at its line, at its column in `source`, but for
/// image1DShadow, image2DShadow, image1DArrayShadow and image2DArrayShadow, which glslang 12
/// and Mesa accept and dEQP-GLES3 expects to compile (VK-GL-CTS#431): a warning that WebGL 2
/// refuses them, and an error under a WebGL target (`webgl`), as the WebGL 2 conformance
/// suite expects.
std::vector<Diagnostic> CheckEs300ReservedWords(std::string_view preprocessed,
                                                std::string_view source, const std::string& file,
                                                bool webgl);

/// A cheap over-estimate: true when some `#extension` line follows a line that is not a
/// directive. Only then does CheckExtensionPlacement need the preprocessed text.
bool MayHaveLateExtension(std::string_view source);

/// Checks glslang's preprocessed text (inactive blocks and comments gone, lines kept) for an
/// `#extension` directive after a non-preprocessor token (GLSL ES 1.00 §3.4 and 3.00 §3.4: a
/// shader-scoped extension directive must come before any of them).
std::vector<Diagnostic> CheckExtensionPlacement(std::string_view preprocessed,
                                                const std::string& file);

/// The lines of the `switch` statements in glslang's preprocessed text (comments and inactive
/// blocks gone, lines kept) whose last case or default label is followed by a statement before
/// the closing brace: an empty statement `;`, an empty compound statement `{}` or an empty
/// declaration such as `float;` all are statements (GLSL ES 3.00 §6.2 and its grammar, §9), but
/// glslang 12 keeps no node for them and so reports "last case/default label not followed by
/// statements". A line holding another `switch` that does end in a bare label is left out.
std::set<int> SwitchesWithStatementAfterLastLabel(std::string_view preprocessed);

/// True when a failed parse failed only for a reason the specification does not make an error,
/// so that parsing again with glslang's relaxed errors is worth trying: `defined` produced by a
/// macro expansion inside `#if` (dEQP requires it to work; glslang refuses it for GLSL ES), and,
/// in a `#version 100` shader, `#define`/`#undef` of a name containing `__` (GLSL ES 1.00 §3.4:
/// reserved, "does not itself result in an error"). For a WebGL target (`webgl`), `defined`
/// from a macro stays an error: WebGL 1.0 §6.34 makes it one. In `#version 300 es`, glslang's
/// error for a switch whose last label has no statement after it is relaxable when the switch is
/// at one of `switch_lines` (see SwitchesWithStatementAfterLastLabel). For a WebGL 1 target
/// (`webgl` and version 100), a global variable initializer that is not a constant expression is
/// relaxable (WebGL 1.0 §6.33).
bool FailedOnlyForRelaxableReasons(const std::vector<Diagnostic>& diagnostics, int version,
                                   bool webgl, const std::set<int>& switch_lines = {});

/// The log of a parse with glslang's relaxed errors, with every warning except the relaxable
/// reasons above made an error again: relaxed mode demotes other errors to warnings too (an
/// undefined name in `#if`, a disabled extension's feature, ...), and a warning it did not
/// demote is also taken as one, which can only make a shader invalid, never valid. The
/// relaxed warning for a switch at one of `switch_lines` is dropped (see
/// SwitchesWithStatementAfterLastLabel). For a WebGL 1 target (`webgl1`), the warning for a
/// global initializer that is not a constant expression stays a warning, reworded (WebGL 1.0
/// §6.33; CheckWebGlGlobalInitializers checks what such an initializer may use).
std::vector<Diagnostic> RestoreDemotedErrors(std::vector<Diagnostic> diagnostics,
                                             const std::set<int>& switch_lines = {},
                                             bool webgl1 = false);

/// True when `diagnostics` holds glslang's error for a switch whose last label it believes has no
/// statement after it, so that SwitchesWithStatementAfterLastLabel is worth computing.
bool MentionsEmptyLastCase(const std::vector<Diagnostic>& diagnostics);

/// A unary `+` of the user's text: its place, and its offset in the text.
struct UnaryPlus {
    int line = 0;
    int column = 0;
    std::size_t offset = 0;
};

/// The unary `+` operators of a stage's text outside preprocessor directives: a `+` (not part of
/// `++` or `+=`) that does not follow an operand (a name, a number, `)` other than the one closing
/// the condition of `if`, `while` or `for`, `]` or a postfix `++` or `--`), and is not directly
/// followed by a number, whose type is never in doubt. glslang 12's
/// grammar drops unary `+` without checking its operand.
std::vector<UnaryPlus> FindUnaryPluses(std::string_view text);

/// A cheap over-estimate: true when a `#define` line of `text` holds a `+`, so that a macro may
/// produce a unary `+` that FindUnaryPluses finds only in the preprocessed text.
bool MacroMayHoldUnaryPlus(std::string_view text);

/// `text` with each of `pluses` replaced by ` - `: unary `-` takes exactly the operands unary
/// `+` takes (GLSL ES 1.00 §5.9, 3.00 §5.9), and glslang does check those. Lines are kept.
std::string NegateUnaryPluses(std::string_view text, const std::vector<UnaryPlus>& pluses);

/// From the log of a parse of NegateUnaryPluses' text, the errors of a `-` glslang refused for
/// its operand's type, reported at the unary `+` of that line (GLSL ES 1.00 §5.9, 3.00 §5.9: the
/// arithmetic unary operators take integer and floating-point scalars, vectors and matrices;
/// not a struct, an array, a bool or a sampler). Any other error of that parse is ignored: the
/// negation may change a constant's value, never a type.
std::vector<Diagnostic> UnaryPlusErrors(const std::vector<Diagnostic>& negated_log,
                                        const std::vector<UnaryPlus>& pluses,
                                        const std::string& file);

/// True when a failed `#version 100` parse failed only where glslang wanted a constant
/// expression (a const initializer, a global initializer, an array size), so that
/// FoldEs100ConstantExpressions may be worth trying.
bool FailedOnlyForConstantExpressions(const std::vector<Diagnostic>& diagnostics);

/// The declarations FoldEs100ConstantExpressions' text needs, given to glslang as its preamble:
/// one struct per matrix size, whose constructor takes exactly that matrix type.
extern const char* const kEs100FoldingPreamble;

/// glslang's preprocessed text of a `#version 100` stage (macros expanded, comments gone, lines
/// kept) rewritten so that glslang 12 folds two kinds of expression GLSL ES 1.00 §5.10 (and
/// §4.3.3) makes constant expressions when their operands are, but glslang does not:
/// - `matrixCompMult(x, y)`, "a built-in function call whose arguments are all constant
///   expressions", becomes `matN(x[0] * y[0], ...)` for N the size of x's type (found from a
///   `matN` constructor or the declaration `matN x` before it; the call is left as it is when
///   neither says), each operand wrapped in a constructor of a preamble struct that takes only a
///   `matN`, so a wrong size or a non-matrix operand stays an error;
/// - the sequence operator in a parenthesised expression, `(a, b)`, "an operator on operands
///   that are constant expressions" in 1.00 (3.00 §4.3.3 excludes it, and is left alone),
///   becomes `((a) == (a) ? (b) : (b))`, which keeps the value of `b` and is constant only when
///   `a` is.
/// Each rewritten expression keeps its lines (the text it replaces is joined onto its first line
/// and the line breaks follow it); `rewritten_lines` receives the lines where one starts. Empty
/// when there is nothing to rewrite, or the text would grow past a bound.
std::string FoldEs100ConstantExpressions(std::string_view preprocessed,
                                         std::set<int>* rewritten_lines);

}  // namespace tidepool
