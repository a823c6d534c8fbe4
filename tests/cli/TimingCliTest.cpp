// The timing flags of `render`, `bench` and `run`: the one timing engine as a user drives it,
// stdout and stderr captured apart.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

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
    // 2000000000 warm-up frames were accepted, and `run` began a render that would never end.
    for (const char* command :
         {"render --warmup 2000000000", "run --coarse-frames 1001", "bench --warmup -1"}) {
        const CommandResult frames =
                RunTidepool(std::string(command) + " --out " + (dir.Path() / "o").string());
        EXPECT_EQ(frames.exit_code, 2) << command;
        EXPECT_EQ(frames.err.rfind("error: --coarse-frames must be between 1 and 1000, --warmup "
                                   "between 0 and 1000, --workers and --threads between 0 and "
                                   "64, not ",
                                   0),
                  0U)
                << command << ": " << frames.err;
    }
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

// `--progress-log` writes the render's first line and then every progress state, each a JSON
// object on a line of its own with the figures behind its ETA, up to the state that ends it.
TEST(TimingCliTest, AProgressLogHoldsEveryStateWithTheFiguresBehindItsEta) {
    TempDir dir;
    const std::filesystem::path log = dir.Path() / "progress.jsonl";
    const CommandResult r = RunTidepool(
            "render --preset full --preset full_no_fog --view three_quarter --size 64x48 "
            "--min-pairs 10 --max-pairs 10 --coarse-frames 2 --no-images --out " +
            (dir.Path() / "render").string() + " --progress-log " + log.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(log);
    std::string text;
    std::vector<nlohmann::json> records;
    while (std::getline(in, text)) {
        records.push_back(nlohmann::json::parse(text));  // throws, failing the test, if not JSON
    }
    ASSERT_GE(records.size(), 3U);
    EXPECT_NE(records[0]["line"].get<std::string>().find("render: 2 configurations"),
              std::string::npos)
            << records[0];
    double t = 0;
    for (std::size_t i = 1; i < records.size(); ++i) {
        const nlohmann::json& state = records[i];
        EXPECT_GE(state["t"].get<double>(), t);
        t = state["t"].get<double>();
        EXPECT_LE(state["done"].get<long>(), state["total"].get<long>()) << state;
        EXPECT_TRUE(state["parts"].contains("image_frames_left")) << state;
        EXPECT_TRUE(state["parts"].contains("own_end_seconds")) << state;
    }
    EXPECT_NEAR(records.back()["percent"].get<double>(), 100.0, 1e-9);
    EXPECT_EQ(records.back()["parts"]["seconds_left"], 0.0);
}

TEST(TimingCliTest, AProgressLogThatCannotBeWrittenIsAUsageErrorBeforeTheRender) {
    TempDir dir;
    const CommandResult r =
            RunTidepool("render --out " + (dir.Path() / "render").string() + " --progress-log " +
                        (dir.Path() / "no" / "such" / "p.jsonl").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("p.jsonl: cannot write it (No such file or directory); give a file in a "
                         "folder that exists"),
              std::string::npos)
            << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.Path() / "render"));
}

}  // namespace
