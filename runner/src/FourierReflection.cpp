#include "tidepool/runner/FourierReflection.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <utility>

namespace tidepool::runner {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kMaxCoefficients = 8;
// Harmonic 4 (a4) needs more than 8 samples per period to be told apart from lower ones.
constexpr int kMinIntegrationSamples = 2 * 4 + 1;
// Upper bounds far past any use (the defaults are 13 directions and a few dozen samples): each
// grid vertex marches every direction and integrates every sample, so 2,000,000,000 directions
// were accepted and began a bake that would never end.
constexpr int kMaxDirections = 360;
constexpr int kMaxIntegrationSamples = 4096;
// Grid positions are computed in float; 1e-3 of a spacing is far above their rounding error and
// far below anything that would move a march sample visibly.
constexpr float kGridTolerance = 1e-3F;

// The distance from p to the closed rectangle [lo, hi] (0 inside).
float DistanceToRectangle(glm::vec2 p, glm::vec2 lo, glm::vec2 hi) {
    return glm::length(glm::max(glm::max(lo - p, p - hi), glm::vec2(0.0F)));
}

}  // namespace

std::optional<float> Heightfield::HeightAt(float x, float z) const {
    if (columns < 2 || rows < 2 || !(spacing > 0.0F)) {
        return std::nullopt;
    }
    const float fx = (x - origin.x) / spacing;
    const float fz = (z - origin.y) / spacing;
    const auto last_column = static_cast<float>(columns - 1);
    const auto last_row = static_cast<float>(rows - 1);
    // Written so that NaN fails every comparison and lands here too.
    if (!(fx >= 0.0F && fx <= last_column && fz >= 0.0F && fz <= last_row)) {
        return std::nullopt;
    }
    // The far edge belongs to the last cell, so column + 1 stays inside the grid.
    const int column = std::min(static_cast<int>(fx), columns - 2);
    const int row = std::min(static_cast<int>(fz), rows - 2);
    const float u = fx - static_cast<float>(column);
    const float v = fz - static_cast<float>(row);
    const std::size_t i = static_cast<std::size_t>(row) * static_cast<std::size_t>(columns) +
                          static_cast<std::size_t>(column);
    const std::size_t below = i + static_cast<std::size_t>(columns);
    const float near_row = heights[i] + u * (heights[i + 1] - heights[i]);
    const float far_row = heights[below] + u * (heights[below + 1] - heights[below]);
    return near_row + v * (far_row - near_row);
}

Heightfield TerrainHeightfield(const Scene& scene) {
    const int columns = scene.terrain_columns;
    const int rows = scene.terrain_rows;
    const std::vector<glm::vec3>& positions = scene.terrain.positions;
    // The grid comes first; the terrain may append more (the seabed skirt) after it.
    if (columns < 2 || rows < 2 ||
        static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows) > positions.size()) {
        return {};
    }
    std::vector<glm::vec3> world;
    const std::size_t grid_size =
            static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
    world.reserve(grid_size);
    for (std::size_t i = 0; i < grid_size; ++i) {
        world.emplace_back(scene.terrain.model_matrix * glm::vec4(positions[i], 1.0F));
    }
    Heightfield heightfield;
    heightfield.origin = {world[0].x, world[0].z};
    heightfield.spacing = world[1].x - world[0].x;
    heightfield.columns = columns;
    heightfield.rows = rows;
    if (!(heightfield.spacing > 0.0F)) {
        return {};
    }
    const float tolerance = kGridTolerance * heightfield.spacing;
    heightfield.heights.reserve(world.size());
    for (int row = 0; row < rows; ++row) {
        for (int column = 0; column < columns; ++column) {
            const glm::vec3& p =
                    world[static_cast<std::size_t>(row) * static_cast<std::size_t>(columns) +
                          static_cast<std::size_t>(column)];
            const glm::vec2 expected =
                    heightfield.origin + heightfield.spacing * glm::vec2(static_cast<float>(column),
                                                                         static_cast<float>(row));
            if (std::abs(p.x - expected.x) > tolerance || std::abs(p.z - expected.y) > tolerance) {
                return {};
            }
            heightfield.heights.push_back(p.y);
        }
    }
    return heightfield;
}

std::string CheckFourierSettings(const FourierSettings& settings) {
    if (settings.coefficients < 1 || settings.coefficients > kMaxCoefficients) {
        return "coefficients must be 1..8 (a0, a1, b1, a2, b2, a3, b3, a4), got " +
               std::to_string(settings.coefficients);
    }
    if (settings.directions < 3 || settings.directions > kMaxDirections) {
        return "directions must be 3..360 march directions, got " +
               std::to_string(settings.directions);
    }
    if (!(settings.march_distance > 0.0F) || !std::isfinite(settings.march_distance)) {
        return "march_distance must be a positive finite distance, got " +
               std::to_string(settings.march_distance);
    }
    if (settings.integration_samples < kMinIntegrationSamples ||
        settings.integration_samples > kMaxIntegrationSamples) {
        return "integration_samples must be 9..4096 (more than 2 per period of harmonic 4), "
               "got " +
               std::to_string(settings.integration_samples);
    }
    if (!(settings.grid_spacing > 0.0F) || !std::isfinite(settings.grid_spacing)) {
        return "grid_spacing must be a positive finite distance, got " +
               std::to_string(settings.grid_spacing);
    }
    if (!(settings.grid_margin >= 0.0F) || !std::isfinite(settings.grid_margin)) {
        return "grid_margin must be a finite distance >= 0, got " +
               std::to_string(settings.grid_margin);
    }
    return "";
}

std::vector<float> ElevationProfile(const Heightfield& heightfield, glm::vec2 point_xz,
                                    float water_height, int directions, float march_distance) {
    if (directions < 1) {
        return {};
    }
    std::vector<float> elevations(static_cast<std::size_t>(directions), 0.0F);
    if (heightfield.heights.empty() || !(heightfield.spacing > 0.0F) ||
        !(march_distance >= heightfield.spacing)) {
        return elevations;
    }
    const float step = heightfield.spacing;
    const auto steps = static_cast<int>(std::floor(march_distance / step));
    for (int j = 0; j < directions; ++j) {
        const double t = kTwoPi * static_cast<double>(j) / static_cast<double>(directions);
        // Azimuth t = atan2(z, x): the direction (cos t, sin t) in world (x, z).
        const glm::vec2 direction(static_cast<float>(std::cos(t)), static_cast<float>(std::sin(t)));
        float highest = 0.0F;  // terrain under the water reflects nothing
        for (int m = 1; m <= steps; ++m) {
            const float distance = step * static_cast<float>(m);
            const glm::vec2 p = point_xz + distance * direction;
            const std::optional<float> height = heightfield.HeightAt(p.x, p.y);
            if (height && *height > water_height) {
                highest = std::max(highest, std::atan2(*height - water_height, distance));
            }
        }
        elevations[static_cast<std::size_t>(j)] = highest;
    }
    return elevations;
}

std::array<float, 8> FourierCoefficients(const std::vector<float>& samples, int coefficients,
                                         int integration_samples) {
    std::array<float, 8> result{};
    if (samples.empty() || coefficients < 1 || coefficients > kMaxCoefficients ||
        integration_samples < 1) {
        return result;
    }
    const std::size_t k = samples.size();
    // Rectangle rule over one period: for a periodic function it equals the trapezoid rule.
    std::array<double, 8> sums{};
    for (int i = 0; i < integration_samples; ++i) {
        const double t = kTwoPi * static_cast<double>(i) / static_cast<double>(integration_samples);
        // Periodic linear interpolation: sample j sits at t = 2 pi j / k.
        const double position = static_cast<double>(i) * static_cast<double>(k) /
                                static_cast<double>(integration_samples);
        const auto j = static_cast<std::size_t>(position);
        const double fraction = position - static_cast<double>(j);
        const double a = samples[j % k];
        const double b = samples[(j + 1) % k];
        const double f = a + fraction * (b - a);
        sums[0] += f;
        for (int n = 1; n <= 4; ++n) {
            const double angle = static_cast<double>(n) * t;
            sums[2 * static_cast<std::size_t>(n) - 1] += f * std::cos(angle);
            if (n < 4) {
                sums[2 * static_cast<std::size_t>(n)] += f * std::sin(angle);
            }
        }
    }
    const auto count = static_cast<double>(integration_samples);
    for (int c = 0; c < coefficients; ++c) {
        // a0 is the mean; an, bn are (1 / pi) * integral = (2 / N) * sum.
        const double scale = c == 0 ? 1.0 / count : 2.0 / count;
        result[static_cast<std::size_t>(c)] =
                static_cast<float>(sums[static_cast<std::size_t>(c)] * scale);
    }
    return result;
}

float EvaluateFourier(const std::array<float, 8>& c, float t) {
    return c[0] + c[1] * std::cos(t) + c[2] * std::sin(t) + c[3] * std::cos(2.0F * t) +
           c[4] * std::sin(2.0F * t) + c[5] * std::cos(3.0F * t) + c[6] * std::sin(3.0F * t) +
           c[7] * std::cos(4.0F * t);
}

FourierWaterGrid BuildFourierWaterGrid(const Scene& scene, const FourierSettings& settings) {
    if (!CheckFourierSettings(settings).empty()) {
        return {};
    }
    const Heightfield heightfield = TerrainHeightfield(scene);
    if (heightfield.heights.empty()) {
        return {};
    }
    const glm::vec2 terrain_min = heightfield.origin;
    const glm::vec2 terrain_max =
            heightfield.origin +
            heightfield.spacing * glm::vec2(static_cast<float>(heightfield.columns - 1),
                                            static_cast<float>(heightfield.rows - 1));
    const glm::vec2 centre = 0.5F * (terrain_min + terrain_max);
    const glm::vec2 extent = terrain_max - terrain_min + 2.0F * settings.grid_margin;
    // Whole cells of exactly grid_spacing, so the grid grows (centred) rather than stretches.
    const double cells_x = std::ceil(static_cast<double>(extent.x / settings.grid_spacing));
    const double cells_z = std::ceil(static_cast<double>(extent.y / settings.grid_spacing));
    constexpr double kMaxVertices = std::numeric_limits<std::uint16_t>::max() + 1.0;
    // Grid vertices plus one skirt vertex per edge vertex: 2 (cells_x + cells_z) of them.
    if ((cells_x + 1.0) * (cells_z + 1.0) + 2.0 * (cells_x + cells_z) >= kMaxVertices) {
        return {};
    }
    const int columns = static_cast<int>(cells_x) + 1;
    const int rows = static_cast<int>(cells_z) + 1;
    const glm::vec2 grid_min = centre - 0.5F * settings.grid_spacing *
                                                glm::vec2(static_cast<float>(columns - 1),
                                                          static_cast<float>(rows - 1));

    // The coefficients are linear in the k samples (interpolation and integration both are), so
    // FourierCoefficients of the k unit vectors gives a k x 8 matrix that turns every vertex's
    // profile into its coefficients with 8k multiply-adds instead of 8 x 400 sines and cosines.
    const auto k = static_cast<std::size_t>(settings.directions);
    std::vector<std::array<float, 8>> basis(k);
    for (std::size_t j = 0; j < k; ++j) {
        std::vector<float> unit(k, 0.0F);
        unit[j] = 1.0F;
        basis[j] = FourierCoefficients(unit, settings.coefficients, settings.integration_samples);
    }
    const float highest_terrain =
            *std::max_element(heightfield.heights.begin(), heightfield.heights.end());
    const bool terrain_above_water = highest_terrain > scene.water_height;

    FourierWaterGrid grid;
    const std::size_t grid_vertices =
            static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
    const std::size_t total = grid_vertices + 2 * static_cast<std::size_t>(columns + rows - 2);
    grid.positions.reserve(total);
    grid.coefficients0.reserve(total);
    grid.coefficients1.reserve(total);
    for (int row = 0; row < rows; ++row) {
        for (int column = 0; column < columns; ++column) {
            const glm::vec2 p =
                    grid_min + settings.grid_spacing * glm::vec2(static_cast<float>(column),
                                                                 static_cast<float>(row));
            std::array<float, 8> c{};
            // Beyond march_distance of the heightfield every march sees nothing: skip it.
            if (terrain_above_water &&
                DistanceToRectangle(p, terrain_min, terrain_max) <= settings.march_distance) {
                const std::vector<float> profile =
                        ElevationProfile(heightfield, p, scene.water_height, settings.directions,
                                         settings.march_distance);
                for (std::size_t j = 0; j < k; ++j) {
                    if (profile[j] != 0.0F) {
                        for (std::size_t n = 0; n < c.size(); ++n) {
                            c[n] += profile[j] * basis[j][n];
                        }
                    }
                }
            }
            grid.positions.emplace_back(p.x, scene.water_height, p.y);
            grid.coefficients0.emplace_back(c[0], c[1], c[2], c[3]);
            grid.coefficients1.emplace_back(c[4], c[5], c[6], c[7]);
        }
    }
    auto vertex = [&](int row, int column) {
        return static_cast<std::uint16_t>(row * columns + column);
    };
    // Rows run along +z and columns along +x, so (row step) x (column step) = +y, as the terrain.
    for (int row = 0; row + 1 < rows; ++row) {
        for (int column = 0; column + 1 < columns; ++column) {
            grid.indices.insert(grid.indices.end(),
                                {vertex(row, column), vertex(row + 1, column),
                                 vertex(row, column + 1), vertex(row + 1, column),
                                 vertex(row + 1, column + 1), vertex(row, column + 1)});
        }
    }

    // The edge walked once around: along row 0, up the last column, back along the last row,
    // down column 0.
    std::vector<std::uint16_t> edge;
    for (int column = 0; column + 1 < columns; ++column) {
        edge.push_back(vertex(0, column));
    }
    for (int row = 0; row + 1 < rows; ++row) {
        edge.push_back(vertex(row, columns - 1));
    }
    for (int column = columns - 1; column > 0; --column) {
        edge.push_back(vertex(rows - 1, column));
    }
    for (int row = rows - 1; row > 0; --row) {
        edge.push_back(vertex(row, 0));
    }
    // Each edge vertex moves out to the skirt square by an affine stretch about the centre, which
    // maps the grid's rectangle onto the square, edge onto edge and corner onto corner.
    const glm::vec2 grid_half = centre - grid_min;
    // A coarse grid could reach past the skirt square; the skirt then moves out to stay outside.
    const float skirt_half =
            std::max(kFourierSkirtHalfSize, 2.0F * std::max(grid_half.x, grid_half.y));
    const glm::vec2 stretch = glm::vec2(skirt_half) / grid_half;
    std::vector<std::uint16_t> skirt;
    skirt.reserve(edge.size());
    for (std::uint16_t e : edge) {
        const glm::vec2 p(grid.positions[e].x, grid.positions[e].z);
        const glm::vec2 q = centre + (p - centre) * stretch;
        skirt.push_back(static_cast<std::uint16_t>(grid.positions.size()));
        grid.positions.emplace_back(q.x, scene.water_height, q.y);
        // Open sea: 20000 units from 25-unit hills is an elevation below 0.1 degree.
        grid.coefficients0.emplace_back(0.0F);
        grid.coefficients1.emplace_back(0.0F);
    }
    // Which way round the edge walk turns is fixed above, but spelling out each side's order is
    // error-prone; every skirt triangle is checked and flipped to face +y instead.
    auto add_upward = [&](std::uint16_t a, std::uint16_t b, std::uint16_t c) {
        const glm::vec3 normal = glm::cross(grid.positions[b] - grid.positions[a],
                                            grid.positions[c] - grid.positions[a]);
        if (normal.y < 0.0F) {
            std::swap(b, c);
        }
        grid.indices.insert(grid.indices.end(), {a, b, c});
    };
    for (std::size_t i = 0; i < edge.size(); ++i) {
        const std::size_t next = (i + 1) % edge.size();
        add_upward(edge[i], skirt[i], edge[next]);
        add_upward(edge[next], skirt[i], skirt[next]);
    }
    return grid;
}

}  // namespace tidepool::runner
