// The render process's side of RunOptions::shared (Results.h): reading back the units a second
// process did. Private to the runner library.
#pragma once

#include "tidepool/runner/Results.h"

#include <filesystem>
#include <functional>
#include <vector>

#include "ConfigurationImages.h"

namespace tidepool::runner {

/// The file in which the second process leaves claim-table unit `unit`'s results.
std::filesystem::path SharedUnitPath(const SharedUnits& shared, std::size_t unit);

/// How many units the render read back from the second process.
struct CollectedUnits {
    int configurations = 0;
};

/// Waits for every unit the second process claimed and puts its results into `results`: a
/// configuration's unit into its ConfigurationResult, a comparison's timing into its
/// ComparisonResult, with the per-pass times of its two configurations where this process has
/// none of its own. Does on `w` any unit the second process left unfinished (its heartbeat
/// stopped) or whose results cannot be read, a comparison through `time_comparison`, so no unit
/// is ever missing. While it waits, the progress line says so (ProgressMeter::Waiting).
CollectedUnits CollectSharedUnits(RenderWorker& w, const ImageUnitContext& context,
                                  RunResults& results,
                                  const std::function<void(std::size_t k)>& time_comparison);

/// `r`'s recorded fields from `entry` (results.json's form of them), as ToResultsFile wrote
/// them; `r.configuration` is left as it is. Inverse of the results file's configuration entry.
void FromResultsEntry(const stagefiles::ResultsConfiguration& entry, ConfigurationResult& r);

/// `out`'s timing and error from `entry`, as ToResultsFile wrote them (the estimate is computed
/// again from the samples); `out.comparison` is left as it is. False when the entry's decision
/// is not one StopDecisionName gives.
bool FromResultsEntry(const stagefiles::ResultsComparison& entry, ComparisonResult& out);

}  // namespace tidepool::runner
