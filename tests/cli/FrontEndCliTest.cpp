// The `tidepool` front end: the commands that need no GL run without loading GL, Mesa or LLVM,
// and the ones that render are handed to tidepool-gl with the same arguments.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "TempDir.h"
#include "TidepoolProcess.h"

namespace {

using tidepool::testing::CommandResult;
using tidepool::testing::RunShell;
using tidepool::testing::RunTidepool;
using tidepool::testing::TempDir;

// Libraries of the GL stack (Mesa's EGL, GLES and OSMesa, its drivers, and what llvmpipe
// drags in: LLVM, z3, ICU, libdrm, gbm); none may be in the front end.
constexpr const char* kGlLibraries[] = {"libEGL", "libGL",  "libOSMesa", "libgallium", "libLLVM",
                                        "libz3",  "libicu", "libgbm",    "libdrm",     "libglapi"};

TEST(FrontEndCliTest, FrontEndLinksNoGlMesaOrLlvmLibrary) {
    const CommandResult ldd = RunShell("ldd '" TIDEPOOL_BINARY "' 2>&1");
    ASSERT_EQ(ldd.exit_code, 0) << ldd.out;
    ASSERT_NE(ldd.out.find("libc.so"), std::string::npos) << ldd.out;
    for (const char* library : kGlLibraries) {
        EXPECT_EQ(ldd.out.find(library), std::string::npos) << library << " in\n" << ldd.out;
    }
}

TEST(FrontEndCliTest, ExpandAndValidateLoadNoGlLibraryAtRunTime) {
    // LD_DEBUG=libs names every library the dynamic loader maps, dlopen included.
    for (const char* command : {"expand", "validate --no-cache -j 1", "--version"}) {
        SCOPED_TRACE(command);
        const CommandResult r =
                RunShell("cd '" TIDEPOOL_SOURCE_ROOT "' && LD_DEBUG=libs '" +
                         std::string(TIDEPOOL_BINARY) + "' " + command + " 2>&1 >/dev/null");
        ASSERT_NE(r.out.find("libc.so"), std::string::npos) << r.out;
        for (const char* library : kGlLibraries) {
            EXPECT_EQ(r.out.find(library), std::string::npos) << library;
        }
    }
}

TEST(FrontEndCliTest, HelpListsEveryCommandTheGlOnesIncluded) {
    const CommandResult r = RunTidepool("--help");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    for (const char* command :
         {"expand", "validate", "stats", "render", "bench", "report", "run", "stability", "plan"}) {
        EXPECT_NE(r.out.find(std::string("  ") + command + " "), std::string::npos)
                << command << " missing from\n"
                << r.out;
    }
}

// CLI11 alone said "A subcommand is required", naming neither the word nor the commands.
TEST(FrontEndCliTest, AnUnknownCommandIsNamedWithTheCommandsAndTheNearestOne) {
    constexpr const char* kCommands =
            "the commands are expand, validate, stats, render, bench, report, run, stability, "
            "plan (tidepool --help says what each does)\n";
    struct Case {
        std::string args;
        std::string error;
    };
    for (const Case& c : {
                 Case{"validat --config v.yaml",
                      std::string("error: 'validat' is not a tidepool command; did you mean "
                                  "'validate'? ") +
                              kCommands},
                 Case{"--version bogus",
                      std::string("error: 'bogus' is not a tidepool command; ") + kCommands},
                 Case{std::string(100, 'x'), "error: '" + std::string(64, 'x') +
                                                     "...' is not a tidepool command; " +
                                                     kCommands},
         }) {
        const CommandResult r = RunTidepool(c.args);
        EXPECT_EQ(r.exit_code, 2) << c.args;
        EXPECT_EQ(r.err, c.error) << c.args;
        EXPECT_EQ(r.out, "") << c.args;
    }
}

// An unset variable in a build script (`--out "$OUTDIR"`) used to be taken as no value at all:
// `expand --out ''` wrote nothing and exited 0, and `--program ''` validated every program.
TEST(FrontEndCliTest, AnEmptyArgumentIsAUsageErrorNamingTheOptionBeforeIt) {
    for (const char* args :
         {"expand --out '' --config variants.yaml", "validate --program '' --json",
          "validate --output-file= --config variants.yaml", "expand --config variants.yaml ''"}) {
        const CommandResult r = RunTidepool(args);
        EXPECT_EQ(r.exit_code, 2) << args;
        EXPECT_NE(r.err.find("no option takes one: give a value, or leave the option out (an "
                             "unset variable in a script?)"),
                  std::string::npos)
                << args << "\n"
                << r.err;
        EXPECT_EQ(r.out, "") << args;
    }
    EXPECT_EQ(RunTidepool("expand --out '' --config variants.yaml").err.substr(0, 44),
              "error: an empty argument after '--out'; no o");
    EXPECT_EQ(RunTidepool("validate --output-file= --config variants.yaml").err.substr(0, 49),
              "error: '--output-file=' gives an empty value; no ");
}

TEST(FrontEndCliTest, GlCommandFlagsAndErrorsComeFromTidepoolGl) {
    const CommandResult help = RunTidepool("render --help");
    EXPECT_EQ(help.exit_code, 0) << help.err;
    EXPECT_NE(help.out.find("--backend"), std::string::npos) << help.out;
    const CommandResult bad = RunTidepool("render --size 3");
    EXPECT_EQ(bad.exit_code, 2) << bad.err;
    EXPECT_NE(bad.err.find("--size"), std::string::npos) << bad.err;
    EXPECT_EQ(bad.out, "");
}

TEST(FrontEndCliTest, GlCommandWithoutTidepoolGlIsAnEnvironmentErrorNamingIt) {
    TempDir dir;
    std::filesystem::copy_file(TIDEPOOL_BINARY, dir.Path() / "tidepool");
    const std::string alone = "cd '" + dir.Path().string() + "' && ./tidepool";
    const CommandResult render = RunShell(alone + " render");
    EXPECT_EQ(render.exit_code, 3) << render.err;
    EXPECT_NE(render.err.find("tidepool-gl"), std::string::npos) << render.err;
    EXPECT_EQ(render.out, "");
    // The commands that need no GL do not need it either.
    const CommandResult version = RunShell(alone + " --version");
    EXPECT_EQ(version.exit_code, 0) << version.err;
    EXPECT_NE(version.out.find("tidepool 0.1.0"), std::string::npos) << version.out;
}

}  // namespace
