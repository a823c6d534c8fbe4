// Static cost analysis over glslang's intermediate tree (private: it names glslang types, but only
// by forward declaration, so including this header does not pull in glslang).
#pragma once

#include "tidepool/StaticCost.h"

namespace glslang {
class TIntermediate;
}  // namespace glslang

namespace tidepool {

/// Counts the operations, selections, loops and referenced interface variables of one parsed
/// (or linked) stage, following the rules in tidepool/StaticCost.h; never fails, and a tree
/// without main() yields an all-zero cost. The intermediate's TShader or TProgram must be alive.
StageCost AnalyzeStageCost(const glslang::TIntermediate& intermediate);

}  // namespace tidepool
