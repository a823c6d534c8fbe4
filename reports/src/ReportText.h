// The small formatting pieces the report's builder, charts, data.json and terminal table share:
// numbers as text, clock and direction names, HTML escaping, and the two "how to produce it"
// sentences data.json repeats from the report.
#pragma once

#include "tidepool/report/ReportModel.h"

#include <string>
#include <string_view>

namespace tidepool::report {

/// `text` with &, <, > and " escaped for HTML text and attribute values (and SVG's XML), and
/// each character XML 1.0 does not allow (C0 controls but tab, newline and carriage return;
/// U+FFFE, U+FFFF) replaced by U+FFFD.
std::string HtmlEscaped(std::string_view text);

/// `value` with `digits` decimals and `unit`; "inf"/"-inf" when infinite, "–" when NaN.
std::string Fixed(double value, int digits, std::string_view unit = "");

/// As Fixed, always with a sign ("+inf"/"-inf" when infinite).
std::string Signed(double value, int digits, std::string_view unit = "");

/// "[low, high]" with signs, or "–" when either end is NaN.
std::string IntervalText(const Interval& ci, int digits, std::string_view unit);

/// "CPU" or "wall".
std::string ClockName(TimingClock clock);

/// "faster" for a positive sign, else "slower".
std::string DirectionText(int sign);

/// The configuration id a panel shows, or "(missing)" when no configuration carries its preset.
std::string PanelId(const ImagePanel& panel);

/// How to produce stability.json when the report found none.
std::string StabilityHowTo();

/// How to produce plans.json when the report found none.
std::string PlansHowTo();

}  // namespace tidepool::report
