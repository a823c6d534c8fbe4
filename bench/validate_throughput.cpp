// Validation throughput of the default variant matrix (variants.yaml), and the same work done the
// way a shell user would do it: glslangValidator run once per stage file.
//
// Usage: validate_throughput [REPEATS]   (REPEATS: timed runs of each side, default 5)
//
// Method, stated again next to every figure it produces:
//  * tidepool: ValidateVariants over every variant and every target of variants.yaml, with
//    jobs = hardware threads. One untimed-for-the-median warm-up run (it pays for glslang's
//    process initialisation and built-in symbol tables) is shown separately; then REPEATS runs,
//    reported as median and min wall time, plus median CPU time of this process (all threads).
//    It deduplicates identical preprocessed stages and links every distinct (vertex, fragment)
//    pair. The same runs with jobs = 1 show the per-core speed.
//  * glslangValidator: each variant's stages, with its defines applied as AssembleDriverSource
//    writes them (what a shell user would feed a compiler), are written to .vert/.frag files in a
//    temporary folder (not timed). Then `glslangValidator FILE` is run once per file, one after
//    another as a shell loop would, output sent to /dev/null; REPEATS loops, median and min wall
//    time, plus the children's CPU time. No -l: the issue asks for one run per stage.
//  * ratio = loop time / tidepool time, both medians of this same run.
//
// Exit codes: 0 (also when glslangValidator is missing: that part is skipped), 1 when
// variants.yaml does not load or expand, 2 on a bad argument.
#include "tidepool/Diagnostic.h"
#include "tidepool/GlslValidator.h"
#include "tidepool/SourceAssembler.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/base/SampleStatistics.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "BenchSupport.h"
#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace {

namespace fs = std::filesystem;
using tidepool::base::Median;
using tidepool::bench::Min;
using tidepool::bench::NowSeconds;
using tidepool::bench::ProcessCpuSeconds;

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;
constexpr int kDefaultRepeats = 5;
// The target: tidepool at least this many times faster than the per-stage loop.
constexpr double kTargetSpeedup = 20.0;

// Wall and CPU seconds of repeated runs of one thing.
struct Timings {
    std::vector<double> wall;
    std::vector<double> cpu;
};

struct TidepoolRun {
    Timings timings;
    double warmup_wall = 0.0;
    tidepool::ValidationReport last;  // of the last timed run, to check and count
};

TidepoolRun TimeTidepool(const tidepool::VariantConfig& config,
                         const std::vector<tidepool::Variant>& variants, int jobs, int repeats) {
    const tidepool::ValidationOptions options{jobs, config.targets};
    TidepoolRun run;
    double start = NowSeconds();
    run.last = tidepool::ValidateVariants(config, variants, options);
    run.warmup_wall = NowSeconds() - start;
    for (int r = 0; r < repeats; ++r) {
        start = NowSeconds();
        const double cpu_start = ProcessCpuSeconds();
        run.last = tidepool::ValidateVariants(config, variants, options);
        run.timings.cpu.push_back(ProcessCpuSeconds() - cpu_start);
        run.timings.wall.push_back(NowSeconds() - start);
    }
    return run;
}

// The first executable called `name` on PATH, or "" (what a shell's lookup would find).
std::string FindOnPath(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path == nullptr ? "" : path);
    for (std::string dir; std::getline(dirs, dir, ':');) {
        const fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
        if (access(candidate.c_str(), X_OK) == 0) {
            return candidate.string();
        }
    }
    return "";
}

// CPU seconds (user + system) of every child process reaped so far.
double ChildrenCpuSeconds() {
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    auto seconds = [](const timeval& t) {
        return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) * 1e-6;
    };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// Runs `program file` with stdout and stderr sent to /dev/null and waits for it; returns its exit
// status, or -1 when it could not be started or did not exit normally.
int RunQuietly(const std::string& program, const std::string& file) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    std::string arg0 = program;
    std::string arg1 = file;
    char* argv[] = {arg0.data(), arg1.data(), nullptr};
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) {
        return -1;
    }
    int status = 0;
    if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) {
        return -1;
    }
    return WEXITSTATUS(status);
}

// One stage file of one variant, as written for glslangValidator.
struct StageFile {
    fs::path path;
    std::string key;  // target|stage|variant id, to find the distinct stage programs
};

std::string StageKey(tidepool::GlslTarget target, tidepool::Stage stage, const std::string& id) {
    return fmt::format("{}|{}|{}", tidepool::TargetName(target), tidepool::StageName(stage), id);
}

// Writes every variant's stages, defines applied, into `folder`; returns "" or an error message.
std::string WriteStageFiles(const tidepool::VariantConfig& config,
                            const std::vector<tidepool::Variant>& variants, const fs::path& folder,
                            std::vector<StageFile>* files) {
    std::map<std::string, std::string> sources;  // shader path as written → its text
    std::size_t index = 0;
    for (tidepool::GlslTarget target : config.targets) {
        for (const tidepool::Variant& variant : variants) {
            const tidepool::ProgramConfig* program = config.FindProgram(variant.program);
            for (tidepool::Stage stage : {tidepool::Stage::kVertex, tidepool::Stage::kFragment}) {
                const bool vertex = stage == tidepool::Stage::kVertex;
                const std::string& shader = vertex ? program->vertex_path : program->fragment_path;
                if (sources.count(shader) == 0) {
                    std::ifstream in(config.Resolve(shader), std::ios::binary);
                    std::ostringstream text;
                    text << in.rdbuf();
                    if (!in) {
                        return fmt::format("{}: cannot read", config.Resolve(shader).string());
                    }
                    sources[shader] = text.str();
                }
                StageFile file;
                file.path = folder / fmt::format("{:04}_{}_{}.{}", index, variant.program,
                                                 tidepool::TargetName(target),
                                                 vertex ? "vert" : "frag");
                file.key = StageKey(target, stage, variant.Id());
                std::ofstream out(file.path, std::ios::binary);
                out << tidepool::AssembleDriverSource(sources[shader], variant.defines, stage,
                                                      target);
                if (!out) {
                    return fmt::format("{}: cannot write", file.path.string());
                }
                files->push_back(std::move(file));
            }
            ++index;
        }
    }
    return "";
}

struct LoopRun {
    Timings timings;
    std::vector<std::vector<double>> per_file;  // [file][repeat] wall seconds
    int failures = 0;                           // nonzero exits (or failed starts), all repeats
};

LoopRun TimeLoop(const std::string& validator, const std::vector<StageFile>& files, int repeats) {
    LoopRun run;
    run.per_file.resize(files.size());
    for (int r = 0; r < repeats; ++r) {
        const double start = NowSeconds();
        const double cpu_start = ChildrenCpuSeconds();
        for (std::size_t i = 0; i < files.size(); ++i) {
            const double file_start = NowSeconds();
            if (RunQuietly(validator, files[i].path.string()) != 0) {
                ++run.failures;
            }
            run.per_file[i].push_back(NowSeconds() - file_start);
        }
        run.timings.cpu.push_back(ChildrenCpuSeconds() - cpu_start);
        run.timings.wall.push_back(NowSeconds() - start);
    }
    return run;
}

std::string Ms(double seconds) {
    return fmt::format("{:.1f} ms", seconds * 1000.0);
}

double PerSecond(std::size_t count, double seconds) {
    return seconds > 0.0 ? static_cast<double>(count) / seconds : 0.0;
}

void PrintTidepool(const char* label, const TidepoolRun& run, std::size_t variant_count,
                   int repeats) {
    const double median = Median(run.timings.wall);
    const double min = Min(run.timings.wall);
    const std::size_t programs = run.last.stage_programs.size();
    fmt::print("  {}: warm-up {}; {} runs: median {}, min {} wall, median CPU {}\n", label,
               Ms(run.warmup_wall), repeats, Ms(median), Ms(min), Ms(Median(run.timings.cpu)));
    fmt::print(
            "    {:.0f} variants/s (median), {:.0f} (best); {:.0f} distinct stage programs/s "
            "(median), {:.0f} (best)\n",
            PerSecond(variant_count, median), PerSecond(variant_count, min),
            PerSecond(programs, median), PerSecond(programs, min));
}

}  // namespace

int main(int argc, char** argv) {
    int repeats = kDefaultRepeats;
    if (argc > 2 || (argc == 2 && (repeats = std::atoi(argv[1])) <= 0)) {
        std::fprintf(stderr, "usage: %s [REPEATS]   (REPEATS >= 1, default %d)\n", argv[0],
                     kDefaultRepeats);
        return kExitUsage;
    }
    fmt::print(
            "validate_throughput: the default variant matrix, tidepool vs a glslangValidator "
            "loop\n");
    fmt::print("environment: {}\n", tidepool::bench::DescribeEnvironment());

    const fs::path yaml = fs::path(TIDEPOOL_SOURCE_ROOT) / "variants.yaml";
    tidepool::ConfigResult loaded = tidepool::LoadVariantConfig(yaml);
    for (const tidepool::Diagnostic& d : loaded.diagnostics) {
        fmt::print(stderr, "{}\n", tidepool::FormatDiagnostic(d));
    }
    if (!loaded.config) {
        return kExitFailure;
    }
    const tidepool::VariantConfig& config = *loaded.config;
    const tidepool::ExpansionResult expansion =
            tidepool::ExpandVariants(config, tidepool::ExpansionOptions{config.max_variants});
    for (const tidepool::Diagnostic& d : expansion.diagnostics) {
        fmt::print(stderr, "{}\n", tidepool::FormatDiagnostic(d));
    }
    if (tidepool::HasErrors(expansion.diagnostics)) {
        return kExitFailure;
    }
    const std::vector<tidepool::Variant>& variants = expansion.variants;
    std::map<std::string, int> per_program;
    for (const tidepool::Variant& v : variants) {
        ++per_program[v.program];
    }
    std::vector<std::string> targets;
    for (tidepool::GlslTarget t : config.targets) {
        targets.push_back(tidepool::TargetName(t));
    }
    std::vector<std::string> programs;
    for (const auto& [name, count] : per_program) {
        programs.push_back(fmt::format("{} {}", name, count));
    }
    fmt::print("matrix: {} ({} variants: {}; targets {})\n", yaml.lexically_normal().string(),
               variants.size(), fmt::join(programs, ", "), fmt::join(targets, ", "));

    // tidepool, all cores and one core.
    const int cores = tidepool::bench::HardwareThreads();
    const TidepoolRun parallel = TimeTidepool(config, variants, cores, repeats);
    const TidepoolRun serial = TimeTidepool(config, variants, 1, repeats);
    const tidepool::ValidationReport& report = parallel.last;
    fmt::print(
            "\ntidepool ValidateVariants (wall clock around the call; CPU = this process, all "
            "threads):\n");
    fmt::print(
            "  work per run: {} stage slots ({} variants x {} target(s) x 2 stages), {} "
            "distinct stage programs parsed, {} programs linked, {} verdicts invalid\n",
            report.stage_slots, variants.size(), config.targets.size(),
            report.stage_programs.size(), report.links, report.InvalidCount());
    PrintTidepool(fmt::format("jobs={}", cores).c_str(), parallel, variants.size(), repeats);
    PrintTidepool("jobs=1", serial, variants.size(), repeats);
    if (report.InvalidCount() > 0) {
        // A benchmark of a failing validation measures error paths, not the real workload.
        fmt::print(
                "  WARNING: {} variant(s) invalid, so these figures time a failing run; first "
                "error: {}\n",
                report.InvalidCount(),
                FormatDiagnostic(report.verdicts[0].diagnostics.empty()
                                         ? tidepool::Diagnostic{}
                                         : report.verdicts[0].diagnostics.front()));
    }

    const std::string validator = FindOnPath("glslangValidator");
    if (validator.empty()) {
        fmt::print(
                "\nglslangValidator: not found on PATH (Debian package glslang-tools); the "
                "comparison is skipped\n");
        return 0;
    }
    char folder_template[] = "/tmp/tidepool-bench-XXXXXX";
    if (mkdtemp(folder_template) == nullptr) {
        fmt::print(
                "\nglslangValidator: cannot create a temporary folder; the comparison is "
                "skipped\n");
        return 0;
    }
    const fs::path folder = folder_template;
    std::vector<StageFile> files;
    const std::string write_error = WriteStageFiles(config, variants, folder, &files);
    if (!write_error.empty()) {
        fmt::print("\nglslangValidator: {}; the comparison is skipped\n", write_error);
        std::error_code ignored;
        fs::remove_all(folder, ignored);
        return 0;
    }
    const LoopRun loop = TimeLoop(validator, files, repeats);
    std::error_code ignored;
    fs::remove_all(folder, ignored);

    // The loop over only the files a deduplicating user would compile: the first variant of
    // each distinct stage program, timed from the same invocations (median per file, summed).
    std::set<std::string> representatives;
    for (const tidepool::StageProgram& program : report.stage_programs) {
        representatives.insert(StageKey(program.target, program.stage, program.variants.front()));
    }
    double distinct_seconds = 0.0;
    for (std::size_t i = 0; i < files.size(); ++i) {
        if (representatives.count(files[i].key) != 0) {
            distinct_seconds += Median(loop.per_file[i]);
        }
    }

    const double loop_median = Median(loop.timings.wall);
    const double tidepool_median = Median(parallel.timings.wall);
    fmt::print(
            "\nglslangValidator loop ({}, `glslangValidator FILE` once per stage file, "
            "sequential, output to /dev/null; CPU = the children's):\n",
            validator);
    fmt::print(
            "  work per loop: {} files ({} variants x 2 stages), no linking; {} nonzero "
            "exit(s) over {} loops\n",
            files.size(), variants.size(), loop.failures, repeats);
    fmt::print("  {} loops: median {}, min {} wall ({} per file), median CPU {}\n", repeats,
               Ms(loop_median), Ms(Min(loop.timings.wall)),
               Ms(loop_median / static_cast<double>(files.size())), Ms(Median(loop.timings.cpu)));
    fmt::print("  distinct stage programs only ({} of the files; sum of per-file medians): {}\n",
               representatives.size(), Ms(distinct_seconds));

    fmt::print("\nratio (loop / tidepool, medians of this run):\n");
    const double speedup = loop_median / tidepool_median;
    fmt::print(
            "  wall, tidepool jobs={} vs the loop:               {:.1f}x (target >= {:.0f}x: "
            "{})\n",
            cores, speedup, kTargetSpeedup, speedup >= kTargetSpeedup ? "met" : "NOT met");
    fmt::print("  wall, tidepool jobs=1 vs the loop:                {:.1f}x\n",
               loop_median / Median(serial.timings.wall));
    fmt::print("  CPU, tidepool jobs={} vs the loop's children:     {:.1f}x\n", cores,
               Median(loop.timings.cpu) / Median(parallel.timings.cpu));
    fmt::print(
            "  wall, tidepool jobs={} vs distinct-only loop:     {:.1f}x (what deduplication "
            "alone does not explain)\n",
            cores, distinct_seconds / tidepool_median);
    // Both sides ran in turn on the same machine, so load from other work slows both, but not
    // necessarily equally: the load average at the end says how busy the cores were meanwhile.
    fmt::print("load average at the end: {}\n", tidepool::bench::LoadAverage());
    return 0;
}
