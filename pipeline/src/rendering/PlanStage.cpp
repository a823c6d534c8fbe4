#include "tidepool/pipeline/PlanStage.h"

#include "tidepool/Manifest.h"
#include "tidepool/pipeline/OutputFiles.h"
#include "tidepool/runner/FrameTimer.h"

#include <algorithm>
#include <cstdlib>
#include <utility>

#include <fmt/format.h>

namespace tidepool::pipeline {
namespace {

// The scene files `request` names, or every scenes/*.yaml with `all`; stops `outcome` when
// --all finds none.
std::vector<std::filesystem::path> ScenePaths(const PlanRequest& request,
                                              const std::filesystem::path& scene_dir,
                                              Outcome* outcome) {
    std::vector<std::filesystem::path> paths;
    if (!request.all) {
        for (const std::string& name : request.scenes) {
            // A name, not a path: "../variants" read the configuration as a scene. Twice, the two
            // plans would write the same images.
            std::string why;
            if (name.empty() || name.find('/') != std::string::npos || name[0] == '.') {
                why = "a scene is named by its file in scenes/ without '.yaml'";
            } else if (name.size() > 5 && name.ends_with(".yaml")) {
                why = fmt::format("name it without '.yaml': --scene {}",
                                  name.substr(0, name.size() - 5));
            } else if (std::count(request.scenes.begin(), request.scenes.end(), name) > 1) {
                why = "it is given twice; give it once";
            }
            if (!why.empty()) {
                outcome->Fail(Status::kUsage, fmt::format("--scene '{}': {}", name, why));
                return {};
            }
            paths.push_back(scene_dir / (name + ".yaml"));
        }
        return paths;
    }
    paths = SceneFilesIn(scene_dir);
    if (paths.empty()) {
        outcome->Fail(Status::kUsage, fmt::format("no scenes/*.yaml next to {}", request.config));
    }
    return paths;
}

}  // namespace

std::vector<std::filesystem::path> SceneFilesIn(const std::filesystem::path& scene_dir) {
    std::vector<std::filesystem::path> paths;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(scene_dir, ec)) {
        if (entry.path().extension() == ".yaml") {
            paths.push_back(entry.path());
        }
    }
    std::sort(paths.begin(), paths.end());
    return paths;
}

PreparedPlans PreparePlans(const PlanRequest& request) {
    PreparedPlans prepared;
    Outcome& outcome = prepared.outcome;
    prepared.options.settings.width = request.width;
    prepared.options.settings.height = request.height;
    prepared.options.rule.resolution_points = request.resolution;
    prepared.options.rule.contended_share = request.contended_share;
    ConfigResult loaded = LoadVariantConfig(request.config);
    outcome.Add(loaded.diagnostics);
    if (!loaded.config) {
        outcome.status = Status::kUsage;
        return prepared;
    }
    const std::vector<std::filesystem::path> paths =
            ScenePaths(request, loaded.config->base_dir / "scenes", &outcome);
    if (outcome.Stopped()) {
        return prepared;
    }
    for (const std::filesystem::path& path : paths) {
        SceneResult scene = LoadSceneDescription(path);
        outcome.Add(scene.diagnostics);
        if (scene.scene) {
            prepared.scenes.push_back(std::move(*scene.scene));
        } else {
            outcome.status = Status::kUsage;
        }
    }
    if (outcome.Stopped()) {
        return prepared;
    }
    // The output folder (plans.json and the candidates' images) is published whole: a folder
    // that is not tidepool's is refused before any rendering, and a killed run leaves the
    // previous plans as they were.
    std::string out = request.out;
    if (out.empty() && request.all) {
        out = "reports/out/plan";
    }
    if (!out.empty()) {
        prepared.publisher = BeginPublishing(out, "tidepool plan", &outcome);
        if (!prepared.publisher) {
            return prepared;
        }
        prepared.options.out_dir = prepared.publisher->Staging();
    }
    // llvmpipe reads its thread count when the first context is created.
    const std::string threads = std::to_string(request.threads);
    setenv("LP_NUM_THREADS", threads.c_str(), 1);
    runner::GlContextResult context = runner::CreateGlContext(request.backend);
    if (!context.context) {
        outcome.Fail(Status::kEnvironment, context.error);
        return prepared;
    }
    const runner::GlEnvironment& gl = context.context->Environment();
    prepared.options.clock = runner::ChooseFrameClock(gl.renderer, threads, gl.timer_query).clock;
    prepared.context = std::move(context.context);
    prepared.config = std::move(loaded.config);
    return prepared;
}

PlanResult PlanScenes(PreparedPlans& prepared) {
    PlanResult result;
    for (const SceneDescription& scene : prepared.scenes) {
        result.plans.push_back(
                lab::PlanScene(*prepared.context, *prepared.config, scene, prepared.options));
        if (result.plans.back().chosen < 0) {
            result.outcome.status = Status::kInvalid;
        }
    }
    result.file = lab::PlansFileFor(result.plans, prepared.options);
    if (!prepared.publisher) {
        return result;
    }
    if (const std::string error = stagefiles::WritePlansFile(
                result.file, prepared.publisher->Staging() / stagefiles::kPlansFileName);
        !error.empty()) {
        result.outcome.Fail(Status::kEnvironment, error);
        return result;
    }
    if (!Publish(*prepared.publisher, &result.outcome)) {
        return result;
    }
    result.path = prepared.publisher->Target() / stagefiles::kPlansFileName;
    return result;
}

}  // namespace tidepool::pipeline
