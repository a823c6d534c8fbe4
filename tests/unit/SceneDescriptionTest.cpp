#include "tidepool/SceneDescription.h"
#include "tidepool/runner/ProceduralScene.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace tidepool {
namespace {

constexpr const char* kTarget = "target: {min_psnr_db: 30}\n";

// Every diagnostic of parsing `yaml` as s.yaml, formatted, one per line.
std::string Errors(const std::string& yaml) {
    std::string out;
    for (const Diagnostic& d : ParseSceneDescription(yaml, "s.yaml").diagnostics) {
        out += FormatDiagnostic(d) + "\n";
    }
    return out;
}

TEST(SceneDescriptionTest, ADescriptionWrittenAsABlockOfOneLineIsThatLine) {
    const SceneResult result = ParseSceneDescription(
            std::string(kTarget) + "description: |\n  a calm sea\n", "scenes/calm.yaml");
    ASSERT_TRUE(result.scene) << Errors(std::string(kTarget) + "description: |\n  a calm sea\n");
    EXPECT_EQ(result.scene->description, "a calm sea");
}

TEST(SceneDescriptionTest, FullDescriptionParsesEveryField) {
    const SceneResult result = ParseSceneDescription(
            "version: 1\n"
            "description: a pond\n"
            "water: {depth: 3, fog_depth: 1.5, waves: 0.4}\n"
            "above: [sky, terrain, objects]\n"
            "below: [terrain]\n"
            "camera: {height: 40, distance: 143, heading: 47, look_at: [-10, 2, -12], "
            "view_range: 900}\n"
            "target: {min_psnr_db: 31, max_share_visible: 0.05, frame_budget_ms: 8}\n",
            "scenes/murky_pond.yaml");
    ASSERT_TRUE(result.scene) << result.diagnostics.size();
    const SceneDescription& s = *result.scene;
    EXPECT_EQ(s.name, "murky_pond");
    EXPECT_EQ(s.description, "a pond");
    EXPECT_FLOAT_EQ(s.water_depth, 3.0F);
    EXPECT_FLOAT_EQ(s.fog_depth, 1.5F);
    EXPECT_FLOAT_EQ(s.wave_strength, 0.4F);
    EXPECT_TRUE(s.above_terrain);
    EXPECT_TRUE(s.above_objects);
    EXPECT_TRUE(s.below_terrain);
    EXPECT_FALSE(s.below_objects);
    EXPECT_FLOAT_EQ(s.camera.height, 40.0F);
    EXPECT_FLOAT_EQ(s.camera.look_at[2], -12.0F);
    EXPECT_FLOAT_EQ(s.camera.view_range, 900.0F);
    EXPECT_DOUBLE_EQ(*s.target.min_psnr_db, 31.0);
    EXPECT_DOUBLE_EQ(*s.target.max_share_visible, 0.05);
    EXPECT_DOUBLE_EQ(*s.target.frame_budget_ms, 8.0);
}

TEST(SceneDescriptionTest, OnlyTargetIsRequired) {
    const SceneResult result = ParseSceneDescription(kTarget, "s.yaml");
    ASSERT_TRUE(result.scene);
    EXPECT_TRUE(result.diagnostics.empty());
    EXPECT_TRUE(result.scene->below_objects);
}

TEST(SceneDescriptionTest, DefaultScenesAllParseAndDiffer) {
    const std::filesystem::path dir = std::filesystem::path(TIDEPOOL_SOURCE_ROOT) / "scenes";
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".yaml") {
            continue;
        }
        const SceneResult result = LoadSceneDescription(entry.path());
        std::string messages;
        for (const Diagnostic& d : result.diagnostics) {
            messages += FormatDiagnostic(d) + "\n";
        }
        EXPECT_TRUE(result.scene) << messages;
        ++count;
    }
    EXPECT_GE(count, 5);
}

TEST(SceneDescriptionTest, MissingFileIsAnError) {
    const SceneResult result = LoadSceneDescription("/nonexistent/x.yaml");
    EXPECT_FALSE(result.scene);
    ASSERT_EQ(result.diagnostics.size(), 1U);
    EXPECT_EQ(
            FormatDiagnostic(result.diagnostics[0]),
            "/nonexistent/x.yaml: error: cannot read the scene file: no such file; scenes live in "
            "scenes/NAME.yaml next to the configuration");
}

SceneDescription ParseOrDie(const std::string& yaml) {
    SceneResult result = ParseSceneDescription(yaml, "s.yaml");
    EXPECT_TRUE(result.scene) << Errors(yaml);
    return result.scene.value_or(SceneDescription{});
}

TEST(SceneDescriptionTest, BuiltSceneFollowsWaterDepthAndWhatIsBelow) {
    const runner::Scene scene = runner::BuildSceneFromDescription(ParseOrDie(
            std::string(kTarget) + "water: {depth: 3, fog_depth: 1}\nbelow: [terrain]\n"));
    // The open floor lies at the described depth (the default is 20 down).
    EXPECT_NEAR(scene.terrain.world_bounds_min.y, -3.0F, 0.5F);
    for (const runner::Mesh& mesh : scene.objects) {
        EXPECT_FALSE(runner::IsEntirelyBelow(mesh, scene.water_height)) << mesh.name;
    }
}

TEST(SceneDescriptionTest, BuiltSceneKeepsSubmergedRocksUnderTheClipSliver) {
    const runner::Scene scene = runner::BuildSceneFromDescription(
            ParseOrDie(std::string(kTarget) + "water: {depth: 2, fog_depth: 50}\n"));
    int rocks = 0;
    for (const runner::Mesh& mesh : scene.objects) {
        if (mesh.name.rfind("submerged_rock", 0) == 0) {
            ++rocks;
            // Below the 0.5 sliver the reflection's clip plane keeps, so it is culled there.
            EXPECT_LE(mesh.world_bounds_max.y, -0.5F) << mesh.name;
        }
    }
    EXPECT_EQ(rocks, 3);
}

TEST(SceneDescriptionTest, OpenSeaHasOnlyAFlatFloorAtItsDepth) {
    const runner::Scene scene = runner::BuildSceneFromDescription(
            ParseOrDie(std::string(kTarget) +
                       "water: {depth: 200, fog_depth: 20}\nabove: [sky]\nbelow: []\n"));
    EXPECT_TRUE(scene.objects.empty());
    EXPECT_FLOAT_EQ(scene.terrain.world_bounds_max.y, -200.0F);
    EXPECT_FLOAT_EQ(scene.terrain.world_bounds_min.y, -200.0F);
}

TEST(SceneDescriptionTest, CameraLooksAtItsTargetFromItsHeightAndDistance) {
    const runner::CameraView view = runner::SceneCameraView(
            ParseOrDie(std::string(kTarget) +
                       "camera: {height: 10, distance: 30, heading: 90, look_at: [1, 2, 3], "
                       "view_range: 500}\n"));
    EXPECT_NEAR(view.eye.x, 31.0F, 1e-4F);
    EXPECT_NEAR(view.eye.y, 10.0F, 1e-4F);
    EXPECT_NEAR(view.eye.z, 3.0F, 1e-4F);
    EXPECT_FLOAT_EQ(view.target.y, 2.0F);
    EXPECT_FLOAT_EQ(view.far_plane, 500.0F);
}

// Bad input and the exact message it gives.
struct BadScene {
    const char* why;
    std::string yaml;
    std::string expected;
};

class SceneDescriptionBadInputTest : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneDescriptionBadInputTest, GivesExactDiagnostic) {
    const BadScene& bad = GetParam();
    EXPECT_FALSE(ParseSceneDescription(bad.yaml, "s.yaml").scene) << bad.why;
    EXPECT_EQ(Errors(bad.yaml), bad.expected) << bad.why;
}

INSTANTIATE_TEST_SUITE_P(
        Table, SceneDescriptionBadInputTest,
        ::testing::Values(
                BadScene{"misspelt key", std::string(kTarget) + "water:\n  depht: 3\n",
                         "s.yaml:3:3: error: unknown key 'depht' in water; allowed keys: "
                         "depth, fog_depth, waves\n"},
                BadScene{"unknown top-level key", std::string(kTarget) + "lighting: 1\n",
                         "s.yaml:2:1: error: unknown key 'lighting' in the top level; allowed "
                         "keys: version, description, water, above, below, camera, target\n"},
                BadScene{"duplicate key", std::string(kTarget) + "target: {min_psnr_db: 31}\n",
                         "s.yaml:2:1: error: duplicate key 'target' (first written at line 1); "
                         "remove one of them\n"},
                BadScene{"wave strength out of range", std::string(kTarget) + "water: {waves: 3}\n",
                         "s.yaml:2:16: error: water.waves must be between 0 and 2, not 3\n"},
                BadScene{"not a number", std::string(kTarget) + "camera:\n  height: high\n",
                         "s.yaml:3:11: error: camera.height must be a number\n"},
                BadScene{"number left empty before another key",
                         std::string(kTarget) + "camera:\n  height:\n  distance: 40\n",
                         "s.yaml:3:3: error: camera.height has no value; give it a number from "
                         "0.6 to 1000\n"},
                BadScene{"number too large for a double",
                         std::string(kTarget) + "water: {depth: 1e999}\n",
                         "s.yaml:2:16: error: water.depth must be between 0.5 and 200, not "
                         "1e999\n"},
                BadScene{"eye under the water", std::string(kTarget) + "camera: {height: 0.2}\n",
                         "s.yaml:2:18: error: camera.height must be between 0.6 and 1000, not "
                         "0.2\n"},
                BadScene{"look_at not a point",
                         std::string(kTarget) + "camera: {look_at: [1, 2]}\n",
                         "s.yaml:2:19: error: camera.look_at must be a point [x, y, z]\n"},
                BadScene{"no target", "water: {depth: 3}\n",
                         "s.yaml:1:1: error: no `target:`; give min_psnr_db, max_share_visible "
                         "or frame_budget_ms\n"},
                BadScene{"empty target", "target: {}\n",
                         "s.yaml:1:1: error: target needs min_psnr_db, max_share_visible or "
                         "frame_budget_ms\n"},
                BadScene{"share above 1", "target: {max_share_visible: 1.5}\n",
                         "s.yaml:1:29: error: target.max_share_visible must be between 0 and 1, "
                         "not 1.5\n"},
                BadScene{"unknown thing above", std::string(kTarget) + "above: [sky, clouds]\n",
                         "s.yaml:2:14: error: unknown name 'clouds' in above; allowed: sky, "
                         "terrain, objects\n"},
                BadScene{"no sky: the renderer always draws it",
                         std::string(kTarget) + "above: [terrain]\n",
                         "s.yaml:2:8: error: the embedded renderer always draws the sky above "
                         "the water; add sky to above\n"},
                BadScene{"objects without the island they stand on",
                         std::string(kTarget) + "above: [sky, objects]\n",
                         "s.yaml:2:8: error: the objects above the water stand on the island "
                         "in the embedded renderer; add terrain to above or drop objects\n"},
                BadScene{"a visible floor said to be out of sight",
                         std::string(kTarget) + "water: {depth: 5, fog_depth: 30}\nbelow: []\n",
                         "s.yaml:3:8: error: the sea floor at depth 5 is within the fog depth "
                         "30, so it is visible; add terrain to below, or make water.depth at "
                         "least water.fog_depth\n"},
                // A block scalar of two lines was accepted, and would break the report's tables.
                BadScene{"a description of two lines",
                         std::string(kTarget) + "description: |\n  calm\n  sea\n",
                         "s.yaml:2:14: error: description must be a single line of text\n"},
                // Only the range error: a second one quoted the default depth, 20.
                BadScene{"a depth out of range, and no floor below",
                         std::string(kTarget) + "water: {depth: 500, fog_depth: 80}\nbelow: []\n",
                         "s.yaml:2:16: error: water.depth must be between 0.5 and 200, not "
                         "500\n"},
                BadScene{"listed twice", std::string(kTarget) + "below: [terrain, terrain]\n",
                         "s.yaml:2:18: error: 'terrain' is listed twice in below\n"},
                BadScene{"unsupported version", std::string(kTarget) + "version: 2\n",
                         "s.yaml:2:10: error: unsupported scene schema version; this tidepool "
                         "reads version 1\n"},
                BadScene{"malformed YAML", "target: {min_psnr_db: 30\n",
                         "s.yaml:2:1: error: malformed YAML: end of map flow not found\n"},
                BadScene{"above not a list", std::string(kTarget) + "above: sky\n",
                         "s.yaml:2:8: error: above must be a list such as [sky, terrain, "
                         "objects]\n"
                         "s.yaml:2:8: error: the embedded renderer always draws the sky "
                         "above the water; add sky to above\n"},
                BadScene{"a list inside a list", std::string(kTarget) + "above: [[sky]]\n",
                         "s.yaml:2:9: error: above lists names, not lists or mappings\n"
                         "s.yaml:2:8: error: the embedded renderer always draws the sky "
                         "above the water; add sky to above\n"},
                BadScene{"description not one line of text",
                         std::string(kTarget) + "description: [a, pond]\n",
                         "s.yaml:2:14: error: description must be a single line of text\n"},
                BadScene{"water not a mapping", std::string(kTarget) + "water: 3\n",
                         "s.yaml:2:8: error: water must be a mapping of keys to values\n"},
                BadScene{"camera value a list", std::string(kTarget) + "camera: {height: [1, 2]}\n",
                         "s.yaml:2:18: error: camera.height must be a number\n"},
                BadScene{"not a mapping", "- 1\n",
                         "s.yaml:1:1: error: a scene must be a mapping with water, above, "
                         "below, camera and target (see docs/SCENES.md)\n"}));

}  // namespace
}  // namespace tidepool
