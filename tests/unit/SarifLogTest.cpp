// The SARIF log of a validation report, built from hand-made reports: no glslang needed.
#include "tidepool/SarifLog.h"

#include <gtest/gtest.h>

#include <string>

namespace {

using tidepool::ArtifactUri;
using tidepool::BuildSarifLog;
using tidepool::Diagnostic;
using tidepool::Severity;
using tidepool::StepStatus;
using tidepool::ValidationReport;
using tidepool::VariantVerdict;

Diagnostic Error(const std::string& file, int line, int column, const std::string& message,
                 const std::string& variant) {
    return Diagnostic{Severity::kError, file, line, column, message, variant};
}

// A verdict whose fragment stage failed with `diagnostic`.
VariantVerdict FragmentFailure(const std::string& id, const Diagnostic& diagnostic) {
    VariantVerdict verdict;
    verdict.vertex.status = StepStatus::kValid;
    verdict.fragment = {StepStatus::kInvalid, {diagnostic}};
    verdict.diagnostics = {diagnostic};
    verdict.variant.program = id;
    return verdict;
}

const nlohmann::json& Results(const nlohmann::json& log) {
    return log["runs"][0]["results"];
}

TEST(SarifLogTest, ArtifactUriPercentEncodesBytesAndMarksAbsolutePaths) {
    struct Case {
        const char* path;
        const char* uri;
    };
    const Case cases[] = {
            {"shaders/water.fsh", "shaders/water.fsh"},
            {"my shaders/a#b.fsh", "my%20shaders/a%23b.fsh"},
            {"./a/../b.fsh", "b.fsh"},
            {"/abs/x.fsh", "file:///abs/x.fsh"},
            {"caf\xe9.fsh", "caf%E9.fsh"},  // Latin-1, not UTF-8: still a valid URI
    };
    for (const Case& c : cases) {
        EXPECT_EQ(ArtifactUri(c.path), c.uri) << c.path;
    }
}

TEST(SarifLogTest, AMessageSharedByVariantsIsOneResultNamingThemAll) {
    ValidationReport report;
    const Diagnostic a = Error("s.fsh", 8, 3, "'x' : undeclared identifier", "p:A");
    Diagnostic b = a;
    b.variant = "p:A,B";
    report.verdicts = {FragmentFailure("p:A", a), FragmentFailure("p:A,B", b),
                       FragmentFailure("p:A", a)};  // p:A again, as for a second target
    const nlohmann::json log = BuildSarifLog(report, "shaders", "1.2.3");
    EXPECT_EQ(log["version"], "2.1.0");
    EXPECT_EQ(log["runs"][0]["tool"]["driver"]["version"], "1.2.3");
    ASSERT_EQ(Results(log).size(), 1u);
    const nlohmann::json& result = Results(log)[0];
    EXPECT_EQ(result["ruleId"], "fragment");
    EXPECT_EQ(result["level"], "error");
    EXPECT_EQ(result["message"]["text"], "'x' : undeclared identifier [2 variants, e.g. p:A]");
    EXPECT_EQ(result["properties"]["variants"], nlohmann::json({"p:A", "p:A,B"}));
    const nlohmann::json& physical = result["locations"][0]["physicalLocation"];
    EXPECT_EQ(physical["artifactLocation"]["uri"], "shaders/s.fsh");
    EXPECT_EQ(physical["region"]["startLine"], 8);
    EXPECT_EQ(physical["region"]["startColumn"], 3);
}

TEST(SarifLogTest, UnknownLineHasNoRegionAndAFileProblemIsAnInputResult) {
    ValidationReport report;
    report.diagnostics = {Error("gone.fsh", 0, 0, "cannot read shader file", "")};
    VariantVerdict verdict;
    verdict.vertex.status = StepStatus::kValid;
    verdict.fragment.status = StepStatus::kValid;
    verdict.link = {StepStatus::kInvalid, {Error("s.fsh", 0, 0, "link failed", "p")}};
    report.verdicts = {verdict};
    const nlohmann::json log = BuildSarifLog(report, "", "0");
    ASSERT_EQ(Results(log).size(), 2u);
    EXPECT_EQ(Results(log)[0]["ruleId"], "input");
    EXPECT_EQ(Results(log)[0]["message"]["text"], "cannot read shader file");
    EXPECT_FALSE(Results(log)[0].contains("properties"));
    EXPECT_EQ(Results(log)[1]["ruleId"], "link");
    EXPECT_EQ(Results(log)[1]["message"]["text"], "link failed [variant p]");
    for (const nlohmann::json& result : Results(log)) {
        EXPECT_FALSE(result["locations"][0]["physicalLocation"].contains("region"));
        const nlohmann::json& rules = log["runs"][0]["tool"]["driver"]["rules"];
        EXPECT_EQ(rules[result["ruleIndex"].get<std::size_t>()]["id"], result["ruleId"]);
    }
}

TEST(SarifLogTest, WarningsAndNotesKeepTheirLevel) {
    ValidationReport report;
    Diagnostic warning = Error("s.vsh", 2, 0, "w", "p");
    warning.severity = Severity::kWarning;
    Diagnostic note = Error("s.vsh", 3, 0, "n", "p");
    note.severity = Severity::kNote;
    VariantVerdict verdict;
    verdict.vertex = {StepStatus::kValid, {warning, note}};
    report.verdicts = {verdict};
    const nlohmann::json log = BuildSarifLog(report, "", "0");
    ASSERT_EQ(Results(log).size(), 2u);
    EXPECT_EQ(Results(log)[0]["level"], "warning");
    EXPECT_EQ(Results(log)[1]["level"], "note");
    EXPECT_EQ(Results(log)[0]["ruleId"], "vertex");
}

}  // namespace
