// The stage files' shapes: a wrongly typed field anywhere in the manifest or results file is
// named with its path (plans.json and stability.json: their readers' tests); nulls stand for NaN
// numbers; unknown and absent fields pass.
#include "tidepool/report/StageFileShapes.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tidepool::report {
namespace {

using nlohmann::json;

TEST(JsonShapeTest, LeavesArraysObjectsAndMapsAreCheckedWithTheirPath) {
    const json shape = json::parse(R"({"n": "number", "s": "string", "b": "bool",
        "list": [{"x": "number"}], "any_list": [], "map": {"*": "number"}, "free": "any"})");
    EXPECT_EQ(CheckJsonShape(json::parse(R"({"n": 1.5, "s": "a", "b": true, "list": [{"x": 1}],
        "any_list": [1, "a"], "map": {"p": 1, "q": 2}, "free": [1]})"),
                             shape),
              "");
    EXPECT_EQ(CheckJsonShape(json::parse(R"({"n": "1"})"), shape),
              "'n' has the wrong type (expected number, found string)");
    EXPECT_EQ(CheckJsonShape(json::parse(R"({"b": 1})"), shape),
              "'b' has the wrong type (expected bool, found number)");
    EXPECT_EQ(CheckJsonShape(json::parse(R"({"list": [{"x": 1}, {"x": true}]})"), shape),
              "'list[1].x' has the wrong type (expected number, found bool)");
    EXPECT_EQ(CheckJsonShape(json::parse(R"({"list": {"x": 1}})"), shape),
              "'list' has the wrong type (expected array, found object)");
    EXPECT_EQ(CheckJsonShape(json::parse(R"({"map": {"p": 1, "q": "2"}})"), shape),
              "'map.q' has the wrong type (expected number, found string)");
    EXPECT_EQ(CheckJsonShape(json::parse("[1]"), shape),
              "'(the document)' has the wrong type (expected object, found array)");
}

TEST(JsonShapeTest, NullIsANumberUnknownAndAbsentFieldsPass) {
    const json shape = json::parse(R"({"n": "number", "s": "string"})");
    EXPECT_EQ(CheckJsonShape(json::parse(R"({"n": null})"), shape), "");  // NaN is written so
    EXPECT_EQ(CheckJsonShape(json::parse(R"({"newer": [1, 2]})"), shape), "");
    EXPECT_EQ(CheckJsonShape(json::object(), shape), "");
    EXPECT_EQ(CheckJsonShape(json::parse(R"({"s": null})"), shape),
              "'s' has the wrong type (expected string, found null)");
    // A verdict not taken is written as null: "bool?".
    const json optional = json::parse(R"({"b": "bool?"})");
    EXPECT_EQ(CheckJsonShape(json::parse(R"({"b": null})"), optional), "");
    EXPECT_EQ(CheckJsonShape(json::parse(R"({"b": false})"), optional), "");
    EXPECT_EQ(CheckJsonShape(json::parse(R"({"b": 0})"), optional),
              "'b' has the wrong type (expected bool?, found number)");
    EXPECT_EQ(CheckStageFileShape(StageFile::kResults,
                                  json::parse(R"({"configurations": [{"glslang_valid": null}]})")),
              "");
}

// One wrongly typed field per stage file, deep and shallow, as the writers lay the files out.
TEST(StageFileShapeTest, AWronglyTypedFieldInEveryStageFileIsNamed) {
    struct Case {
        StageFile file;
        const char* document;
        const char* message;
    };
    const std::vector<Case> cases = {
            {StageFile::kManifest, R"({"counts": {"variants": "163"}})",
             "'counts.variants' has the wrong type (expected number, found string)"},
            {StageFile::kManifest,
             R"({"variants": [{"id": "water:", "stages": {"vertex": {"cost": {"builtin_calls":
                 {"dot": "2"}}}}}]})",
             "'variants[0].stages.vertex.cost.builtin_calls.dot' has the wrong type (expected "
             "number, found string)"},
            {StageFile::kManifest, R"({"pruned_by_rule": [{"count": [1]}]})",
             "'pruned_by_rule[0].count' has the wrong type (expected number, found array)"},
            {StageFile::kResults, R"({"timing": {"resolution_points": "1.5"}})",
             "'timing.resolution_points' has the wrong type (expected number, found string)"},
            {StageFile::kResults, R"({"comparisons": [{"baseline_ms": [1, 2, "x"]}]})",
             "'comparisons[0].baseline_ms[2]' has the wrong type (expected number, found "
             "string)"},
            {StageFile::kResults, R"({"configurations": [{"pass_ms": {"main": false}}]})",
             "'configurations[0].pass_ms.main' has the wrong type (expected number, found bool)"},
            {StageFile::kResults, R"({"configurations": [{"statistics": {"median_ms": "5"}}]})",
             "'configurations[0].statistics.median_ms' has the wrong type (expected number, "
             "found string)"},
            {StageFile::kResults, R"({"diagnostics": [{"line": "7"}]})",
             "'diagnostics[0].line' has the wrong type (expected number, found string)"},
            {StageFile::kManifest, R"({"stage_programs": [{"cost": {"total_ops": false}}]})",
             "'stage_programs[0].cost.total_ops' has the wrong type (expected number, found "
             "bool)"},
            {StageFile::kManifest, R"({"presets": [{"passes": {"culling": "no"}}]})",
             "'presets[0].passes.culling' has the wrong type (expected bool, found string)"},
            {StageFile::kResults, R"({"environment": [1]})",
             "'environment' has the wrong type (expected object, found array)"},
    };
    for (const Case& c : cases) {
        EXPECT_EQ(CheckStageFileShape(c.file, json::parse(c.document)), c.message) << c.document;
    }
}

}  // namespace
}  // namespace tidepool::report
