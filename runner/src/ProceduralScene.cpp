#include "tidepool/runner/ProceduralScene.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <utility>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace tidepool::runner {
namespace {

constexpr float kPi = glm::pi<float>();
constexpr float kTwoPiF = 2.0F * kPi;

// ---------------------------------------------------------------------------------------------
// Deterministic noise: a 32-bit integer hash (Wellons' "lowbias32"), never rand().

std::uint32_t Hash(std::uint32_t x) {
    x ^= x >> 16U;
    x *= 0x7feb352dU;
    x ^= x >> 15U;
    x *= 0x846ca68bU;
    x ^= x >> 16U;
    return x;
}

// A hash of `seed` mapped to [0, 1); 24 bits is all a float mantissa holds.
float HashUnit(std::uint32_t seed) {
    return static_cast<float>(Hash(seed) >> 8U) / 16777216.0F;
}

// ---------------------------------------------------------------------------------------------
// Images and cube maps.

std::uint8_t ToByte(float value) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0F, 1.0F) * 255.0F));
}

base::RgbaImage MakeImage(int width, int height) {
    return {width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width * height) * 4)};
}

void StoreTexel(base::RgbaImage& image, int column, int row, const glm::vec3& rgb) {
    const auto offset = static_cast<std::size_t>(row * image.width + column) * 4;
    image.pixels[offset + 0] = ToByte(rgb.r);
    image.pixels[offset + 1] = ToByte(rgb.g);
    image.pixels[offset + 2] = ToByte(rgb.b);
    image.pixels[offset + 3] = 255;
}

// The direction of face coordinates (sc, tc) in [-1, 1]: GLES 2 spec table 3.21 solved for the
// direction, e.g. +X has sc = -z, tc = -y, major axis x.
glm::vec3 FaceDirection(int face, float sc, float tc) {
    switch (face) {
        case 0:
            return {1.0F, -tc, -sc};
        case 1:
            return {-1.0F, -tc, sc};
        case 2:
            return {sc, 1.0F, tc};
        case 3:
            return {sc, -1.0F, -tc};
        case 4:
            return {sc, -tc, 1.0F};
        default:
            return {-sc, -tc, -1.0F};
    }
}

template <typename ColourOfDirection>
CubeMapImage BuildCubeMap(int size, ColourOfDirection colour_of) {
    if (size < 1) {
        return {};
    }
    CubeMapImage cube_map{size, {}};
    for (int face = 0; face < 6; ++face) {
        base::RgbaImage& image = cube_map.faces[static_cast<std::size_t>(face)];
        image = MakeImage(size, size);
        for (int row = 0; row < size; ++row) {
            for (int column = 0; column < size; ++column) {
                StoreTexel(image, column, row,
                           colour_of(CubeMapTexelDirection(face, size, column, row)));
            }
        }
    }
    return cube_map;
}

// A soft cloud: a gaussian blob of angular radius `radius` around `direction`.
struct CloudPuff {
    glm::vec3 direction;
    float radius;
};

std::vector<CloudPuff> MakeClouds() {
    constexpr std::uint32_t kClouds = 6;
    constexpr std::uint32_t kPuffsPerCloud = 4;
    std::vector<CloudPuff> puffs;
    for (std::uint32_t cloud = 0; cloud < kClouds; ++cloud) {
        const float azimuth = kTwoPiF * HashUnit(cloud * 16U + 1U);
        // Between 6 and 30 degrees up: low enough to be seen (and reflected) from the views.
        const float elevation = glm::radians(6.0F + 24.0F * HashUnit(cloud * 16U + 2U));
        for (std::uint32_t puff = 0; puff < kPuffsPerCloud; ++puff) {
            // Puffs strung out horizontally make a cloud look flat-bottomed and wide.
            const float a = azimuth + 0.12F * (HashUnit(cloud * 16U + 3U + puff) - 0.5F) +
                            0.06F * static_cast<float>(puff);
            const float e = elevation + 0.03F * (HashUnit(cloud * 16U + 8U + puff) - 0.5F);
            const float radius = glm::radians(4.0F + 5.0F * HashUnit(cloud * 16U + 12U + puff));
            puffs.push_back(
                    {{std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a)}, radius});
        }
    }
    return puffs;
}

glm::vec3 SkyColour(const glm::vec3& direction, const glm::vec3& sun,
                    const std::vector<CloudPuff>& clouds) {
    constexpr glm::vec3 kHorizon(0.78F, 0.86F, 0.93F);
    constexpr glm::vec3 kZenith(0.10F, 0.28F, 0.65F);
    constexpr glm::vec3 kBelowHorizon(0.16F, 0.20F, 0.26F);
    constexpr glm::vec3 kCloud(0.97F, 0.97F, 0.99F);
    constexpr glm::vec3 kSun(1.0F, 0.97F, 0.88F);
    constexpr glm::vec3 kSunGlow(1.0F, 0.85F, 0.6F);

    const float elevation = direction.y;
    glm::vec3 sky = glm::mix(kHorizon, kZenith, std::pow(std::max(elevation, 0.0F), 0.6F));
    float cover = 0.0F;
    for (const CloudPuff& puff : clouds) {
        const float angle = std::acos(std::clamp(glm::dot(direction, puff.direction), -1.0F, 1.0F));
        cover = std::max(cover, std::exp(-(angle * angle) / (puff.radius * puff.radius)));
    }
    sky = glm::mix(sky, kCloud, 0.85F * cover);
    const float cos_sun = std::max(glm::dot(direction, sun), 0.0F);
    sky += kSunGlow * (0.5F * std::pow(cos_sun, 300.0F) + 0.15F * std::pow(cos_sun, 12.0F));
    // A 2-degree disc (four times the real sun) stays visible at cube-map sizes down to 64.
    const float disc =
            glm::smoothstep(std::cos(glm::radians(2.0F)), std::cos(glm::radians(1.6F)), cos_sun);
    sky = glm::mix(sky, kSun, disc);
    // A narrow blend instead of a hard step, so bilinear filtering shows no seam at the horizon.
    return glm::mix(kBelowHorizon, sky, glm::smoothstep(-0.02F, 0.0F, elevation));
}

// ---------------------------------------------------------------------------------------------
// Water normal map.

// A sine wave over the unit tile; integer frequencies make the sum periodic in s and t.
struct Wave {
    int frequency_s;
    int frequency_t;
    float slope;  // largest slope the wave contributes, so the sum's tilt is bounded
    float phase;
};

// Slopes sum to 0.5, a tilt of at most 27 degrees, so n.z always stays the largest component.
constexpr std::array<Wave, 6> kWaves{{{1, 2, 0.11F, 0.0F},
                                      {3, -1, 0.10F, 1.3F},
                                      {-2, 5, 0.09F, 2.1F},
                                      {6, 3, 0.08F, 0.7F},
                                      {-7, -4, 0.07F, 4.0F},
                                      {11, -9, 0.05F, 5.5F}}};

// ---------------------------------------------------------------------------------------------
// Mesh building.

// Appends a grid of (rows + 1) x (cols + 1) vertices at point(row / rows, col / cols), wound so
// that (d point / d row) x (d point / d col) faces the front. Normals are smooth inside the grid
// (a lathe's seam and poles included) and creased against other grids.
template <typename PointFn>
void AppendGrid(Mesh& mesh, int rows, int cols, const glm::vec3& colour, PointFn point) {
    const std::size_t base = mesh.positions.size();
    const auto stride = static_cast<std::size_t>(cols) + 1;
    for (int i = 0; i <= rows; ++i) {
        for (int j = 0; j <= cols; ++j) {
            mesh.positions.push_back(point(static_cast<float>(i) / static_cast<float>(rows),
                                           static_cast<float>(j) / static_cast<float>(cols)));
            mesh.normals.emplace_back(0.0F);
            mesh.colours.push_back(colour);
        }
    }
    // GLES 2 draws with 16-bit indices only.
    assert(mesh.positions.size() <= std::numeric_limits<std::uint16_t>::max() + std::size_t{1});
    auto vertex = [&](int i, int j) {
        return base + static_cast<std::size_t>(i) * stride + static_cast<std::size_t>(j);
    };
    auto add_triangle = [&](std::size_t a, std::size_t b, std::size_t c) {
        const glm::vec3 area_normal = glm::cross(mesh.positions[b] - mesh.positions[a],
                                                 mesh.positions[c] - mesh.positions[a]);
        for (std::size_t v : {a, b, c}) {
            mesh.indices.push_back(static_cast<std::uint16_t>(v));
            mesh.normals[v] += area_normal;  // area-weighted, so slivers barely count
        }
    };
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            add_triangle(vertex(i, j), vertex(i + 1, j), vertex(i, j + 1));
            add_triangle(vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1));
        }
    }
    // Vertices at the same place (rounded to 1e-4 units, far above the float error of sin(2 pi)
    // or cos(pi / 2) and far below the spacing of distinct vertices) share their normals, unless
    // the surfaces meet at a crease sharper than 60 degrees, such as the hull's stem.
    constexpr float kCreaseCos = 0.5F;
    std::map<std::array<long, 3>, std::vector<std::size_t>> same_place;
    for (std::size_t v = base; v < mesh.positions.size(); ++v) {
        const glm::vec3& p = mesh.positions[v];
        same_place[{std::lround(p.x * 1e4F), std::lround(p.y * 1e4F), std::lround(p.z * 1e4F)}]
                .push_back(v);
    }
    const std::vector<glm::vec3> accumulated(mesh.normals.begin(), mesh.normals.end());
    for (const auto& [place, vertices] : same_place) {
        for (std::size_t v : vertices) {
            glm::vec3 sum(0.0F);
            for (std::size_t w : vertices) {
                const float lengths = glm::length(accumulated[v]) * glm::length(accumulated[w]);
                if (glm::dot(accumulated[v], accumulated[w]) >= kCreaseCos * lengths) {
                    sum += accumulated[w];
                }
            }
            const float length = glm::length(sum);
            mesh.normals[v] = length > 0.0F ? sum / length : glm::vec3(0.0F, 1.0F, 0.0F);
        }
    }
}

// Appends a surface of revolution about the object's y axis; profile(s) gives (radius, y) for
// s in [0, 1]. A profile walking from the bottom outwards and up faces outwards.
template <typename ProfileFn>
void AppendLathe(Mesh& mesh, int rows, int segments, const glm::vec3& colour, ProfileFn profile) {
    AppendGrid(mesh, rows, segments, colour, [&](float s, float turn) {
        const glm::vec2 radius_y = profile(s);
        const float angle = kTwoPiF * turn;
        return glm::vec3(radius_y.x * std::cos(angle), radius_y.y, radius_y.x * std::sin(angle));
    });
}

// A closed vertical cylinder (or cone when top_radius is 0) with flat caps.
void AppendCylinder(Mesh& mesh, float bottom, float top, float bottom_radius, float top_radius,
                    int segments, const glm::vec3& colour) {
    AppendLathe(mesh, 1, segments, colour,
                [&](float s) { return glm::vec2(bottom_radius * s, bottom); });
    AppendLathe(mesh, 1, segments, colour, [&](float s) {
        return glm::vec2(glm::mix(bottom_radius, top_radius, s), glm::mix(bottom, top, s));
    });
    if (top_radius > 0.0F) {
        AppendLathe(mesh, 1, segments, colour,
                    [&](float s) { return glm::vec2(top_radius * (1.0F - s), top); });
    }
}

// An axis-aligned box; each face is its own grid, so the edges stay sharp.
void AppendBox(Mesh& mesh, const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& colour) {
    const glm::vec3 size = hi - lo;
    const glm::vec3 x(size.x, 0, 0), y(0, size.y, 0), z(0, 0, size.z);
    // (origin, row edge, column edge) with row edge x column edge pointing out of the box.
    const std::array<std::array<glm::vec3, 3>, 6> faces{{{glm::vec3(hi.x, lo.y, lo.z), y, z},
                                                         {lo, z, y},
                                                         {glm::vec3(lo.x, hi.y, lo.z), z, x},
                                                         {lo, x, z},
                                                         {glm::vec3(lo.x, lo.y, hi.z), x, y},
                                                         {lo, y, x}}};
    for (const auto& face : faces) {
        AppendGrid(mesh, 1, 1, colour,
                   [&](float r, float c) { return face[0] + r * face[1] + c * face[2]; });
    }
}

// A sphere of `radius` scaled per axis by `stretch`, its radius modulated by `bumpiness` times a
// smooth function of direction (so the seam and the poles stay closed).
void AppendBlob(Mesh& mesh, float radius, const glm::vec3& stretch, float bumpiness,
                std::uint32_t seed, const glm::vec3& colour) {
    const glm::vec3 phase(kTwoPiF * HashUnit(seed), kTwoPiF * HashUnit(seed + 1U),
                          kTwoPiF * HashUnit(seed + 2U));
    AppendGrid(mesh, 16, 24, colour, [&](float s, float turn) {
        const float latitude = kPi * (s - 0.5F);
        const float longitude = kTwoPiF * turn;
        const glm::vec3 d(std::cos(latitude) * std::cos(longitude), std::sin(latitude),
                          std::cos(latitude) * std::sin(longitude));
        const float bump = std::sin(2.7F * d.x + phase.x) * std::sin(3.1F * d.y + phase.y) *
                           std::sin(2.3F * d.z + phase.z);
        return d * stretch * (radius * (1.0F + bumpiness * bump));
    });
}

void FinishMesh(Mesh& mesh) {
    mesh.world_bounds_min = glm::vec3(std::numeric_limits<float>::max());
    mesh.world_bounds_max = glm::vec3(std::numeric_limits<float>::lowest());
    for (const glm::vec3& p : mesh.positions) {
        const glm::vec3 world(mesh.model_matrix * glm::vec4(p, 1.0F));
        mesh.world_bounds_min = glm::min(mesh.world_bounds_min, world);
        mesh.world_bounds_max = glm::max(mesh.world_bounds_max, world);
    }
}

Mesh MakeMesh(std::string name, const glm::mat4& model_matrix) {
    Mesh mesh;
    mesh.name = std::move(name);
    mesh.model_matrix = model_matrix;
    return mesh;
}

// ---------------------------------------------------------------------------------------------
// The island.

constexpr glm::vec2 kIslandCentre(-30.0F, -30.0F);
constexpr float kTerrainHalfSize = 100.0F;
constexpr int kTerrainSegments = 128;  // 129 x 129 = 16641 vertices

// Ground height of the island: a gaussian hill from the -20 seabed to about +22, roughened by a
// few sines that fade on the flat seabed. The shore (height 0) is about 43 units from the centre.
float TerrainHeight(float x, float z) {
    const float r = glm::length(glm::vec2(x, z) - kIslandCentre) / 50.0F;
    const float island = std::exp(-r * r);
    const float roughness = 2.5F * std::sin(0.11F * x + 0.7F) * std::sin(0.13F * z + 1.9F) +
                            1.2F * std::sin(0.31F * x - 0.23F * z + 0.4F);
    return -20.0F + 42.0F * island + roughness * (0.3F + 0.7F * island);
}

// Lowest ground under a disc, so an object standing there never floats above the slope.
float LowestGroundUnder(const glm::vec2& centre, float radius) {
    float lowest = TerrainHeight(centre.x, centre.y);
    for (int k = 0; k < 16; ++k) {
        const float a = kTwoPiF * static_cast<float>(k) / 16.0F;
        lowest = std::min(lowest, TerrainHeight(centre.x + radius * std::cos(a),
                                                centre.y + radius * std::sin(a)));
    }
    return lowest;
}

// How far the seabed reaches: the longest view range a scene description allows (10000), so the
// floor meets the far plane from any camera and the refraction never shows the clear colour
// past a floor edge.
constexpr float kSeabedSkirtHalfSize = 10000.0F;
constexpr float kSeabedHeight = -20.0F;

// Appends a flat skirt around the border of the (segments + 1)^2 grid that starts the mesh: one
// new vertex per border vertex, pushed out along its direction from the centre to the square
// of half-size kSeabedSkirtHalfSize at the seabed's height, and two triangles per border edge.
// The grid's vertices stay first and unchanged (FourierReflection.h marches them as a grid).
void AppendSeabedSkirt(Mesh& mesh, int segments) {
    const auto stride = static_cast<std::size_t>(segments) + 1;
    const auto last = static_cast<std::size_t>(segments);
    auto at = [&](std::size_t row, std::size_t column) { return row * stride + column; };
    std::vector<std::size_t> border;  // walked once around, each corner once
    for (std::size_t k = 0; k < last; ++k)
        border.push_back(at(0, k));
    for (std::size_t k = 0; k < last; ++k)
        border.push_back(at(k, last));
    for (std::size_t k = last; k > 0; --k)
        border.push_back(at(last, k));
    for (std::size_t k = last; k > 0; --k)
        border.push_back(at(k, 0));
    const std::size_t base = mesh.positions.size();
    for (std::size_t v : border) {
        const glm::vec3 inner = mesh.positions[v];
        const float scale = kSeabedSkirtHalfSize / std::max(std::abs(inner.x), std::abs(inner.z));
        mesh.positions.emplace_back(inner.x * scale, kSeabedHeight, inner.z * scale);
        mesh.normals.emplace_back(0.0F, 1.0F, 0.0F);
        mesh.colours.push_back(mesh.colours[v]);
    }
    assert(mesh.positions.size() <= std::numeric_limits<std::uint16_t>::max() + std::size_t{1});
    auto add_triangle = [&](std::size_t a, std::size_t b, std::size_t c) {
        const glm::vec3 face = glm::cross(mesh.positions[b] - mesh.positions[a],
                                          mesh.positions[c] - mesh.positions[a]);
        if (face.y < 0.0F) {
            std::swap(b, c);  // front faces up, as the grid's
        }
        for (std::size_t v : {a, b, c}) {
            mesh.indices.push_back(static_cast<std::uint16_t>(v));
        }
    };
    for (std::size_t k = 0; k < border.size(); ++k) {
        const std::size_t next = (k + 1) % border.size();
        add_triangle(border[k], border[next], base + next);
        add_triangle(border[k], base + next, base + k);
    }
}

Mesh BuildTerrain() {
    Mesh terrain = MakeMesh("terrain", glm::mat4(1.0F));
    // Rows run along +z and columns along +x, so z x x = +y: triangles face up.
    AppendGrid(terrain, kTerrainSegments, kTerrainSegments, glm::vec3(0.0F), [](float s, float t) {
        const float x = kTerrainHalfSize * (2.0F * t - 1.0F);
        const float z = kTerrainHalfSize * (2.0F * s - 1.0F);
        return glm::vec3(x, TerrainHeight(x, z), z);
    });
    AppendSeabedSkirt(terrain, kTerrainSegments);
    constexpr glm::vec3 kSeabed(0.62F, 0.58F, 0.42F);
    constexpr glm::vec3 kSand(0.86F, 0.80F, 0.58F);
    constexpr glm::vec3 kGrass(0.30F, 0.55F, 0.22F);
    constexpr glm::vec3 kRock(0.50F, 0.48F, 0.45F);
    for (std::size_t v = 0; v < terrain.positions.size(); ++v) {
        const float height = terrain.positions[v].y;
        glm::vec3& colour = terrain.colours[v];
        colour = height < -1.0F ? kSeabed : height < 2.0F ? kSand : height < 15.0F ? kGrass : kRock;
        // Slopes steeper than about 45 degrees show bare rock above the beach.
        if (height >= 2.0F && terrain.normals[v].y < 0.7F) {
            colour = kRock;
        }
    }
    FinishMesh(terrain);
    return terrain;
}

Mesh BuildHull() {
    constexpr float kLength = 18.0F;
    constexpr float kBeam = 6.0F;
    constexpr float kDepth = 3.0F;
    constexpr float kDeckHeight = 1.4F;  // deck above the water; the keel is 1.6 below it
    const glm::mat4 model =
            glm::rotate(glm::translate(glm::mat4(1.0F), {25.0F, kDeckHeight, 18.0F}),
                        glm::radians(35.0F), glm::vec3(0.0F, 1.0F, 0.0F));
    Mesh hull = MakeMesh("hull", model);
    // Half-width along the length u in [-1, 1]: pointed at the bow (+x), blunt at the stern.
    auto half_beam = [](float u) {
        return 0.5F * kBeam * (u > 0.0F ? 1.0F - u * u : 1.0F - std::pow(u, 6.0F));
    };
    auto depth = [](float u) { return kDepth * (1.0F - 0.5F * u * u); };
    // Rows go around the cross-section from one gunwale under the keel to the other (-z at the
    // keel), columns along +x: (-z) x x = -y, facing out of the bottom.
    AppendGrid(hull, 12, 24, glm::vec3(0.90F, 0.08F, 0.06F), [&](float s, float t) {
        const float u = 2.0F * t - 1.0F;
        const float angle = kPi * s;
        return glm::vec3(0.5F * kLength * u, -depth(u) * std::sin(angle),
                         half_beam(u) * std::cos(angle));
    });
    AppendGrid(hull, 1, 24, glm::vec3(0.60F, 0.10F, 0.08F), [&](float s, float t) {
        const float u = 2.0F * t - 1.0F;
        return glm::vec3(0.5F * kLength * u, 0.0F, half_beam(u) * (2.0F * s - 1.0F));
    });
    AppendBox(hull, {-5.0F, 0.0F, -1.8F}, {0.0F, 2.2F, 1.8F}, glm::vec3(0.95F, 0.30F, 0.25F));
    FinishMesh(hull);
    return hull;
}

Mesh BuildPillar(int index, const glm::vec2& where) {
    constexpr float kRadius = 1.6F;
    constexpr float kTop = 14.0F;
    Mesh pillar = MakeMesh("pillar_" + std::to_string(index),
                           glm::translate(glm::mat4(1.0F), glm::vec3(where.x, 0.0F, where.y)));
    const float bottom = LowestGroundUnder(where, kRadius) - 1.0F;  // sunk into the seabed
    AppendCylinder(pillar, bottom, kTop, kRadius, kRadius, 20, glm::vec3(0.95F, 0.85F, 0.10F));
    FinishMesh(pillar);
    return pillar;
}

Mesh BuildSubmergedRock(int index, float angle_degrees, float distance) {
    const float a = glm::radians(angle_degrees);
    const glm::vec2 where = kIslandCentre + distance * glm::vec2(std::cos(a), std::sin(a));
    // Centred half a unit above the slope: half buried, top several units under the water.
    const glm::vec3 centre(where.x, TerrainHeight(where.x, where.y) + 0.5F, where.y);
    Mesh rock = MakeMesh("submerged_rock_" + std::to_string(index),
                         glm::translate(glm::mat4(1.0F), centre));
    AppendBlob(rock, 2.5F, {1.1F, 0.6F, 0.9F}, 0.2F, 100U + static_cast<std::uint32_t>(index),
               glm::vec3(0.90F, 0.10F, 0.80F));
    FinishMesh(rock);
    return rock;
}

Mesh BuildTower() {
    constexpr float kRadius = 3.0F;
    // On the seaward slope, facing the default views, so its reflection lies in open water.
    const glm::vec2 where(-8.8F, -8.8F);
    const float base = LowestGroundUnder(where, kRadius) - 1.0F;
    Mesh tower =
            MakeMesh("tower", glm::translate(glm::mat4(1.0F), glm::vec3(where.x, base, where.y)));
    constexpr glm::vec3 kOrange(1.0F, 0.50F, 0.05F);
    AppendCylinder(tower, 0.0F, 22.0F, kRadius, kRadius, 16, kOrange);
    AppendCylinder(tower, 22.0F, 28.0F, kRadius + 0.8F, 0.0F, 16, kOrange * 0.8F);
    FinishMesh(tower);
    return tower;
}

Mesh BuildSphere() {
    constexpr float kRadius = 4.0F;
    const float ground = TerrainHeight(kIslandCentre.x, kIslandCentre.y);
    Mesh sphere = MakeMesh(
            "sphere", glm::translate(glm::mat4(1.0F), glm::vec3(kIslandCentre.x, ground + kRadius,
                                                                kIslandCentre.y)));
    AppendBlob(sphere, kRadius, glm::vec3(1.0F), 0.0F, 0U, glm::vec3(0.10F, 0.90F, 0.90F));
    FinishMesh(sphere);
    return sphere;
}

}  // namespace

glm::vec3 CubeMapTexelDirection(int face, int size, int column, int row) {
    const float sc = 2.0F * (static_cast<float>(column) + 0.5F) / static_cast<float>(size) - 1.0F;
    const float tc = 2.0F * (static_cast<float>(row) + 0.5F) / static_cast<float>(size) - 1.0F;
    return glm::normalize(FaceDirection(face, sc, tc));
}

glm::u8vec4 SampleCubeMapNearest(const CubeMapImage& cube_map, const glm::vec3& direction) {
    const glm::vec3 a = glm::abs(direction);
    if (cube_map.size < 1 || (a.x == 0.0F && a.y == 0.0F && a.z == 0.0F)) {
        return glm::u8vec4(0);
    }
    // The major axis picks the face; then (sc, tc, ma) from GLES 2 spec table 3.21.
    int face = 0;
    float sc = 0.0F, tc = 0.0F, ma = 0.0F;
    if (a.x >= a.y && a.x >= a.z) {
        face = direction.x > 0.0F ? 0 : 1;
        sc = direction.x > 0.0F ? -direction.z : direction.z;
        tc = -direction.y;
        ma = a.x;
    } else if (a.y >= a.z) {
        face = direction.y > 0.0F ? 2 : 3;
        sc = direction.x;
        tc = direction.y > 0.0F ? direction.z : -direction.z;
        ma = a.y;
    } else {
        face = direction.z > 0.0F ? 4 : 5;
        sc = direction.z > 0.0F ? direction.x : -direction.x;
        tc = -direction.y;
        ma = a.z;
    }
    auto texel = [&](float coordinate) {
        const float st = 0.5F * (coordinate / ma + 1.0F);
        return std::clamp(static_cast<int>(std::floor(st * static_cast<float>(cube_map.size))), 0,
                          cube_map.size - 1);
    };
    const base::RgbaImage& image = cube_map.faces[static_cast<std::size_t>(face)];
    const auto offset = static_cast<std::size_t>(texel(tc) * image.width + texel(sc)) * 4;
    return {image.pixels[offset], image.pixels[offset + 1], image.pixels[offset + 2],
            image.pixels[offset + 3]};
}

CubeMapImage BuildSkyCubeMap(int size, glm::vec3 sun_direction) {
    const glm::vec3 sun = glm::normalize(sun_direction);
    const std::vector<CloudPuff> clouds = MakeClouds();
    return BuildCubeMap(size, [&](const glm::vec3& d) { return SkyColour(d, sun, clouds); });
}

CubeMapImage BuildNormalisationCubeMap(int size) {
    return BuildCubeMap(size, [](const glm::vec3& d) { return d * 0.5F + 0.5F; });
}

base::RgbaImage BuildWaterNormalMap(int size) {
    if (size < 1) {
        return {};
    }
    base::RgbaImage image = MakeImage(size, size);
    for (int row = 0; row < size; ++row) {
        for (int column = 0; column < size; ++column) {
            // Texel centres, as the sampler sees them.
            const glm::vec2 st((static_cast<float>(column) + 0.5F) / static_cast<float>(size),
                               (static_cast<float>(row) + 0.5F) / static_cast<float>(size));
            // h = sum a sin(2 pi k.st + phase) with a = slope / (2 pi |k|), so the gradient is
            // sum slope (k / |k|) cos(...) and each wave's steepest slope is exactly `slope`.
            glm::vec2 gradient(0.0F);
            for (const Wave& wave : kWaves) {
                const glm::vec2 k(static_cast<float>(wave.frequency_s),
                                  static_cast<float>(wave.frequency_t));
                gradient += wave.slope * glm::normalize(k) *
                            std::cos(kTwoPiF * glm::dot(k, st) + wave.phase);
            }
            const glm::vec3 normal = glm::normalize(glm::vec3(-gradient, 1.0F));
            StoreTexel(image, column, row, normal * 0.5F + 0.5F);
        }
    }
    return image;
}

Scene BuildDefaultScene() {
    Scene scene;
    scene.water_height = 0.0F;
    scene.sun_direction = glm::normalize(glm::vec3(0.45F, 0.6F, -0.65F));
    scene.terrain = BuildTerrain();
    scene.terrain_columns = kTerrainSegments + 1;
    scene.terrain_rows = kTerrainSegments + 1;
    scene.objects.push_back(BuildHull());
    const std::array<glm::vec2, 3> pillars{{{15.0F, 35.0F}, {42.0F, 40.0F}, {48.0F, 8.0F}}};
    for (std::size_t i = 0; i < pillars.size(); ++i) {
        scene.objects.push_back(BuildPillar(static_cast<int>(i), pillars[i]));
    }
    const std::array<float, 3> rock_angles{25.0F, 45.0F, 65.0F};
    for (std::size_t i = 0; i < rock_angles.size(); ++i) {
        scene.objects.push_back(BuildSubmergedRock(static_cast<int>(i), rock_angles[i], 55.0F));
    }
    scene.objects.push_back(BuildTower());
    scene.objects.push_back(BuildSphere());
    return scene;
}

Scene BuildSceneFromDescription(const SceneDescription& description) {
    Scene scene = BuildDefaultScene();
    // The default seabed lies at -20 (TerrainHeight far from the island).
    constexpr float kDefaultSeabed = 20.0F;
    // Moved rocks stay this far below the water: below the 0.5-unit
    // sliver the reflection's clip plane keeps (RenderSettings::clip_plane_offset), so the
    // reflection pass culls them as wholly under water.
    constexpr float kSubmergedClearance = 0.6F;
    const float depth_scale = description.water_depth / kDefaultSeabed;
    auto reshape = [&](float y) {
        if (y < scene.water_height) {
            y = scene.water_height + (y - scene.water_height) * depth_scale;
        }
        return y;
    };
    // Only heights change, so the terrain keeps BuildDefaultScene's grid layout, flat floor too.
    for (glm::vec3& p : scene.terrain.positions) {
        // Without the island the floor is flat at the water's depth (open water).
        p.y = description.above_terrain ? reshape(p.y)
                                        : scene.water_height - description.water_depth;
    }
    FinishMesh(scene.terrain);
    std::vector<Mesh> kept;
    for (Mesh& object : scene.objects) {
        const bool below = IsEntirelyBelow(object, scene.water_height);
        const bool above = IsEntirelyAbove(object, scene.water_height);
        // Hull and pillars cross the water: they are seen above it, so `above` decides.
        const bool wanted = below ? description.below_objects : description.above_objects;
        if (!wanted) {
            continue;
        }
        if (below) {
            // Whole rocks move with the floor under them, their top kept under the water.
            const float centre = 0.5F * (object.world_bounds_min.y + object.world_bounds_max.y);
            float shift = reshape(centre) - centre;
            shift = std::min(shift,
                             scene.water_height - kSubmergedClearance - object.world_bounds_max.y);
            object.model_matrix = glm::translate(glm::mat4(1.0F), glm::vec3(0.0F, shift, 0.0F)) *
                                  object.model_matrix;
        } else if (!above) {
            // Parts through the water stretch with the floor (model matrices are rigid).
            const glm::mat4 inverse = glm::inverse(object.model_matrix);
            for (glm::vec3& p : object.positions) {
                glm::vec3 world(object.model_matrix * glm::vec4(p, 1.0F));
                world.y = reshape(world.y);
                p = glm::vec3(inverse * glm::vec4(world, 1.0F));
            }
        }
        FinishMesh(object);
        kept.push_back(std::move(object));
    }
    scene.objects = std::move(kept);
    return scene;
}

CameraView SceneCameraView(const SceneDescription& description) {
    const SceneCamera& camera = description.camera;
    const float heading = glm::radians(camera.heading_degrees);
    const glm::vec3 target(camera.look_at[0], camera.look_at[1], camera.look_at[2]);
    const glm::vec3 eye(target.x + camera.distance * std::sin(heading), camera.height,
                        target.z + camera.distance * std::cos(heading));
    // Near 1 as in DefaultViews: 24-bit depth stays precise out to the far plane.
    return {description.name, eye, target, glm::radians(50.0F), 1.0F, camera.view_range};
}

bool IsEntirelyBelow(const Mesh& mesh, float plane_height) {
    return mesh.world_bounds_max.y <= plane_height;
}

bool IsEntirelyAbove(const Mesh& mesh, float plane_height) {
    return mesh.world_bounds_min.y >= plane_height;
}

bool IntersectsDepthBand(const Mesh& mesh, float plane_height, float max_depth) {
    return max_depth >= 0.0F && mesh.world_bounds_min.y <= plane_height &&
           mesh.world_bounds_max.y >= plane_height - max_depth;
}

std::vector<CameraView> DefaultViews() {
    // Near 1 keeps 24-bit depth precise out to the 2000-unit far plane the fog distance needs.
    constexpr float kNear = 1.0F;
    constexpr float kFar = 2000.0F;
    const float fov = glm::radians(50.0F);
    const glm::vec2 shore(-3.0F, -3.0F);  // on the beach, the tower behind, the objects ahead
    const float shore_eye = std::max(TerrainHeight(shore.x, shore.y), 0.0F) + 1.7F;
    return {
            {"three_quarter", {95.0F, 40.0F, 85.0F}, {-10.0F, 2.0F, -12.0F}, fov, kNear, kFar},
            {"grazing", {80.0F, 1.5F, 60.0F}, {-20.0F, 2.0F, -20.0F}, fov, kNear, kFar},
            {"high", {25.0F, 150.0F, 30.0F}, {5.0F, 0.0F, 0.0F}, fov, kNear, kFar},
            {"shore", {shore.x, shore_eye, shore.y}, {40.0F, 3.0F, 30.0F}, fov, kNear, kFar},
    };
}

const CameraView* FindView(const std::vector<CameraView>& views, std::string_view name) {
    const auto found = std::find_if(views.begin(), views.end(),
                                    [&](const CameraView& view) { return view.name == name; });
    return found == views.end() ? nullptr : &*found;
}

glm::mat4 ViewMatrix(const CameraView& view) {
    return glm::lookAt(view.eye, view.target, glm::vec3(0.0F, 1.0F, 0.0F));
}

glm::mat4 ProjectionMatrix(const CameraView& view, float aspect) {
    return glm::perspective(view.fov_y_radians, aspect, view.near_plane, view.far_plane);
}

}  // namespace tidepool::runner
