// The report's charts as standalone SVG: scatter charts with an optional step line, and the
// whitepaper table's bars.
#include "tidepool/report/ReportCharts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ReportText.h"
#include <fmt/format.h>

namespace tidepool::report {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Axis {
    double low = 0;
    double high = 1;
};

Axis NiceAxis(double low, double high) {
    if (!std::isfinite(low) || !std::isfinite(high)) {
        return {};
    }
    if (high <= low) {
        const double pad = low == 0 ? 1.0 : std::abs(low) * 0.1;
        return {low - pad, high + pad};
    }
    const double pad = (high - low) * 0.06;
    // Times and error measures are never negative: keep the axis from suggesting they could be.
    return {low >= 0 ? std::max(0.0, low - pad) : low - pad, high + pad};
}

std::string TickLabel(double value, double span) {
    const int digits = span >= 20 ? 0 : span >= 2 ? 1 : span >= 0.2 ? 2 : span >= 0.02 ? 3 : 4;
    return fmt::format("{:.{}f}", value, digits);
}

// The bar colour of a whitepaper row by its standing, as the table's rows are coloured: green,
// blue, red, grey.
const char* VerdictColour(Verdict verdict) {
    switch (StandingOf(verdict)) {
        case VerdictStanding::kAgrees:
            return "#27ae60";
        case VerdictStanding::kAgreesInDirection:
            return "#2e86c1";
        case VerdictStanding::kDisagrees:
            return "#c0392b";
        case VerdictStanding::kUndecided:
            return "#95a5a6";
    }
    return "#95a5a6";
}

}  // namespace

std::string ScatterSvg(const std::vector<ChartPoint>& points, const std::vector<std::size_t>& line,
                       const std::string& x_label, const std::string& y_label,
                       const std::string& title) {
    constexpr double kWidth = 760;
    constexpr double kHeight = 420;
    constexpr double kLeft = 70;
    constexpr double kRight = 20;
    constexpr double kTop = 30;
    constexpr double kBottom = 50;
    double x_min = kInf, x_max = -kInf, y_min = kInf, y_max = -kInf;
    for (const ChartPoint& p : points) {
        if (std::isfinite(p.x) && std::isfinite(p.y)) {
            x_min = std::min(x_min, p.x);
            x_max = std::max(x_max, p.x);
            y_min = std::min(y_min, p.y);
            y_max = std::max(y_max, p.y);
        }
    }
    const Axis xa = NiceAxis(x_min, x_max);
    const Axis ya = NiceAxis(y_min, y_max);
    auto sx = [&](double x) {
        return kLeft + (x - xa.low) / (xa.high - xa.low) * (kWidth - kLeft - kRight);
    };
    auto sy = [&](double y) {
        return kHeight - kBottom - (y - ya.low) / (ya.high - ya.low) * (kHeight - kTop - kBottom);
    };
    std::string svg = fmt::format(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {0} {1}\" width=\"{0}\" "
            "height=\"{1}\" font-family=\"sans-serif\" font-size=\"11\" role=\"img\">"
            "<title>{2}</title><rect width=\"100%\" height=\"100%\" fill=\"white\"/>",
            kWidth, kHeight, HtmlEscaped(title));
    svg += fmt::format("<text x=\"{}\" y=\"18\" font-size=\"13\" font-weight=\"bold\">{}</text>",
                       kLeft, HtmlEscaped(title));
    for (int i = 0; i <= 5; ++i) {
        const double xv = xa.low + (xa.high - xa.low) * i / 5.0;
        const double yv = ya.low + (ya.high - ya.low) * i / 5.0;
        svg += fmt::format(
                "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>"
                "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4}</text>",
                sx(xv), kTop, kHeight - kBottom, kHeight - kBottom + 15,
                TickLabel(xv, xa.high - xa.low));
        svg += fmt::format(
                "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
                "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>",
                kLeft, sy(yv), kWidth - kRight, kLeft - 5, sy(yv) + 4,
                TickLabel(yv, ya.high - ya.low));
    }
    svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
                       (kLeft + kWidth - kRight) / 2, kHeight - 12, HtmlEscaped(x_label));
    svg += fmt::format(
            "<text transform=\"translate(16 {}) rotate(-90)\" text-anchor=\"middle\">{}</text>",
            (kTop + kHeight - kBottom) / 2, HtmlEscaped(y_label));
    // The frontier as a step line: from each point right along its error, then down to the next.
    std::string path;
    for (std::size_t k = 0; k < line.size(); ++k) {
        if (line[k] >= points.size()) {
            continue;
        }
        const ChartPoint& p = points[line[k]];
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
            continue;
        }
        if (path.empty()) {
            path = fmt::format("M{:.1f},{:.1f}", sx(p.x), sy(p.y));
        } else {
            path += fmt::format(" H{:.1f} V{:.1f}", sx(p.x), sy(p.y));
        }
    }
    if (!path.empty()) {
        svg += fmt::format(
                "<path d=\"{}\" fill=\"none\" stroke=\"#c0392b\" stroke-width=\"1.5\" "
                "stroke-dasharray=\"4 3\"/>",
                path);
    }
    for (const ChartPoint& p : points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
            continue;
        }
        svg += fmt::format(
                "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{}\" fill=\"{}\" "
                "fill-opacity=\"0.8\"><title>{}</title></circle>",
                sx(p.x), sy(p.y), p.highlight ? 5 : 3.5, p.highlight ? "#c0392b" : "#5d6d7e",
                HtmlEscaped(p.tooltip));
        if (!p.label.empty()) {
            svg += fmt::format(
                    "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"10\" fill=\"#333\">{}</text>",
                    sx(p.x) + 6, sy(p.y) - 4, HtmlEscaped(p.label));
        }
    }
    svg += "</svg>";
    return svg;
}

// Horizontal bars: measured change with its interval per row, the whitepaper's figure marked.
std::string WhitepaperChartSvg(const ReportModel& model) {
    constexpr double kWidth = 760;
    constexpr double kRowHeight = 26;
    constexpr double kLeft = 200;
    constexpr double kRight = 20;
    constexpr double kTop = 40;
    const double height = kTop + kRowHeight * static_cast<double>(model.rows.size()) + 40;
    double low = -10, high = 10;
    for (const RowComparison& r : model.rows) {
        for (double v :
             {r.change_percent, r.change_ci.low, r.change_ci.high, r.row.whitepaper_percent}) {
            if (std::isfinite(v)) {
                low = std::min(low, v);
                high = std::max(high, v);
            }
        }
    }
    // Frame-rate changes below -100% cannot happen; above +150% the chart would squash the rest.
    low = std::max(low - 5, -100.0);
    high = std::min(high + 5, 150.0);
    auto sx = [&](double v) {
        return kLeft + (std::clamp(v, low, high) - low) / (high - low) * (kWidth - kLeft - kRight);
    };
    std::string svg = fmt::format(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {0} {1}\" width=\"{0}\" "
            "height=\"{1}\" font-family=\"sans-serif\" font-size=\"11\" role=\"img\">"
            "<title>Performance change per whitepaper row</title>"
            "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>"
            "<text x=\"10\" y=\"18\" font-size=\"12\" font-weight=\"bold\">Performance change "
            "(frame rate, + = faster): bar = measured, line = 95% interval, &#9670; = "
            "whitepaper</text>",
            kWidth, height);
    for (int t = static_cast<int>(std::ceil(low / 20.0)) * 20; t <= high; t += 20) {
        svg += fmt::format(
                "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"{3}\"/>"
                "<text x=\"{0:.1f}\" y=\"{4}\" text-anchor=\"middle\">{5:+d}%</text>",
                sx(t), kTop - 8, height - 30, t == 0 ? "#333" : "#ddd", height - 15, t);
    }
    for (std::size_t i = 0; i < model.rows.size(); ++i) {
        const RowComparison& r = model.rows[i];
        const double y = kTop + kRowHeight * static_cast<double>(i);
        svg += fmt::format("<text x=\"{}\" y=\"{:.1f}\" text-anchor=\"end\">{}. {}</text>",
                           kLeft - 8, y + 15, r.row.number, HtmlEscaped(r.candidate.preset));
        if (std::isfinite(r.change_percent)) {
            const double x0 = sx(0);
            const double x1 = sx(r.change_percent);
            const char* colour = VerdictColour(r.verdict);
            svg += fmt::format(
                    "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"12\" "
                    "fill=\"{}\"><title>row {}: {} ({})</title></rect>",
                    std::min(x0, x1), y + 5, std::max(1.0, std::abs(x1 - x0)), colour, r.row.number,
                    Signed(r.change_percent, 1, "%"), VerdictName(r.verdict));
            if (std::isfinite(r.change_ci.low)) {
                svg += fmt::format(
                        "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" "
                        "stroke=\"#111\" stroke-width=\"1.5\"/>",
                        sx(r.change_ci.low), y + 11, sx(r.change_ci.high), y + 11);
            }
        } else {
            svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" fill=\"#c0392b\">{}</text>",
                               sx(0) + 4, y + 15, VerdictName(r.verdict));
        }
        if (r.row.kind == FigureKind::kPercent && std::isfinite(r.row.whitepaper_percent)) {
            const double wx = sx(r.row.whitepaper_percent);
            svg += fmt::format(
                    "<path d=\"M{0:.1f},{1:.1f} l5,6 l-5,6 l-5,-6 z\" fill=\"#f39c12\" "
                    "stroke=\"#7e5109\"><title>whitepaper: {2}</title></path>",
                    wx, y + 5, HtmlEscaped(r.row.whitepaper_text));
        }
    }
    svg += "</svg>";
    return svg;
}

namespace {

std::vector<ChartPoint> AccuracyPoints(const ReportModel& model) {
    std::vector<ChartPoint> points;
    for (const AccuracyEntry& e : model.accuracy) {
        ChartPoint p;
        p.x = e.measured ? e.median_ms : std::numeric_limits<double>::quiet_NaN();
        p.y = e.measured ? e.SsimLoss() : std::numeric_limits<double>::quiet_NaN();
        p.highlight = e.on_frontier;
        if (!e.configuration->presets.empty()) {
            p.label = e.configuration->presets.front();
        }
        p.tooltip = fmt::format("{}: {} ms, 1-SSIM {}, PSNR {} dB", e.configuration->id,
                                Fixed(e.median_ms, 2), Fixed(e.SsimLoss(), 4), Fixed(e.psnr_db, 1));
        points.push_back(std::move(p));
    }
    return points;
}

std::vector<ChartPoint> StaticPoints(const ReportModel& model) {
    std::vector<ChartPoint> points;
    for (std::size_t i = 0; i < model.static_cost.entries.size(); ++i) {
        const StaticCostEntry& e = model.static_cost.entries[i];
        ChartPoint p;
        p.x = e.total_ops;
        p.y = e.median_ms;
        p.highlight =
                std::find(model.static_cost.misleading.begin(), model.static_cost.misleading.end(),
                          i) != model.static_cost.misleading.end();
        if (p.highlight && !e.configuration->presets.empty()) {
            p.label = e.configuration->presets.front();
        }
        p.tooltip = fmt::format("{}: {} ops, {} ms", e.configuration->id, e.total_ops,
                                Fixed(e.median_ms, 2));
        points.push_back(std::move(p));
    }
    return points;
}

// The time axis of the charts and the single-clock columns, naming the clock compared on.
std::string TimeAxisLabel(const ReportModel& model) {
    return fmt::format("median frame time (ms, {} time)", ClockName(model.clock));
}

}  // namespace

std::string AccuracyChartSvg(const ReportModel& model) {
    return ScatterSvg(AccuracyPoints(model), model.frontier, TimeAxisLabel(model),
                      "mean SSIM loss vs reference (1 - SSIM)",
                      "Accuracy versus time (red: Pareto frontier)");
}

std::string StaticCostChartSvg(const ReportModel& model) {
    return ScatterSvg(StaticPoints(model), {}, "static operations (vertex + fragment total_ops)",
                      TimeAxisLabel(model), "Static cost versus measured time");
}

}  // namespace tidepool::report
