// Builds the report document from the ReportModel: every heading, sentence and table of the
// report is worded here once, for both the HTML and the Markdown writer.
#pragma once

#include "tidepool/report/ReportDocument.h"
#include "tidepool/report/ReportModel.h"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace tidepool::report {

/// Relative file names of an image panel's three images (empty for a panel with a note).
struct PanelFiles {
    std::string image;
    std::string reference;
    std::string heat;
};

/// The Reflection techniques section's panels follow the Images section's in every per-panel
/// list (files, data: URIs), so panel j of that section is at this offset plus j.
std::size_t ReflectionPanelOffset(const ReportModel& model);

/// The whole report as a document. `files` and `data_uris` hold one entry per panel, the Images
/// section's first (ReflectionPanelOffset); `data_uris` are the embedded copies index.html shows.
/// Reads a few settings straight from results.json: one of an unexpected type throws
/// nlohmann::json::exception (WriteReport turns it into an error naming the file).
doc::Document BuildReportDocument(const ReportModel& model, const std::vector<PanelFiles>& files,
                                  const std::vector<std::array<std::string, 3>>& data_uris);

}  // namespace tidepool::report
