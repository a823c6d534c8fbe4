// GLSL ES rules that glslang 12 gets wrong or checks too late, found by the dEQP conformance
// corpus (issue 13): each check or relaxation cites the section of the GLSL ES specification
// (1.00 rev 17, 3.00 rev 6) it implements. Kept apart from GlslEsRules.h, which holds the
// resource bounds, so that the two grow without touching each other. Private to the compiler
// library.
#pragma once

#include "tidepool/Diagnostic.h"

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

/// Checks a linked vertex and fragment stage for mismatches glslang 12 lets through: a uniform
/// declared in both stages whose struct or block members differ in precision (GLSL ES 1.00
/// §4.5.3, 3.00 §4.3.5; glslang compares the precision of the top-level declaration only), and
/// an output and input of the same name with different interpolation qualifiers (3.00 §4.3.9).
/// `fragment_source` is the fragment file's text, where the declaration is found for its line.
std::vector<Diagnostic> CheckLinkConformance(const glslang::TIntermediate& vertex,
                                             const std::string& vertex_file,
                                             const glslang::TIntermediate& fragment,
                                             const std::string& fragment_file,
                                             std::string_view fragment_source);

/// A cheap over-estimate: true when some `#extension` line follows a line that is not a
/// directive. Only then does CheckExtensionPlacement need the preprocessed text.
bool MayHaveLateExtension(std::string_view source);

/// Checks glslang's preprocessed text (inactive blocks and comments gone, lines kept) for an
/// `#extension` directive after a non-preprocessor token (GLSL ES 1.00 §3.4 and 3.00 §3.4: a
/// shader-scoped extension directive must come before any of them).
std::vector<Diagnostic> CheckExtensionPlacement(std::string_view preprocessed,
                                                const std::string& file);

/// True when a failed parse failed only for a reason the specification does not make an error,
/// so that parsing again with glslang's relaxed errors is worth trying: `defined` produced by a
/// macro expansion inside `#if` (dEQP requires it to work; glslang refuses it for GLSL ES), and,
/// in a `#version 100` shader, `#define`/`#undef` of a name containing `__` (GLSL ES 1.00 §3.4:
/// reserved, "does not itself result in an error"). For a WebGL target (`webgl`), `defined`
/// from a macro stays an error: WebGL 1.0 §6.34 makes it one.
bool FailedOnlyForRelaxableReasons(const std::vector<Diagnostic>& diagnostics, int version,
                                   bool webgl);

/// The log of a parse with glslang's relaxed errors, with every warning except the relaxable
/// reasons above made an error again: relaxed mode demotes other errors to warnings too (an
/// undefined name in `#if`, a disabled extension's feature, ...), and a warning it did not
/// demote is also taken as one, which can only make a shader invalid, never valid.
std::vector<Diagnostic> RestoreDemotedErrors(std::vector<Diagnostic> diagnostics);

/// In a `#version 300 es` shader, glslang only warns when `#define` or `#undef` names a macro
/// containing `__`; GLSL ES 3.00 §3.4 reserves those names, so each such warning becomes an
/// error at the same place. Other versions are returned unchanged.
std::vector<Diagnostic> PromoteReservedMacroNames(std::vector<Diagnostic> diagnostics, int version);

}  // namespace tidepool
