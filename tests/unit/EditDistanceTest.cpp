// base::EditDistance and base::ClosestName: the "did you mean" of limit names and commands.
#include "tidepool/base/EditDistance.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using tidepool::base::ClosestName;
using tidepool::base::EditDistance;

TEST(EditDistanceTest, CountsInsertionsDeletionsAndSubstitutions) {
    EXPECT_EQ(EditDistance("", ""), 0u);
    EXPECT_EQ(EditDistance("run", "run"), 0u);
    EXPECT_EQ(EditDistance("", "plan"), 4u);
    EXPECT_EQ(EditDistance("validat", "validate"), 1u);  // one insertion
    EXPECT_EQ(EditDistance("stats", "stat"), 1u);        // one deletion
    EXPECT_EQ(EditDistance("bench", "bunch"), 1u);       // one substitution
    EXPECT_EQ(EditDistance("rnu", "run"), 2u);           // a swap is two edits
    EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);
    EXPECT_EQ(EditDistance("sitting", "kitten"), 3u);
}

TEST(EditDistanceTest, ClosestNameIsTheNearestAndTheFirstOfEquals) {
    const std::vector<std::string> names = {"expand", "validate", "render", "report"};
    EXPECT_EQ(ClosestName("valdate", names), "validate");
    EXPECT_EQ(ClosestName("repo", names), "report");
    EXPECT_EQ(ClosestName("rexxxx", names), "render");  // 4 from render and from report
    EXPECT_EQ(ClosestName("anything", {}), "");
}

}  // namespace
