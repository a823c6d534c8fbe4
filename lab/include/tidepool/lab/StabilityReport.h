// Runs the hard-case catalogue (CPU sweeps and GL renders of every water variant into a float
// target), the precision study and the shader-guard comparison, for stability.json (schema
// "tidepool.stability", version 1).
#pragma once

#include "tidepool/VariantConfig.h"
#include "tidepool/lab/HardCases.h"
#include "tidepool/lab/PrecisionStudy.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/stagefiles/StabilityFile.h"

#include <map>
#include <string>
#include <vector>

namespace tidepool::runner {

/// The outcome of one hard case.
struct StabilityCaseResult {
    std::string name;
    std::string description;
    HardCaseKind kind = HardCaseKind::kCpu;
    int variants_checked = 0;  // GL: configurations rendered; CPU: 0
    long nan_count = 0;        // GL: pixel channels; CPU: evaluated values
    long inf_count = 0;
    double max_error = 0;  // GL: largest distance of a channel outside [0, 1]; CPU: see bound
    double bound = 0;      // the largest max_error that passes, and why (in `note`)
    bool passed = false;
    std::string fix;
    std::string note;  // what max_error measures and failures, if any
};

/// What removing one shader guard changes on the default views.
struct GuardResult {
    std::string guard;  // the guard, and the test-only define that removes it
    double max_channel_diff_normal_views = 0;
    double tolerance = 0;
    bool passed = false;
};

/// Everything stability.json holds.
struct StabilityReport {
    std::map<std::string, std::string> environment;
    std::vector<StabilityCaseResult> cases;
    std::vector<PrecisionRow> precision;
    std::vector<GuardResult> guards;
};

/// Runs one kCpu hard case's sweep. Fails through `passed` false (and `note`) when the case is
/// not a CPU case or its bound is broken.
StabilityCaseResult RunCpuHardCase(const HardCase& hard_case);

/// How GL hard cases are rendered.
struct GlStabilityOptions {
    int width = 64;  // small: every variant at every case must stay fast
    int height = 48;
};

/// Renders every configuration at every kGl case in `cases` into an RGBA32F target and counts
/// NaN, Inf and out-of-range channels. Fails (empty, `error` set) when the context cannot render
/// to float; a configuration that does not compile fails its case.
std::vector<StabilityCaseResult> RunGlHardCases(GlContext& context, const VariantConfig& config,
                                                const std::vector<RenderConfiguration>& configs,
                                                const std::vector<HardCase>& cases,
                                                const GlStabilityOptions& options,
                                                std::string* error);

/// Renders the default views with and without each water.fsh guard (test-only TP_NO_* defines)
/// for the variants the guard applies to, and records the largest channel difference. Fails
/// (empty, `error` set) when the context cannot render to float.
std::vector<GuardResult> MeasureGuards(GlContext& context, const VariantConfig& config,
                                       const GlStabilityOptions& options, std::string* error);

/// The water variants of `variants` as configurations with default passes. Never fails.
std::vector<RenderConfiguration> WaterVariantConfigurations(const std::vector<Variant>& variants);

/// `report` as stability.json holds it (stagefiles/StabilityFile.h). Never fails.
stagefiles::StabilityFile StabilityFileFor(const StabilityReport& report);

}  // namespace tidepool::runner
