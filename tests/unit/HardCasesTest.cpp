// The catalogue of numerical hard cases (lab/include/tidepool/lab/HardCases.h): unique, documented
// names, CPU sweeps first, lookup by name. Running the cases is StabilityReportTest's.
#include "tidepool/lab/HardCases.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

namespace tidepool::lab {
namespace {

TEST(HardCasesTest, NamesAreUniqueAndEveryCaseIsDocumented) {
    std::set<std::string> names;
    for (const HardCase& c : HardCaseCatalogue()) {
        EXPECT_TRUE(names.insert(c.name).second) << c.name;
        EXPECT_FALSE(c.description.empty()) << c.name;
    }
    EXPECT_NE(FindHardCase(HardCaseCatalogue(), "camera_on_water"), nullptr);
    EXPECT_EQ(FindHardCase(HardCaseCatalogue(), "no_such_case"), nullptr);
}

TEST(HardCasesTest, CpuSweepsComeFirstAndBothKindsArePresent) {
    const std::vector<HardCase> catalogue = HardCaseCatalogue();
    const auto first_gl = std::find_if(catalogue.begin(), catalogue.end(), [](const HardCase& c) {
        return c.kind == HardCaseKind::kGl;
    });
    ASSERT_NE(first_gl, catalogue.begin());
    ASSERT_NE(first_gl, catalogue.end());
    EXPECT_TRUE(std::all_of(first_gl, catalogue.end(),
                            [](const HardCase& c) { return c.kind == HardCaseKind::kGl; }));
    EXPECT_STREQ(HardCaseKindName(HardCaseKind::kCpu), "cpu");
    EXPECT_STREQ(HardCaseKindName(HardCaseKind::kGl), "gl");
}

TEST(HardCasesTest, FindHardCasePointsIntoTheListGiven) {
    const std::vector<HardCase> catalogue = HardCaseCatalogue();
    const HardCase* found = FindHardCase(catalogue, catalogue.back().name);
    EXPECT_EQ(found, &catalogue.back());
    EXPECT_EQ(FindHardCase({}, catalogue.front().name), nullptr);
}

}  // namespace
}  // namespace tidepool::lab
