// results.json's reader and writer: what the writer writes reads back as the same value and
// text, a field of the wrong type anywhere is an error naming the file and the field, fields
// older runners did not write are optional, and a file that carries its version under the old
// key `schema_version` still reads.
#include "tidepool/stagefiles/ResultsFile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "TempDir.h"

namespace tidepool::stagefiles {
namespace {

using nlohmann::json;
using tidepool::testing::TempDir;

ResultsStatistics Statistics(double median) {
    return {3,          median - 1,   median + 1,   median,
            median,     median - 0.5, median + 0.5, 1,
            median - 1, median + 1,   0.75,         "order statistics"};
}

// A run of two configurations and one comparison, every field set.
ResultsFile OneOfEachResult() {
    ResultsFile file;
    file.started_utc = "2026-11-26T02:00:00Z";
    file.wall_seconds = 12.5;
    file.environment = {"egl", "OpenGL ES", "llvmpipe", "3.2 Mesa 22.3.6", "3.20",   "22.3.6", true,
                        false, "cpu",       "0",        "Release",         "abc123", "render"};
    file.settings.config = "variants.yaml";
    file.settings.width = 160;
    file.settings.height = 120;
    file.settings.views = {{"three_quarter", {1, 2, 3}, {0, 0, -1}, 0.8, 0.5, 500}};
    file.settings.timing_view = "three_quarter";
    file.settings.bump_scale = {{{0.25, 0.25}, {0.5, 0.5}}};
    file.settings.water_colour = {0.05, 0.15, 0.1, 0.4};
    file.settings.fourier = {8, 13, 100, 400, 4, 100};
    for (const char* id : {"water:A", "water:B"}) {
        ResultsConfiguration& c = file.configurations.emplace_back();
        c.id = id;
        c.variant = id;
        c.program = "water";
        c.defines = {"A"};
        c.presets = {"full"};
        c.passes.refraction_size = 128;
        c.driver = {true, true, true, true, "", "", "", {{"warning", "w.fsh", 1, 2, "m", id, "t"}}};
        c.glslang_valid = true;
        c.views = {{"three_quarter",
                    "images/a.png",
                    3,
                    {"reflection", "main"},
                    9,
                    false,
                    "",
                    ResultsAccuracy{40.5, 0.99, 0.01}}};
        c.samples_ms = {{4.5}, {4.25}};
        c.statistics = Statistics(4.5);
        c.cpu_samples_ms = {{4.0}, {4.125}};
        c.cpu_statistics = Statistics(4.0);
        c.pass_ms = {{"main", 1.5}, {"reflection", 2.0}};
        c.instrumented_frame_ms = 4.75;
        c.ok = true;
    }
    file.configurations[1].glslang_valid.reset();
    file.timing = {.clock = "thread_cpu",
                   .clock_reason = "software",
                   .resolution_points = 1.5,
                   .min_pairs = 20,
                   .max_pairs = 400,
                   .batch_pairs = 10,
                   .contended_share = 0.5,
                   .confidence = 0.95,
                   .estimator = "Hodges-Lehmann",
                   .boundary_pairs = 80,
                   .boundary_standard_errors = 1.5};
    file.comparisons = {{"row 1",
                         "water:A",
                         "water:B",
                         "",
                         2,
                         "resolved",
                         1.1,
                         1.0,
                         1.2,
                         -9.1,
                         -16.7,
                         0,
                         {4.5, 4.25},
                         {5.0, 4.75},
                         {4.5, 4.5},
                         {5.0, 5.0},
                         {4.75, 4.5},
                         {5.25, 5.0},
                         -17.5,
                         0.5,
                         {{"main", 2.5}},
                         {{"main", 2.75}, {"low_res_water", 1.0}},
                         4.5,
                         5.0,
                         "second_process"}};
    file.disagreements = {{"water:B", true, false}};
    file.diagnostics = {{"error", "", 0, 0, "oops", "", "error: oops"}};
    file.ok = true;
    return file;
}

TEST(ResultsFileTest, WhatIsWrittenReadsBackAsTheSameValueAndText) {
    TempDir dir;
    const ResultsFile file = OneOfEachResult();
    const std::filesystem::path path = dir.Write("results.json", ResultsFileText(file));
    const ReadResult<ResultsFile> read = ReadResultsFile(path);
    ASSERT_TRUE(read.value) << read.error;
    EXPECT_EQ(read.failure, ReadFailure::kNone);
    EXPECT_EQ(*read.value, file);
    EXPECT_EQ(ResultsFileText(*read.value), ResultsFileText(file));
}

// A verdict not compared is null; an estimate that does not exist is NaN, written as null.
TEST(ResultsFileTest, NullVerdictIsAbsentAndNullNumbersReadAsNaN) {
    json document = ToJson(OneOfEachResult());
    EXPECT_TRUE(document["configurations"][1]["glslang_valid"].is_null());
    document["comparisons"][0]["ratio"] = nullptr;
    document["configurations"][0]["views"][0]["accuracy"]["psnr_db"] = nullptr;
    const ReadResult<ResultsFile> read = ResultsFileFromJson(document, "r.json");
    ASSERT_TRUE(read.value) << read.error;
    EXPECT_FALSE(read.value->configurations[1].glslang_valid);
    EXPECT_TRUE(std::isnan(read.value->comparisons[0].ratio));
    EXPECT_TRUE(std::isnan(read.value->configurations[0].views[0].accuracy->psnr_db));
}

// Results written before the runner recorded CPU time, statistics, per-view draw calls, the
// refraction's own size, the resolution asked or the stopping rule's boundary clauses: those
// fields are absent and read as absent.
TEST(ResultsFileTest, FieldsOlderRunnersDidNotWriteAreOptional) {
    json document = ToJson(OneOfEachResult());
    json& c = document["configurations"][0];
    for (const char* key : {"cpu_samples_ms", "cpu_statistics", "statistics", "variant"}) {
        c.erase(key);
    }
    c["passes"].erase("refraction_size");
    c["views"][0].erase("draw_calls");
    c["views"][0].erase("accuracy");
    for (const char* key : {"resolution_points", "boundary_pairs", "boundary_standard_errors"}) {
        document["timing"].erase(key);
    }
    const ReadResult<ResultsFile> read = ResultsFileFromJson(document, "r.json");
    ASSERT_TRUE(read.value) << read.error;
    EXPECT_FALSE(read.value->timing.resolution_points);
    EXPECT_FALSE(read.value->timing.boundary_pairs);
    EXPECT_FALSE(read.value->timing.boundary_standard_errors);
    const ResultsConfiguration& r = read.value->configurations[0];
    EXPECT_TRUE(r.cpu_samples_ms.empty());
    EXPECT_FALSE(r.cpu_statistics);
    EXPECT_FALSE(r.statistics);
    EXPECT_FALSE(r.variant);
    EXPECT_FALSE(r.passes.refraction_size);
    EXPECT_FALSE(r.views[0].draw_calls);
    EXPECT_FALSE(r.views[0].accuracy);
}

// One wrongly typed field per part of the file, deep and shallow, as the writer lays it out.
TEST(ResultsFileTest, AWronglyTypedFieldNamesTheFileAndTheField) {
    struct Case {
        const char* pointer;
        json value;
        const char* message;
    };
    const std::vector<Case> cases = {
            {"/timing/resolution_points", "1.5",
             "'timing.resolution_points' has the wrong type (expected number, found string)"},
            {"/comparisons/0/baseline_ms/1", "x",
             "'comparisons[0].baseline_ms[1]' has the wrong type (expected number, found "
             "string)"},
            {"/configurations/0/pass_ms/main", false,
             "'configurations[0].pass_ms.main' has the wrong type (expected number, found bool)"},
            {"/configurations/0/statistics/median_ms", "5",
             "'configurations[0].statistics.median_ms' has the wrong type (expected number, "
             "found string)"},
            {"/diagnostics/0/line", "7",
             "'diagnostics[0].line' has the wrong type (expected number, found string)"},
            {"/environment", json::array({1}),
             "'environment' has the wrong type (expected object, found array)"},
            {"/configurations/0/uniform_bools", "yes",
             "'configurations[0].uniform_bools' has the wrong type (expected bool, found "
             "string)"},
            {"/configurations/0/driver/valid", 1,
             "'configurations[0].driver.valid' has the wrong type (expected bool, found number)"},
            {"/configurations/0/passes/culling", "no",
             "'configurations[0].passes.culling' has the wrong type (expected bool, found "
             "string)"},
            {"/configurations/1/glslang_valid", 0,
             "'configurations[1].glslang_valid' has the wrong type (expected bool, found "
             "number)"},
            {"/configurations/0/samples_ms/0", 4.5,
             "'configurations[0].samples_ms[0]' has the wrong type (expected array, found "
             "number)"},
            {"/configurations/0/views/0/image", 3,
             "'configurations[0].views[0].image' has the wrong type (expected string, found "
             "number)"},
            {"/settings/views/0/eye", json::array({1, 2}),
             "'settings.views[0].eye' has the wrong type (expected 3 items, found array)"},
            {"/settings/width", "160",
             "'settings.width' has the wrong type (expected number, found string)"},
            {"/disagreements/0/mesa_valid", "no",
             "'disagreements[0].mesa_valid' has the wrong type (expected bool, found string)"},
            {"/ok", 1, "'ok' has the wrong type (expected bool, found number)"},
    };
    for (const Case& c : cases) {
        json document = ToJson(OneOfEachResult());
        document[json::json_pointer(c.pointer)] = c.value;
        const ReadResult<ResultsFile> read = ResultsFileFromJson(document, "run/results.json");
        EXPECT_FALSE(read.value) << c.pointer;
        EXPECT_EQ(read.failure, ReadFailure::kWrongType) << c.pointer;
        EXPECT_EQ(read.error, std::string("run/results.json: ") + c.message) << c.pointer;
    }
}

TEST(ResultsFileTest, MissingRequiredFieldsAreNamed) {
    struct Case {
        void (*edit)(json&);
        const char* message;
    };
    const std::vector<Case> cases = {
            {[](json& j) { j.erase("configurations"); }, "r.json: 'configurations' is missing"},
            {[](json& j) { j["configurations"][1].erase("id"); },
             "r.json: 'configurations[1].id' is missing"},
            {[](json& j) { j["configurations"][0].erase("ok"); },
             "r.json: 'configurations[0].ok' is missing"},
            {[](json& j) { j["comparisons"][0].erase("candidate_ms"); },
             "r.json: 'comparisons[0].candidate_ms' is missing"},
            {[](json& j) { j["comparisons"][0].erase("label"); },
             "r.json: 'comparisons[0].label' is missing"},
    };
    for (const Case& c : cases) {
        json document = ToJson(OneOfEachResult());
        c.edit(document);
        const ReadResult<ResultsFile> read = ResultsFileFromJson(document, "r.json");
        EXPECT_FALSE(read.value) << c.message;
        EXPECT_EQ(read.failure, ReadFailure::kMissingField) << c.message;
        EXPECT_EQ(read.error, c.message);
    }
}

// Every stage file carries its version under "version"; results.json once said
// "schema_version", and such files still read. A file with both is judged by "version".
TEST(ResultsFileTest, TheOldVersionKeyStillReadsAndAWrongVersionIsNamed) {
    json document = ToJson(OneOfEachResult());
    document.erase("version");
    document["schema_version"] = 1;
    ReadResult<ResultsFile> read = ResultsFileFromJson(document, "r.json");
    ASSERT_TRUE(read.value) << read.error;
    EXPECT_EQ(*read.value, OneOfEachResult());
    document["schema_version"] = 2;
    read = ResultsFileFromJson(document, "r.json");
    EXPECT_EQ(read.failure, ReadFailure::kForeign);
    EXPECT_EQ(read.error, "r.json: schema_version must be 1");
    document["version"] = 1;
    read = ResultsFileFromJson(document, "r.json");
    EXPECT_TRUE(read.value) << read.error;
    document.erase("version");
    document.erase("schema_version");
    read = ResultsFileFromJson(document, "r.json");
    EXPECT_EQ(read.error, "r.json: version must be 1");
    // The writer writes only the one key.
    EXPECT_FALSE(ToJson(OneOfEachResult()).contains("schema_version"));
}

TEST(ResultsFileTest, AnotherSchemaIsForeignAndAMissingFileUnreadable) {
    json document = ToJson(OneOfEachResult());
    document["schema"] = "tidepool.manifest";
    ReadResult<ResultsFile> read = ResultsFileFromJson(document, "r.json");
    EXPECT_EQ(read.failure, ReadFailure::kForeign);
    EXPECT_EQ(read.error, "r.json: schema is not 'tidepool.render-results'");
    TempDir dir;
    read = ReadResultsFile(dir.Path() / "none.json");
    EXPECT_EQ(read.failure, ReadFailure::kUnreadable);
    EXPECT_EQ(read.error, (dir.Path() / "none.json").string() + ": no such file");
}

}  // namespace
}  // namespace tidepool::stagefiles
