// The report's charts as standalone SVG (inline in index.html, files beside report.md).
#pragma once

#include "tidepool/report/ReportModel.h"

#include <cstddef>
#include <string>
#include <vector>

namespace tidepool::report {

/// One point of a scatter chart.
struct ChartPoint {
    double x = 0;
    double y = 0;
    std::string label;    // drawn beside the point when not empty
    std::string tooltip;  // the SVG <title>
    bool highlight = false;
};

/// A scatter chart as standalone SVG; `line` (indices into points, in drawing order) is drawn
/// as a step line (the Pareto frontier). Points with a non-finite coordinate are left out.
/// Never fails: with no drawable point it draws empty axes.
std::string ScatterSvg(const std::vector<ChartPoint>& points, const std::vector<std::size_t>& line,
                       const std::string& x_label, const std::string& y_label,
                       const std::string& title);

/// The whitepaper rows as horizontal bars: the measured change, its 95% interval and the
/// whitepaper's figure. Never fails.
std::string WhitepaperChartSvg(const ReportModel& model);

/// Every configuration's median frame time against 1 - SSIM, the Pareto frontier as a step
/// line. Never fails.
std::string AccuracyChartSvg(const ReportModel& model);

/// The static operation count against the median frame time, the most misleading configurations
/// highlighted. Never fails.
std::string StaticCostChartSvg(const ReportModel& model);

}  // namespace tidepool::report
