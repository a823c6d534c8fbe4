// A folder holding a small variant matrix (two programs over one valid shader pair), for the
// pipeline's unit tests.
#pragma once

#include "tidepool/Diagnostic.h"

#include <string>
#include <vector>

#include "TempDir.h"

namespace tidepool::testing {

/// Writes s.vsh, s.fsh and v.yaml (programs `p`, features A and B, and `q`) into a temp folder.
class SmallMatrix {
public:
    SmallMatrix() {
        dir_.Write("s.vsh", "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n");
        dir_.Write("s.fsh",
                   "#version 100\nprecision mediump float;\nvoid main() {\n#ifdef A\n"
                   "  gl_FragColor = vec4(0.5);\n#else\n  gl_FragColor = vec4(1.0);\n#endif\n}\n");
        config_ = dir_.Write("v.yaml",
                             "programs:\n"
                             "  p:\n"
                             "    vertex: s.vsh\n"
                             "    fragment: s.fsh\n"
                             "    features: [A, B]\n"
                             "  q:\n"
                             "    vertex: s.vsh\n"
                             "    fragment: s.fsh\n")
                          .string();
    }

    /// Makes the variants with B fail to compile: an undeclared identifier on s.fsh line 5.
    void BreakFeatureB() const {
        dir_.Write("s.fsh",
                   "#version 100\nprecision mediump float;\nvoid main() {\n#ifdef B\n"
                   "  gl_FragColor = nope;\n#else\n  gl_FragColor = vec4(1.0);\n#endif\n}\n");
    }

    const TempDir& Dir() const { return dir_; }
    const std::string& Config() const { return config_; }

private:
    TempDir dir_;
    std::string config_;
};

/// Every diagnostic formatted as the CLI prints it, one per line.
inline std::string Formatted(const std::vector<Diagnostic>& diagnostics) {
    std::string text;
    for (const Diagnostic& d : diagnostics) {
        text += FormatDiagnostic(d) + "\n";
    }
    return text;
}

}  // namespace tidepool::testing
