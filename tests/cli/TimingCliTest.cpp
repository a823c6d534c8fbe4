// The timing flags of `render`, `bench` and `run`: the one timing engine as a user drives it,
// stdout and stderr captured apart.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "TempDir.h"
#include "TidepoolProcess.h"
#include <nlohmann/json.hpp>

namespace {

using tidepool::testing::CommandResult;
using tidepool::testing::RunTidepool;
using tidepool::testing::TempDir;

TEST(TimingCliTest, OutOfRangeTimingFlagsAreUsageErrorsNamingTheFlag) {
    TempDir dir;
    const CommandResult resolution =
            RunTidepool("render --resolution 0 --out " + (dir.Path() / "o").string());
    EXPECT_EQ(resolution.exit_code, 2);
    EXPECT_NE(resolution.err.find("error: --resolution must be above 0 and at most 50 percent "
                                  "points, not 0"),
              std::string::npos)
            << resolution.err;
    const CommandResult pairs =
            RunTidepool("run --min-pairs 5 --out " + (dir.Path() / "o").string());
    EXPECT_EQ(pairs.exit_code, 2);
    EXPECT_NE(pairs.err.find("error: --min-pairs must be at least 10 and --max-pairs between "
                             "--min-pairs and 100000, not 5 and 400"),
              std::string::npos)
            << pairs.err;
    EXPECT_FALSE(std::filesystem::exists(dir.Path() / "o"));
}

TEST(TimingCliTest, RenderTimesEveryComparedPresetPairOnTheThreadClock) {
    TempDir dir;
    const CommandResult r = RunTidepool(
            "render --preset full --preset full_no_fog --preset full_constant_mix "
            "--view three_quarter --size 64x48 --min-pairs 10 --max-pairs 10 "
            "--coarse-frames 2 --no-images --json --out " +
            (dir.Path() / "render").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json results = nlohmann::json::parse(r.out);
    EXPECT_EQ(results["timing"]["clock"], "thread_cpu");
    EXPECT_EQ(results["environment"]["lp_num_threads"], "0");
    // Rows 4 (full -> full_no_fog) and 5 (full_constant_mix -> full), 10 pairs each.
    ASSERT_EQ(results["comparisons"].size(), 2U);
    for (const nlohmann::json& c : results["comparisons"]) {
        EXPECT_EQ(c["pairs"], 10);
        EXPECT_EQ(c["baseline_ms"].size(), 10U);
        // 10 pairs either reach the resolution (resolved) or stop at the cap (capped).
        EXPECT_TRUE(c["decision"] == "resolved" || c["decision"] == "capped") << c["decision"];
    }
    EXPECT_EQ(results["comparisons"][0]["label"], "row 4");
    EXPECT_EQ(results["comparisons"][1]["label"], "row 5");
    // The progress and summary go to stderr, the JSON alone to stdout.
    EXPECT_NE(r.err.find("2 comparisons to +/-1.5 points"), std::string::npos) << r.err;
}

}  // namespace
