// The last stage: the report built from a saved manifest and results (and stability.json and
// plans.json beside the results) and written into its folder. No GL.
#pragma once

#include "tidepool/pipeline/Outcome.h"
#include "tidepool/report/ReportInputs.h"
#include "tidepool/report/ReportModel.h"
#include "tidepool/report/ReportWriter.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace tidepool::pipeline {

/// What the report stage reads and where it writes.
struct ReportRequest {
    std::filesystem::path manifest;
    std::filesystem::path results;
    std::string name = "default";  // the report folder's name under `out`
    std::filesystem::path out;
};

/// What the report stage built and wrote. `model` points into `inputs`, which is why they are
/// held by pointer: moving the result keeps the model valid.
struct ReportResult {
    Outcome outcome;  // warnings for a corrupt stability.json or plans.json, or why it stopped
    std::unique_ptr<report::ReportInputs> inputs;
    std::optional<report::ReportModel> model;
    report::WrittenReport written;
    double model_seconds = 0;  // reading the inputs and comparing images
    double seconds = 0;        // the whole stage
};

/// Loads the inputs, builds the report model and writes the report to `out`/`name`. Stops with
/// kUsage for unusable inputs (the error names the file) or a folder tidepool did not write,
/// kEnvironment when writing fails; kInvalid when a configuration failed (the report is written).
ReportResult BuildReport(const ReportRequest& request);

}  // namespace tidepool::pipeline
