// The `tidepool` command as a user runs it: exit codes, messages and outputs.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TempDir.h"

namespace {

using tidepool::testing::TempDir;

struct CommandResult {
    int exit_code = -1;
    std::string out;  // stdout and stderr together
};

// Runs the tidepool binary with `args` (a shell fragment) in `cwd`.
CommandResult RunTidepool(const std::string& args, const std::filesystem::path& cwd = TIDEPOOL_SOURCE_ROOT) {
    const std::string command =
            "cd '" + cwd.string() + "' && '" + std::string(TIDEPOOL_BINARY) + "' " + args + " 2>&1";
    CommandResult result;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return result;
    }
    std::array<char, 4096> buffer{};
    std::size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
        result.out.append(buffer.data(), n);
    }
    const int status = ::pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

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
    TempDir dir_;
};

TEST_F(CliTest, ValidateDefaultMatrixPrintsCountsAndExitsZero) {
    const CommandResult r = RunTidepool("validate");
    EXPECT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("variants ("), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("pruned combinations"), std::string::npos);
    EXPECT_NE(r.out.find("shared"), std::string::npos);
    EXPECT_NE(r.out.find("all valid"), std::string::npos);
}

TEST_F(CliTest, ShaderErrorExitsOneWithGccStyleDiagnosticAndVariant) {
    dir_.Write("v.yaml",
               "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n    features: [A, B]\n");
    const CommandResult r = RunTidepool("validate --config v.yaml", dir_.Path());
    EXPECT_EQ(r.exit_code, 1) << r.out;
    EXPECT_NE(r.out.find("s.fsh:5:23: error: 'oops' : undeclared identifier [p:B]"),
              std::string::npos)
            << r.out;
    EXPECT_NE(r.out.find("s.fsh:5:23: error: 'oops' : undeclared identifier [p:A,B]"),
              std::string::npos);
    EXPECT_NE(r.out.find("2 INVALID"), std::string::npos);
}

TEST_F(CliTest, ConfigurationErrorExitsTwoAndNamesFileLineColumn) {
    dir_.Write("v.yaml", "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n    colour: 1\n");
    const CommandResult r = RunTidepool("validate --config v.yaml", dir_.Path());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.out.find("v.yaml:5:5: error: unknown key 'colour' in program 'p'"),
              std::string::npos)
            << r.out;
}

TEST_F(CliTest, MissingConfigurationExitsTwo) {
    const CommandResult r = RunTidepool("expand --config nowhere.yaml", dir_.Path());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.out.find("nowhere.yaml: error: cannot read the configuration file"),
              std::string::npos)
            << r.out;
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
        EXPECT_EQ(refused.out, c.expected);
    }
    EXPECT_EQ(RunTidepool("expand --config v.yaml --max-variants 8", dir_.Path()).exit_code, 0);
}

TEST_F(CliTest, MaxVariantsOutOfRangeIsAUsageErrorNamingTheFlagAndRange) {
    WriteConfig("");
    for (const char* value : {"-1", "-5", "0", "65537", "18446744073709551616",
                              "100000000000000000000000", "1e3", "4x"}) {
        const CommandResult r =
                RunTidepool(std::string("expand --config v.yaml --max-variants=") + value,
                            dir_.Path());
        EXPECT_EQ(r.exit_code, 2) << value << r.out;
        EXPECT_EQ(r.out, std::string("error: --max-variants must be a whole number from 1 to "
                                     "65536 (up to 16777216 with --allow-large-matrix), not '") +
                                 value + "'\n")
                << value;
    }
    // Empty is not "not given" (which would silently mean the file's limit).
    const CommandResult empty = RunTidepool("expand --config v.yaml --max-variants=", dir_.Path());
    EXPECT_EQ(empty.exit_code, 2);
    EXPECT_EQ(empty.out.rfind("--max-variants: 1 required TEXT missing", 0), 0U) << empty.out;
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
    EXPECT_EQ(r.out, "error: --max-variants must be a whole number from 1 to 16777216, not "
                     "'16777217'\n");
}

TEST_F(CliTest, FileLimitOutOfRangeOrAboveTheCeilingIsRefusedAtItsLine) {
    // 2147483647 loads nowhere; 100000 loads, but expansion needs --allow-large-matrix for it.
    for (const auto& [limit, expected] :
         {std::pair{"100000", "v.yaml:1:15: error: max_variants of 100000 is over the ceiling of "
                              "65536 valid variants; lower it, or pass --allow-large-matrix to "
                              "allow up to 16777216\n"},
          std::pair{"2147483647", "v.yaml:1:15: error: max_variants must be a whole number from "
                                  "1 to 16777216 (valid variants; above 65536 only with "
                                  "--allow-large-matrix), not '2147483647'\n"}}) {
        WriteConfig(std::string("max_variants: ") + limit + "\n");
        const CommandResult r = RunTidepool("validate --config v.yaml", dir_.Path());
        EXPECT_EQ(r.exit_code, 2) << limit;
        EXPECT_EQ(r.out, expected);
    }
    WriteConfig("max_variants: 100000\n");
    EXPECT_EQ(RunTidepool("expand --config v.yaml --allow-large-matrix", dir_.Path()).exit_code,
              0);
}

TEST_F(CliTest, ExpandCountsPrunedCombinationsPerRuleWithoutListingThem) {
    WriteConfig("", "    features: [A, C]\n    rules: [{ if: C, requires: A }]\n");
    const CommandResult r = RunTidepool("expand --config v.yaml", dir_.Path());
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.out, "p:\np:A\np:A,C\n1 pruned by p: C requires A  (v.yaml:6)\n"
                     "3 variants, 1 pruned combinations\n");
}

TEST_F(CliTest, ExpandPrunedListsPrunedCombinationsWithTheirRule) {
    WriteConfig("", "    features: [A, C]\n    rules: [{ if: C, requires: A }]\n");
    const CommandResult r = RunTidepool("expand --config v.yaml --pruned", dir_.Path());
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.out.find("pruned p:C  (C requires A, v.yaml:6)\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("3 variants, 1 pruned combinations"), std::string::npos);
}

TEST_F(CliTest, ExpandPrunedLimitListsThatManyAndSaysHowManyAreLeft) {
    WriteConfig("", "    features: [A, B, C]\n"
                    "    rules: [{ if: B, requires: A }, { if: C, requires: A }]\n");
    const CommandResult r =
            RunTidepool("expand --config v.yaml --pruned --pruned-limit 1 --json", dir_.Path());
    EXPECT_EQ(r.exit_code, 0) << r.out;
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
    ASSERT_EQ(r.exit_code, 0) << r.out;
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
    EXPECT_EQ(r.out, "error: --pruned-limit must be a whole number from 1 to 65536, not '-1'\n");
}

TEST_F(CliTest, ExpandOutWritesDriverReadySourcesAndManifest) {
    dir_.Write("v.yaml", "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n"
                         "    features: [A]\n");
    const CommandResult r = RunTidepool("expand --config v.yaml --out gen", dir_.Path());
    ASSERT_EQ(r.exit_code, 0) << r.out;
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
    EXPECT_NE(r.out.find("was not written by tidepool"), std::string::npos) << r.out;
}

TEST_F(CliTest, ValidatePlainFilesLinksVertexWithFragment) {
    const CommandResult ok = RunTidepool("validate s.vsh s.fsh", dir_.Path());
    EXPECT_EQ(ok.exit_code, 0) << ok.out;
    const CommandResult bad = RunTidepool("validate s.vsh s.fsh -D B", dir_.Path());
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.out.find("s.fsh:5:23: error: 'oops' : undeclared identifier"),
              std::string::npos)
            << bad.out;
}

TEST_F(CliTest, ValidatePlainFileWithUnknownExtensionAsksForStage) {
    dir_.Write("x.glsl", kVertex);
    const CommandResult r = RunTidepool("validate x.glsl", dir_.Path());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.out.find("x.glsl: error: cannot tell the stage from the extension"),
              std::string::npos);
    EXPECT_EQ(RunTidepool("validate x.glsl --stage vert", dir_.Path()).exit_code, 0);
}

TEST_F(CliTest, ValidateJsonIsAManifestWithVerdictsAndCosts) {
    const CommandResult r = RunTidepool("validate --json");
    ASSERT_EQ(r.exit_code, 0);
    const nlohmann::json manifest = nlohmann::json::parse(r.out);
    EXPECT_EQ(manifest["version"], 1);
    EXPECT_GT(manifest["counts"]["shared_stage_slots"].get<int>(), 0);
    const nlohmann::json& first = manifest["variants"][0];
    EXPECT_TRUE(first["valid"].get<bool>());
    EXPECT_TRUE(first["stages"]["fragment"].contains("cost"));
}

TEST_F(CliTest, StatsShowsShortestAndLongestPathOfTheUniformProgram) {
    const CommandResult r = RunTidepool("stats --json");
    ASSERT_EQ(r.exit_code, 0) << r.out;
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

}  // namespace
