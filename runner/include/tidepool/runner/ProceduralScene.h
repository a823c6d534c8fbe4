// The default scene of the embedded water renderer, generated at start-up with no external assets:
// sky and normalisation cube maps, the water normal map, an island with brightly coloured objects
// around the water plane, and the fixed camera views. Everything is deterministic (fixed hashes,
// no rand()), so the same build renders the same pixels every run.
#pragma once

#include "tidepool/SceneDescription.h"
#include "tidepool/base/RgbaImage.h"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/ext/vector_uint4_sized.hpp>
#include <glm/glm.hpp>

namespace tidepool::runner {

/// A cube map with square faces in GL order +X, -X, +Y, -Y, +Z, -Z, laid out with the GL face
/// conventions (GLES 2 spec, table 3.21), so that uploading face k as-is to
/// GL_TEXTURE_CUBE_MAP_POSITIVE_X + k makes textureCube(dir) return the texel for direction dir.
struct CubeMapImage {
    int size = 0;
    std::array<base::RgbaImage, 6> faces;
};

/// Returns the unit direction through the centre of texel (column, row) of cube face `face`
/// (0..5 in GL order) of a `size`-texel cube map. Fails (returns a meaningless direction) when
/// face is outside 0..5.
glm::vec3 CubeMapTexelDirection(int face, int size, int column, int row);

/// Returns the texel textureCube(direction) reads with GL_NEAREST filtering (a CPU reference for
/// tests and image checks). Fails (returns zero) when the cube map is empty or direction is zero.
glm::u8vec4 SampleCubeMapNearest(const CubeMapImage& cube_map, const glm::vec3& direction);

/// Builds the sky: pale horizon to deep-blue zenith, a sun disc with a glow around
/// `sun_direction` (normalised inside), a few soft clouds, and dark blue-grey below the horizon.
/// Fails (returns an empty cube map) when size < 1.
CubeMapImage BuildSkyCubeMap(int size, glm::vec3 sun_direction);

/// Builds the normalisation cube map: rgb = normalize(dir) * 0.5 + 0.5, alpha 255. Fails (returns
/// an empty cube map) when size < 1.
CubeMapImage BuildNormalisationCubeMap(int size);

/// Builds a seamlessly tiling water normal map, z-major (rgb = n * 0.5 + 0.5, n.z up; n.x along
/// texture s, n.y along t), from a sum of sine waves with integer frequencies and analytic
/// normals. Fails (returns an empty image) when size < 1.
base::RgbaImage BuildWaterNormalMap(int size);

/// A triangle mesh in object space with per-vertex albedo; triangles are counter-clockwise seen
/// from outside (GL's default front face), and every mesh has fewer than 65536 vertices because
/// GLES 2 has 16-bit indices only.
struct Mesh {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec3> colours;
    std::vector<std::uint16_t> indices;
    glm::mat4 model_matrix{1.0F};      ///< object → world, rigid (rotation, translation)
    glm::vec3 world_bounds_min{0.0F};  ///< tight world-space box of the transformed vertices
    glm::vec3 world_bounds_max{0.0F};
};

/// The default scene: an island heightfield, the objects around it and the sun.
struct Scene {
    float water_height = 0;
    Mesh terrain;
    /// The terrain starts with a regular grid of terrain_rows x terrain_columns vertices,
    /// positions row-major (index = row * terrain_columns + column), columns along +x and rows
    /// along +z in object space (vertices after the grid, such as the seabed skirt, are not part
    /// of it); 0 x 0 when the terrain is not such a grid. CPU passes that march the
    /// heightfield (FourierReflection.h) read the layout from here instead of guessing it.
    int terrain_columns = 0;
    int terrain_rows = 0;
    std::vector<Mesh> objects;
    glm::vec3 sun_direction{0.0F, 1.0F, 0.0F};  ///< unit vector towards the sun, world space
};

/// Builds the default scene: a 129x129 island heightfield over 200x200 units, with a flat seabed
/// skirt around it out to 10000 units so the floor reaches any far plane (heights about -20 to
/// +25) and, by name, "hull" (red boat, half submerged), "pillar_0..2" (yellow, through the water),
/// "submerged_rock_0..2" (magenta, fully under water), "tower" (orange) and "sphere" (cyan), both
/// on the island and fully above the water. Never fails.
Scene BuildDefaultScene();

/// Builds the default scene reshaped to a description: heights under the water scaled so the
/// open sea floor lies at `water.depth` (the island's slope and the submerged parts of hull and
/// pillars with it; submerged rocks move, staying whole), a flat floor at that depth when
/// terrain is not above, the submerged rocks only when objects are below, and the objects
/// through or above the water only when objects are above. Never fails: the
/// description's parser already refused what the renderer cannot draw.
Scene BuildSceneFromDescription(const SceneDescription& description);

/// True when the mesh's world bounds lie at or below the plane y = plane_height (nothing to draw
/// above it). Never fails.
bool IsEntirelyBelow(const Mesh& mesh, float plane_height);

/// True when the mesh's world bounds lie at or above the plane y = plane_height. Never fails.
bool IsEntirelyAbove(const Mesh& mesh, float plane_height);

/// True when the mesh's world bounds overlap the band from the plane y = plane_height down to
/// plane_height - max_depth (what the refraction pass sees before depth fog hides everything).
/// Fails (returns false) when max_depth is negative.
bool IntersectsDepthBand(const Mesh& mesh, float plane_height, float max_depth);

/// A fixed camera: position, target and a symmetric perspective.
struct CameraView {
    std::string name;
    glm::vec3 eye{0.0F};
    glm::vec3 target{0.0F, 0.0F, -1.0F};
    float fov_y_radians = 0.0F;
    float near_plane = 0.0F;
    float far_plane = 0.0F;
};

/// Returns the fixed views of the default scene, the default "three_quarter" first, then
/// "grazing", "high" and "shore"; every eye is above the water. Never fails.
std::vector<CameraView> DefaultViews();

/// Returns the view called `name`, or nullptr when there is none.
const CameraView* FindView(const std::vector<CameraView>& views, std::string_view name);

/// The camera a description asks for: look_at seen from `distance` away at `height` above the
/// water, 50-degree vertical field of view, near plane 1, far plane `view_range`. Never fails.
CameraView SceneCameraView(const SceneDescription& description);

/// Returns the world → view matrix (right-handed, y up). Fails (non-finite values) when eye equals
/// target or looks straight along the y axis.
glm::mat4 ViewMatrix(const CameraView& view);

/// Returns the OpenGL-style (clip z in [-w, w]) perspective projection for `aspect` = width /
/// height. Fails (non-finite values) when aspect or the field of view is zero.
glm::mat4 ProjectionMatrix(const CameraView& view, float aspect);

}  // namespace tidepool::runner
