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
    const CommandResult r = RunShell("'" TIDEPOOL_BINARY "' --help 2>&1");
    EXPECT_EQ(r.exit_code, 0) << r.out;
    for (const char* command :
         {"expand", "validate", "stats", "render", "bench", "report", "run", "stability", "plan"}) {
        EXPECT_NE(r.out.find(std::string("  ") + command + " "), std::string::npos)
                << command << " missing from\n"
                << r.out;
    }
}

TEST(FrontEndCliTest, GlCommandFlagsAndErrorsComeFromTidepoolGl) {
    const CommandResult help = RunShell("'" TIDEPOOL_BINARY "' render --help 2>&1");
    EXPECT_EQ(help.exit_code, 0) << help.out;
    EXPECT_NE(help.out.find("--backend"), std::string::npos) << help.out;
    const CommandResult bad = RunShell("'" TIDEPOOL_BINARY "' render --size 3 2>&1");
    EXPECT_EQ(bad.exit_code, 2) << bad.out;
    EXPECT_NE(bad.out.find("--size"), std::string::npos) << bad.out;
}

TEST(FrontEndCliTest, GlCommandWithoutTidepoolGlIsAnEnvironmentErrorNamingIt) {
    TempDir dir;
    std::filesystem::copy_file(TIDEPOOL_BINARY, dir.Path() / "tidepool");
    const std::string alone = "cd '" + dir.Path().string() + "' && ./tidepool";
    const CommandResult render = RunShell(alone + " render 2>&1");
    EXPECT_EQ(render.exit_code, 3) << render.out;
    EXPECT_NE(render.out.find("tidepool-gl"), std::string::npos) << render.out;
    // The commands that need no GL do not need it either.
    const CommandResult version = RunShell(alone + " --version 2>&1");
    EXPECT_EQ(version.exit_code, 0) << version.out;
    EXPECT_NE(version.out.find("tidepool 0.1.0"), std::string::npos) << version.out;
}

}  // namespace
