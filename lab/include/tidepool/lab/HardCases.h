// The catalogue of numerical hard cases: named configurations where the whitepaper's shortcuts
// (a unit bump normal, a camera above the water, a clip plane facing away from the camera, a
// short animation) stop holding. `tidepool stability` and the Stability* tests run the same
// list; docs/HARD_CASES.md describes it for readers.
#pragma once

#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/Renderer.h"

#include <string>
#include <string_view>
#include <vector>

namespace tidepool::lab {

// The lab's experiments are built on the renderer: its types are used here unqualified.
using namespace tidepool::runner;  // NOLINT(google-build-using-namespace)

/// Whether a hard case is a CPU sweep against a double reference or a GL render of every variant.
enum class HardCaseKind { kCpu, kGl };

/// "cpu" or "gl", as stability.json writes it.
const char* HardCaseKindName(HardCaseKind kind);

/// One named configuration of the catalogue.
struct HardCase {
    std::string name;         // stable identifier, used on the command line and in tests
    std::string description;  // what it sets up and which assumption it breaks
    HardCaseKind kind = HardCaseKind::kGl;
    std::string fix;  // what the code needed for the case to pass; "" when nothing
    // The rest applies to kGl cases only.
    CameraView view;          // the camera (a free camera: any eye, target, near and far)
    RenderSettings settings;  // the defaults with the case's changes; width/height only count
                              // when fixed_size is true
    bool fixed_size = false;  // the case is about the render size itself
    int reflection_size = 0;  // reflection/refraction texture size; 0 keeps the configuration's
};

/// Returns every hard case, CPU sweeps first, in a fixed order. Never fails.
std::vector<HardCase> HardCaseCatalogue();

/// Returns the case called `name` in `cases`, or nullptr when there is none.
const HardCase* FindHardCase(const std::vector<HardCase>& cases, std::string_view name);

}  // namespace tidepool::lab
