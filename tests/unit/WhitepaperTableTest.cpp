// The whitepaper's table as data: eleven rows, each with its presets and note, and which rows
// give only a direction (reports/include/tidepool/report/WhitepaperTable.h).
#include "tidepool/report/WhitepaperTable.h"

#include <gtest/gtest.h>

#include <cstddef>

namespace {

using namespace tidepool::report;

const WhitepaperRow& TableRow(int number) {
    return WhitepaperRows()[static_cast<std::size_t>(number - 1)];
}

TEST(WhitepaperTableTest, HasElevenRowsWithPresetsAndDirectionOnlyRowsEightToEleven) {
    ASSERT_EQ(WhitepaperRows().size(), 11u);
    for (const WhitepaperRow& row : WhitepaperRows()) {
        EXPECT_FALSE(row.baseline_preset.empty()) << row.number;
        EXPECT_FALSE(row.candidate_preset.empty()) << row.number;
        EXPECT_FALSE(row.llvmpipe_note.empty()) << row.number;
        EXPECT_EQ(row.kind == FigureKind::kDirection, row.number >= 8) << row.number;
    }
    EXPECT_EQ(TableRow(1).whitepaper_percent, -60.0);
    EXPECT_EQ(TableRow(4).baseline_preset, "full");
    EXPECT_EQ(TableRow(4).candidate_preset, "full_no_fog");
    EXPECT_EQ(TableRow(9).baseline_preset, "full_uniform_bools");
    EXPECT_EQ(TableRow(10).baseline_preset, "full_clip_discard");
}

}  // namespace
