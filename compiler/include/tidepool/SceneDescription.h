// A scene description (scenes/*.yaml, schema in docs/SCENES.md): what the water looks like, what
// stands above and lies below it, where the camera is, and the quality target a plan must meet.
// The planner reads it to decide which water effects the scene needs.
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/VariantConfig.h"

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tidepool {

/// Where the camera stands: it looks at `look_at` from `distance` units away (horizontally),
/// `height` units above the water, from the compass direction `heading_degrees`.
struct SceneCamera {
    float height = 40.0F;           // eye height above the water surface
    float distance = 130.0F;        // horizontal distance from the eye to look_at
    float heading_degrees = 45.0F;  // 0 = eye on +z of look_at, 90 = eye on +x
    std::array<float, 3> look_at{-10.0F, 2.0F, -12.0F};  // world point the camera looks at
    float view_range = 2000.0F;                          // far plane; distance fog reaches 1 there
};

/// What a plan must achieve; every bound given must hold. With a frame budget, the plan picks
/// the most accurate candidate within it instead of the cheapest that is accurate enough.
struct QualityTarget {
    std::optional<double> min_psnr_db;        // PSNR against the full-effect image, dB
    std::optional<double> max_share_visible;  // share of visibly different pixels, 0..1
    std::optional<double> frame_budget_ms;    // median frame time, ms
};

/// One scene, parsed and range-checked.
struct SceneDescription {
    std::string name;            // the file stem, e.g. "murky_pond"
    std::string description;     // one line for people
    std::string path;            // the file as named
    float water_depth = 20.0F;   // depth of the sea floor away from the shore, world units
    float fog_depth = 80.0F;     // underwater visibility: depth fog is opaque at this depth
    float wave_strength = 1.0F;  // 0 = mirror-flat, 1 = the demo's waves, up to 2
    bool above_terrain = true;   // the island stands above the water
    bool above_objects = true;   // tower, sphere and the tops of hull and pillars
    bool below_terrain = true;   // the sea floor is within sight (shallower than it is murky)
    bool below_objects = true;   // the submerged rocks and the lower halves of hull and pillars
    SceneCamera camera;
    QualityTarget target;
    SourceLocation where;  // the top of the file
};

/// A scene description or why there is none: every problem found, not just the first.
struct SceneResult {
    std::optional<SceneDescription> scene;
    std::vector<Diagnostic> diagnostics;
};

/// Parses a scene description held in memory; `file_name` is used in diagnostics and gives the
/// scene its name (the stem). Fails (no scene, diagnostics at file:line:col) on malformed YAML,
/// unknown or duplicate keys, values out of range, a missing quality target, or a request the
/// embedded renderer cannot draw (no sky above, objects above without the island they stand on,
/// a sea floor said to be out of sight although it is shallower than the fog depth).
SceneResult ParseSceneDescription(std::string_view text, const std::string& file_name);

/// Reads and parses a scene file; fails as ParseSceneDescription, or when the file is unreadable.
SceneResult LoadSceneDescription(const std::filesystem::path& path);

}  // namespace tidepool
