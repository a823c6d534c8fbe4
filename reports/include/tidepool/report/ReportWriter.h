// Writes a ReportModel as one self-contained HTML page (tables, SVG charts, images embedded as
// data: URIs) and a Markdown page for repository viewers (PNG and SVG files beside it), both
// rendered from one report document (ReportDocument.h), plus data.json (schema
// "tidepool.report" v1), and publishes them atomically as one folder.
#pragma once

#include "tidepool/report/ReportModel.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tidepool::report {

/// The schema name and version of data.json. Version 2 (2026-11-27): a row's verdict may be
/// "same-direction-magnitude-at-band-edge", and "same-direction-and-magnitude" needs the whole
/// interval in the band (version 1 gave it to an interval overlapping the band).
inline constexpr const char* kReportSchema = "tidepool.report";
inline constexpr int kReportSchemaVersion = 2;

/// Upper bound on the bytes of PNG data embedded in index.html: images are downscaled by 2, 3,
/// ... until they fit, so the page stays under about 10 MB (base64 adds a third) and opens
/// quickly from disk.
inline constexpr std::uintmax_t kHtmlImageBudgetBytes = 6u * 1024u * 1024u;

/// Every figure of the report as JSON (schema kReportSchema, version kReportSchemaVersion);
/// NaN and infinite numbers are written as null. Never fails.
nlohmann::json ReportToJson(const ReportModel& model);

/// The whitepaper table as plain text for a terminal. Never fails.
std::string WhitepaperTableText(const ReportModel& model);

/// What WriteReport wrote.
struct WrittenReport {
    std::filesystem::path folder;              // out_dir / model.options.name
    std::vector<std::filesystem::path> files;  // relative to folder
    std::uintmax_t html_bytes = 0;
    int image_downscale = 1;  // factor applied to the images embedded in HTML
    std::string error;        // "" on success, otherwise naming the path
    bool refused = false;     // the error is a refusal to replace a folder tidepool did not write
};

/// Writes index.html, report.md, data.json, images/ and charts/ into a staging folder beside
/// out_dir / name, then renames it into place (replacing an earlier report), so a reader never
/// sees half a report. Fails (error naming the path, nothing published) when a file cannot be
/// written, or (`refused`) the destination exists and is not tidepool's output (no marker file).
WrittenReport WriteReport(const ReportModel& model, const std::filesystem::path& out_dir);

}  // namespace tidepool::report
