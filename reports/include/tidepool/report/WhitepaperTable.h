// The whitepaper's cost table (../shared/seeds/README.md, from "Shader Based Water Effects",
// PowerVR SDK REL_16.1) as data: for each of its 11 rows the change, the figure as the
// whitepaper words it, the presets of variants.yaml that reproduce the comparison, and one line
// on why Mesa's llvmpipe may agree or differ.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace tidepool::report {

/// How a whitepaper figure can be compared with a measurement.
enum class FigureKind {
    kPercent,     // a performance change in percent of frame rate ("reduced by 60%")
    kNegligible,  // "reduced by <1%": no change to within the magnitude tolerance
    kDirection,   // a qualitative claim ("significantly faster"): only the direction is compared
};

/// One row of the whitepaper's cost table.
struct WhitepaperRow {
    int number = 0;
    std::string change;           // what the row changes, in the whitepaper's terms
    std::string whitepaper_text;  // the figure as the whitepaper words it
    FigureKind kind = FigureKind::kPercent;
    // Performance change in percent of frame rate, positive = faster (kPercent rows); for
    // kNegligible the bound's sign (-1: slower by at most 1%); NaN for kDirection rows.
    double whitepaper_percent = std::numeric_limits<double>::quiet_NaN();
    int expected_sign = 0;         // +1: the candidate should be faster, -1 slower
    std::string baseline_preset;   // the configuration before the change
    std::string candidate_preset;  // the configuration after the change
    std::string llvmpipe_note;     // why llvmpipe agrees or differs, one line
};

/// The 11 rows, in the whitepaper's order. Never fails.
const std::vector<WhitepaperRow>& WhitepaperRows();

/// One paragraph for the report's Method section: which rows' configurations changed from the
/// previous definitions, and why (Markdown inline code for names). Never fails.
std::string RowDefinitionChanges();

}  // namespace tidepool::report
