// `tidepool stats`: flags → pipeline::MeasureStaticCosts → a table or JSON → exit code.
#include "tidepool/Manifest.h"
#include "tidepool/pipeline/CompilerStages.h"

#include <cstdio>
#include <memory>

#include "CliSupport.h"
#include "Commands.h"

namespace tidepool::cli {
namespace {

struct StatsCommandOptions {
    pipeline::StatsOptions stats;
    bool json = false;
};

int RunStats(const StatsCommandOptions& options) {
    const pipeline::StatsResult result = pipeline::MeasureStaticCosts(options.stats);
    const int code = PrintOutcome(result.matrix.outcome);
    if (!result.matrix.config) {
        return code;
    }
    nlohmann::json json = nlohmann::json::array();
    if (!options.json) {
        std::printf("%-62s %6s %6s %5s %4s %4s %5s %9s\n", "variant", "vs.ops", "fs.ops", "tex",
                    "pow", "norm", "brnch", "fs.paths");
    }
    auto builtin = [](const StageCost& cost, const char* name) {
        auto it = cost.builtin_calls.find(name);
        return it == cost.builtin_calls.end() ? 0 : it->second;
    };
    for (const pipeline::VariantCost& cost : result.costs) {
        const StageCost& v = cost.vertex;
        const StageCost& f = cost.fragment;
        json.push_back({{"id", cost.id}, {"vertex", ToJson(v)}, {"fragment", ToJson(f)}});
        if (!options.json) {
            std::printf("%-62s %6d %6d %5d %4d %4d %5d %4d-%-4d\n", cost.id.c_str(), v.TotalOps(),
                        f.TotalOps(), v.texture_samples + f.texture_samples,
                        builtin(v, "pow") + builtin(f, "pow"),
                        builtin(v, "normalize") + builtin(f, "normalize"), v.branches + f.branches,
                        f.shortest_path_ops, f.longest_path_ops);
        }
    }
    if (options.json) {
        std::printf("%s\n", JsonText(json, 2).c_str());
    }
    return code;
}

}  // namespace

void RegisterStatsCommand(CLI::App& app, int& exit_code) {
    auto options = std::make_shared<StatsCommandOptions>();
    CLI::App* stats = app.add_subcommand(
            "stats",
            "Static cost of every variant from glslang's tree: ops, texture samples, "
            "pow/normalize calls, branches, shortest and longest fragment path");
    AddMatrixFlags(stats, &options->stats.config, &options->json, &options->stats.limits);
    AddJobsOption(stats, &options->stats.jobs);
    stats->callback([options, &exit_code] { exit_code = RunStats(*options); });
}

}  // namespace tidepool::cli
