// The `tidepool` command as a user runs it: exit codes, messages and outputs.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "FileContents.h"
#include "NestedStructs.h"
#include "TempDir.h"
#include "TidepoolProcess.h"
#include <nlohmann/json.hpp>
#include <sys/stat.h>
#include <sys/wait.h>

namespace {

using tidepool::testing::ReadText;
using tidepool::testing::TempDir;

using tidepool::testing::CommandResult;
using tidepool::testing::RunTidepool;

constexpr const char* kVertex =
        "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n";
constexpr const char* kFragment =
        "#version 100\nprecision mediump float;\nvoid main() {\n#ifdef B\n  gl_FragColor = "
        "vec4(oops);\n#else\n  gl_FragColor = vec4(1.0);\n#endif\n}\n";

class CliTest : public ::testing::Test {
protected:
    CliTest() {
        dir_.Write("s.vsh", kVertex);
        dir_.Write("s.fsh", kFragment);
    }
    // Writes v.yaml: `top` (top-level keys), then program p on s.vsh/s.fsh with `program_keys`.
    void WriteConfig(const std::string& top, const std::string& program_keys = "") {
        dir_.Write("v.yaml", top + "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n" +
                                     program_keys);
    }
    // Runs `validate ARGS` in the test folder for each case, expecting exit code 2, exactly
    // that error on stderr and nothing on stdout.
    struct UsageCase {
        const char* args;
        const char* error;
    };
    void ExpectUsageErrors(std::initializer_list<UsageCase> cases) {
        for (const UsageCase& c : cases) {
            const CommandResult r = RunTidepool(std::string("validate ") + c.args, dir_.Path());
            EXPECT_EQ(r.exit_code, 2) << c.args;
            EXPECT_EQ(r.err, c.error) << c.args;
            EXPECT_EQ(r.out, "") << c.args;
        }
    }
    TempDir dir_;
};

TEST_F(CliTest, ValidateDefaultMatrixPrintsCountsAndExitsZero) {
    const CommandResult r = RunTidepool("validate");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("variants ("), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("pruned combinations"), std::string::npos);
    EXPECT_NE(r.out.find("shared"), std::string::npos);
    EXPECT_NE(r.out.find("all valid"), std::string::npos);
    EXPECT_EQ(r.err, "");
}

TEST_F(CliTest, ShaderErrorExitsOneWithGccStyleDiagnosticAndVariant) {
    dir_.Write("v.yaml",
               "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n    features: [A, B]\n");
    const CommandResult r = RunTidepool("validate --config v.yaml", dir_.Path());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("s.fsh:5:23: error: 'oops' : undeclared identifier [p:B]"),
              std::string::npos)
            << r.err;
    EXPECT_NE(r.err.find("s.fsh:5:23: error: 'oops' : undeclared identifier [p:A,B]"),
              std::string::npos);
    EXPECT_NE(r.out.find("2 INVALID"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("error:"), std::string::npos) << r.out;
}

// A program names its shaders relative to the configuration's folder; a diagnostic names the
// file as it is found from where tidepool runs, so a terminal, an IDE or a build log opens it.
TEST_F(CliTest, ShaderDiagnosticsOfAConfigurationElsewhereNameThePathFromHere) {
    dir_.Write("sub/v.yaml",
               "programs:\n  p:\n    vertex: ../s.vsh\n    fragment: ../s.fsh\n"
               "    features: [B]\n");
    const CommandResult r = RunTidepool("validate --config sub/v.yaml", dir_.Path());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(r.err.rfind("s.fsh:5:23: error: 'oops' : undeclared identifier [p:B]\n", 0), 0U)
            << r.err;
    dir_.Write("sub/s.fsh", ReadText(dir_.Path() / "s.fsh"));
    dir_.Write("sub/s.vsh", kVertex);
    dir_.Write("sub/v.yaml",
               "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n"
               "    features: [B]\n");
    const CommandResult nested = RunTidepool("validate --config sub/v.yaml", dir_.Path());
    EXPECT_EQ(nested.err.rfind("sub/s.fsh:5:23: error: 'oops' : undeclared identifier [p:B]\n", 0),
              0U)
            << nested.err;
}

TEST_F(CliTest, ConfigurationErrorExitsTwoAndNamesFileLineColumn) {
    dir_.Write("v.yaml",
               "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n    colour: 1\n");
    const CommandResult r = RunTidepool("validate --config v.yaml", dir_.Path());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err,
              "v.yaml:5:5: error: unknown key 'colour' in program 'p'; allowed keys: vertex, "
              "fragment, features, axes, rules, description\n");
    EXPECT_EQ(r.out, "");
}

// A name holding a NUL cut the message short, and an escape sequence drove the terminal.
TEST_F(CliTest, ControlCharactersInAMessageAreShownAsEscapes) {
    dir_.Write("v.yaml",
               "programs:\n  \"p\\0x\\e[31m\":\n    vertex: s.vsh\n    fragment: s.fsh\n");
    for (const char* command : {"validate", "expand"}) {
        const CommandResult r = RunTidepool(std::string(command) + " --config v.yaml", dir_.Path());
        EXPECT_EQ(r.exit_code, 2) << command;
        EXPECT_EQ(r.err,
                  "v.yaml:2:3: error: program name 'p\\x00x\\x1b[31m' must be an identifier "
                  "(letters, digits, _)\n")
                << command;
    }
}

TEST_F(CliTest, MissingConfigurationExitsTwo) {
    const CommandResult r = RunTidepool("expand --config nowhere.yaml", dir_.Path());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("nowhere.yaml: error: cannot read the configuration file"),
              std::string::npos)
            << r.err;
    EXPECT_EQ(r.out, "");
}

TEST_F(CliTest, MatrixOverTheLimitIsRefusedUnlessTheFlagRaisesIt) {
    // The flag's limit is reported at the program that passed it; the file's at its own line.
    struct Case {
        const char* limit_line;
        const char* flags;
        const char* expected;
    };
    for (const Case& c :
         {Case{"", " --max-variants 4",
               "v.yaml:2:3: error: program 'p' takes the matrix over 4 valid variants, the limit "
               "set by --max-variants; add rules, remove features, or raise the limit\n"},
          Case{"max_variants: 4\n", "",
               "v.yaml:1:15: error: program 'p' takes the matrix over 4 valid variants, the "
               "limit set by max_variants; add rules, remove features, or raise the limit\n"}}) {
        WriteConfig(c.limit_line, "    features: [A, C, D]\n");
        const CommandResult refused =
                RunTidepool(std::string("expand --config v.yaml") + c.flags, dir_.Path());
        EXPECT_EQ(refused.exit_code, 2);
        EXPECT_EQ(refused.err, c.expected);
        EXPECT_EQ(refused.out, "");
    }
    EXPECT_EQ(RunTidepool("expand --config v.yaml --max-variants 8", dir_.Path()).exit_code, 0);
}

TEST_F(CliTest, MaxVariantsOutOfRangeIsAUsageErrorNamingTheFlagAndRange) {
    WriteConfig("");
    for (const char* value : {"-1", "-5", "0", "65537", "18446744073709551616",
                              "100000000000000000000000", "1e3", "4x"}) {
        const CommandResult r = RunTidepool(
                std::string("expand --config v.yaml --max-variants=") + value, dir_.Path());
        EXPECT_EQ(r.exit_code, 2) << value << r.err;
        EXPECT_EQ(r.err, std::string("error: --max-variants must be a whole number from 1 to "
                                     "65536 (up to 16777216 with --allow-large-matrix), not '") +
                                 value + "'\n")
                << value;
    }
    // Empty is not "not given" (which would silently mean the file's limit).
    const CommandResult empty = RunTidepool("expand --config v.yaml --max-variants=", dir_.Path());
    EXPECT_EQ(empty.exit_code, 2);
    EXPECT_EQ(empty.err.rfind("error: '--max-variants=' gives an empty value; no option takes "
                              "one",
                              0),
              0U)
            << empty.err;
}

// Before, any number went: -j 0 and -j -1 silently meant one per core, and -j 999999 forked a
// worker for every item of a large matrix.
TEST_F(CliTest, JobsOutOfRangeIsAUsageErrorNamingTheFlagAndRange) {
    WriteConfig("");
    // 1e2 was "not in range 1 to 256" and 0x2 was taken for 2, unlike every other count.
    for (const char* value : {"0", "-1", "257", "999999", "abc", "1e2", "0x2", "2.0"}) {
        for (const char* command : {"validate --no-cache", "stats"}) {
            const CommandResult r =
                    RunTidepool(std::string(command) + " --config v.yaml -j " + value, dir_.Path());
            EXPECT_EQ(r.exit_code, 2) << value << r.err;
            EXPECT_EQ(r.err.rfind(std::string("error: --jobs must be a whole number from 1 to "
                                              "256, not '") +
                                          value + "'",
                                  0),
                      0U)
                    << value << r.err;
        }
    }
    EXPECT_EQ(RunTidepool("validate --no-cache --config v.yaml -j 256", dir_.Path()).exit_code, 0);
}

TEST_F(CliTest, AllowLargeMatrixLiftsTheCeilingButNotBeyondItsOwn) {
    WriteConfig("");
    EXPECT_EQ(RunTidepool("expand --config v.yaml --max-variants 100000 --allow-large-matrix",
                          dir_.Path())
                      .exit_code,
              0);
    const CommandResult r = RunTidepool(
            "expand --config v.yaml --max-variants 16777217 --allow-large-matrix", dir_.Path());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err,
              "error: --max-variants must be a whole number from 1 to 16777216, not "
              "'16777217'\n");
}

TEST_F(CliTest, FileLimitOutOfRangeOrAboveTheCeilingIsRefusedAtItsLine) {
    // 2147483647 loads nowhere; 100000 loads, but expansion needs --allow-large-matrix for it.
    for (const auto& [limit, expected] :
         {std::pair{"100000",
                    "v.yaml:1:15: error: max_variants of 100000 is over the ceiling of "
                    "65536 valid variants; lower it, or pass --allow-large-matrix to "
                    "allow up to 16777216\n"},
          std::pair{"2147483647",
                    "v.yaml:1:15: error: max_variants must be a whole number from "
                    "1 to 16777216 (valid variants; above 65536 only with "
                    "--allow-large-matrix), not '2147483647'\n"}}) {
        WriteConfig(std::string("max_variants: ") + limit + "\n");
        const CommandResult r = RunTidepool("validate --config v.yaml", dir_.Path());
        EXPECT_EQ(r.exit_code, 2) << limit;
        EXPECT_EQ(r.err, expected);
        EXPECT_EQ(r.out, "");
    }
    WriteConfig("max_variants: 100000\n");
    EXPECT_EQ(RunTidepool("expand --config v.yaml --allow-large-matrix", dir_.Path()).exit_code, 0);
}

TEST_F(CliTest, ExpandCountsPrunedCombinationsPerRuleWithoutListingThem) {
    WriteConfig("", "    features: [A, C]\n    rules: [{ if: C, requires: A }]\n");
    const CommandResult r = RunTidepool("expand --config v.yaml", dir_.Path());
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.out,
              "p:\np:A\np:A,C\n1 pruned by p: C requires A  (v.yaml:6)\n"
              "3 variants, 1 pruned combinations\n");
    EXPECT_EQ(r.err, "");
}

TEST_F(CliTest, ExpandPrunedListsPrunedCombinationsWithTheirRule) {
    WriteConfig("", "    features: [A, C]\n    rules: [{ if: C, requires: A }]\n");
    const CommandResult r = RunTidepool("expand --config v.yaml --pruned", dir_.Path());
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.out.find("pruned p:C  (C requires A, v.yaml:6)\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("3 variants, 1 pruned combinations"), std::string::npos);
}

TEST_F(CliTest, ExpandPrunedLimitListsThatManyAndSaysHowManyAreLeft) {
    WriteConfig("",
                "    features: [A, B, C]\n"
                "    rules: [{ if: B, requires: A }, { if: C, requires: A }]\n");
    const CommandResult r =
            RunTidepool("expand --config v.yaml --pruned --pruned-limit 1 --json", dir_.Path());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json json = nlohmann::json::parse(r.out);
    ASSERT_EQ(json["pruned"].size(), 1U);
    EXPECT_EQ(json["pruned_unlisted"], 2);
    EXPECT_EQ(json["counts"]["pruned"], 3);
    EXPECT_EQ(json["pruned_by_rule"][0]["count"], 2);
    EXPECT_EQ(json["pruned_by_rule"][1]["count"], 1);
    const CommandResult text =
            RunTidepool("expand --config v.yaml --pruned --pruned-limit 1", dir_.Path());
    EXPECT_NE(text.out.find("... 2 more pruned combinations not listed (raise --pruned-limit)"),
              std::string::npos)
            << text.out;
}

TEST_F(CliTest, ManifestKeepsPrunedCountsPerRuleNotTheCombinations) {
    WriteConfig("", "    features: [A, C]\n    rules: [{ if: C, requires: A }]\n");
    const CommandResult r = RunTidepool("expand --config v.yaml --json", dir_.Path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json json = nlohmann::json::parse(r.out);
    EXPECT_FALSE(json.contains("pruned"));
    EXPECT_EQ(json["pruned_by_rule"],
              nlohmann::json::parse(R"([{"program": "p", "rule": "C requires A", "file": "v.yaml",
                                         "line": 6, "count": 1}])"));
    EXPECT_EQ(json["counts"]["pruned"], 1);
}

TEST_F(CliTest, PrunedLimitOutOfRangeIsAUsageError) {
    WriteConfig("");
    const CommandResult r =
            RunTidepool("expand --config v.yaml --pruned --pruned-limit=-1", dir_.Path());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "error: --pruned-limit must be a whole number from 1 to 65536, not '-1'\n");
}

TEST_F(CliTest, ExpandOutWritesDriverReadySourcesAndManifest) {
    dir_.Write("v.yaml",
               "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n"
               "    features: [A]\n");
    const CommandResult r = RunTidepool("expand --config v.yaml --out gen", dir_.Path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(dir_.Path() / "gen/100/p/p.A.frag");
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str().substr(0, 36), "#version 100\n#define A 1\n#line 2\npre");
    std::ifstream manifest_file(dir_.Path() / "gen/manifest.json");
    const nlohmann::json manifest = nlohmann::json::parse(manifest_file);
    EXPECT_EQ(manifest["schema"], "tidepool.manifest");
    EXPECT_EQ(manifest["variants"].size(), 2U);
}

TEST_F(CliTest, ExpandOutRefusesToOverwriteAForeignFolder) {
    dir_.Write("v.yaml", "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n");
    dir_.Write("mine/notes.txt", "keep me");
    const CommandResult r = RunTidepool("expand --config v.yaml --out mine", dir_.Path());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(std::filesystem::exists(dir_.Path() / "mine/notes.txt"));
    EXPECT_NE(r.err.find("was not written by tidepool"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");  // the variant list used to come first, as if the run had worked
}

TEST_F(CliTest, ValidatePlainFilesLinksVertexWithFragment) {
    const CommandResult ok = RunTidepool("validate s.vsh s.fsh", dir_.Path());
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
    const CommandResult bad = RunTidepool("validate s.vsh s.fsh -D B", dir_.Path());
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.err.find("s.fsh:5:23: error: 'oops' : undeclared identifier"), std::string::npos)
            << bad.err;
}

TEST_F(CliTest, ValidatePlainFileWithUnknownExtensionAsksForStage) {
    dir_.Write("x.glsl", kVertex);
    const CommandResult r = RunTidepool("validate x.glsl", dir_.Path());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("x.glsl: error: cannot tell the stage from the extension"),
              std::string::npos)
            << r.err;
    EXPECT_EQ(RunTidepool("validate x.glsl --stage vert", dir_.Path()).exit_code, 0);
}

TEST_F(CliTest, ValidateJsonIsAManifestWithVerdictsAndCosts) {
    const CommandResult r = RunTidepool("validate --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json manifest = nlohmann::json::parse(r.out);
    EXPECT_EQ(manifest["version"], 1);
    EXPECT_GT(manifest["counts"]["shared_stage_slots"].get<int>(), 0);
    const nlohmann::json& first = manifest["variants"][0];
    EXPECT_TRUE(first["valid"].get<bool>());
    EXPECT_TRUE(first["stages"]["fragment"].contains("cost"));
}

TEST_F(CliTest, StatsShowsShortestAndLongestPathOfTheUniformProgram) {
    const CommandResult r = RunTidepool("stats --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json stats = nlohmann::json::parse(r.out);
    bool found = false;
    for (const nlohmann::json& entry : stats) {
        if (entry["id"] == "water_uniform:") {
            found = true;
            EXPECT_LT(entry["fragment"]["shortest_path_ops"].get<int>(),
                      entry["fragment"]["longest_path_ops"].get<int>());
        }
    }
    EXPECT_TRUE(found);
}

TEST_F(CliTest, HelpExitsZeroAndUnknownFlagExitsTwo) {
    EXPECT_EQ(RunTidepool("validate --help").exit_code, 0);
    EXPECT_EQ(RunTidepool("validate --no-such-flag").exit_code, 2);
    EXPECT_EQ(RunTidepool("").exit_code, 2);
}

// ---- Hostile input (issue 15) ------------------------------------------------------------------

TEST_F(CliTest, CyclicAliasInConfigExitsTwoWithItsPosition) {
    dir_.Write("v.yaml",
               "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n"
               "    features: &loop [A, *loop]\n");
    for (const char* command : {"validate", "expand", "stats"}) {
        const CommandResult r = RunTidepool(std::string(command) + " --config v.yaml", dir_.Path());
        EXPECT_EQ(r.exit_code, 2) << command << r.err;
        EXPECT_EQ(r.err,
                  "v.yaml:5:25: error: alias '*loop' refers to the node that contains "
                  "it, a cycle; an alias may only repeat a node that is complete\n")
                << command;
        EXPECT_EQ(r.out, "") << command;
    }
}

// Every command that reads the configuration, `run` included: a Latin-1 byte in a preset's name
// or in its description is an error at its line and column, and nothing is written.
TEST_F(CliTest, LatinOneConfigExitsTwoAtTheByte) {
    const std::string program = "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n";
    const std::pair<std::string, std::string> cases[] = {
            {"presets:\n  caf\xE9: {program: p}\n", "v.yaml:6:6"},
            {"presets:\n  cafe:\n    program: p\n    description: caf\xE9\n", "v.yaml:8:21"}};
    for (const auto& [presets, place] : cases) {
        dir_.Write("v.yaml", program + presets);
        for (const char* command :
             {"expand --json", "validate --json --out out", "run --out out"}) {
            const CommandResult r =
                    RunTidepool(std::string(command) + " --config v.yaml", dir_.Path());
            EXPECT_EQ(r.exit_code, 2) << command << ": " << r.err;
            EXPECT_EQ(r.err, place + ": error: this byte is not UTF-8; YAML files are Unicode "
                                     "text: save the file as UTF-8\n")
                    << command;
            EXPECT_EQ(r.out, "") << command;
            EXPECT_FALSE(std::filesystem::exists(dir_.Path() / "out")) << command;
        }
    }
}

TEST_F(CliTest, ConfigFileNameThatIsNotUtf8StillWritesJson) {
    dir_.Write("v\xE9.yaml", "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n");
    const CommandResult expand =
            RunTidepool("expand --json --out out --config 'v\xE9.yaml'", dir_.Path());
    EXPECT_EQ(expand.exit_code, 0) << expand.err;
    EXPECT_TRUE(nlohmann::json::accept(expand.out)) << expand.out;
    const CommandResult validate =
            RunTidepool("validate --json --out vout --config 'v\xE9.yaml'", dir_.Path());
    EXPECT_EQ(validate.exit_code, 0) << validate.err;
    EXPECT_TRUE(nlohmann::json::accept(validate.out));
}

TEST_F(CliTest, ShaderDiagnosticQuotingANonUtf8ByteIsEscapedInJson) {
    dir_.Write("bad.fsh",
               "#version 100\nprecision mediump float;\nvoid main() { gl_FragColor = "
               "vec4(caf\xE9); }\n");
    const CommandResult plain = RunTidepool("validate --json bad.fsh", dir_.Path());
    EXPECT_EQ(plain.exit_code, 1) << plain.err;
    const nlohmann::json json = nlohmann::json::parse(plain.out);
    EXPECT_EQ(json[0]["valid"], false);
    EXPECT_NE(plain.err.find("bad.fsh:3:"), std::string::npos) << plain.err;

    dir_.Write("v.yaml", "programs:\n  p:\n    vertex: s.vsh\n    fragment: bad.fsh\n");
    const CommandResult matrix =
            RunTidepool("validate --json --out m --config v.yaml", dir_.Path());
    EXPECT_EQ(matrix.exit_code, 1) << matrix.err;
    EXPECT_TRUE(nlohmann::json::accept(matrix.out));
    EXPECT_TRUE(std::filesystem::exists(dir_.Path() / "m" / "manifest.json"));
}

// `run` writes every diagnostic into its manifest and report: one that quotes a byte that is not
// UTF-8 is escaped there, never an abort. A tiny matrix (one water variant, the programs the
// renderer draws with, and the broken program) at 16x16 keeps the render short.
TEST_F(CliTest, RunWithANonUtf8ByteInAShaderKeepsItsJsonValid) {
    const std::string shaders = std::string(TIDEPOOL_SOURCE_ROOT) + "/shaders/";
    std::string config = "programs:\n";
    for (const char* program : {"water", "water_composite", "skybox", "model"}) {
        config += std::string("  ") + program + ":\n    vertex: " + shaders + program +
                  ".vsh\n    fragment: " + shaders + program + ".fsh\n";
    }
    config += "  broken:\n    vertex: s.vsh\n    fragment: bad.fsh\n";
    dir_.Write("v.yaml", config);
    dir_.Write("bad.fsh",
               "#version 100\nprecision mediump float;\nvoid main() { gl_FragColor = "
               "vec4(caf\xE9); }\n");
    const CommandResult r = RunTidepool(
            "run --config v.yaml --out out --size 16x16 --coarse-frames 1 --warmup 0 "
            "--min-pairs 10 --max-pairs 10 --no-stability --no-plans",
            dir_.Path());
    // 1 for the broken variant (and the comparisons, whose presets this matrix lacks); an abort
    // of the JSON writer was 134.
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("bad.fsh:3:"), std::string::npos) << r.err;
    const std::string manifest = ReadText(dir_.Path() / "out/manifest/manifest.json");
    ASSERT_TRUE(nlohmann::json::accept(manifest)) << manifest.substr(0, 200);
    // glslang quotes a byte of its own for it ('\x80', no UTF-8); the message names the byte
    // instead (ManifestTest checks that quoted bytes which are not UTF-8 become U+FFFD).
    EXPECT_NE(manifest.find("a character outside GLSL ES's character set (byte 0xE9, not ASCII)"),
              std::string::npos)
            << manifest;
    EXPECT_TRUE(nlohmann::json::accept(ReadText(dir_.Path() / "out/default/data.json")));
}

TEST_F(CliTest, ShaderWithAByteOrderMarkIsValidAndKeepsItsLineNumbers) {
    dir_.Write("bom.vsh", std::string("\xEF\xBB\xBF") + kVertex);
    dir_.Write("bom.fsh",
               "\xEF\xBB\xBF#version 100\nprecision mediump float;\nvoid main() { "
               "gl_FragColor = vec4(oops); }\n");
    const CommandResult ok = RunTidepool("validate bom.vsh s.fsh", dir_.Path());
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
    const CommandResult bad = RunTidepool("validate bom.fsh", dir_.Path());
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_EQ(bad.err, "bom.fsh:3:35: error: 'oops' : undeclared identifier\n");
}

TEST_F(CliTest, ShaderThatCrashesGlslangIsAnInternalCompilerErrorAndTheRunGoesOn) {
    // A public conformance case that makes glslang 12 dereference a null pointer.
    dir_.Write("crash.fsh", "#define m(a)\n#define a m((a)\na)\n");
    // Two fragment files are validated (and linked) one by one.
    const CommandResult r = RunTidepool("validate --json crash.fsh s.fsh", dir_.Path());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("crash.fsh: error: internal compiler error: glslang crashed ("),
              std::string::npos)
            << r.err;
    const nlohmann::json json = nlohmann::json::parse(r.out);
    ASSERT_EQ(json.size(), 2U);
    EXPECT_EQ(json[0]["valid"], false);
    EXPECT_EQ(json[1]["valid"], true);  // the other file was still validated
}

TEST_F(CliTest, MacroBombIsRefusedQuicklyWithItsPosition) {
    std::string bomb = "#version 100\n";
    for (int level = 0; level < 30; ++level) {
        bomb += "#define M" + std::to_string(level) + " M" + std::to_string(level + 1) + " M" +
                std::to_string(level + 1) + "\n";
    }
    bomb += "void main() { M0; }\n";
    dir_.Write("bomb.vsh", bomb);
    const CommandResult r = RunTidepool("validate bomb.vsh", dir_.Path());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err,
              "bomb.vsh:32:15: error: macro 'M0' expands to more than 131072 tokens (a "
              "macro bomb); tidepool refuses shaders that large: write repeated code as functions "
              "and loops rather than macros, or split the shader\n");
}

// A shader that keeps glslang busy far beyond its time limit: an `#if` whose condition expands
// to 2^40 tokens (the macro-size check measures code, not `#if` lines; the time limit is the
// guard for what that check misses). TIDEPOOL_TEST_GLSLANG_SECONDS lowers the 20 s limit to 1 s.
TEST_F(CliTest, GlslangHangFailsItsStageAndTheOtherVariantsAreStillValidated) {
    // A local of a structure that holds another twice over, 40 levels deep: glslang walks its
    // members anew (TType::contains) for 2^40 steps. Declared through a macro, out of the sight
    // of tidepool's source guard on structures. (A macro bomb in an #if did this until the token
    // guard took #if lines in too.)
    const std::string fragment = "#version 100\nprecision mediump float;\n#ifdef HANG\n" +
                                 tidepool::testing::DoublingStructsByMacro(40) +
                                 "#endif\nvoid main() {\n#ifdef HANG\n    S40 deep;\n#endif\n"
                                 "    gl_FragColor = vec4(1.0);\n}\n";
    dir_.Write("s.fsh", fragment);
    WriteConfig("", "    features: [HANG]\n");
    const auto start = std::chrono::steady_clock::now();
    const CommandResult r =
            RunTidepool("validate --config v.yaml", dir_.Path(), "TIDEPOOL_TEST_GLSLANG_SECONDS=1");
    const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(r.err,
              "s.fsh: error: internal compiler error: glslang took longer than 1 s while "
              "parsing this stage; the shader may be valid or not, and the run went "
              "on without it [p:HANG]\n");
    // The variant without HANG was validated, and found valid.
    EXPECT_NE(r.out.find("2 variants"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("; 1 INVALID"), std::string::npos) << r.out;
    EXPECT_LT(seconds, 15.0);
}

TEST_F(CliTest, FunctionLikeMacroBombIsRefusedQuicklyWithItsPosition) {
    // Each level uses its parameter twice over: F29(x) is 2^59 copies of x.
    std::string bomb = "#version 100\n#define F0(x) x x\n";
    for (int level = 1; level < 30; ++level) {
        bomb += "#define F" + std::to_string(level) + "(x) F" + std::to_string(level - 1) + "(F" +
                std::to_string(level - 1) + "(x))\n";
    }
    bomb += "attribute vec4 p;\nvoid main() { gl_Position = p * F29(1.0); }\n";
    dir_.Write("bomb.vsh", bomb);
    const auto start = std::chrono::steady_clock::now();
    const CommandResult r = RunTidepool("validate bomb.vsh", dir_.Path());
    const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err,
              "bomb.vsh:33:33: error: macro 'F29' expands to more than 131072 tokens (a "
              "macro bomb); tidepool refuses shaders that large: write repeated code as functions "
              "and loops rather than macros, or split the shader\n");
    // Refused by the pre-check, not by the worker's 20 s limit.
    EXPECT_LT(seconds, 5.0);
}

TEST_F(CliTest, ADefineNameLongerThanGlslangsLongestTokenIsAUsageError) {
    const CommandResult r =
            RunTidepool("validate -D " + std::string(2000, 'N') + "=1 s.vsh", dir_.Path());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err, "error: -D '" + std::string(64, 'N') +
                             "...': the name has 2000 characters, more than the 1024 of "
                             "glslang's longest token\n");
}

TEST_F(CliTest, DefineTakesOneValueSoTheFileAfterItIsValidated) {
    const CommandResult r = RunTidepool("validate -D B s.fsh", dir_.Path());
    EXPECT_EQ(r.exit_code, 1) << r.err;  // B selects the branch with the error
    EXPECT_NE(r.err.find("s.fsh:5:23: error: 'oops' : undeclared identifier"), std::string::npos)
            << r.err;
    EXPECT_EQ(r.out, "1 file(s): INVALID\n");
    EXPECT_EQ(RunTidepool("validate -D B=1 s.vsh", dir_.Path()).exit_code, 0);
}

TEST_F(CliTest, DefineMustBeANameOrNameEqualsOneLineValue) {
    const std::string long_token = "-D A=" + std::string(1025, '7') + " s.vsh";
    ExpectUsageErrors({
            UsageCase{"-D GL_X s.vsh",
                      "error: -D 'GL_X': 'GL_X' is not a valid define name: use "
                      "letters, digits and _, start with a letter, no 'GL_' "
                      "prefix and no '__'\n"},
            UsageCase{"-D 'FOO BAR' s.vsh",
                      "error: -D 'FOO BAR': 'FOO BAR' is not a valid "
                      "define name: use letters, digits and _, start with "
                      "a letter, no 'GL_' prefix and no '__'\n"},
            UsageCase{"-D \"$(printf 'A=1\\n#error injected')\" s.vsh",
                      "error: -D 'A': the value must be a single line (a newline would add "
                      "preprocessor lines)\n"},
            UsageCase{"-D A",
                      "error: -D applies to the shader FILEs given, and none was given; "
                      "the variants of a configuration get their defines from it\n"},
            // Before, these came from glslang at line -1 with exit code 1.
            UsageCase{"-D A=1 -D A=2 s.vsh", "error: -D 'A' is given twice; keep one\n"},
            UsageCase{"-D 'A=/*' s.vsh",
                      "error: -D 'A': the value may not hold '/*' (a comment it opens would run "
                      "on past the define)\n"},
            UsageCase{"-D defined s.vsh",
                      "error: -D 'defined': 'defined' is the preprocessor's operator and cannot "
                      "be a macro name (GLSL ES §3.4)\n"},
            // These too, with glslang's location "-1:1:" in the message.
            UsageCase{"-D 'A=1.0 \\' s.vsh",
                      "error: -D 'A': the value may not hold '\\', which GLSL ES has only to "
                      "continue a line (§3.1)\n"},
            UsageCase{long_token.c_str(),
                      "error: -D 'A': the value holds a token of more than the 1024 characters "
                      "of glslang's longest token\n"},
    });
}

// The longest-token check counted every run of non-blank characters, so a long expression of
// short tokens was refused as one token.
TEST_F(CliTest, ADefineOfManyShortTokensIsNotOneLongToken) {
    std::string sum = "1.0";
    for (int i = 0; i < 2000; ++i) {
        sum += "+1.0";
    }
    const CommandResult r = RunTidepool("validate -D 'A=" + sum + "' s.vsh", dir_.Path());
    EXPECT_EQ(r.exit_code, 0) << r.err;
}

// Each of these flags used to be dropped without a word in the other mode: `validate --config
// v.yaml s.vsh` validated s.vsh alone and exited 0, whatever v.yaml held.
TEST_F(CliTest, AFlagOfTheOtherModeIsAUsageErrorNotIgnored) {
    WriteConfig("");
    ExpectUsageErrors({
            UsageCase{"--config v.yaml s.vsh",
                      "error: --config and shader FILEs were both given; validate checks a "
                      "configuration or plain files, not both: drop one\n"},
            UsageCase{"--out o s.vsh s.fsh",
                      "error: --out applies to a configuration, not to the shader FILEs given; "
                      "drop --out, or drop the FILEs to validate the configuration\n"},
            UsageCase{"s.vsh --program p",
                      "error: --program applies to a configuration, not to the shader FILEs "
                      "given; drop --program, or drop the FILEs to validate the "
                      "configuration\n"},
            UsageCase{"--max-variants 8 s.vsh",
                      "error: --max-variants applies to a configuration, not to the shader "
                      "FILEs given; drop --max-variants, or drop the FILEs to validate the "
                      "configuration\n"},
            UsageCase{"--config v.yaml --stage frag",
                      "error: --stage applies to the shader FILEs given, and none was given; a "
                      "configuration's programs name their own vertex and fragment files\n"},
    });
    EXPECT_FALSE(std::filesystem::exists(dir_.Path() / "o"));
    // Each mode on its own still runs.
    EXPECT_EQ(RunTidepool("validate --config v.yaml --no-cache", dir_.Path()).exit_code, 0);
    EXPECT_EQ(RunTidepool("validate --stage vert s.vsh --no-cache", dir_.Path()).exit_code, 0);
}

// A plain-file validation that must fail with exit code 1 and exactly this stderr.
struct RejectedShaders {
    const char* why;
    std::vector<std::pair<std::string, std::string>> files;  // name, content
    const char* args;
    const char* err;
};

class RejectedShadersTest : public ::testing::TestWithParam<RejectedShaders> {};

TEST_P(RejectedShadersTest, ExitsOneWithTheExactDiagnostic) {
    const RejectedShaders& c = GetParam();
    TempDir dir;
    dir.Write("s.vsh", kVertex);
    for (const auto& [name, content] : c.files) {
        dir.Write(name, content);
    }
    const CommandResult r = RunTidepool(std::string("validate ") + c.args, dir.Path());
    EXPECT_EQ(r.exit_code, 1) << c.why;
    EXPECT_EQ(r.err, c.err) << c.why;
}

INSTANTIATE_TEST_SUITE_P(
        Table, RejectedShadersTest,
        ::testing::Values(
                RejectedShaders{"NUL byte",
                                {{"nul.vsh", std::string("#version 100\nattribute vec4 p;\nvoid "
                                                         "main() {\0 }\n",
                                                         48)}},
                                "nul.vsh",
                                "nul.vsh:3:14: error: NUL byte in the shader source; GLSL ES "
                                "source is text (GLSL ES §3.1) and glslang would stop reading "
                                "here\n"},
                RejectedShaders{"huge uniform array",
                                {{"big.fsh",
                                  "#version 100\nprecision mediump float;\nuniform "
                                  "float big[1000000000];\nvoid main() { "
                                  "gl_FragColor = vec4(big[0]); }\n"}},
                                "big.fsh",
                                "big.fsh:3:15: error: uniform 'big' needs 1000000000 uniform "
                                "vectors, more than the 16 a fragment shader has "
                                "(gl_MaxFragmentUniformVectors; GLSL ES 1.00 Appendix A §7, GLSL "
                                "ES 3.00 §4.3.5)\n"},
                RejectedShaders{"huge local array",
                                {{"local.fsh",
                                  "#version 100\nprecision mediump float;\nvoid "
                                  "main() {\n  float big[1000000000];\n  "
                                  "gl_FragColor = vec4(big[0]);\n}\n"}},
                                "local.fsh",
                                "local.fsh:4:9: error: 'big' holds 1000000000 array elements, "
                                "more than the 65536 one declaration may hold; no GPU gives a "
                                "shader invocation that much memory\n"},
                RejectedShaders{"stages of different versions",
                                {{"es3.fsh",
                                  "#version 300 es\nprecision mediump float;\nout "
                                  "vec4 c;\nvoid main() { c = vec4(1.0); }\n"}},
                                "s.vsh es3.fsh",
                                "es3.fsh: error: cannot link a '#version 300 es' fragment shader "
                                "with the '#version 100' vertex shader s.vsh; both stages of a "
                                "program must use the same GLSL ES version (GLSL ES 3.00 "
                                "§3.3)\n"},
                RejectedShaders{"varying the vertex stage never declares",
                                {{"uv.fsh",
                                  "#version 100\nprecision mediump float;\nvarying "
                                  "vec2 uv;\nvarying vec2 unused;\nvoid main() { "
                                  "gl_FragColor = vec4(uv, 0.0, 1.0); }\n"}},
                                "s.vsh uv.fsh",
                                "uv.fsh:5:35: error: 'uv' is read by the fragment shader but the "
                                "vertex shader s.vsh does not declare it; declare it there as a "
                                "varying (GLSL ES 1.00 §4.3.5, GLSL ES 3.00 §4.3.4)\n"}));

TEST_F(CliTest, ConfigPathThatIsAFolderSaysSo) {
    std::filesystem::create_directories(dir_.Path() / "folder.yaml");
    const CommandResult r = RunTidepool("validate --config folder.yaml", dir_.Path());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err,
              "folder.yaml: error: cannot read the configuration file: is a folder, not a "
              "file; check the path or pass --config PATH\n");
}

TEST_F(CliTest, ShaderPathThatIsAFolderOrAFifoSaysSoWithoutHanging) {
    std::filesystem::create_directories(dir_.Path() / "dir.vsh");
    ASSERT_EQ(::mkfifo((dir_.Path() / "pipe.fsh").c_str(), 0600), 0);
    const CommandResult folder = RunTidepool("validate dir.vsh", dir_.Path());
    EXPECT_EQ(folder.exit_code, 2);
    EXPECT_EQ(folder.err, "dir.vsh: error: cannot read the shader file: is a folder, not a file\n");
    const CommandResult fifo = RunTidepool("validate pipe.fsh", dir_.Path());
    EXPECT_EQ(fifo.exit_code, 2);
    EXPECT_EQ(fifo.err,
              "pipe.fsh: error: cannot read the shader file: is a FIFO (named pipe), "
              "not a regular file\n");
}

TEST_F(CliTest, OutWithATrailingSlashWritesTheFolderAndReplacesItsOwnOutput) {
    dir_.Write("v.yaml", "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n");
    for (int run = 0; run < 2; ++run) {
        const CommandResult r = RunTidepool("expand --config v.yaml --out out/", dir_.Path());
        EXPECT_EQ(r.exit_code, 0) << "run " << run << ": " << r.err;
        EXPECT_TRUE(std::filesystem::exists(dir_.Path() / "out" / "manifest.json"));
    }
    const CommandResult v = RunTidepool("validate --config v.yaml --out vout/", dir_.Path());
    EXPECT_EQ(v.exit_code, 0) << v.err;
    EXPECT_TRUE(std::filesystem::exists(dir_.Path() / "vout" / "manifest.json"));
}

}  // namespace
