// Static cost of one GLSL ES stage program: operation counts read from glslang's intermediate
// tree, so variants can be compared before anything runs on a GPU.
//
// Counting rules (each rule is about one node of glslang's tree after constant folding, so
// `2.0 * 3.0` costs nothing and `a * b` costs one op whether a and b are floats or mat4s):
//
//  * Only code reachable from main() counts. A call to a user function counts the callee's body
//    once per call site (as if inlined); a function that is never called contributes nothing.
//    The call itself, parameter passing and `return` are free. A recursive call (which GLSL ES
//    forbids and glslang's linker rejects) contributes nothing, so a bad tree cannot hang us.
//  * One arithmetic op per node for: + - * / (scalar, vector or matrix, including
//    vector*scalar, matrix*vector and matrix*matrix), unary minus, ++ and --, the compound
//    assignments (+= -= *= /=), comparisons (< > <= >= == !=), and && || ^^ !.
//  * Free: plain assignment, constructors and type conversions (`vec4(x)`, `float(i)`),
//    indexing, swizzles, field selection, the comma operator, constants and variable reads.
//  * One builtin call per call of a built-in function, counted under its GLSL name ("pow",
//    "normalize", "mix", "dot", "lessThan", "not", "matrixCompMult", "dFdx", ...). Texture
//    lookups are builtin calls too ("texture2D", "texture2DProj", "textureCube",
//    "texture2DLod", "textureCubeLod", and in fragment shaders "texture2DLodEXT",
//    "texture2DGradEXT", ...), and each also adds one to texture_samples.
//  * A selection (if, if/else, ?:) adds one to branches; `else if` is a second selection. A
//    loop (for, while, do) adds one to loops. && and || are counted as arithmetic, not branches.
//  * Loops are counted statically: the condition, the body and the increment expression count
//    once each, whatever the trip count, because the trip count is not known in general.
//  * Shortest/longest path: a selection costs its condition plus the cheaper (shortest) or the
//    dearer (longest) of its two arms (a missing else is an empty arm); everything else costs
//    the sum of its parts. Early exits (return, discard, break) do not end a path, and both
//    operands of && and || are always counted. Without selections, shortest == longest ==
//    TotalOps(); with them, shortest <= longest <= TotalOps().
//  * Interface: uniforms, varyings and samplers count declarations (an array or a struct is
//    one), deduplicated by name, and only those referenced in reachable code. Names starting with
//    "gl_" are built-ins and never count. Varyings are the vertex shader's outputs and the
//    fragment shader's inputs (vertex attributes are not varyings).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace tidepool {

/// Operation counts of one stage program, read from glslang's intermediate tree.
struct StageCost {
    int arithmetic_ops = 0;                    // operator nodes; see the rules above
    int texture_samples = 0;                   // texture lookups, also listed in builtin_calls
    std::map<std::string, int> builtin_calls;  // calls by GLSL name, texture lookups included
    int branches = 0;                          // if, if/else and ?: selections
    int loops = 0;                             // for, while and do-while loops
    int uniforms = 0;                          // referenced non-sampler uniform declarations
    int varyings = 0;           // referenced varyings: vertex outputs or fragment inputs, not gl_*
    int samplers = 0;           // referenced sampler uniform declarations
    int shortest_path_ops = 0;  // TotalOps-style ops on the cheapest path through all selections
    int longest_path_ops = 0;   // ... on the dearest path (as Mali's offline compiler reports)

    /// Returns arithmetic_ops plus all builtin calls; a texture lookup counts once because
    /// texture_samples is a subset of builtin_calls.
    int TotalOps() const;
};

/// Serialises a cost with one key per field name plus "total_ops"; never fails.
nlohmann::json ToJson(const StageCost& cost);

/// Parses `glsl_es_source` as a GLSL ES vertex or fragment shader (`#version 100` when the source
/// has no #version line) and analyses it; returns nullopt with glslang's info log in `error_log`
/// (when not null) if the source does not compile. Link-time checks (missing main, recursion) are
/// not run: a missing main() costs zero.
std::optional<StageCost> AnalyzeSourceCost(std::string_view glsl_es_source, bool is_fragment,
                                           std::string* error_log);

}  // namespace tidepool
