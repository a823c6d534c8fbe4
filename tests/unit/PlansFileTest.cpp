// plans.json's reader and writer: what the writer writes reads back as the same value, and a
// field of the wrong type, a missing required field or a foreign file is an error naming the file
// and the field.
#include "tidepool/stagefiles/PlansFile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "TempDir.h"

namespace tidepool::stagefiles {
namespace {

using nlohmann::json;
using tidepool::testing::TempDir;

PlanConfiguration Configuration(const std::string& id, std::vector<std::string> passes) {
    PlanConfiguration c;
    c.id = id;
    c.variant = id.substr(0, id.find('@'));
    c.pass_draw_calls.assign(passes.size(), 3);
    c.passes = std::move(passes);
    c.pass_options = {128, true};
    c.draw_calls = 9;
    c.image = "images/" + id + ".png";
    c.pixels_shaded_estimate = 5'000'000'000LL;  // beyond 32 bits
    return c;
}

// Two scenes: one planned with a valid and an invalid candidate, one whose plan failed.
PlansFile TwoScenes() {
    PlansFile file;
    file.size = {160, 120};
    file.timing = {3.0, 20, 400, 20, 0.5};
    PlannedScene pond;
    pond.scene = "murky_pond";
    pond.description = "murky";
    pond.target.min_psnr_db = 30.0;
    pond.target.frame_budget_ms = 16.5;
    pond.needed = {"fog: murky water"};
    pond.met = true;
    PlanChoice& choice = pond.choice.emplace();
    choice.chosen = Configuration("water:ENABLE_FOG@refl128", {"reflection", "main"});
    choice.full = Configuration("water:FULL", {"reflection", "refraction", "main"});
    choice.time_ms_chosen = 8.06;
    choice.time_ms_full = 15.0;
    choice.time_change_percent = -46.3;
    choice.time_change_interval = {-48.0, -44.5};
    choice.choice_reason = "fastest that meets the target";
    choice.error = {41.1, 0.998, 0.018};
    choice.dropped = {{"refraction", "fog hides the floor", 41.1, -37.0}};
    choice.kept = {{"fog", "breaks the target", 12.5, -2.0}};
    choice.passes_saved = 1;
    choice.draws_saved = 5;
    choice.pixels_saved = 19200;
    PlanCandidate measured;
    measured.configuration = choice.chosen;
    measured.proposed_because = "fog hides the floor";
    measured.valid = true;
    measured.measurement = {{41.1, 0.998, 0.018}, 8.06, -46.3, {-48.0, -44.5}, 40, true};
    PlanCandidate invalid;
    invalid.configuration = Configuration("water:ENABLE_WATER_COLOUR", {"main"});
    invalid.proposed_because = "no refraction";
    invalid.water_colour_alpha = 0.75;
    invalid.diagnostics = {"water.fsh:3:1: error: no"};
    choice.candidates = {measured, invalid};
    PlannedScene failed;
    failed.scene = "broken";
    failed.errors = {"scenes/broken.yaml:1:1: error: full is invalid"};
    file.plans = {pond, failed};
    return file;
}

TEST(PlansFileTest, WhatIsWrittenReadsBackAsTheSameValueAndText) {
    TempDir dir;
    const std::filesystem::path path = dir.Path() / "plans.json";
    const PlansFile file = TwoScenes();
    ASSERT_EQ(WritePlansFile(file, path), "");
    const ReadResult<PlansFile> read = ReadPlansFile(path);
    ASSERT_TRUE(read.value) << read.error;
    EXPECT_EQ(read.failure, ReadFailure::kNone);
    EXPECT_EQ(*read.value, file);
    EXPECT_EQ(JsonText(ToJson(*read.value), 2), JsonText(ToJson(file), 2));
}

TEST(PlansFileTest, TheWriterLaysTheFileOutAsDocsScenesMdSays) {
    const json j = ToJson(TwoScenes());
    EXPECT_EQ(j["schema"], "tidepool.plans");
    EXPECT_EQ(j["version"], 1);
    EXPECT_EQ(j["size"], json::parse("[160, 120]"));
    const json& candidates = j["plans"][0]["candidates"];
    // A candidate is flat: its measurement only when valid, its diagnostics only when not.
    EXPECT_EQ(candidates[0]["psnr_db"], 41.1);
    EXPECT_FALSE(candidates[0].contains("diagnostics"));
    EXPECT_FALSE(candidates[0].contains("water_colour_alpha"));
    EXPECT_FALSE(candidates[1].contains("psnr_db"));
    EXPECT_EQ(candidates[1]["water_colour_alpha"], 0.75);
    EXPECT_EQ(j["plans"][0]["target"], json::parse(R"({"min_psnr_db": 30.0,
        "frame_budget_ms": 16.5})"));
    // A failed plan has no choice at all.
    EXPECT_EQ(j["plans"][1], json::parse(R"({"scene": "broken", "description": "",
        "target": {}, "needed": [], "met": false,
        "errors": ["scenes/broken.yaml:1:1: error: full is invalid"]})"));
}

TEST(PlansFileTest, NullNumbersReadAsNaN) {
    json j = ToJson(TwoScenes());
    j["plans"][0]["error"]["psnr_db"] = nullptr;
    const ReadResult<PlansFile> read = PlansFileFromJson(j, "p.json");
    ASSERT_TRUE(read.value) << read.error;
    EXPECT_TRUE(std::isnan(read.value->plans[0].choice->error.psnr_db));
}

TEST(PlansFileTest, AWronglyTypedFieldNamesTheFileAndTheField) {
    struct Case {
        const char* pointer;
        json value;
        const char* message;
    };
    const std::vector<Case> cases = {
            {"/plans/0/candidates", "none",
             "'plans[0].candidates' has the wrong type (expected array, found string)"},
            {"/plans/0/full/passes/0", 3,
             "'plans[0].full.passes[0]' has the wrong type (expected string, found number)"},
            {"/plans/0/kept/0/reason", 1,
             "'plans[0].kept[0].reason' has the wrong type (expected string, found number)"},
            {"/plans/0/chosen", 5,
             "'plans[0].chosen' has the wrong type (expected object, found number)"},
            {"/plans/0/candidates/0/psnr_db", "high",
             "'plans[0].candidates[0].psnr_db' has the wrong type (expected number, found "
             "string)"},
            {"/plans/0/candidates/1/water_colour_alpha", false,
             "'plans[0].candidates[1].water_colour_alpha' has the wrong type (expected number, "
             "found bool)"},
            {"/plans/0/time_change_interval", json::parse("[1]"),
             "'plans[0].time_change_interval' has the wrong type (expected 2 items, found "
             "array)"},
            {"/plans/1/met", "yes",
             "'plans[1].met' has the wrong type (expected bool, found "
             "string)"},
            {"/timing/min_pairs", json::parse("[20]"),
             "'timing.min_pairs' has the wrong type (expected number, found array)"},
            {"/plans", json::object(), "'plans' has the wrong type (expected array, found object)"},
    };
    for (const Case& c : cases) {
        json j = ToJson(TwoScenes());
        j[json::json_pointer(c.pointer)] = c.value;
        const ReadResult<PlansFile> read = PlansFileFromJson(j, "run/plans.json");
        EXPECT_FALSE(read.value) << c.pointer;
        EXPECT_EQ(read.failure, ReadFailure::kWrongType) << c.pointer;
        EXPECT_EQ(read.error, std::string("run/plans.json: ") + c.message);
    }
}

TEST(PlansFileTest, AMissingPlanListOrSceneNameIsNamed) {
    json j = ToJson(TwoScenes());
    j.erase("plans");
    ReadResult<PlansFile> read = PlansFileFromJson(j, "p.json");
    EXPECT_EQ(read.failure, ReadFailure::kMissingField);
    EXPECT_EQ(read.error, "p.json: 'plans' is missing");
    j = ToJson(TwoScenes());
    j["plans"][1].erase("scene");
    read = PlansFileFromJson(j, "p.json");
    EXPECT_EQ(read.failure, ReadFailure::kMissingField);
    EXPECT_EQ(read.error, "p.json: 'plans[1].scene' is missing");
}

TEST(PlansFileTest, AnotherSchemaOrVersionIsForeignAndAMissingFileUnreadable) {
    json j = ToJson(TwoScenes());
    j["schema"] = "tidepool.stability";
    ReadResult<PlansFile> read = PlansFileFromJson(j, "p.json");
    EXPECT_EQ(read.failure, ReadFailure::kForeign);
    EXPECT_EQ(read.error, "p.json: schema is not 'tidepool.plans'");
    j = ToJson(TwoScenes());
    j["version"] = 2;
    read = PlansFileFromJson(j, "p.json");
    EXPECT_EQ(read.failure, ReadFailure::kForeign);
    EXPECT_EQ(read.error, "p.json: version must be 1");
    TempDir dir;
    read = ReadPlansFile(dir.Path() / "none.json");
    EXPECT_EQ(read.failure, ReadFailure::kUnreadable);
    EXPECT_EQ(read.error, (dir.Path() / "none.json").string() + ": no such file");
    read = ReadPlansFile(dir.Write("cut.json", "{\"schema\": \"tidepool.pla"));
    EXPECT_EQ(read.failure, ReadFailure::kUnreadable);
    EXPECT_EQ(read.error.rfind((dir.Path() / "cut.json").string() + ":1:25: not valid JSON: ", 0),
              0U)
            << read.error;
}

}  // namespace
}  // namespace tidepool::stagefiles
