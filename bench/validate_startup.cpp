// Start-up of `tidepool validate FILE` against glslangValidator on the same file pair, whole
// process as a user runs it: the figure issue 12 asks for ("tidepool validate FILE should start
// about as fast as glslangValidator").
//
// Usage: validate_startup [ROUNDS] [TIDEPOOL_BINARY]   (ROUNDS: runs of every case, default 21)
//
// Method, stated again next to the figures it produces:
//  * The file pair is the shipped water shader (shaders/water.vsh and .fsh, GLSL ES 1.00, no
//    defines), copied to a temporary folder as .vert/.frag so that glslangValidator knows the
//    stages from the names. Both tools parse both stages and link them:
//    `tidepool validate --no-cache w.vert w.frag` and `glslangValidator -l w.vert w.frag`.
//  * `tidepool validate --cache DIR w.vert w.frag` is the same pair with a validation cache that
//    is warm after the first round (which is timed too: its median is the warm figure).
//  * `tidepool --version` and `glslangValidator --version` are start-up alone, for reference.
//  * Each run is a process started with posix_spawn and reaped with wait4 (peak RSS from its
//    rusage); rounds are interleaved (every case once per round), so that load from other work
//    on the machine spreads over all cases. Medians are compared.
//  * Every run must succeed (exit 0; tidepool's last line "2 file(s): valid"); a case that does
//    not is reported as WRONG and not timed.
//  * Target (issue 12): tidepool validate FILE <= 1.5x glslangValidator. Printed with the
//    figures as met or NOT met; this program never fails on it.
//
// Exit codes: 0 (figures printed), 1 when a tool cannot run or a case is WRONG, 2 on a bad
// argument.
#include "tidepool/base/SampleStatistics.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "BenchSupport.h"
#include <fmt/format.h>

namespace {

struct Case {
    std::string name;
    std::string binary;
    std::vector<std::string> args;
    std::string expected_last_line;  // "" when the exit code alone says it worked
    std::vector<double> wall_ms;
    std::vector<double> rss_mb;
    bool wrong = false;
};

}  // namespace

int main(int argc, char** argv) {
    const int rounds = tidepool::bench::RoundsArgument(
            argc, argv, 21, 10000, "validate_startup [ROUNDS 1..10000] [TIDEPOOL_BINARY]");
    if (rounds == 0) {
        return 2;
    }
    const std::string tidepool = argc > 2 ? argv[2] : TIDEPOOL_BINARY;
    const std::string glslang = "glslangValidator";

    const std::filesystem::path dir = tidepool::bench::MakeTempFolder("validate-startup");
    if (dir.empty()) {
        return 1;
    }
    const std::filesystem::path shaders = std::filesystem::path(TIDEPOOL_SOURCE_ROOT) / "shaders";
    std::filesystem::copy_file(shaders / "water.vsh", dir / "w.vert");
    std::filesystem::copy_file(shaders / "water.fsh", dir / "w.frag");
    const std::string vert = (dir / "w.vert").string();
    const std::string frag = (dir / "w.frag").string();

    // The target is judged without the validation cache (every run validates); the warm-cache
    // case is what a rerun on unchanged files costs, for reference.
    const std::string cache = (dir / "cache").string();
    std::vector<Case> cases = {
            {"tidepool validate pair",
             tidepool,
             {"validate", "--no-cache", vert, frag},
             "2 file(s): valid",
             {},
             {},
             false},
            {"glslangValidator -l pair", glslang, {"-l", vert, frag}, "", {}, {}, false},
            {"tidepool --version", tidepool, {"--version"}, "tidepool", {}, {}, false},
            {"glslangValidator --version", glslang, {"--version"}, "", {}, {}, false},
            {"tidepool validate, cached",
             tidepool,
             {"validate", "--cache", cache, vert, frag},
             "2 file(s): valid",
             {},
             {},
             false},
    };
    std::printf(
            "%s\nbinary: %s\nfiles: shaders/water.vsh + water.fsh as .vert/.frag\n"
            "%d interleaved rounds per case\n\n",
            tidepool::bench::DescribeEnvironment().c_str(), tidepool.c_str(), rounds);
    bool all_right = true;
    for (int round = 0; round < rounds; ++round) {
        for (Case& c : cases) {
            const tidepool::bench::ProcessRun run = tidepool::bench::RunProcess(c.binary, c.args);
            if (!run.ok || run.last_line.rfind(c.expected_last_line, 0) != 0) {
                if (!c.wrong) {
                    std::fprintf(stderr, "%s: WRONG: exit %d, output:\n%s\n", c.name.c_str(),
                                 run.exit_code, run.output.c_str());
                }
                c.wrong = true;
                all_right = false;
                continue;
            }
            c.wall_ms.push_back(run.wall_ms);
            c.rss_mb.push_back(run.rss_mb);
        }
    }
    std::printf("%-28s %10s %9s %12s\n", "case", "median ms", "min ms", "peak RSS MB");
    for (const Case& c : cases) {
        if (c.wrong) {
            std::printf("%-28s %10s\n", c.name.c_str(), "WRONG");
            continue;
        }
        std::printf("%-28s %10.1f %9.1f %12.1f\n", c.name.c_str(),
                    tidepool::base::Median(c.wall_ms), tidepool::bench::Min(c.wall_ms),
                    tidepool::base::Median(c.rss_mb));
    }
    if (!cases[0].wrong && !cases[1].wrong) {
        const double ratio =
                tidepool::base::Median(cases[0].wall_ms) / tidepool::base::Median(cases[1].wall_ms);
        std::printf(
                "\ntidepool validate FILE / glslangValidator (medians): %.2fx; target <= 1.5x: "
                "%s\n",
                ratio, tidepool::bench::Verdict(ratio <= 1.5));
    }
    std::printf("load average after: %s\n", tidepool::bench::LoadAverage().c_str());
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    return all_right ? 0 : 1;
}
