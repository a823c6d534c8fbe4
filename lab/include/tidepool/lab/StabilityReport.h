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

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace tidepool::lab {

// The lab's experiments are built on the renderer: its types are used here unqualified.
using namespace tidepool::runner;  // NOLINT(google-build-using-namespace)

// The catalogue's results are the types of the file they are written to, so that stability.json
// has one C++ type (stagefiles/StabilityFile.h).
using StabilityCaseResult = stagefiles::StabilityCase;
using GuardResult = stagefiles::GuardEntry;
using StabilityReport = stagefiles::StabilityFile;

/// Runs one kCpu hard case's sweep. Fails through `passed` false (and `note`) when the case is
/// not a CPU case or its bound is broken.
StabilityCaseResult RunCpuHardCase(const HardCase& hard_case);

/// How GL hard cases are rendered.
struct GlStabilityOptions {
    int width = 64;  // small: every variant at every case must stay fast
    int height = 48;
    // Called after each GL case with the share of them done (0 to 1]; may be empty.
    std::function<void(double share_done)> on_case_done;
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

}  // namespace tidepool::lab
