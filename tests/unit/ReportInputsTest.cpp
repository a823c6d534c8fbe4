// The report's inputs read from a small hand-made run: presets resolved to configurations,
// corrupt, missing or foreign files rejected with the file named, old version keys still read.
#include "tidepool/report/ReportInputs.h"
#include "tidepool/report/WhitepaperTable.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "FakeReportRun.h"
#include "FileContents.h"
#include "TempDir.h"
#include <nlohmann/json.hpp>

namespace {

using namespace tidepool::report;
using namespace tidepool::testing;

TEST(ReportInputsTest, RowPresetsResolveToTheConfigurationsCarryingThem) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    ASSERT_TRUE(loaded.inputs) << loaded.error;
    for (const WhitepaperRow& row : WhitepaperRows()) {
        ASSERT_NE(loaded.inputs->FindByPreset(row.baseline_preset), nullptr) << row.number;
        ASSERT_NE(loaded.inputs->FindByPreset(row.candidate_preset), nullptr) << row.number;
    }
    EXPECT_EQ(loaded.inputs->FindByPreset("full_clip_discard")->id, "water:FULL@discard");
    EXPECT_EQ(loaded.inputs->FindByPreset("full_clip_discard")->clip, "discard");
    EXPECT_EQ(loaded.inputs->FindByPreset("full_reflection_128")->reflection_size, 128);
    EXPECT_EQ(loaded.inputs->FindByPreset("no_such_preset"), nullptr);
}

TEST(ReportInputsTest, CorruptManifestIsAnErrorNamingTheFile) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    dir.Write("manifest/manifest.json", "{\"schema\": \"tidepool.manifest\", \"vers");
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_FALSE(loaded.inputs);
    EXPECT_EQ(loaded.error.rfind(run.manifest.string() + ":1:", 0), 0u) << loaded.error;
    EXPECT_NE(loaded.error.find(": not valid JSON: "), std::string::npos) << loaded.error;
}

TEST(ReportInputsTest, MissingResultsFileIsAnErrorNamingTheFile) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    std::filesystem::remove(run.results);
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_FALSE(loaded.inputs);
    EXPECT_EQ(loaded.error, run.results.string() + ": no such file");
}

TEST(ReportInputsTest, ForeignSchemaIsAnErrorNamingTheFile) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    dir.Write("render/results.json", R"({"schema": "something.else", "schema_version": 1})");
    const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_FALSE(loaded.inputs);
    EXPECT_EQ(loaded.error, run.results.string() + ": schema is not 'tidepool.render-results'");
}

// A pair's time of 0 or null (NaN) is no measurement: the row would read "failed" in a report
// that exits 0 and looks whole.
TEST(ReportInputsTest, APairTimeThatIsZeroOrMissingIsAnErrorNamingIt) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    nlohmann::json results = nlohmann::json::parse(ReadText(run.results));
    const std::string id = results["configurations"][0]["id"];
    results["comparisons"] = nlohmann::json::array({{{"label", "row"},
                                                     {"baseline", id},
                                                     {"candidate", id},
                                                     {"baseline_ms", {2.0, 2.1}},
                                                     {"candidate_ms", {1.9, 2.0}}}});
    dir.Write("render/results.json", results.dump());
    EXPECT_TRUE(LoadReportInputs(run.manifest, run.results).inputs);
    for (const nlohmann::json& bad : {nlohmann::json(0.0), nlohmann::json(nullptr)}) {
        results["comparisons"][0]["candidate_ms"][1] = bad;
        dir.Write("render/results.json", results.dump());
        const ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
        EXPECT_FALSE(loaded.inputs);
        EXPECT_EQ(loaded.error, run.results.string() + ": 'comparisons[0].candidate_ms[1]' is " +
                                        (bad.is_null() ? "null" : "0") +
                                        ", which is not a pair's time (above 0 ms)");
    }
}

// Every stage file carries its version under "version"; results.json once said
// "schema_version", and old runs still report.
TEST(ReportInputsTest, ResultsWithTheOldVersionKeyStillLoadAndAWrongVersionIsNamed) {
    TempDir dir;
    const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
    nlohmann::json results = nlohmann::json::parse(ReadText(run.results));
    results.erase("version");
    results["schema_version"] = 1;
    dir.Write("render/results.json", results.dump());
    ReportInputsResult loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_TRUE(loaded.inputs) << loaded.error;
    results["schema_version"] = 2;
    dir.Write("render/results.json", results.dump());
    loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_FALSE(loaded.inputs);
    EXPECT_EQ(loaded.error, run.results.string() + ": schema_version must be 1");
    results.erase("schema_version");
    dir.Write("render/results.json", results.dump());
    loaded = LoadReportInputs(run.manifest, run.results);
    EXPECT_FALSE(loaded.inputs);
    EXPECT_EQ(loaded.error, run.results.string() + ": version must be 1");
}

}  // namespace

namespace {

// Rewrites one stage file of a fake run through `edit` and returns what loading then says.
template <typename Edit>
ReportInputsResult LoadEdited(const TempDir& dir, const std::filesystem::path& file, Edit edit) {
    nlohmann::json json = nlohmann::json::parse(ReadText(file));
    edit(json);
    dir.Write(std::filesystem::relative(file, dir.Path()).string(), json.dump());
    return LoadReportInputs(dir.Path() / "manifest/manifest.json",
                            dir.Path() / "render/results.json");
}

}  // namespace

// Corrupt in meaning, though well typed: each replaced a good report with an empty or wrong
// one and exit 0 before.
TEST(ReportInputsTest, InputsCorruptInMeaningAreErrorsNamingTheFileAndField) {
    struct Case {
        const char* what;
        bool manifest;  // edit the manifest, else results.json
        void (*edit)(nlohmann::json&);
        const char* message;
    };
    const std::vector<Case> cases = {
            {"empty configurations", false,
             [](nlohmann::json& j) { j["configurations"] = nlohmann::json::array(); },
             "'configurations' is empty"},
            {"duplicate configuration id", false,
             [](nlohmann::json& j) { j["configurations"][1]["id"] = j["configurations"][0]["id"]; },
             "appears more than once"},
            {"variant not an object", true, [](nlohmann::json& j) { j["variants"][0] = 7; },
             "'variants[0]' has the wrong type (expected object, found number)"},
            {"variant without id", true, [](nlohmann::json& j) { j["variants"][1].erase("id"); },
             "'variants[1].id' is not a non-empty string"},
            {"variant valid not boolean", true,
             [](nlohmann::json& j) { j["variants"][0]["valid"] = "yes"; },
             "'variants[0].valid' has the wrong type"},
            {"absolute image path", false,
             [](nlohmann::json& j) { j["configurations"][0]["views"][0]["image"] = "/etc/passwd"; },
             "'image' must be a path inside the results folder, not '/etc/passwd'"},
            {"image path with ..", false,
             [](nlohmann::json& j) {
                 j["configurations"][0]["views"][0]["image"] = "images/../../secret.png";
             },
             "'image' must be a path inside the results folder, not 'images/../../secret.png'"},
            // View names name the report's image files: a path would write outside its folder.
            {"view name a path", false,
             [](nlohmann::json& j) { j["configurations"][0]["views"][0]["view"] = "../../x"; },
             "view name '../../x' must be a plain name"},
            {"view twice in one configuration", false,
             [](nlohmann::json& j) {
                 j["configurations"][0]["views"].push_back(j["configurations"][0]["views"][0]);
             },
             "appears more than once"},
            {"timing view a path", false,
             [](nlohmann::json& j) { j["settings"]["timing_view"] = "../x"; },
             "settings.timing_view '../x' must be a plain name"},
            // Results of another configuration's run, or a comparison of nothing measured.
            {"variant the manifest does not list", false,
             [](nlohmann::json& j) { j["configurations"][0]["variant"] = "water:NOPE"; },
             "renders variant 'water:NOPE', which"},
            {"comparison of an unknown configuration", false,
             [](nlohmann::json& j) {
                 j["comparisons"] =
                         nlohmann::json::array({{{"label", "row"},
                                                 {"baseline", j["configurations"][0]["id"]},
                                                 {"candidate", "water:NOPE"},
                                                 {"baseline_ms", {2.0, 2.1}},
                                                 {"candidate_ms", {1.9, 2.0}}}});
             },
             "comparisons[0].candidate 'water:NOPE' is not the id of one of 'configurations'"},
            // Wrongly typed fields (issue 15 class 3): an error naming the field, not an abort.
            {"uniform_bools a string", false,
             [](nlohmann::json& j) { j["configurations"][0]["uniform_bools"] = "yes"; },
             "'configurations[0].uniform_bools' has the wrong type (expected bool, found string)"},
            {"driver.valid a number", false,
             [](nlohmann::json& j) { j["configurations"][0]["driver"]["valid"] = 1; },
             "'configurations[0].driver.valid' has the wrong type (expected bool, found number)"},
            {"passes.culling a string", false,
             [](nlohmann::json& j) { j["configurations"][0]["passes"]["culling"] = "no"; },
             "'configurations[0].passes.culling' has the wrong type (expected bool, found "
             "string)"},
    };
    for (const Case& c : cases) {
        TempDir dir;
        const FakeRun run = WriteFakeRun(dir, WhitepaperConfigurations());
        const ReportInputsResult loaded =
                LoadEdited(dir, c.manifest ? run.manifest : run.results, c.edit);
        EXPECT_FALSE(loaded.inputs) << c.what;
        const std::filesystem::path file = c.manifest ? run.manifest : run.results;
        EXPECT_EQ(loaded.error.rfind(file.string() + ": ", 0), 0u)
                << c.what << ": " << loaded.error;
        EXPECT_NE(loaded.error.find(c.message), std::string::npos)
                << c.what << ": " << loaded.error;
    }
}
