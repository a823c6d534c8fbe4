// A device's resource limits, read from a file, so that shaders are validated against one GPU's
// limits instead of the minimums every GLSL ES context has.
#pragma once

#include "tidepool/Diagnostic.h"

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tidepool {

/// Resource limits by glslang's configuration name (`glslangValidator -c` prints every name with
/// its default), in the order the file gave them. They replace, name by name, the limits a
/// `#version 100` or `#version 300 es` stage is otherwise checked against.
struct DeviceLimits {
    std::string path;                                 // the file they were read from
    std::vector<std::pair<std::string, int>> values;  // {name, value}

    /// "Name value" lines, for cache keys: equal limits give equal text.
    std::string Text() const;
};

/// The outcome of reading a limits file: `ok` with the limits, or the errors.
struct DeviceLimitsRead {
    bool ok = false;
    DeviceLimits limits;
    std::vector<Diagnostic> diagnostics;
};

/// Parses limits written one per line as `Name value` (glslang's `-c` format; blank lines and
/// comments from `#` or `//` to the end of a line are ignored). Every problem is reported at
/// `path:line:column`: a line that is not a name and a value, a name glslang does not know
/// (with the closest known name), a name given twice, a value that is not a whole number, a
/// negative value (allowed only for the `Min...` limits) and a value other than 0 or 1 for the
/// loop and indexing switches (`nonInductiveForLoops`, ...).
DeviceLimitsRead ParseDeviceLimits(std::string_view text, const std::string& path);

/// ParseDeviceLimits on a file's text; a file that cannot be read is one error naming it.
DeviceLimitsRead ReadDeviceLimits(const std::string& path);

}  // namespace tidepool
