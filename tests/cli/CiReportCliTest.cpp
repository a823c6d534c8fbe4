// What `validate` tells a CI system: per-variant step verdicts in --json (which of vertex,
// fragment and link failed) and a SARIF 2.1.0 log that code scanning can place on shader lines.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "FileContents.h"
#include "TempDir.h"
#include "TidepoolProcess.h"
#include <nlohmann/json.hpp>

namespace {

using tidepool::testing::CommandResult;
using tidepool::testing::ReadText;
using tidepool::testing::RunTidepool;
using tidepool::testing::TempDir;

// A: the vertex stage does not compile. B: the fragment stage does not. C: both compile, but the
// fragment stage reads a varying the vertex stage never writes, so the link fails.
constexpr const char* kCiVertex =
        "#version 100\nattribute vec4 p;\nvoid main() {\n#ifdef A\n  gl_Position = vertex_oops;\n"
        "#else\n  gl_Position = p;\n#endif\n}\n";
constexpr const char* kCiFragment =
        "#version 100\nprecision mediump float;\n#ifdef C\nvarying vec4 never_written;\n#endif\n"
        "void main() {\n#ifdef B\n  gl_FragColor = fragment_oops;\n#elif defined(C)\n"
        "  gl_FragColor = never_written;\n#else\n  gl_FragColor = vec4(1.0);\n#endif\n}\n";

class CiReportCliTest : public ::testing::Test {
protected:
    CiReportCliTest() {
        dir_.Write("s.vsh", kCiVertex);
        dir_.Write("s.fsh", kCiFragment);
        // One feature at a time: p: (valid), p:A, p:B, p:C.
        dir_.Write("v.yaml",
                   "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n"
                   "    features: [A, B, C]\n    rules:\n"
                   "      - { if: A, excludes: [B, C] }\n      - { if: B, excludes: C }\n");
    }
    // The manifest entry of variant `id` in validate's JSON.
    static nlohmann::json Variant(const nlohmann::json& manifest, const std::string& id) {
        for (const nlohmann::json& variant : manifest["variants"]) {
            if (variant["id"] == id) {
                return variant;
            }
        }
        ADD_FAILURE() << "no variant " << id;
        return {};
    }
    TempDir dir_;
};

struct StepCase {
    const char* variant;
    const char* vertex;
    const char* fragment;
    const char* link;
    std::vector<std::string> failed;
};

TEST_F(CiReportCliTest, JsonSaysPerVariantWhichStepFailed) {
    const CommandResult r = RunTidepool("validate --config v.yaml --json", dir_.Path());
    ASSERT_EQ(r.exit_code, 1) << r.err;
    const nlohmann::json manifest = nlohmann::json::parse(r.out);
    const StepCase cases[] = {
            {"p:", "valid", "valid", "valid", {}},
            {"p:A", "invalid", "valid", "not run", {"vertex"}},
            {"p:B", "valid", "invalid", "not run", {"fragment"}},
            {"p:C", "valid", "valid", "invalid", {"link"}},
    };
    for (const StepCase& c : cases) {
        SCOPED_TRACE(c.variant);
        const nlohmann::json variant = Variant(manifest, c.variant);
        EXPECT_EQ(variant["steps"]["vertex"], c.vertex);
        EXPECT_EQ(variant["steps"]["fragment"], c.fragment);
        EXPECT_EQ(variant["steps"]["link"], c.link);
        EXPECT_EQ(variant["failed_steps"].get<std::vector<std::string>>(), c.failed);
        EXPECT_EQ(variant["valid"].get<bool>(), c.failed.empty());
    }
}

TEST_F(CiReportCliTest, PlainFileJsonSaysWhichStepFailed) {
    dir_.Write("bad.vsh", "#version 100\nvoid main() { gl_Position = vertex_oops; }\n");
    dir_.Write("ok.vsh", "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n");
    struct PlainCase {
        const char* args;
        std::vector<std::string> failed;
        const char* link;
    };
    const PlainCase cases[] = {
            {"bad.vsh s.fsh", {"vertex"}, "not run"},
            {"ok.vsh s.fsh -D B", {"fragment"}, "not run"},
            {"ok.vsh s.fsh -D C", {"link"}, "invalid"},
    };
    for (const PlainCase& c : cases) {
        SCOPED_TRACE(c.args);
        const CommandResult r = RunTidepool(std::string("validate --json ") + c.args, dir_.Path());
        ASSERT_EQ(r.exit_code, 1) << r.err;
        const nlohmann::json json = nlohmann::json::parse(r.out);
        ASSERT_EQ(json.size(), 1u);
        EXPECT_EQ(json[0]["failed_steps"].get<std::vector<std::string>>(), c.failed);
        EXPECT_EQ(json[0]["steps"]["link"], c.link);
    }
}

// The properties SARIF 2.1.0's schema requires (and those code scanning needs to place an alert),
// checked field by field: version, $schema, runs[].tool.driver.name, results[] with ruleId,
// level, message.text and locations[].physicalLocation.artifactLocation.uri + region.startLine.
void ExpectSarifShape(const nlohmann::json& log) {
    ASSERT_TRUE(log.is_object());
    EXPECT_EQ(log["version"], "2.1.0");
    ASSERT_TRUE(log["$schema"].is_string());
    EXPECT_NE(log["$schema"].get<std::string>().find("sarif-2.1.0"), std::string::npos);
    ASSERT_TRUE(log["runs"].is_array());
    ASSERT_FALSE(log["runs"].empty());
    for (const nlohmann::json& run : log["runs"]) {
        ASSERT_TRUE(run["tool"]["driver"]["name"].is_string());
        ASSERT_TRUE(run["results"].is_array());
        const nlohmann::json& rules = run["tool"]["driver"]["rules"];
        for (const nlohmann::json& result : run["results"]) {
            ASSERT_TRUE(result["message"]["text"].is_string()) << result;
            ASSERT_TRUE(result["ruleId"].is_string()) << result;
            ASSERT_TRUE(result["ruleIndex"].is_number_integer()) << result;
            EXPECT_EQ(rules[result["ruleIndex"].get<std::size_t>()]["id"], result["ruleId"]);
            const std::string level = result["level"].get<std::string>();
            EXPECT_TRUE(level == "none" || level == "note" || level == "warning" ||
                        level == "error")
                    << level;
            ASSERT_TRUE(result["locations"].is_array()) << result;
            for (const nlohmann::json& location : result["locations"]) {
                const nlohmann::json& physical = location["physicalLocation"];
                ASSERT_TRUE(physical["artifactLocation"]["uri"].is_string()) << result;
                if (physical.contains("region")) {
                    ASSERT_TRUE(physical["region"]["startLine"].is_number_integer());
                    EXPECT_GE(physical["region"]["startLine"].get<int>(), 1);
                }
            }
        }
    }
}

TEST_F(CiReportCliTest, SarifHasTheRequiredFieldsAndOneResultPerStepAtTheShaderLine) {
    const CommandResult r = RunTidepool("validate --config v.yaml --format sarif", dir_.Path());
    ASSERT_EQ(r.exit_code, 1) << r.err;
    const nlohmann::json log = nlohmann::json::parse(r.out);
    ExpectSarifShape(log);
    // glslang follows each undeclared identifier with a failed assignment at the same line, so
    // the stages have two results each; the first is the one a reader needs.
    const nlohmann::json& results = log["runs"][0]["results"];
    ASSERT_EQ(results.size(), 5u) << results.dump(2);
    struct Expected {
        std::size_t index;
        const char* rule;
        const char* uri;
        int line;
        const char* text;
    };
    const Expected expected[] = {
            {0, "vertex", "s.vsh", 5, "'vertex_oops' : undeclared identifier [variant p:A]"},
            {2, "fragment", "s.fsh", 8, "'fragment_oops' : undeclared identifier [variant p:B]"},
            {4, "link", "s.fsh", 10, "'never_written' is read by the fragment shader"},
    };
    for (const Expected& e : expected) {
        SCOPED_TRACE(e.rule);
        const nlohmann::json& result = results[e.index];
        EXPECT_EQ(result["ruleId"], e.rule);
        EXPECT_EQ(result["level"], "error");
        const nlohmann::json& physical = result["locations"][0]["physicalLocation"];
        EXPECT_EQ(physical["artifactLocation"]["uri"], e.uri);
        EXPECT_EQ(physical["region"]["startLine"], e.line) << result.dump(2);
        EXPECT_NE(result["message"]["text"].get<std::string>().find(e.text), std::string::npos)
                << result["message"]["text"];
        EXPECT_EQ(result["properties"]["variants"].size(), 1u);
    }
}

TEST_F(CiReportCliTest, SarifOfPlainFilesAndIntoAFile) {
    const CommandResult r = RunTidepool(
            "validate s.vsh s.fsh -D B --format sarif --output-file out/log.sarif", dir_.Path());
    ASSERT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(r.out.find('{'), std::string::npos) << "the log goes to the file only: " << r.out;
    const nlohmann::json log = nlohmann::json::parse(ReadText(dir_.Path() / "out/log.sarif"));
    ExpectSarifShape(log);
    ASSERT_EQ(log["runs"][0]["results"].size(), 2u);  // the error and glslang's follow-on
    const nlohmann::json& result = log["runs"][0]["results"][0];
    EXPECT_EQ(result["ruleId"], "fragment");
    EXPECT_EQ(result["locations"][0]["physicalLocation"]["artifactLocation"]["uri"], "s.fsh");
    EXPECT_EQ(result["locations"][0]["physicalLocation"]["region"]["startLine"], 8);
}

TEST_F(CiReportCliTest, SarifOfAValidMatrixHasNoResults) {
    const CommandResult r = RunTidepool("validate --format sarif", TIDEPOOL_SOURCE_ROOT);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json log = nlohmann::json::parse(r.out);
    ExpectSarifShape(log);
    EXPECT_TRUE(log["runs"][0]["results"].empty());
}

TEST_F(CiReportCliTest, FormatAndOutputFileMisuseIsAUsageError) {
    EXPECT_EQ(RunTidepool("validate --json --format sarif", dir_.Path()).exit_code, 2);
    EXPECT_EQ(RunTidepool("validate --format xml", dir_.Path()).exit_code, 2);
    const CommandResult text =
            RunTidepool("validate --config v.yaml --output-file log.txt", dir_.Path());
    EXPECT_EQ(text.exit_code, 2);
    EXPECT_NE(text.err.find("error: --output-file takes the json or sarif report"),
              std::string::npos)
            << text.err;
}

}  // namespace
