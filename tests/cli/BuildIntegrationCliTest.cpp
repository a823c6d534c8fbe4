// The build integration as a user project sees it: `--depfile` and `--program` on the command
// line, and the CMake module (cmake/TidepoolShaderVariants.cmake) driving examples/shader_variants
// from a clean folder with Ninja and with Make: it builds, a build with nothing changed runs
// nothing, and touching one shader reruns only the step of the program that reads it.
#include <gtest/gtest.h>

#include <cctype>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "FileContents.h"
#include "TempDir.h"
#include "TidepoolProcess.h"
#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;
using tidepool::testing::CommandResult;
using tidepool::testing::ReadText;
using tidepool::testing::RunShell;
using tidepool::testing::RunTidepool;
using tidepool::testing::TempDir;

constexpr const char* kIntegrationVertex =
        "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n";
constexpr const char* kIntegrationFragment =
        "#version 100\nprecision mediump float;\nvoid main() { gl_FragColor = vec4(1.0); }\n";

// A folder with shaders s.vsh, "a b.vsh", s.fsh and t.fsh, for configurations to name.
class DepfileCliTest : public ::testing::Test {
protected:
    DepfileCliTest() {
        for (const char* name : {"s.vsh", "a b.vsh"}) {
            dir_.Write(name, kIntegrationVertex);
        }
        for (const char* name : {"s.fsh", "t.fsh"}) {
            dir_.Write(name, kIntegrationFragment);
        }
    }
    // The depfile expected for o/manifest.json and these files of the folder, in this order.
    std::string Depfile(const std::vector<std::string>& files) const {
        const std::string root = dir_.Path().string();
        std::string text = root + "/o/manifest.json:";
        for (const std::string& file : files) {
            text += " \\\n  " + root + "/" + file;
        }
        return text + "\n";
    }
    TempDir dir_;
};

TEST_F(DepfileCliTest, ValidateDepfileNamesTheManifestTheConfigAndEveryShaderRead) {
    dir_.Write("v.yaml",
               "programs:\n  p:\n    vertex: a b.vsh\n    fragment: s.fsh\n"
               "  q:\n    vertex: a b.vsh\n    fragment: t.fsh\n");
    const CommandResult r =
            RunTidepool("validate --config v.yaml --out o --depfile o.d", dir_.Path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // A space is escaped for Make and Ninja; a shader two programs share is named once.
    EXPECT_EQ(ReadText(dir_.Path() / "o.d"), Depfile({"v.yaml", "a\\ b.vsh", "s.fsh", "t.fsh"}));
}

TEST_F(DepfileCliTest, ProgramNarrowsTheDepfileTheManifestAndTheSources) {
    dir_.Write("v.yaml",
               "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n"
               "    features: [A]\n  q:\n    vertex: s.vsh\n    fragment: t.fsh\n");
    const CommandResult r = RunTidepool(
            "validate --config v.yaml --program q --out o --sources --depfile o.d", dir_.Path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(ReadText(dir_.Path() / "o.d"), Depfile({"v.yaml", "s.vsh", "t.fsh"}));
    const nlohmann::json manifest =
            nlohmann::json::parse(ReadText(dir_.Path() / "o/manifest.json"));
    ASSERT_EQ(manifest["variants"].size(), 1u);
    EXPECT_EQ(manifest["variants"][0]["id"], "q:");
    EXPECT_EQ(manifest["variants"][0]["sources"]["fragment"], "100/q/q..frag");
    EXPECT_EQ(ReadText(dir_.Path() / "o/100/q/q..frag"),
              "#version 100\n#line 2\nprecision mediump float;\nvoid main() { gl_FragColor = "
              "vec4(1.0); }\n");
    const CommandResult unknown = RunTidepool("validate --config v.yaml --program r", dir_.Path());
    EXPECT_EQ(unknown.exit_code, 2);
    EXPECT_NE(unknown.err.find("error: --program r: v.yaml has no such program; it has p, q"),
              std::string::npos)
            << unknown.err;
    EXPECT_EQ(RunTidepool("validate --config v.yaml --depfile o.d", dir_.Path()).exit_code, 2)
            << "a depfile names the output it belongs to, so it needs --out";
}

// A step's depfile must not name another program's shader, or touching it would rerun the step;
// that is only right when the step's output does not depend on that shader, which the unchanged
// manifest shows. The cache's miss, its run-record hit and the miss after the edit agree.
TEST_F(DepfileCliTest, ProgramDepfileLeavesOutOtherProgramsShadersOnEveryCachePath) {
    dir_.Write("v.yaml",
               "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n"
               "  q:\n    vertex: s.vsh\n    fragment: t.fsh\n");
    const std::string cache = "--cache '" + (dir_.Path() / "cache").string() + "'";
    const std::string narrowed = "validate --config v.yaml --program q --out o --depfile o.d ";
    const std::string expected = Depfile({"v.yaml", "s.vsh", "t.fsh"});
    std::string manifest;
    for (const char* edit : {"", "", "#version 100\nprecision lowp float;\nvoid main() {}\n"}) {
        SCOPED_TRACE(edit);
        if (*edit != '\0') {
            dir_.Write("s.fsh", edit);  // p's fragment shader only
        }
        const CommandResult r = RunTidepool(narrowed + cache, dir_.Path());
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(ReadText(dir_.Path() / "o.d"), expected);
        const std::string written = ReadText(dir_.Path() / "o/manifest.json");
        EXPECT_EQ(written, manifest.empty() ? written : manifest);
        manifest = written;
    }
    const CommandResult all =
            RunTidepool("validate --config v.yaml --out o --depfile o.d " + cache, dir_.Path());
    ASSERT_EQ(all.exit_code, 0) << all.err;
    EXPECT_EQ(ReadText(dir_.Path() / "o.d"), Depfile({"v.yaml", "s.vsh", "s.fsh", "t.fsh"}));
}

TEST_F(DepfileCliTest, ExpandWritesADepfileToo) {
    dir_.Write("v.yaml", "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n");
    ASSERT_EQ(RunTidepool("expand --config v.yaml --out o --depfile o.d", dir_.Path()).exit_code,
              0);
    EXPECT_EQ(ReadText(dir_.Path() / "o.d"), Depfile({"v.yaml", "s.vsh", "s.fsh"}));
}

// Checked before any work, so nothing is written: not the depfile, not the manifest.
TEST_F(DepfileCliTest, OutputsThatWouldReplaceAnInputOrEachOtherAreRefused) {
    const std::string config = "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n";
    dir_.Write("v.yaml", config);
    struct Case {
        const char* args;
        const char* error;
    };
    for (const Case& c :
         {Case{"validate --config v.yaml --out o --depfile v.yaml",
               "error: --depfile: v.yaml is a file this command reads; writing it would replace "
               "it: choose another path\n"},
          Case{"expand --config v.yaml --out o --depfile s.vsh",
               "error: --depfile: s.vsh is a file this command reads; writing it would replace "
               "it: choose another path\n"},
          Case{"validate --config v.yaml --json --output-file s.fsh",
               "error: --output-file: s.fsh is a file this command reads; writing it would "
               "replace it: choose another path\n"},
          Case{"validate s.vsh s.fsh --json --output-file s.vsh",
               "error: --output-file: s.vsh is a file this command reads; writing it would "
               "replace it: choose another path\n"},
          Case{"validate --config v.yaml --out o --depfile o/manifest.json",
               "error: --depfile: o/manifest.json is also where --out writes; give each output "
               "its own path\n"},
          Case{"validate --config v.yaml --out o --depfile o",
               "error: --depfile: o is the folder --out writes manifest.json into; give the path "
               "of a file beside it\n"},
          Case{"expand --config v.yaml --out o --depfile o/manifest.json",
               "error: --depfile: o/manifest.json is also where --out writes; give each output "
               "its own path\n"},
          Case{"expand --config v.yaml --out o --depfile o",
               "error: --depfile: o is the folder --out writes manifest.json into; give the path "
               "of a file beside it\n"},
          Case{"validate --config v.yaml --out o --depfile s.vsh/o.d",
               "error: --depfile: s.vsh/o.d: s.vsh is a file, not a folder; choose another "
               "path\n"}}) {
        SCOPED_TRACE(c.args);
        const CommandResult r = RunTidepool(c.args, dir_.Path());
        EXPECT_EQ(r.exit_code, 2);
        EXPECT_EQ(r.err, c.error);
        EXPECT_EQ(ReadText(dir_.Path() / "v.yaml"), config);
        EXPECT_EQ(ReadText(dir_.Path() / "s.vsh"), kIntegrationVertex);
        EXPECT_EQ(ReadText(dir_.Path() / "s.fsh"), kIntegrationFragment);
        EXPECT_FALSE(fs::exists(dir_.Path() / "o"));
    }
}

// The write failed with "File name too long" (exit 3) after the work, naming a staging folder.
TEST_F(DepfileCliTest, AVariantFileNameTooLongForTheFileSystemIsAUsageErrorBeforeAnyWork) {
    const std::string feature(130, 'F');
    dir_.Write("v.yaml",
               "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n"
               "    features: [A" +
                       feature + ", B" + feature + "]\n");
    for (const char* args :
         {"expand --config v.yaml --out o", "validate --config v.yaml --out o --sources"}) {
        SCOPED_TRACE(args);
        const CommandResult r = RunTidepool(args, dir_.Path());
        EXPECT_EQ(r.exit_code, 2);
        EXPECT_EQ(r.err.rfind("v.yaml:2:3: error: variant 'p:A" + feature + ",B" + feature +
                                      "' would be written to a file name of 270 bytes",
                              0),
                  0U)
                << r.err;
        EXPECT_FALSE(fs::exists(dir_.Path() / "o"));
    }
}

TEST_F(DepfileCliTest, AShaderNameADepfileCannotHoldIsAUsageErrorBeforeAnyWork) {
    dir_.Write("t\tb.vsh", kIntegrationVertex);
    dir_.Write("v.yaml", "programs:\n  p:\n    vertex: \"t\\tb.vsh\"\n    fragment: s.fsh\n");
    const CommandResult r =
            RunTidepool("validate --config v.yaml --out o --depfile o.d", dir_.Path());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "error: --depfile: \"" + (dir_.Path() / "t\\tb.vsh").string() +
                             "\" has a tab in its name, which Make or Ninja would read as "
                             "something else in a depfile; rename it, or leave out --depfile\n");
    EXPECT_FALSE(fs::exists(dir_.Path() / "o"));
    EXPECT_FALSE(fs::exists(dir_.Path() / "o.d"));
    // Without a depfile the same configuration validates.
    EXPECT_EQ(RunTidepool("validate --config v.yaml --out o", dir_.Path()).exit_code, 0);
}

TEST_F(DepfileCliTest, TheLimitsFileIsADependencyToo) {
    dir_.Write("v.yaml", "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n");
    dir_.Write("device.txt", "MaxDrawBuffers 1\n");
    const CommandResult r = RunTidepool(
            "validate --config v.yaml --limits device.txt --out o --depfile o.d", dir_.Path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(ReadText(dir_.Path() / "o.d"), Depfile({"v.yaml", "s.vsh", "s.fsh", "device.txt"}));
}

// examples/shader_variants, copied to a clean folder and built with one CMake generator.
class ExampleProjectTest : public ::testing::TestWithParam<const char*> {
protected:
    ExampleProjectTest() {
        fs::copy(fs::path(TIDEPOOL_SOURCE_ROOT) / "examples/shader_variants", Source(),
                 fs::copy_options::recursive);
    }
    fs::path Source() const { return dir_.Path() / "src"; }
    fs::path Build() const { return dir_.Path() / "build"; }

    CommandResult Configure() const {
        return RunShell("'" CMAKE_COMMAND "' -S '" + Source().string() + "' -B '" +
                        Build().string() + "' -G '" + GetParam() +
                        "' -Dtidepool_DIR='" TIDEPOOL_BUILD_DIR "' 2>&1");
    }
    // Builds; with Ninja, `-d explain` says why each step ran.
    CommandResult BuildAll() const {
        const bool ninja = std::string(GetParam()) == "Ninja";
        return RunShell("'" CMAKE_COMMAND "' --build '" + Build().string() + "'" +
                        (ninja ? " -- -d explain" : "") + " 2>&1");
    }
    // Runs the example's program with `args`, stdout and stderr apart.
    CommandResult RunLoader(const std::string& args) const {
        // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "'" + string + "...".
        std::string command = "'";
        command += (Build() / "variant_loader").string();
        command += "' ";
        command += args;
        return RunShell(command);
    }
    // Gives `file` a time stamp later than every output so far, without changing its content.
    static void Touch(const fs::path& file) {
        // File time stamps come from the kernel's coarse clock (a few ms), so wait past one tick.
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        fs::last_write_time(file, fs::file_time_type::clock::now());
    }
    TempDir dir_;
};

bool Contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

TEST_P(ExampleProjectTest, BuildsFromACleanFolderAndRebuildsOnlyWhatATouchedShaderFeeds) {
    const CommandResult configure = Configure();
    ASSERT_EQ(configure.exit_code, 0) << configure.out;
    const CommandResult first = BuildAll();
    ASSERT_EQ(first.exit_code, 0) << first.out;
    EXPECT_TRUE(Contains(first.out, "validating the tint variants")) << first.out;
    EXPECT_TRUE(Contains(first.out, "validating the outline variants")) << first.out;

    // The program finds a variant by its feature set, in any order, and refuses a pruned one.
    const CommandResult loaded = RunLoader("tint TINT FOG");
    EXPECT_EQ(loaded.exit_code, 0) << loaded.err;
    EXPECT_TRUE(Contains(loaded.out, "tint:FOG,TINT\n  vertex   100/tint/tint.FOG.TINT.vert"))
            << loaded.out;
    const CommandResult pruned = RunLoader("tint FOG_EXP2");
    EXPECT_EQ(pruned.exit_code, 1) << pruned.err;
    EXPECT_TRUE(
            Contains(pruned.err, "error: tint has no valid variant with exactly those features"))
            << pruned.err;
    EXPECT_EQ(pruned.out, "");

    // Nothing changed: nothing runs.
    const CommandResult idle = BuildAll();
    ASSERT_EQ(idle.exit_code, 0) << idle.out;
    EXPECT_FALSE(Contains(idle.out, "validating")) << idle.out;
    EXPECT_FALSE(Contains(idle.out, "Linking")) << idle.out;
    if (std::string(GetParam()) == "Ninja") {
        EXPECT_TRUE(Contains(idle.out, "ninja: no work to do.")) << idle.out;
    }

    // One shader of one program: that program's step alone, and nothing is relinked.
    const fs::path tint_source = Build() / "shaders/tint/100/tint/tint.FOG.TINT.frag";
    const fs::file_time_type tint_stamp = fs::last_write_time(tint_source);
    Touch(Source() / "shaders/outline.frag");
    const CommandResult outline = BuildAll();
    ASSERT_EQ(outline.exit_code, 0) << outline.out;
    EXPECT_TRUE(Contains(outline.out, "validating the outline variants")) << outline.out;
    EXPECT_FALSE(Contains(outline.out, "validating the tint variants")) << outline.out;
    EXPECT_FALSE(Contains(outline.out, "Linking")) << outline.out;
    if (std::string(GetParam()) == "Ninja") {
        // Ninja's reason names the shader the depfile listed.
        EXPECT_TRUE(Contains(outline.out, "outline.frag")) << outline.out;
    }
    EXPECT_EQ(fs::last_write_time(tint_source), tint_stamp);
    const CommandResult settled = BuildAll();
    EXPECT_FALSE(Contains(settled.out, "validating")) << settled.out;

    // A touched shader whose content is unchanged reruns its step, which rewrites the manifest
    // but leaves every variant's source (and so whatever an engine builds from it) untouched.
    const fs::file_time_type manifest_stamp =
            fs::last_write_time(Build() / "shaders/tint/manifest.json");
    Touch(Source() / "shaders/tint.frag");
    const CommandResult tint = BuildAll();
    ASSERT_EQ(tint.exit_code, 0) << tint.out;
    EXPECT_TRUE(Contains(tint.out, "validating the tint variants")) << tint.out;
    EXPECT_FALSE(Contains(tint.out, "validating the outline variants")) << tint.out;
    EXPECT_EQ(fs::last_write_time(tint_source), tint_stamp);
    EXPECT_GT(fs::last_write_time(Build() / "shaders/tint/manifest.json"), manifest_stamp);

    // The configuration feeds every program.
    Touch(Source() / "variants.yaml");
    const CommandResult config = BuildAll();
    ASSERT_EQ(config.exit_code, 0) << config.out;
    EXPECT_TRUE(Contains(config.out, "validating the tint variants")) << config.out;
    EXPECT_TRUE(Contains(config.out, "validating the outline variants")) << config.out;
}

TEST_P(ExampleProjectTest, AnInvalidVariantFailsTheBuildAtTheShaderLine) {
    ASSERT_EQ(Configure().exit_code, 0);
    ASSERT_EQ(BuildAll().exit_code, 0);
    std::string shader = ReadText(Source() / "shaders/outline.frag");
    shader.replace(shader.find("gl_FragColor = colour;"), 22, "gl_FragColor = oops;");
    dir_.Write("src/shaders/outline.frag", shader);
    const CommandResult broken = BuildAll();
    EXPECT_NE(broken.exit_code, 0);
    EXPECT_TRUE(Contains(broken.out, "shaders/outline.frag:6:")) << broken.out;
    EXPECT_TRUE(Contains(broken.out, "'oops' : undeclared identifier")) << broken.out;
    // A failed step is not recorded as done: the next build tries again.
    EXPECT_NE(BuildAll().exit_code, 0);
}

// `cmake --install` into a prefix, which is then moved (the package finds its binary relative to
// itself): find_package(tidepool) through CMAKE_PREFIX_PATH alone builds the example project
// with the installed binary, and the installed front end finds the installed tidepool-gl.
// CMake's depfile transform drops tidepool's `$$` and turns `\:` into `/:` (Ninja then reran
// every step on every build; Make stopped), and CMake splits paths at `;`: the module refuses
// such paths, and a second target on one OUTPUT_DIR, when CMake configures, in its own words.
TEST(ShaderVariantsModuleTest, PathsCMakeBreaksAndASharedOutputDirAreRefusedAtConfigure) {
    struct Case {
        const char* calls;
        const char* error;
    };
    for (const Case& c :
         {Case{"tidepool_add_shader_variants(TARGET a CONFIG variants.yaml PROGRAMS tint "
               "OUTPUT_DIR \"o$x\")",
               "holds one of $ : ; # or a newline"},
          Case{"tidepool_add_shader_variants(TARGET a CONFIG variants.yaml PROGRAMS tint "
               "OUTPUT_DIR o:x)",
               "holds one of $ : ; # or a newline"},
          Case{"tidepool_add_shader_variants(TARGET a CONFIG variants.yaml PROGRAMS tint "
               "OUTPUT_DIR o)\ntidepool_add_shader_variants(TARGET b CONFIG variants.yaml "
               "PROGRAMS tint OUTPUT_DIR o)",
               "is already the output folder of target 'a'; give each target its own "
               "OUTPUT_DIR"}}) {
        SCOPED_TRACE(c.calls);
        TempDir dir;
        fs::copy(fs::path(TIDEPOOL_SOURCE_ROOT) / "examples/shader_variants", dir.Path() / "src",
                 fs::copy_options::recursive);
        dir.Write("src/CMakeLists.txt",
                  std::string("cmake_minimum_required(VERSION 3.20)\nproject(p NONE)\n"
                              "find_package(tidepool REQUIRED CONFIG)\n") +
                          c.calls + "\n");
        const CommandResult configure =
                RunShell("'" CMAKE_COMMAND "' -S '" + (dir.Path() / "src").string() + "' -B '" +
                         (dir.Path() / "build").string() +
                         "' -G Ninja -Dtidepool_DIR='" TIDEPOOL_BUILD_DIR "' 2>&1");
        EXPECT_NE(configure.exit_code, 0) << configure.out;
        // CMake wraps a message's lines; read it as one line.
        std::string words;
        for (const char ch : configure.out) {
            if (!std::isspace(static_cast<unsigned char>(ch))) {
                words += ch;
            } else if (!words.empty() && words.back() != ' ') {
                words += ' ';
            }
        }
        EXPECT_TRUE(Contains(words, c.error)) << configure.out;
    }
}

TEST(InstalledPackageTest, AMovedInstallPrefixBuildsTheExampleProject) {
    const TempDir dir;
    const fs::path staged = dir.Path() / "staged";
    const fs::path prefix = dir.Path() / "prefix";
    const CommandResult install =
            RunShell("'" CMAKE_COMMAND "' --install '" TIDEPOOL_BUILD_DIR "' --prefix '" +
                     staged.string() + "' 2>&1");
    ASSERT_EQ(install.exit_code, 0) << install.out;
    fs::rename(staged, prefix);
    for (const char* file :
         {"bin/tidepool", "bin/tidepool-gl", "lib/cmake/tidepool/tidepoolConfig.cmake",
          "lib/cmake/tidepool/tidepoolConfigVersion.cmake",
          "lib/cmake/tidepool/TidepoolShaderVariants.cmake"}) {
        EXPECT_TRUE(fs::exists(prefix / file)) << file;
    }
    // A GL command: the front end execs tidepool-gl from its own folder.
    const CommandResult gl =
            RunShell("'" + (prefix / "bin/tidepool").string() + "' render --help 2>&1");
    EXPECT_EQ(gl.exit_code, 0) << gl.out;
    EXPECT_TRUE(Contains(gl.out, "--size")) << gl.out;

    fs::copy(fs::path(TIDEPOOL_SOURCE_ROOT) / "examples/shader_variants", dir.Path() / "src",
             fs::copy_options::recursive);
    const CommandResult configure =
            RunShell("'" CMAKE_COMMAND "' -S '" + (dir.Path() / "src").string() + "' -B '" +
                     (dir.Path() / "build").string() + "' -G Ninja -DCMAKE_PREFIX_PATH='" +
                     prefix.string() + "' 2>&1");
    ASSERT_EQ(configure.exit_code, 0) << configure.out;
    EXPECT_TRUE(Contains(ReadText(dir.Path() / "build/CMakeCache.txt"),
                         "tidepool_DIR:PATH=" + (prefix / "lib/cmake/tidepool").string()));
    // -v: Ninja prints each command, so the log shows which binary validated.
    const CommandResult build = RunShell("'" CMAKE_COMMAND "' --build '" +
                                         (dir.Path() / "build").string() + "' -- -v 2>&1");
    ASSERT_EQ(build.exit_code, 0) << build.out;
    EXPECT_TRUE(Contains(build.out, (prefix / "bin/tidepool").string() + " validate --config"))
            << build.out;
    const CommandResult loaded =
            RunShell("'" + (dir.Path() / "build/variant_loader").string() + "' tint FOG TINT 2>&1");
    EXPECT_EQ(loaded.exit_code, 0) << loaded.out;
    EXPECT_TRUE(Contains(loaded.out, "tint:FOG,TINT")) << loaded.out;
}

INSTANTIATE_TEST_SUITE_P(Generators, ExampleProjectTest,
                         ::testing::Values("Ninja", "Unix Makefiles"),
                         [](const ::testing::TestParamInfo<const char*>& param) {
                             return std::string(param.param) == "Ninja" ? "Ninja" : "Make";
                         });

}  // namespace
