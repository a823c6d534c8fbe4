// The generated textures, meshes and views of the default scene.
#include "tidepool/runner/ProceduralScene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace tidepool::runner {
namespace {

// One 8-bit step of an encoded unit vector component is 2/255; rounding costs half of it, and
// the decoded length of three such components can be off by up to sqrt(3) steps.
constexpr float kEncodedStep = 2.0F / 255.0F;

glm::vec3 Texel(const base::RgbaImage& image, int column, int row) {
    const auto offset = static_cast<std::size_t>(row * image.width + column) * 4;
    return {image.pixels[offset], image.pixels[offset + 1], image.pixels[offset + 2]};
}

glm::vec3 DecodeUnit(const glm::vec3& rgb) {
    return rgb / 255.0F * 2.0F - 1.0F;
}

float Luminance(const glm::u8vec4& texel) {
    return glm::dot(glm::vec3(texel), glm::vec3(0.2126F, 0.7152F, 0.0722F));
}

const Scene& DefaultProceduralScene() {
    static const Scene scene = BuildDefaultScene();
    return scene;
}

const Mesh& Object(const std::string& name) {
    const auto& objects = DefaultProceduralScene().objects;
    const auto found = std::find_if(objects.begin(), objects.end(),
                                    [&](const Mesh& mesh) { return mesh.name == name; });
    if (found == objects.end()) {
        ADD_FAILURE() << "no object named " << name;
        return DefaultProceduralScene().terrain;
    }
    return *found;
}

std::vector<const Mesh*> AllMeshes() {
    std::vector<const Mesh*> meshes{&DefaultProceduralScene().terrain};
    for (const Mesh& mesh : DefaultProceduralScene().objects) {
        meshes.push_back(&mesh);
    }
    return meshes;
}

glm::vec3 Corner(const Mesh& mesh, std::size_t triangle, std::size_t corner) {
    return mesh.positions[mesh.indices[triangle * 3 + corner]];
}

// ----- Cube maps ------------------------------------------------------------------------------

TEST(ProceduralSceneTest, NormalisationCubeMapPositiveXCentreDecodesToPlusX) {
    // An odd size puts a texel exactly at the face centre.
    const CubeMapImage cube = BuildNormalisationCubeMap(17);
    const glm::vec3 n = DecodeUnit(Texel(cube.faces[0], 8, 8));
    EXPECT_NEAR(n.x, 1.0F, kEncodedStep);
    EXPECT_NEAR(n.y, 0.0F, kEncodedStep);
    EXPECT_NEAR(n.z, 0.0F, kEncodedStep);
}

TEST(ProceduralSceneTest, CubeMapFacesFollowGlOrientation) {
    // First texel (s, t near 0, so sc = tc = -1) of each face, from GLES 2 table 3.21:
    // +X sc=-z tc=-y; -X sc=z tc=-y; +Y sc=x tc=z; -Y sc=x tc=-z; +Z sc=x tc=-y; -Z sc=-x tc=-y.
    const std::array<glm::vec3, 6> expected_signs{
            {{1, 1, 1}, {-1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {-1, 1, 1}, {1, 1, -1}}};
    const CubeMapImage cube = BuildNormalisationCubeMap(8);
    for (std::size_t face = 0; face < 6; ++face) {
        const glm::vec3 n = DecodeUnit(Texel(cube.faces[face], 0, 0));
        for (glm::length_t i = 0; i < 3; ++i) {
            EXPECT_GT(n[i] * expected_signs[face][i], 0.3F) << "face " << face << " axis " << i;
        }
    }
}

TEST(ProceduralSceneTest, SampleCubeMapNearestReadsTheTexelOfItsDirection) {
    const int size = 8;
    const CubeMapImage cube = BuildNormalisationCubeMap(size);
    for (int face = 0; face < 6; ++face) {
        for (const auto& [column, row] : {std::pair{0, 0}, {7, 0}, {3, 5}, {7, 7}}) {
            const glm::u8vec4 sampled =
                    SampleCubeMapNearest(cube, CubeMapTexelDirection(face, size, column, row));
            const glm::vec3 stored = Texel(cube.faces[static_cast<std::size_t>(face)], column, row);
            EXPECT_EQ(glm::vec3(sampled), stored) << face << ": " << column << ", " << row;
        }
    }
}

TEST(ProceduralSceneTest, SkyIsBrighterTowardsTheSun) {
    const glm::vec3 sun = glm::normalize(glm::vec3(0.45F, 0.6F, -0.65F));
    const CubeMapImage sky = BuildSkyCubeMap(64, sun);
    const glm::u8vec4 at_sun = SampleCubeMapNearest(sky, sun);
    // Same elevation, opposite azimuth.
    const glm::u8vec4 away = SampleCubeMapNearest(sky, {-sun.x, sun.y, -sun.z});
    EXPECT_GT(Luminance(at_sun), Luminance(away) + 40.0F);
    EXPECT_GE(std::min({at_sun.r, at_sun.g, at_sun.b}), 220) << "the sun disc is near white";
}

TEST(ProceduralSceneTest, SkyIsBlueAtZenithAndDarkBelowHorizon) {
    const CubeMapImage sky = BuildSkyCubeMap(32, {0.45F, 0.6F, -0.65F});
    const glm::u8vec4 zenith = SampleCubeMapNearest(sky, {0, 1, 0});
    const glm::u8vec4 below = SampleCubeMapNearest(sky, {0.2F, -1, 0.3F});
    const glm::u8vec4 horizon = SampleCubeMapNearest(sky, {-1, 0.05F, 0.3F});
    EXPECT_GT(zenith.b, zenith.r + 80);
    EXPECT_LT(Luminance(below), 80.0F);
    EXPECT_GT(Luminance(horizon), Luminance(zenith));
}

// ----- Water normal map -----------------------------------------------------------------------

// Mean absolute channel difference between columns a and b (or rows, when `rows` is true).
float MeanDifference(const base::RgbaImage& image, int a, int b, bool rows) {
    float sum = 0.0F;
    for (int i = 0; i < image.width; ++i) {
        sum += glm::dot(glm::abs(rows ? Texel(image, i, a) - Texel(image, i, b)
                                      : Texel(image, a, i) - Texel(image, b, i)),
                        glm::vec3(1.0F));
    }
    return sum / static_cast<float>(image.width);
}

TEST(ProceduralSceneTest, WaterNormalMapTilesSeamlessly) {
    const int size = 64;
    const base::RgbaImage map = BuildWaterNormalMap(size);
    for (const bool rows : {false, true}) {
        float largest_step = 0.0F;
        for (int i = 0; i + 1 < size; ++i) {
            largest_step = std::max(largest_step, MeanDifference(map, i, i + 1, rows));
        }
        const float wrap_step = MeanDifference(map, size - 1, 0, rows);
        // The wrap is just another step of the same smooth function, so it is no larger than
        // the largest neighbour step; one extra unit absorbs 8-bit rounding.
        EXPECT_LE(wrap_step, largest_step + 1.0F) << (rows ? "rows" : "columns");
        EXPECT_GT(largest_step, 1.0F) << "the map has waves";
    }
}

TEST(ProceduralSceneTest, WaterNormalMapIsZMajorUnitNormals) {
    const base::RgbaImage map = BuildWaterNormalMap(32);
    for (int row = 0; row < map.height; ++row) {
        for (int column = 0; column < map.width; ++column) {
            const glm::vec3 n = DecodeUnit(Texel(map, column, row));
            EXPECT_GT(n.z, std::max(std::abs(n.x), std::abs(n.y)));
            EXPECT_NEAR(glm::length(n), 1.0F, std::sqrt(3.0F) * kEncodedStep);
        }
    }
}

TEST(ProceduralSceneTest, InvalidSizesGiveEmptyImages) {
    EXPECT_TRUE(BuildWaterNormalMap(0).pixels.empty());
    EXPECT_EQ(BuildNormalisationCubeMap(0).size, 0);
    EXPECT_EQ(BuildSkyCubeMap(-1, {0, 1, 0}).size, 0);
}

// ----- Meshes ---------------------------------------------------------------------------------

TEST(ProceduralSceneTest, SceneIsDeterministic) {
    const Scene again = BuildDefaultScene();
    EXPECT_EQ(again.terrain.positions, DefaultProceduralScene().terrain.positions);
    ASSERT_EQ(again.objects.size(), DefaultProceduralScene().objects.size());
    for (std::size_t i = 0; i < again.objects.size(); ++i) {
        EXPECT_EQ(again.objects[i].positions, DefaultProceduralScene().objects[i].positions);
    }
    EXPECT_EQ(BuildSkyCubeMap(16, {0, 1, 1}).faces[4].pixels,
              BuildSkyCubeMap(16, {0, 1, 1}).faces[4].pixels);
}

TEST(ProceduralSceneTest, MeshesFitSixteenBitIndices) {
    for (const Mesh* mesh : AllMeshes()) {
        SCOPED_TRACE(mesh->name);
        EXPECT_LT(mesh->positions.size(), 65536U);
        EXPECT_EQ(mesh->normals.size(), mesh->positions.size());
        EXPECT_EQ(mesh->colours.size(), mesh->positions.size());
        EXPECT_FALSE(mesh->indices.empty());
        EXPECT_EQ(mesh->indices.size() % 3, 0U);
        EXPECT_LT(*std::max_element(mesh->indices.begin(), mesh->indices.end()),
                  mesh->positions.size());
    }
}

TEST(ProceduralSceneTest, MeshNormalsAreUnitLength) {
    for (const Mesh* mesh : AllMeshes()) {
        SCOPED_TRACE(mesh->name);
        for (const glm::vec3& n : mesh->normals) {
            ASSERT_NEAR(glm::length(n), 1.0F, 1e-5F);  // normalised floats: a few ulps
        }
    }
}

TEST(ProceduralSceneTest, ClosedObjectsAreWoundCounterClockwiseFromOutside) {
    for (const Mesh& mesh : DefaultProceduralScene().objects) {
        // The divergence theorem: outward-facing (CCW) triangles of a closed surface enclose a
        // positive volume.
        double volume = 0.0;
        for (std::size_t t = 0; t < mesh.indices.size() / 3; ++t) {
            volume += glm::dot(glm::dvec3(Corner(mesh, t, 0)),
                               glm::cross(glm::dvec3(Corner(mesh, t, 1)),
                                          glm::dvec3(Corner(mesh, t, 2)))) /
                      6.0;
        }
        EXPECT_GT(volume, 1.0) << mesh.name;
    }
}

TEST(ProceduralSceneTest, TriangleWindingAgreesWithVertexNormals) {
    for (const Mesh* mesh : AllMeshes()) {
        for (std::size_t t = 0; t < mesh->indices.size() / 3; ++t) {
            const glm::vec3 face = glm::cross(Corner(*mesh, t, 1) - Corner(*mesh, t, 0),
                                              Corner(*mesh, t, 2) - Corner(*mesh, t, 0));
            if (glm::length(face) < 1e-6F) {
                continue;  // the degenerate triangles at poles and stems face nowhere
            }
            glm::vec3 normal(0.0F);
            for (std::size_t c = 0; c < 3; ++c) {
                normal += mesh->normals[mesh->indices[t * 3 + c]];
            }
            ASSERT_GT(glm::dot(face, normal), 0.0F) << mesh->name << " triangle " << t;
        }
    }
}

TEST(ProceduralSceneTest, TerrainIsAnIslandCrossingTheWater) {
    const Mesh& terrain = DefaultProceduralScene().terrain;
    // The 129 x 129 grid over 200 x 200, then a seabed skirt (one vertex per border vertex) out
    // to the longest view range, so the floor has no edge before the far plane.
    EXPECT_EQ(terrain.positions.size(), 129U * 129U + 4U * 128U);
    EXPECT_FLOAT_EQ(terrain.world_bounds_min.x, -10000.0F);
    EXPECT_FLOAT_EQ(terrain.world_bounds_max.z, 10000.0F);
    EXPECT_FLOAT_EQ(terrain.positions[129U * 129U - 1U].x, 100.0F);
    EXPECT_LT(terrain.world_bounds_min.y, -18.0F);
    EXPECT_GT(terrain.world_bounds_max.y, 20.0F);
    EXPECT_LT(terrain.world_bounds_max.y, 30.0F);
    for (std::size_t t = 0; t < terrain.indices.size() / 3; ++t) {
        const glm::vec3 face = glm::cross(Corner(terrain, t, 1) - Corner(terrain, t, 0),
                                          Corner(terrain, t, 2) - Corner(terrain, t, 0));
        ASSERT_GT(face.y, 0.0F) << "triangle " << t << " faces up (CCW from above)";
    }
}

TEST(ProceduralSceneTest, WorldBoundsAreTightAroundTransformedVertices) {
    for (const Mesh* mesh : AllMeshes()) {
        glm::vec3 lo(std::numeric_limits<float>::max());
        glm::vec3 hi(std::numeric_limits<float>::lowest());
        for (const glm::vec3& p : mesh->positions) {
            const glm::vec3 world(mesh->model_matrix * glm::vec4(p, 1.0F));
            lo = glm::min(lo, world);
            hi = glm::max(hi, world);
        }
        EXPECT_EQ(mesh->world_bounds_min, lo) << mesh->name;
        EXPECT_EQ(mesh->world_bounds_max, hi) << mesh->name;
    }
}

TEST(ProceduralSceneTest, SceneHasTheNamedObjects) {
    for (const char* name : {"hull", "pillar_0", "pillar_1", "pillar_2", "submerged_rock_0",
                             "submerged_rock_1", "submerged_rock_2", "tower", "sphere"}) {
        EXPECT_EQ(Object(name).name, name);
    }
    EXPECT_FLOAT_EQ(glm::length(DefaultProceduralScene().sun_direction), 1.0F);
    EXPECT_EQ(DefaultProceduralScene().water_height, 0.0F);
}

// ----- Culling --------------------------------------------------------------------------------

TEST(ProceduralSceneTest, CullingPredicatesSortTheSceneAroundTheWater) {
    const float water = DefaultProceduralScene().water_height;
    for (const char* name : {"submerged_rock_0", "submerged_rock_1", "submerged_rock_2"}) {
        EXPECT_TRUE(IsEntirelyBelow(Object(name), water)) << name;
        EXPECT_FALSE(IsEntirelyAbove(Object(name), water)) << name;
    }
    for (const char* name : {"tower", "sphere"}) {
        EXPECT_TRUE(IsEntirelyAbove(Object(name), water)) << name;
        EXPECT_FALSE(IsEntirelyBelow(Object(name), water)) << name;
    }
    for (const char* name : {"hull", "pillar_0", "pillar_1", "pillar_2"}) {
        EXPECT_FALSE(IsEntirelyAbove(Object(name), water)) << name;
        EXPECT_FALSE(IsEntirelyBelow(Object(name), water)) << name;
    }
    EXPECT_FALSE(IsEntirelyAbove(DefaultProceduralScene().terrain, water));
    EXPECT_FALSE(IsEntirelyBelow(DefaultProceduralScene().terrain, water));
}

TEST(ProceduralSceneTest, DepthBandSelectsWhatReachesBetweenPlaneAndMaxDepth) {
    EXPECT_TRUE(IntersectsDepthBand(Object("submerged_rock_0"), 0.0F, 80.0F));
    EXPECT_TRUE(IntersectsDepthBand(Object("hull"), 0.0F, 80.0F));
    EXPECT_FALSE(IntersectsDepthBand(Object("tower"), 0.0F, 80.0F));
    // The rocks' tops are a few units down, so a one-unit band misses them.
    EXPECT_FALSE(IntersectsDepthBand(Object("submerged_rock_0"), 0.0F, 1.0F));
    EXPECT_FALSE(IntersectsDepthBand(Object("hull"), 0.0F, -1.0F));
}

TEST(ProceduralSceneTest, PredicatesTreatTouchingThePlaneAsOnOneSide) {
    Mesh box;
    box.world_bounds_min = {0, -2, 0};
    box.world_bounds_max = {1, 0, 1};
    EXPECT_TRUE(IsEntirelyBelow(box, 0.0F));
    EXPECT_FALSE(IsEntirelyAbove(box, 0.0F));
    EXPECT_TRUE(IsEntirelyAbove(box, -2.0F));
    EXPECT_TRUE(IntersectsDepthBand(box, 5.0F, 5.0F));
    EXPECT_FALSE(IntersectsDepthBand(box, 5.0F, 4.9F));
}

// ----- Views ----------------------------------------------------------------------------------

TEST(ProceduralSceneTest, DefaultViewsHaveTheFourNamedViewsAboveWater) {
    const std::vector<CameraView> views = DefaultViews();
    ASSERT_GE(views.size(), 4U);
    EXPECT_EQ(views.front().name, "three_quarter");
    for (const char* name : {"three_quarter", "grazing", "high", "shore"}) {
        const CameraView* view = FindView(views, name);
        ASSERT_NE(view, nullptr) << name;
        EXPECT_GT(view->eye.y, DefaultProceduralScene().water_height) << name;
        EXPECT_GT(view->far_plane, view->near_plane) << name;
    }
    EXPECT_NEAR(FindView(views, "grazing")->eye.y, 1.5F, 0.5F);
    EXPECT_NEAR(FindView(views, "high")->eye.y, 150.0F, 10.0F);
    EXPECT_EQ(FindView(views, "missing"), nullptr);
}

TEST(ProceduralSceneTest, ThreeQuarterViewShowsObjectsAndTheTowerReflection) {
    const std::vector<CameraView> views = DefaultViews();
    const CameraView& view = *FindView(views, "three_quarter");
    const glm::mat4 view_projection = ProjectionMatrix(view, 4.0F / 3.0F) * ViewMatrix(view);
    auto on_screen = [&](const glm::vec3& world) {
        const glm::vec4 clip = view_projection * glm::vec4(world, 1.0F);
        return clip.w > 0.0F && std::abs(clip.x) < clip.w && std::abs(clip.y) < clip.w &&
               std::abs(clip.z) < clip.w;
    };
    for (const char* name : {"hull", "pillar_0", "pillar_1", "pillar_2", "tower"}) {
        const Mesh& mesh = Object(name);
        EXPECT_TRUE(on_screen((mesh.world_bounds_min + mesh.world_bounds_max) * 0.5F)) << name;
    }
    // The tower's top mirrored in the water plane is where its reflection appears.
    const Mesh& tower = Object("tower");
    const glm::vec3 top((tower.world_bounds_min.x + tower.world_bounds_max.x) * 0.5F,
                        -tower.world_bounds_max.y,
                        (tower.world_bounds_min.z + tower.world_bounds_max.z) * 0.5F);
    EXPECT_TRUE(on_screen(top));
}

TEST(ProceduralSceneTest, ViewAndProjectionMatricesFollowTheCamera) {
    const CameraView view{"test", {10, 5, 0}, {0, 5, 0}, glm::radians(60.0F), 1.0F, 100.0F};
    const glm::mat4 view_matrix = ViewMatrix(view);
    const glm::vec4 eye = view_matrix * glm::vec4(view.eye, 1.0F);
    const glm::vec4 target = view_matrix * glm::vec4(view.target, 1.0F);
    EXPECT_NEAR(glm::length(glm::vec3(eye)), 0.0F, 1e-5F);
    EXPECT_NEAR(target.x, 0.0F, 1e-5F);
    EXPECT_NEAR(target.y, 0.0F, 1e-5F);
    EXPECT_NEAR(target.z, -10.0F, 1e-5F);  // looking down -z, 10 units ahead
    // OpenGL depth range: the near plane maps to -1, the far plane to +1.
    const glm::mat4 projection = ProjectionMatrix(view, 2.0F);
    const glm::vec4 near_point = projection * glm::vec4(0, 0, -1, 1);
    const glm::vec4 far_point = projection * glm::vec4(0, 0, -100, 1);
    EXPECT_NEAR(near_point.z / near_point.w, -1.0F, 1e-5F);
    EXPECT_NEAR(far_point.z / far_point.w, 1.0F, 1e-5F);
}

}  // namespace
}  // namespace tidepool::runner
