// Whole-process cost of `tidepool expand` as the matrix grows while its valid variants stay few:
// the figures issue 12 asks for (expansion proportional to valid variants, not 2^features).
//
// Usage: expand_scaling [ROUNDS]   (ROUNDS: runs of every case, default 7)
//
// Method, stated again next to the figures it produces:
//  * Cases, each a variants.yaml written with a tiny pair of shader files to a temporary folder:
//    - chain k (k = 12, 18, 24, 30): features F0..F(k-1), each requiring the one before, so
//      k + 1 valid variants out of 2^k combinations;
//    - axes: 10 axes G0..G9 of 3 mutually exclusive values (30 defines, 3^10 = 59,049
//      combinations); adjacent axes may pair value `a` only with `a` (36 `exclude` rules), so
//      the valid variants are all-`a` plus every string over {b, c}: 1 + 2^10 = 1,025;
//    - the shipped variants.yaml (163 valid of 24,598), and `tidepool --version`, which does no
//      expansion at all: what start-up alone costs.
//  * Each run is the real binary (TIDEPOOL_BINARY, or argv[2]) started with posix_spawn, stdout
//    read through a pipe, and reaped with wait4, whose rusage gives that child's own peak
//    resident set (ru_maxrss). Wall time is from spawn to reap. Rounds are interleaved (every
//    case once per round) so that load from other work on the machine spreads over all cases.
//  * Each run's last line must state the expected number of valid variants; a run that does not
//    is reported as WRONG, never timed as if it were right.
//  * Targets (issue 12): chain ≤ 50 ms and ≤ 30 MB for every k; axes ≤ 100 ms. Printed next to
//    the figures; this program never passes or fails on them.
//
// Exit codes: 0 (figures printed), 1 when the binary cannot run or a case gives a wrong count,
// 2 on a bad argument.
#include "tidepool/base/SampleStatistics.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "BenchSupport.h"
#include <fmt/format.h>
#include <unistd.h>

namespace {

struct Case {
    std::string name;
    std::vector<std::string> args;   // after the binary
    std::string expected_last_line;  // prefix the run's last output line must start with
    std::string combinations;
    std::string target;
    std::vector<double> wall_ms;
    std::vector<double> rss_mb;
    bool wrong = false;
};

void WriteFile(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

constexpr const char* kProgramHead = "programs:\n  p:\n    vertex: s.vsh\n    fragment: s.fsh\n";

std::string ChainConfig(int k) {
    std::string yaml = kProgramHead;
    yaml += "    features: [";
    for (int i = 0; i < k; ++i) {
        yaml += fmt::format("{}F{}", i == 0 ? "" : ", ", i);
    }
    yaml += "]\n    rules:\n";
    for (int i = 1; i < k; ++i) {
        yaml += fmt::format("      - {{ if: F{}, requires: F{} }}\n", i, i - 1);
    }
    return yaml;
}

std::string AxesConfig() {
    std::string yaml = kProgramHead;
    yaml += "    axes:\n";
    for (int g = 0; g < 10; ++g) {
        yaml += fmt::format("      G{}: [a, b, c]\n", g);
    }
    yaml += "    rules:\n";
    for (int g = 0; g + 1 < 10; ++g) {
        for (const auto& [x, y] :
             {std::pair{"A", "B"}, std::pair{"A", "C"}, std::pair{"B", "A"}, std::pair{"C", "A"}}) {
            yaml += fmt::format("      - {{ exclude: [G{}_{}, G{}_{}] }}\n", g, x, g + 1, y);
        }
    }
    return yaml;
}

}  // namespace

int main(int argc, char** argv) {
    const int rounds = tidepool::bench::RoundsArgument(
            argc, argv, 7, 1000, "expand_scaling [ROUNDS 1..1000] [TIDEPOOL_BINARY]");
    if (rounds == 0) {
        return 2;
    }
    const std::string binary = argc > 2 ? argv[2] : TIDEPOOL_BINARY;

    const std::filesystem::path dir = tidepool::bench::MakeTempFolder("expand-scaling");
    if (dir.empty()) {
        return 1;
    }
    WriteFile(dir / "s.vsh", "#version 100\nattribute vec4 p;\nvoid main() { gl_Position = p; }\n");
    WriteFile(dir / "s.fsh",
              "#version 100\nprecision mediump float;\nvoid main() { "
              "gl_FragColor = vec4(1.0); }\n");

    std::vector<Case> cases;
    cases.push_back({"--version (start-up only)", {"--version"}, "tidepool", "-", "-", {}, {}});
    for (int k : {12, 18, 24, 30}) {
        const std::filesystem::path config = dir / fmt::format("chain{}.yaml", k);
        WriteFile(config, ChainConfig(k));
        cases.push_back({fmt::format("chain k={}", k),
                         {"expand", "--config", config.string()},
                         fmt::format("{} variants, ", k + 1),
                         fmt::format("2^{}", k),
                         "<= 50 ms, <= 30 MB",
                         {},
                         {}});
    }
    WriteFile(dir / "axes.yaml", AxesConfig());
    cases.push_back({"axes 10x3",
                     {"expand", "--config", (dir / "axes.yaml").string()},
                     "1025 variants, ",
                     "3^10",
                     "<= 100 ms",
                     {},
                     {}});
    cases.push_back({"default variants.yaml",
                     {"expand", "--config",
                      (std::filesystem::path(TIDEPOOL_SOURCE_ROOT) / "variants.yaml").string()},
                     "163 variants, ",
                     "24598",
                     "-",
                     {},
                     {}});

    std::printf("%s\nload average before: %s\nbinary: %s\n%d interleaved rounds per case\n\n",
                tidepool::bench::DescribeEnvironment().c_str(),
                tidepool::bench::LoadAverage().c_str(), binary.c_str(), rounds);
    bool all_right = true;
    for (int round = 0; round < rounds; ++round) {
        for (Case& c : cases) {
            const tidepool::bench::ProcessRun run = tidepool::bench::RunProcess(binary, c.args);
            if (!run.ok || run.last_line.rfind(c.expected_last_line, 0) != 0) {
                if (!c.wrong) {
                    std::fprintf(stderr, "%s: WRONG: exit %s, last line '%s', expected '%s...'\n",
                                 c.name.c_str(), run.ok ? "0" : "non-zero", run.last_line.c_str(),
                                 c.expected_last_line.c_str());
                }
                c.wrong = true;
                all_right = false;
                continue;
            }
            c.wall_ms.push_back(run.wall_ms);
            c.rss_mb.push_back(run.rss_mb);
        }
    }

    std::printf("%-26s %8s %7s %10s %9s %12s   %s\n", "case", "combos", "valid", "median ms",
                "min ms", "peak RSS MB", "target");
    for (const Case& c : cases) {
        const std::string valid =
                c.expected_last_line.find(" variants") == std::string::npos
                        ? "-"
                        : c.expected_last_line.substr(0, c.expected_last_line.find(' '));
        if (c.wrong) {
            std::printf("%-26s %8s %7s %10s %9s %12s   %s\n", c.name.c_str(),
                        c.combinations.c_str(), valid.c_str(), "WRONG", "-", "-", c.target.c_str());
            continue;
        }
        std::printf("%-26s %8s %7s %10.1f %9.1f %12.1f   %s\n", c.name.c_str(),
                    c.combinations.c_str(), valid.c_str(), tidepool::base::Median(c.wall_ms),
                    tidepool::bench::Min(c.wall_ms), tidepool::base::Median(c.rss_mb),
                    c.target.c_str());
    }
    std::printf(
            "\nload average after: %s\n"
            "Wall time is the whole process, start-up included; compare with the --version "
            "row, which is start-up alone.\n",
            tidepool::bench::LoadAverage().c_str());
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    return all_right ? 0 : 1;
}
