// manifest.json's reader and writer: what the writer writes reads back as the same value and
// text, a field of the wrong type anywhere is an error naming the file and the field, the
// fields a validation adds are optional (`tidepool expand` writes none), and a foreign or
// incomplete file is named.
#include "tidepool/stagefiles/ManifestFile.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "TempDir.h"

namespace tidepool::stagefiles {
namespace {

using nlohmann::json;
using tidepool::testing::TempDir;

StageCostEntry Cost(int ops) {
    StageCostEntry cost;
    cost.arithmetic_ops = ops;
    cost.texture_samples = 1;
    cost.builtin_calls = {{"dot", 2}, {"texture2D", 1}};
    cost.total_ops = ops + 3;
    return cost;
}

// A validated manifest with one valid and one expanded-only variant.
ManifestFile OneOfEach() {
    ManifestFile file;
    file.config = "variants.yaml";
    file.targets = {"100"};
    file.programs = {{"water", "shaders/water.vsh", "shaders/water.fsh", {"ENABLE_FOG"}}};
    file.presets = {{"full", "everything", "water:ENABLE_FOG", {"fog"}, {}}};
    file.presets[0].passes.refraction_size = 128;
    ManifestVariant& validated = file.variants.emplace_back();
    validated.id = "water:ENABLE_FOG";
    validated.program = "water";
    validated.defines = {"ENABLE_FOG"};
    validated.target = "100";
    validated.valid = true;
    validated.stages = ManifestStages{{"abc", "shaders/water.vsh", Cost(4)},
                                      {"def", "shaders/water.fsh", std::nullopt}};
    validated.diagnostics = {
            {"warning", "shaders/water.fsh", 3, 7, "unused", "water:ENABLE_FOG", std::nullopt}};
    validated.steps = {{"vertex", "valid"}, {"fragment", "valid"}, {"link", "valid"}};
    validated.failed_steps = std::vector<std::string>{};
    validated.sources = ManifestSources{"100/water/a.vert", "100/water/a.frag"};
    ManifestVariant& expanded = file.variants.emplace_back();
    expanded.id = "water:";
    expanded.program = "water";
    file.pruned_by_rule = {{"water", "A requires B", "variants.yaml", 36, 4608}};
    file.stage_programs = {{"fragment",
                            "100",
                            "shaders/water.fsh",
                            "def",
                            {"ENABLE_FOG"},
                            {"water:ENABLE_FOG"},
                            true,
                            Cost(9)}};
    file.counts = {2, 4608, 2, 2, 0, 1, 0};
    return file;
}

TEST(ManifestFileTest, WhatIsWrittenReadsBackAsTheSameValueAndText) {
    TempDir dir;
    const ManifestFile file = OneOfEach();
    const std::filesystem::path path = dir.Write("manifest.json", ManifestFileText(file));
    const ReadResult<ManifestFile> read = ReadManifestFile(path);
    ASSERT_TRUE(read.value) << read.error;
    EXPECT_EQ(read.failure, ReadFailure::kNone);
    EXPECT_EQ(*read.value, file);
    EXPECT_EQ(ManifestFileText(*read.value), ManifestFileText(file));
}

// `tidepool expand` writes no verdicts, stage programs or validation counts: absent, not empty.
TEST(ManifestFileTest, FieldsOfAValidationAreLeftOutWhenAbsent) {
    ManifestFile file;
    ManifestVariant& variant = file.variants.emplace_back();
    variant.id = "water:";
    variant.program = "water";
    const json written = ToJson(file);
    EXPECT_EQ(written["variants"][0], json::parse(R"({"id": "water:", "program": "water",
        "defines": []})"));
    EXPECT_FALSE(written.contains("stage_programs"));
    EXPECT_FALSE(written.contains("pruned_by_rule"));
    EXPECT_EQ(written["counts"], json::parse(R"({"variants": 0, "pruned": 0})"));
    const ReadResult<ManifestFile> read = ManifestFileFromJson(written, "m.json");
    ASSERT_TRUE(read.value) << read.error;
    EXPECT_FALSE(read.value->variants[0].valid);
    EXPECT_FALSE(read.value->stage_programs);
    EXPECT_FALSE(read.value->counts.stage_slots);
}

// Manifests written before `pruned_by_rule` listed every pruned combination under `pruned`.
TEST(ManifestFileTest, TheOldListOfPrunedCombinationsIsRead) {
    json document = ToJson(OneOfEach());
    document.erase("pruned_by_rule");
    document["pruned"] = json::parse(R"([{"id": "water:A", "program": "water",
        "rule": "A requires B", "file": "variants.yaml", "line": 36}])");
    const ReadResult<ManifestFile> read = ManifestFileFromJson(document, "m.json");
    ASSERT_TRUE(read.value) << read.error;
    EXPECT_FALSE(read.value->pruned_by_rule);
    ASSERT_EQ(read.value->pruned.size(), 1U);
    EXPECT_EQ(read.value->pruned[0].line, 36);
}

// One wrongly typed field per part of the file, deep and shallow, as the writer lays it out.
TEST(ManifestFileTest, AWronglyTypedFieldNamesTheFileAndTheField) {
    struct Case {
        const char* pointer;
        json value;
        const char* message;
    };
    const std::vector<Case> cases = {
            {"/counts/variants", "163",
             "'counts.variants' has the wrong type (expected number, found string)"},
            {"/counts/links", true,
             "'counts.links' has the wrong type (expected number, found bool)"},
            {"/variants/0/stages/vertex/cost/builtin_calls/dot", "2",
             "'variants[0].stages.vertex.cost.builtin_calls.dot' has the wrong type (expected "
             "number, found string)"},
            {"/pruned_by_rule/0/count", json::array({1}),
             "'pruned_by_rule[0].count' has the wrong type (expected number, found array)"},
            {"/stage_programs/0/cost/total_ops", false,
             "'stage_programs[0].cost.total_ops' has the wrong type (expected number, found "
             "bool)"},
            {"/presets/0/passes/culling", "no",
             "'presets[0].passes.culling' has the wrong type (expected bool, found string)"},
            {"/variants/0/valid", "yes",
             "'variants[0].valid' has the wrong type (expected bool, found string)"},
            {"/variants/0/diagnostics/0/line", "3",
             "'variants[0].diagnostics[0].line' has the wrong type (expected number, found "
             "string)"},
            {"/variants/0/steps/link", 1,
             "'variants[0].steps.link' has the wrong type (expected string, found number)"},
            {"/variants/1", 7, "'variants[1]' has the wrong type (expected object, found number)"},
            {"/programs/0/defines", "ENABLE_FOG",
             "'programs[0].defines' has the wrong type (expected array, found string)"},
            {"/targets/0", 100, "'targets[0]' has the wrong type (expected string, found number)"},
            {"/config", json::object(),
             "'config' has the wrong type (expected string, found object)"},
    };
    for (const Case& c : cases) {
        json document = ToJson(OneOfEach());
        document[json::json_pointer(c.pointer)] = c.value;
        const ReadResult<ManifestFile> read = ManifestFileFromJson(document, "run/manifest.json");
        EXPECT_FALSE(read.value) << c.pointer;
        EXPECT_EQ(read.failure, ReadFailure::kWrongType) << c.pointer;
        EXPECT_EQ(read.error, std::string("run/manifest.json: ") + c.message) << c.pointer;
    }
}

TEST(ManifestFileTest, MissingVariantsCountsOrVariantIdsAreNamed) {
    struct Case {
        void (*edit)(json&);
        const char* message;
    };
    const std::vector<Case> cases = {
            {[](json& j) { j.erase("variants"); }, "m.json: 'variants' is missing"},
            {[](json& j) { j.erase("counts"); }, "m.json: 'counts' is missing"},
            {[](json& j) { j["variants"][1].erase("id"); },
             "m.json: 'variants[1].id' is not a non-empty string"},
            {[](json& j) { j["variants"][0]["program"] = ""; },
             "m.json: 'variants[0].program' is not a non-empty string"},
    };
    for (const Case& c : cases) {
        json document = ToJson(OneOfEach());
        c.edit(document);
        const ReadResult<ManifestFile> read = ManifestFileFromJson(document, "m.json");
        EXPECT_FALSE(read.value) << c.message;
        EXPECT_EQ(read.failure, ReadFailure::kMissingField) << c.message;
        EXPECT_EQ(read.error, c.message);
    }
}

TEST(ManifestFileTest, AnotherSchemaOrVersionIsForeignAndAMissingFileUnreadable) {
    json document = ToJson(OneOfEach());
    document["version"] = 2;
    ReadResult<ManifestFile> read = ManifestFileFromJson(document, "m.json");
    EXPECT_EQ(read.failure, ReadFailure::kForeign);
    EXPECT_EQ(read.error, "m.json: version must be 1");
    document["schema"] = "tidepool.plans";
    read = ManifestFileFromJson(document, "m.json");
    EXPECT_EQ(read.failure, ReadFailure::kForeign);
    EXPECT_EQ(read.error, "m.json: schema is not 'tidepool.manifest'");
    TempDir dir;
    read = ReadManifestFile(dir.Path() / "none.json");
    EXPECT_EQ(read.failure, ReadFailure::kUnreadable);
    EXPECT_EQ(read.error, (dir.Path() / "none.json").string() + ": no such file");
}

}  // namespace
}  // namespace tidepool::stagefiles
