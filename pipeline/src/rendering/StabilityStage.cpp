#include "tidepool/pipeline/StabilityStage.h"

#include "tidepool/pipeline/MatrixLoading.h"
#include "tidepool/pipeline/OutputFiles.h"

#include <cstdlib>
#include <utility>

namespace tidepool::pipeline {
namespace {

Outcome WriteStabilityInto(const std::filesystem::path& folder, const std::string& json,
                           bool check_only = false) {
    return WriteOwnJson(folder, std::string(stagefiles::kStabilityFileName),
                        std::string(stagefiles::kStabilitySchemaName), "stability report", json,
                        check_only);
}

}  // namespace

lab::StabilityReport RunStabilityCatalogue(runner::GlContext& context, const VariantConfig& config,
                                           const std::vector<Variant>& variants,
                                           const StabilityRun& run, std::string* error) {
    using namespace tidepool::lab;  // and, through it, the runner
    StabilityReport report;
    const std::vector<HardCase> catalogue = HardCaseCatalogue();
    for (const HardCase& hard_case : catalogue) {
        if (hard_case.kind == HardCaseKind::kCpu) {
            report.cases.push_back(RunCpuHardCase(hard_case));
        }
    }
    report.precision = RunPrecisionStudy();
    const GlEnvironment& env = context.Environment();
    report.environment = {{"backend", env.backend},
                          {"renderer", env.renderer},
                          {"version", env.version},
                          {"mesa_version", env.mesa_version},
                          {"lp_num_threads", run.lp_num_threads},
                          {"size", run.size},
                          {"config", run.config_path}};
    GlStabilityOptions gl_options;
    gl_options.width = run.width;
    gl_options.height = run.height;
    gl_options.on_case_done = run.on_progress;
    std::vector<StabilityCaseResult> gl_cases = RunGlHardCases(
            context, config, WaterVariantConfigurations(variants), catalogue, gl_options, error);
    if (!error->empty()) {
        return report;
    }
    for (StabilityCaseResult& r : gl_cases) {
        report.cases.push_back(std::move(r));
    }
    report.guards = MeasureGuards(context, config, gl_options, error);
    return report;
}

StabilityResult RunStability(const StabilityOptions& options) {
    StabilityResult result;
    // A stability.json of someone else's is refused before the catalogue runs; tidepool's own is
    // replaced atomically, so a killed run leaves the previous one whole.
    result.path = options.out / stagefiles::kStabilityFileName;
    result.outcome = WriteStabilityInto(options.out, "", true);
    if (result.outcome.Stopped()) {
        return result;
    }
    LoadedMatrix loaded = LoadMatrix(options.config);
    result.outcome = std::move(loaded.outcome);
    if (!loaded.config) {
        return result;
    }
    // llvmpipe reads its thread count when the first context is created.
    StabilityRun run = options.run;
    run.lp_num_threads = std::to_string(options.threads);
    setenv("LP_NUM_THREADS", run.lp_num_threads.c_str(), 1);
    runner::GlContextResult context = runner::CreateGlContext(options.backend);
    if (!context.context) {
        result.outcome.Fail(Status::kEnvironment, context.error);
        return result;
    }
    std::string error;
    result.report = RunStabilityCatalogue(*context.context, *loaded.config,
                                          loaded.expansion.variants, run, &error);
    if (!error.empty()) {
        result.outcome.Fail(Status::kEnvironment, error);
        return result;
    }
    result.json = stagefiles::StabilityFileText(result.report);
    if (Outcome write = WriteStabilityInto(options.out, result.json); write.Stopped()) {
        result.outcome.Add(write.diagnostics);
        result.outcome.status = write.status;
        return result;
    }
    for (const lab::StabilityCaseResult& r : result.report.cases) {
        result.failed += r.passed ? 0 : 1;
    }
    result.outcome.status = result.failed == 0 ? Status::kOk : Status::kInvalid;
    return result;
}

}  // namespace tidepool::pipeline
