// Loading scenes/*.yaml on top of the shared YAML reading layer (YamlReader.h): no exception
// leaves the library and every position becomes a 1-based file:line:col.
#include "tidepool/SceneDescription.h"

#include "tidepool/TextFile.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <system_error>

#include "YamlReader.h"
#include <fmt/format.h>

namespace tidepool {
namespace {

// A closed range a number must lie in, and why.
struct Range {
    double low;
    double high;
};

// Water shallower than half a unit would put the sea floor inside the 0.5-unit sliver the
// refraction clip plane keeps above the water (RenderSettings::clip_plane_offset); 200 is ten
// times the island's seabed, deeper than any fog lets one see.
constexpr Range kWaterDepth{0.5, 200.0};
// Fog depth: below half a unit the refraction is the fog colour everywhere; beyond the far
// plane it changes nothing.
constexpr Range kFogDepth{0.5, 10000.0};
// Wave strength scales the demo's WaveDistortion (texture units per unit of bump normal, over
// the eye distance); at 1 the default view's pillars already reflect as scattered speckles, so
// beyond 2 the water is noise.
constexpr Range kWaveStrength{0.0, 2.0};
// The eye must stay above the reflection's 0.5-unit clip sliver, or the mirrored camera sees
// under the water; 1000 is five times the terrain's size, where the scene is a dot.
constexpr Range kCameraHeight{0.6, 1000.0};
constexpr Range kCameraDistance{1.0, 1000.0};
constexpr Range kHeading{-360.0, 360.0};
constexpr Range kLookAt{-1000.0, 1000.0};
// The near plane is 1; 24-bit depth keeps the water polygon and the terrain apart up to about
// 10000 units, and below 10 the island itself is cut off.
constexpr Range kViewRange{10.0, 10000.0};
// PSNR between 10 dB (unrelated images) and 99 dB (the cap used for identical images).
constexpr Range kPsnr{10.0, 99.0};
constexpr Range kShare{0.0, 1.0};
constexpr Range kFrameBudget{0.001, 10000.0};

// Whether `text` is a decimal number too large for a double (1e999), which yaml-cpp does not
// decode: a number, out of range, not "not a number".
bool BeyondDouble(const std::string& text) {
    double value = 0;
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    return stop == end && error == std::errc::result_out_of_range;
}

// Collects diagnostics while walking the YAML tree; every check reports and carries on.
class SceneParser : public YamlReader {
public:
    explicit SceneParser(std::string file_name) : YamlReader(std::move(file_name)) {}

    SceneResult Parse(std::string_view text);

private:
    // Reads a number in `range` into `value`; leaves it unchanged (and reports) otherwise.
    template <typename T>
    void ReadNumber(const YAML::Node& node, std::string_view what, Range range, T* value) {
        double number = 0;
        if (node.IsNull()) {
            Error(node, fmt::format("{} has no value; give it a number from {} to {}", what,
                                    range.low, range.high));
            return;
        }
        const bool decoded = node.IsScalar() && YAML::convert<double>::decode(node, number);
        if (!decoded && !(node.IsScalar() && BeyondDouble(node.Scalar()))) {
            Error(node, fmt::format("{} must be a number", what));
            return;
        }
        if (!decoded || !std::isfinite(number) || number < range.low || number > range.high) {
            Error(node, fmt::format("{} must be between {} and {}, not {}", what, range.low,
                                    range.high, node.Scalar()));
            return;
        }
        *value = static_cast<T>(number);
    }
    // Reads a list of names from `allowed` into a set of flags.
    std::vector<std::string> ReadNames(const YAML::Node& node, std::string_view what,
                                       const std::vector<std::string>& allowed) {
        std::vector<std::string> names;
        if (node.IsNull()) {
            return names;
        }
        if (!node.IsSequence()) {
            Error(node,
                  fmt::format("{} must be a list such as [{}]", what, fmt::join(allowed, ", ")));
            return names;
        }
        for (const YAML::Node& item : node) {
            if (!item.IsScalar()) {
                Error(item, fmt::format("{} lists names, not lists or mappings", what));
                continue;
            }
            if (std::find(allowed.begin(), allowed.end(), item.Scalar()) == allowed.end()) {
                Error(item, fmt::format("unknown name '{}' in {}; allowed: {}", item.Scalar(), what,
                                        fmt::join(allowed, ", ")));
                continue;
            }
            if (std::find(names.begin(), names.end(), item.Scalar()) != names.end()) {
                Error(item, fmt::format("'{}' is listed twice in {}", item.Scalar(), what));
                continue;
            }
            names.push_back(item.Scalar());
        }
        return names;
    }

    void ParseWater(const YAML::Node& node, SceneDescription& scene);
    void ParseCamera(const YAML::Node& node, SceneDescription& scene);
    void ParseTarget(const YAML::Node& key, const YAML::Node& node, SceneDescription& scene);
};

void SceneParser::ParseWater(const YAML::Node& node, SceneDescription& scene) {
    if (!ExpectMap(node, "water")) {
        return;
    }
    CheckKeys(node, "water", {"depth", "fog_depth", "waves"});
    if (node["depth"]) {
        ReadNumber(node["depth"], "water.depth", kWaterDepth, &scene.water_depth);
    }
    if (node["fog_depth"]) {
        ReadNumber(node["fog_depth"], "water.fog_depth", kFogDepth, &scene.fog_depth);
    }
    if (node["waves"]) {
        ReadNumber(node["waves"], "water.waves", kWaveStrength, &scene.wave_strength);
    }
}

void SceneParser::ParseCamera(const YAML::Node& node, SceneDescription& scene) {
    if (!ExpectMap(node, "camera")) {
        return;
    }
    CheckKeys(node, "camera", {"height", "distance", "heading", "look_at", "view_range"});
    SceneCamera& camera = scene.camera;
    if (node["height"]) {
        ReadNumber(node["height"], "camera.height", kCameraHeight, &camera.height);
    }
    if (node["distance"]) {
        ReadNumber(node["distance"], "camera.distance", kCameraDistance, &camera.distance);
    }
    if (node["heading"]) {
        ReadNumber(node["heading"], "camera.heading", kHeading, &camera.heading_degrees);
    }
    if (node["view_range"]) {
        ReadNumber(node["view_range"], "camera.view_range", kViewRange, &camera.view_range);
    }
    if (const YAML::Node look_at = node["look_at"]) {
        if (!look_at.IsSequence() || look_at.size() != 3) {
            Error(look_at, "camera.look_at must be a point [x, y, z]");
        } else {
            for (std::size_t i = 0; i < 3; ++i) {
                ReadNumber(look_at[i], "camera.look_at", kLookAt, &camera.look_at[i]);
            }
        }
    }
}

void SceneParser::ParseTarget(const YAML::Node& key, const YAML::Node& node,
                              SceneDescription& scene) {
    if (!ExpectMap(node, "target")) {
        return;
    }
    CheckKeys(node, "target", {"min_psnr_db", "max_share_visible", "frame_budget_ms"});
    QualityTarget& target = scene.target;
    double value = 0;
    if (node["min_psnr_db"]) {
        ReadNumber(node["min_psnr_db"], "target.min_psnr_db", kPsnr, &value);
        target.min_psnr_db = value;
    }
    if (node["max_share_visible"]) {
        ReadNumber(node["max_share_visible"], "target.max_share_visible", kShare, &value);
        target.max_share_visible = value;
    }
    if (node["frame_budget_ms"]) {
        ReadNumber(node["frame_budget_ms"], "target.frame_budget_ms", kFrameBudget, &value);
        target.frame_budget_ms = value;
    }
    if (!target.min_psnr_db && !target.max_share_visible && !target.frame_budget_ms) {
        Error(key, "target needs min_psnr_db, max_share_visible or frame_budget_ms");
    }
}

SceneResult SceneParser::Parse(std::string_view text) {
    SceneResult result;
    const std::optional<YAML::Node> loaded = Load(text);
    if (!loaded) {
        result.diagnostics = std::move(diagnostics_);
        return result;
    }
    const YAML::Node& root = *loaded;
    if (!root || !root.IsMap()) {
        Error(SourceLocation{FileName(), 1, 1},
              "a scene must be a mapping with water, above, below, camera and target "
              "(see docs/SCENES.md)");
        result.diagnostics = std::move(diagnostics_);
        return result;
    }
    // yaml-cpp throws on conversions and odd trees; nothing may escape the library.
    try {
        CheckKeys(root, "the top level",
                  {"version", "description", "water", "above", "below", "camera", "target"});
        SceneDescription scene;
        scene.path = FileName();
        scene.name = std::filesystem::path(FileName()).stem().string();
        scene.where = SourceLocation{FileName(), 1, 1};
        if (const YAML::Node version = root["version"]) {
            if (!version.IsScalar() || version.Scalar() != "1") {
                Error(version, "unsupported scene schema version; this tidepool reads version 1");
            }
        }
        if (const YAML::Node description = root["description"]) {
            // A block scalar (`description: |`) is a scalar too: of one line, it ends in a line
            // break; of more, it would break the report's tables.
            std::string written = description.IsScalar() ? description.Scalar() : std::string();
            while (!written.empty() && written.back() == '\n') {
                written.pop_back();
            }
            if (description.IsScalar() && written.find('\n') == std::string::npos) {
                scene.description = written;
            } else {
                Error(description, "description must be a single line of text");
            }
        }
        if (const YAML::Node water = root["water"]) {
            ParseWater(water, scene);
        }
        if (const YAML::Node camera = root["camera"]) {
            ParseCamera(camera, scene);
        }
        bool has_target = false;
        for (auto it = root.begin(); it != root.end(); ++it) {
            if (it->first.Scalar() == "target") {
                has_target = true;
                ParseTarget(it->first, it->second, scene);
                break;
            }
        }
        if (!has_target) {
            Error(SourceLocation{FileName(), 1, 1},
                  "no `target:`; give min_psnr_db, max_share_visible or frame_budget_ms");
        }
        if (const YAML::Node above = root["above"]) {
            const std::vector<std::string> names =
                    ReadNames(above, "above", {"sky", "terrain", "objects"});
            auto has = [&](std::string_view n) {
                return std::find(names.begin(), names.end(), n) != names.end();
            };
            scene.above_terrain = has("terrain");
            scene.above_objects = has("objects");
            if (!has("sky")) {
                Error(above,
                      "the embedded renderer always draws the sky above the water; "
                      "add sky to above");
            }
            if (scene.above_objects && !scene.above_terrain) {
                Error(above,
                      "the objects above the water stand on the island in the embedded "
                      "renderer; add terrain to above or drop objects");
            }
        }
        if (const YAML::Node below = root["below"]) {
            const std::vector<std::string> names =
                    ReadNames(below, "below", {"terrain", "objects"});
            auto has = [&](std::string_view n) {
                return std::find(names.begin(), names.end(), n) != names.end();
            };
            scene.below_terrain = has("terrain");
            scene.below_objects = has("objects");
            // The renderer always has a sea floor; saying it is out of sight is only true when
            // the fog hides it. Not after an error, which leaves a depth at its default: the
            // message would quote a number the file does not hold.
            if (!HasErrors(diagnostics_) && !scene.below_terrain &&
                scene.water_depth < scene.fog_depth) {
                Error(below, fmt::format("the sea floor at depth {} is within the fog depth {}, "
                                         "so it is visible; add terrain to below, or make "
                                         "water.depth at least water.fog_depth",
                                         scene.water_depth, scene.fog_depth));
            }
        }
        if (!HasErrors(diagnostics_)) {
            result.scene = std::move(scene);
        }
    } catch (const YAML::Exception& e) {
        Error(At(e.mark), fmt::format("unexpected YAML structure: {}", e.msg));
        result.scene.reset();
    }
    result.diagnostics = std::move(diagnostics_);
    return result;
}

}  // namespace

SceneResult ParseSceneDescription(std::string_view text, const std::string& file_name) {
    SceneParser parser(file_name);
    return parser.Parse(text);
}

SceneResult LoadSceneDescription(const std::filesystem::path& path) {
    const TextFileRead read = ReadTextFile(path);
    if (!read.ok) {
        SceneResult result;
        result.diagnostics.push_back(
                MakeError(path.string(), 0, 0,
                          fmt::format("cannot read the scene file: {}; scenes live in "
                                      "scenes/NAME.yaml next to the configuration",
                                      read.error)));
        return result;
    }
    return ParseSceneDescription(read.text, path.string());
}

}  // namespace tidepool
