// The render process's side of RunOptions::shared (Results.h): reading back the units a second
// process rendered. Private to the runner library.
#pragma once

#include "tidepool/runner/Results.h"

#include <filesystem>
#include <vector>

#include "ConfigurationImages.h"

namespace tidepool::runner {

/// The file in which the second process leaves configuration `i`'s results.
std::filesystem::path SharedUnitPath(const SharedImageUnits& shared, std::size_t i);

/// Waits for every unit the second process claimed and puts its results into `configurations`.
/// Renders on `w` any unit the second process left unfinished (its heartbeat stopped) or whose
/// results cannot be read, so no configuration is ever missing. Returns how many units came
/// from the second process.
int CollectSharedUnits(RenderWorker& w, const ImageUnitContext& context,
                       std::vector<ConfigurationResult>& configurations);

/// `r`'s recorded fields from `entry` (results.json's form of them), as ToResultsFile wrote
/// them; `r.configuration` is left as it is. Inverse of the results file's configuration entry.
void FromResultsEntry(const stagefiles::ResultsConfiguration& entry, ConfigurationResult& r);

}  // namespace tidepool::runner
