// The resource limits glslang checks a stage against: the GLSL ES minimums of its version, a
// device's own limits when given, and WebGL 1's restrictions. Private to the compiler library.
#pragma once

#include "tidepool/DeviceLimits.h"

#include <glslang/Include/ResourceLimits.h>

#include <string>
#include <vector>

namespace tidepool {

/// The limits for a stage of GLSL ES `version` (100 or 300; any other version gets glslang's
/// defaults): the minimums every ES 2.0 or ES 3.0 context has (GLSL ES 1.00 §7.4, 3.00 §7.3),
/// then each of `device`'s values in their place, then, when `appendix_a` is set, the
/// restrictions of GLSL ES 1.00 Appendix A §4 and §5 on loops and indexing, which WebGL 1
/// requires of every shader whatever the device (WebGL 1.0 §4.3 "Supported GLSL Constructs").
TBuiltInResource ResourcesFor(int version, const DeviceLimits* device, bool appendix_a);

/// Every limit name glslang's configuration format has, in the order `glslangValidator -c`
/// prints them.
const std::vector<std::string>& ResourceLimitNames();

/// True for the names of the loop and indexing switches (`nonInductiveForLoops`, ...), which
/// take 0 or 1.
bool IsResourceSwitch(const std::string& name);

}  // namespace tidepool
