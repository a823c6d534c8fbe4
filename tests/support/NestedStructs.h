// GLSL struct declarations that nest deep and wide in few lines, for the rules that walk
// structure types (GLSL ES uniform vectors and array elements, WebGL's nesting and packing).
#pragma once

#include <string>

namespace tidepool::testing {

/// `struct S1 { float a; float b; };`, then `levels` - 1 more structures, each holding the one
/// before twice (`struct S2 { S1 a; S1 b; };` ...): 2^levels floats in `levels` lines. A walk
/// that visits each member anew takes 2^levels steps.
inline std::string DoublingStructs(int levels) {
    std::string text = "struct S1 { float a; float b; };\n";
    for (int level = 2; level <= levels; ++level) {
        std::string inner(1, 'S');  // appended, not `"S" + string`: GCC 12 warns falsely
        inner += std::to_string(level - 1);
        text.append("struct S").append(std::to_string(level)).append(" { ");
        text.append(inner).append(" a; ").append(inner).append(" b; };\n");
    }
    return text;
}

/// DoublingStructs(levels) with each structure after S1 declared through a macro,
/// `DOUBLE(S1, S2)` for `struct S2 { S1 a; S1 b; };`: one line for the macro, then one per
/// level. tidepool's source-level guard on structures (which reads code, not macro expansions)
/// does not see them, so glslang and the rules over its parsed types do.
inline std::string DoublingStructsByMacro(int levels) {
    std::string text =
            "#define DOUBLE(A, B) struct B { A a; A b; };\nstruct S1 { float a; float b; };\n";
    for (int level = 2; level <= levels; ++level) {
        text.append("DOUBLE(S").append(std::to_string(level - 1)).append(", S");
        text.append(std::to_string(level)).append(")\n");
    }
    return text;
}

}  // namespace tidepool::testing
