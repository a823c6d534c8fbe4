// Fake water reflections from Fourier coefficients (seeds/004, "Faking water reflections with
// fourier coefficients"): every water vertex stores, as a short Fourier series over the azimuth,
// how high the terrain rises above the water plane all around it. The water shader evaluates the
// series at the reflected ray's azimuth and shows terrain where the ray climbs less steeply than
// the terrain, sky otherwise. Everything here runs once on the CPU at start-up.
//
// Conventions the shader must share:
// - Azimuth t of a horizontal direction d (world x/z) is atan2(d.z, d.x) mapped to [0, 2 pi): t = 0
//   along +x, t = pi / 2 along +z. The seed's atan2(-r.z, -r.x) + pi is the same angle.
// - Elevations are angles in radians above the water plane, atan2(height - water, distance),
//   never below 0 (terrain under the water reflects nothing).
// - Coefficients in the seed's order a0, a1, b1, a2, b2, a3, b3, a4; a vertex's first vec4 holds
//   (a0, a1, b1, a2) and its second (b2, a3, b3, a4).
//
// Only the terrain heightfield is marched: the scene's objects (tower, sphere, hull, pillars) and
// anything moving are missing from these reflections, the limit the seed names ("it only reflects
// static objects").
#pragma once

#include "tidepool/runner/ProceduralScene.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tidepool::runner {

/// A regular heightfield in world x/z: vertex (column, row) lies at origin + spacing * (column,
/// row) with columns along +x and rows along +z; heights are world y, row-major.
struct Heightfield {
    glm::vec2 origin{0.0F};  ///< world (x, z) of column 0, row 0
    float spacing = 0.0F;    ///< world units between neighbouring vertices, both axes
    int columns = 0;
    int rows = 0;
    std::vector<float> heights;  ///< rows * columns, index = row * columns + column

    /// Returns the bilinearly interpolated height at world (x, z). Fails (nullopt) outside the
    /// grid's closed rectangle, for non-finite x or z, and for a grid of fewer than 2 x 2 vertices.
    std::optional<float> HeightAt(float x, float z) const;
};

/// Returns the scene's terrain as a heightfield (world = terrain.model_matrix * position), using
/// scene.terrain_columns and scene.terrain_rows. Fails (returns an empty heightfield, 0 x 0) when
/// the layout is smaller than 2 x 2 or does not match the vertex count, or when the world
/// positions are not a regular grid with equal spacing along +x (columns) and +z (rows).
Heightfield TerrainHeightfield(const Scene& scene);

/// How the per-vertex coefficients are computed; the defaults are the seed's (13 directions, 400
/// integration samples, 8 coefficients) except the march: the seed's 5 texels suit overhead views,
/// this scene's grazing views see the island from far out, so 100 units (64 terrain texels).
struct FourierSettings {
    int coefficients = 8;           ///< 1..8, taken in the order a0, a1, b1, a2, b2, a3, b3, a4
    int directions = 13;            ///< k >= 3 march directions, evenly spaced in azimuth
    float march_distance = 100.0F;  ///< how far each march reaches, world units (> 0)
    int integration_samples = 400;  ///< samples of the periodic function per integral (>= 9)
    float grid_spacing = 4.0F;      ///< water grid spacing, world units (> 0)
    float grid_margin = 100.0F;     ///< water grid extent beyond the terrain's, world units (>= 0)
};

/// Returns "" when the settings can be used, otherwise one message naming the first broken rule
/// and its allowed range. Never fails otherwise.
std::string CheckFourierSettings(const FourierSettings& settings);

/// Returns the terrain's elevation above the water seen from point_xz in k = `directions`
/// directions, direction j at azimuth t_j = 2 pi j / k: the largest atan2(height - water_height,
/// s) over the heightfield samples at distances s = spacing, 2 spacing, ... up to march_distance
/// (one heightfield texel per step, as the seed marches), and 0 when nothing rises above the
/// water. Samples outside the heightfield count as open water. Fails (returns an empty vector) when
/// directions < 1; returns all zeros for an empty heightfield or a march_distance shorter than
/// one step.
std::vector<float> ElevationProfile(const Heightfield& heightfield, glm::vec2 point_xz,
                                    float water_height, int directions, float march_distance);

/// Returns the first `coefficients` Fourier coefficients (a0, a1, b1, ... a4) of the periodic
/// function that joins the k samples (sample j at t = 2 pi j / k) by periodic linear
/// interpolation, integrated numerically with `integration_samples` evenly spaced points:
/// a0 = mean, an = (1 / pi) integral f cos(n t), bn = (1 / pi) integral f sin(n t); the entries
/// not asked for are 0. Linear interpolation damps harmonic n by (sin(x) / x)^2 with
/// x = n pi / k, so 13 directions keep 72% of a4 and 360 keep 99.96% of it.
/// Fails (returns all zeros) when samples is empty, coefficients is outside 1..8 or
/// integration_samples < 1.
std::array<float, 8> FourierCoefficients(const std::vector<float>& samples, int coefficients,
                                         int integration_samples);

/// Evaluates the series at azimuth t with the seed's formula: a0 + a1 cos t + b1 sin t +
/// a2 cos 2t + b2 sin 2t + a3 cos 3t + b3 sin 3t + a4 cos 4t. Never fails.
float EvaluateFourier(const std::array<float, 8>& c, float t);

/// The water mesh the Fourier reflection draws: positions in world space at the water height,
/// two vec4 of coefficients per vertex (see the conventions above), 16-bit triangle indices.
struct FourierWaterGrid {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec4> coefficients0;  ///< (a0, a1, b1, a2) per vertex
    std::vector<glm::vec4> coefficients1;  ///< (b2, a3, b3, a4) per vertex
    std::vector<std::uint16_t> indices;    ///< triangles, counter-clockwise seen from above (+y)
};

/// Half-size of the skirt square around the grid's centre, world units: ten times the default
/// views' 2000-unit far plane, so the water never ends inside a view.
inline constexpr float kFourierSkirtHalfSize = 20000.0F;

/// Builds the water grid: a regular grid at y = scene.water_height with spacing exactly
/// grid_spacing, centred on the terrain and covering its x/z extent plus grid_margin on every
/// side (rounded up to whole cells), each vertex's coefficients from ElevationProfile and
/// FourierCoefficients over the terrain heightfield (vertices under the island see it at nearly
/// 90 degrees; the terrain hides them). Around it one ring of skirt vertices on the square
/// kFourierSkirtHalfSize around the grid's centre (twice the grid's half-size if that is
/// larger), joined to the grid's edge. Skirt coefficients are 0 (open sea: at that range the
/// terrain rises less than 0.1 degree); with the default settings the grid's edge is 0 too (its
/// marches end on the terrain's border, which is sea floor), so the skirt shows no seam. Triangles
/// are counter-clockwise seen from above, as the terrain's; the renderer draws water without face
/// culling, so this only matters to a caller that culls. Fails (returns an empty grid) when
/// CheckFourierSettings rejects the settings, the terrain is not a heightfield (see
/// TerrainHeightfield), or the grid would need 65536 vertices or more (GLES 2 indices are 16-bit).
FourierWaterGrid BuildFourierWaterGrid(const Scene& scene, const FourierSettings& settings);

}  // namespace tidepool::runner
