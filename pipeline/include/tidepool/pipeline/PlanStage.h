// The plan stage (`plan`): scene descriptions -> the cheapest water configuration that meets each
// scene's quality target, chosen by rendering and timing a short candidate list; plans.json and
// the candidates' images in a folder published whole. Part of tidepool_pipeline_gl.
#pragma once

#include "tidepool/SceneDescription.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/base/FolderPublisher.h"
#include "tidepool/lab/ScenePlanner.h"
#include "tidepool/pipeline/Outcome.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/stagefiles/PlansFile.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tidepool::pipeline {

/// What `plan` is asked to do.
struct PlanRequest {
    std::string config = "variants.yaml";  // scenes/ lies next to it
    std::vector<std::string> scenes;       // scenes/NAME.yaml to plan
    bool all = false;                      // every scenes/*.yaml instead
    int width = 320;
    int height = 240;
    double resolution = 3.0;       // each candidate timed against the full effect to +/- this
    double contended_share = 0.5;  // pairs timed with the core shared, per as-run pair
    runner::BackendKind backend = runner::BackendKind::kAuto;
    int threads = 0;  // LP_NUM_THREADS
    std::string out;  // folder for plans.json and the images; "" for none (reports/out/plan
                      // with `all`)
};

/// Every scenes/*.yaml in `scene_dir`, sorted; none when there is none or no such folder.
std::vector<std::filesystem::path> SceneFilesIn(const std::filesystem::path& scene_dir);

/// Everything planning needs, ready: the configuration, the scenes, the output folder being
/// staged, and a GL context.
struct PreparedPlans {
    Outcome outcome;  // why nothing can be planned, or the loaders' warnings
    std::optional<VariantConfig> config;
    std::vector<SceneDescription> scenes;
    std::unique_ptr<base::FolderPublisher> publisher;  // null without an output folder
    std::unique_ptr<runner::GlContext> context;
    lab::PlanOptions options;
};

/// Loads the configuration and the scenes, begins publishing the output folder and creates the
/// context (LP_NUM_THREADS set first). Stops with kUsage when the configuration or a scene does
/// not load, --all finds no scene or the folder is someone else's; kEnvironment without GL.
PreparedPlans PreparePlans(const PlanRequest& request);

/// What planning found and wrote.
struct PlanResult {
    Outcome outcome;  // kInvalid when a scene could not be planned; why plans.json was not
                      // written or published
    std::vector<lab::ScenePlan> plans;  // one per scene, in order
    stagefiles::PlansFile file;         // plans.json
    std::filesystem::path path;         // where plans.json is once published; "" for none
};

/// Plans every scene of `prepared` and, with an output folder, writes plans.json there and
/// publishes it. Stops with kEnvironment when the file cannot be written, or PublishStatus.
PlanResult PlanScenes(PreparedPlans& prepared);

}  // namespace tidepool::pipeline
