#include "tidepool/pipeline/Timing.h"

#include "tidepool/pipeline/Host.h"
#include "tidepool/report/ReportModel.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <optional>

namespace tidepool::pipeline {

void ApplyTiming(const TimingSettings& settings, runner::BackendKind backend,
                 runner::RunOptions* run) {
    setenv("LP_NUM_THREADS", std::to_string(settings.threads).c_str(), 1);
    run->host.lp_num_threads = std::to_string(settings.threads);
    run->rule.resolution_points = settings.resolution;
    run->rule.min_pairs = settings.min_pairs;
    run->rule.max_pairs = settings.max_pairs;
    run->rule.contended_share = settings.contended_share;
    run->coarse_frames = settings.coarse_frames;
    run->warmup_frames = settings.warmup;
    run->workers = settings.workers > 0 ? settings.workers : DefaultJobs();
    run->make_context = [backend] { return runner::CreateGlContext(backend).context; };
    run->comparisons.clear();
    auto find = [&](const std::string& preset) -> std::optional<std::size_t> {
        for (std::size_t i = 0; i < run->configurations.size(); ++i) {
            const auto& presets = run->configurations[i].presets;
            if (std::find(presets.begin(), presets.end(), preset) != presets.end()) {
                return i;
            }
        }
        return std::nullopt;
    };
    for (const report::PresetPair& pair : report::ComparedPresetPairs()) {
        const std::optional<std::size_t> a = find(pair.baseline);
        const std::optional<std::size_t> b = find(pair.candidate);
        if (a && b && *a != *b) {
            run->comparisons.push_back({pair.label, *a, *b, pair.boundaries_points});
        }
    }
}

runner::HostInfo DescribeHost(const std::string& command, const std::string& config_path) {
    runner::HostInfo host;
    host.cpu_model = CpuModel();
    if (const char* threads = std::getenv("LP_NUM_THREADS"); threads != nullptr) {
        host.lp_num_threads = threads;
    }
#ifdef NDEBUG
    host.build_type = "release (NDEBUG)";
#else
    host.build_type = "debug (assertions on)";
#endif
    host.git_revision = GitRevision(std::filesystem::absolute(config_path).parent_path());
    host.command = command;
    return host;
}

}  // namespace tidepool::pipeline
