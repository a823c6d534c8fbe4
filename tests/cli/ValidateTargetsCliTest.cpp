// `tidepool validate --limits FILE` and `--target webgl1|webgl2`, in plain-file and config mode:
// exit codes and the exact diagnostics a user sees.
#include <gtest/gtest.h>

#include <string>

#include "TempDir.h"
#include "TidepoolProcess.h"

namespace {

using tidepool::testing::CommandResult;
using tidepool::testing::RunTidepool;
using tidepool::testing::TempDir;

constexpr const char* kTargetsVertex =
        "#version 100\n"
        "attribute vec4 position;\n"
        "varying float depth;\n"
        "void main() { depth = position.z; gl_Position = position; }\n";

// Valid GLSL ES 1.00, but a while loop is outside what WebGL 1 accepts (Appendix A §4).
constexpr const char* kFragmentWithWhile =
        "#version 100\n"
        "precision mediump float;\n"
        "varying float depth;\n"
        "void main() {\n"
        "    float d = depth; while (d > 1.0) { d *= 0.5; }\n"
        "    gl_FragColor = vec4(d);\n"
        "}\n";

// 20 uniform vectors: more than the 16 of GLSL ES 1.00 §7.4's minimum.
constexpr const char* kFragmentWithTwentyVectors =
        "#version 100\n"
        "precision mediump float;\n"
        "uniform vec4 palette[20];\n"
        "void main() { gl_FragColor = palette[0] + palette[19]; }\n";

TEST(ValidateTargetsCliTest, LimitsFileRaisesAMinimumForPlainFiles) {
    TempDir dir;
    dir.Write("a.fsh", kFragmentWithTwentyVectors);
    dir.Write("phone.conf", "# our phone\nMaxFragmentUniformVectors 64\n");
    const CommandResult minimums = RunTidepool("validate a.fsh", dir.Path());
    EXPECT_EQ(minimums.exit_code, 1) << minimums.err;
    const CommandResult phone = RunTidepool("validate --limits phone.conf a.fsh", dir.Path());
    EXPECT_EQ(phone.exit_code, 0) << phone.err;
}

TEST(ValidateTargetsCliTest, BadLimitsFileExitsTwoNamingLineAndFix) {
    TempDir dir;
    dir.Write("a.fsh", kFragmentWithTwentyVectors);
    dir.Write("phone.conf", "MaxDrawBuffers 4\nMaxFragmentUniformVector 64\n");
    const CommandResult r = RunTidepool("validate --limits phone.conf a.fsh", dir.Path());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("phone.conf:2:1: error: unknown limit 'MaxFragmentUniformVector'; did "
                         "you mean 'MaxFragmentUniformVectors'?"),
              std::string::npos)
            << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(ValidateTargetsCliTest, WebGl1TargetRefusesAWhileLoopThatGlslEsAllows) {
    TempDir dir;
    dir.Write("w.vsh", kTargetsVertex);
    dir.Write("w.fsh", kFragmentWithWhile);
    EXPECT_EQ(RunTidepool("validate w.vsh w.fsh", dir.Path()).exit_code, 0);
    const CommandResult r = RunTidepool("validate --target webgl1 w.vsh w.fsh", dir.Path());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("w.fsh:5: error: 'limitation' : while loops not available"),
              std::string::npos)
            << r.err;
    EXPECT_EQ(r.out.find("error:"), std::string::npos) << r.out;
}

TEST(ValidateTargetsCliTest, WebGlTargetsInConfigurationAndOnTheCommandLine) {
    TempDir dir;
    dir.Write("w.vsh", kTargetsVertex);
    dir.Write("w.fsh", kFragmentWithWhile);
    const std::string program = "programs:\n  p:\n    vertex: w.vsh\n    fragment: w.fsh\n";
    dir.Write("plain.yaml", "targets: [100]\n" + program);
    dir.Write("web.yaml", "targets: [100, webgl1]\n" + program);
    EXPECT_EQ(RunTidepool("validate --config plain.yaml", dir.Path()).exit_code, 0);
    const CommandResult web = RunTidepool("validate --config web.yaml", dir.Path());
    EXPECT_EQ(web.exit_code, 1) << web.err;
    EXPECT_NE(web.err.find("w.fsh:5: error: 'limitation' : while loops not available [p:]"),
              std::string::npos)
            << web.err;
    const CommandResult flag =
            RunTidepool("validate --config plain.yaml --target webgl1", dir.Path());
    EXPECT_EQ(flag.exit_code, 1) << flag.err;
    // WebGL 2 runs the sources as GLSL ES 3.00, where while loops are fine.
    EXPECT_EQ(RunTidepool("validate --config plain.yaml --target webgl2", dir.Path()).exit_code, 0);
}

}  // namespace
