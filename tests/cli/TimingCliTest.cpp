// The timing flags of `render`, `bench` and `run`: the one timing engine as a user drives it,
// stdout and stderr captured apart.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "TempDir.h"
#include <nlohmann/json.hpp>
#include <sys/wait.h>

namespace {

using tidepool::testing::TempDir;

struct Output {
    int exit_code = -1;
    std::string out;
    std::string err;
};

// Runs the binary with `args` in the source root; stderr goes to a file read back afterwards.
Output RunSeparately(const std::string& args, const TempDir& dir) {
    const std::filesystem::path err = dir.Path() / "stderr.txt";
    const std::string command = "cd '" + std::string(TIDEPOOL_SOURCE_ROOT) + "' && '" +
                                std::string(TIDEPOOL_BINARY) + "' " + args + " 2>'" + err.string() +
                                "'";
    Output result;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return result;
    }
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) {
        result.out.append(buffer, n);
    }
    const int status = ::pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(err);
    result.err.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return result;
}

TEST(TimingCliTest, OutOfRangeTimingFlagsAreUsageErrorsNamingTheFlag) {
    TempDir dir;
    const Output resolution =
            RunSeparately("render --resolution 0 --out " + (dir.Path() / "o").string(), dir);
    EXPECT_EQ(resolution.exit_code, 2);
    EXPECT_NE(resolution.err.find("error: --resolution must be above 0 and at most 50 percent "
                                  "points, not 0"),
              std::string::npos)
            << resolution.err;
    const Output pairs =
            RunSeparately("run --min-pairs 5 --out " + (dir.Path() / "o").string(), dir);
    EXPECT_EQ(pairs.exit_code, 2);
    EXPECT_NE(pairs.err.find("error: --min-pairs must be at least 10 and --max-pairs between "
                             "--min-pairs and 100000, not 5 and 400"),
              std::string::npos)
            << pairs.err;
    EXPECT_FALSE(std::filesystem::exists(dir.Path() / "o"));
}

TEST(TimingCliTest, RenderTimesEveryComparedPresetPairOnTheThreadClock) {
    TempDir dir;
    const Output r = RunSeparately(
            "render --preset full --preset full_no_fog --preset full_constant_mix "
            "--view three_quarter --size 64x48 --min-pairs 10 --max-pairs 10 "
            "--coarse-frames 2 --no-images --json --out " +
                    (dir.Path() / "render").string(),
            dir);
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
