#include "ReportText.h"

#include <cmath>

#include <fmt/format.h>

namespace tidepool::report {

std::string HtmlEscaped(std::string_view text) {
    constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        // XML 1.0 allows no C0 control but tab, newline and carriage return, nor U+FFFE and
        // U+FFFF (EF BF BE, EF BF BF), even as references: one makes an SVG chart unreadable.
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 && c != '\t' && c != '\n' && c != '\r') {
            out += kReplacement;
            continue;
        }
        if (byte == 0xEF && text.substr(i + 1, 1) == "\xBF" && i + 2 < text.size() &&
            (text[i + 2] == '\xBE' || text[i + 2] == '\xBF')) {
            out += kReplacement;
            i += 2;
            continue;
        }
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string Fixed(double value, int digits, std::string_view unit) {
    if (std::isinf(value)) {
        return value > 0 ? "inf" : "-inf";
    }
    if (!std::isfinite(value)) {
        return "–";
    }
    return fmt::format("{:.{}f}{}", value, digits, unit);
}

std::string Signed(double value, int digits, std::string_view unit) {
    if (!std::isfinite(value)) {
        return std::isinf(value) ? (value > 0 ? "+inf" : "-inf") : "–";
    }
    return fmt::format("{:+.{}f}{}", value, digits, unit);
}

std::string IntervalText(const Interval& ci, int digits, std::string_view unit) {
    if (std::isnan(ci.low) || std::isnan(ci.high)) {
        return "–";
    }
    return fmt::format("[{}, {}]", Signed(ci.low, digits, unit), Signed(ci.high, digits, unit));
}

std::string ClockName(TimingClock clock) {
    return clock == TimingClock::kCpu ? "CPU" : "wall";
}

std::string DirectionText(int sign) {
    return sign > 0 ? "faster" : "slower";
}

std::string PanelId(const ImagePanel& panel) {
    return panel.configuration != nullptr ? panel.configuration->id : std::string("(missing)");
}

std::string StabilityHowTo() {
    return "No numerical-stability catalogue was found next to results.json. Produce one with "
           "`tidepool stability` (it writes stability.json, schema \"tidepool.stability\", beside "
           "the results), then rebuild this report with `tidepool report`.";
}

std::string PlansHowTo() {
    return "No scene plans were found next to results.json. Produce them with `tidepool plan "
           "--all --out DIR` (DIR = the folder of results.json; it writes plans.json, schema "
           "\"tidepool.plans\"), or let `tidepool run` make them (unless --no-plans), then "
           "rebuild this report with `tidepool report`.";
}

}  // namespace tidepool::report
