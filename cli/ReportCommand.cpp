// `tidepool report`: build the report from a saved manifest and results: flags → options →
// library calls → print → exit code. Needs no GL, so it lives in the `tidepool` front end.
#include "tidepool/report/ReportInputs.h"
#include "tidepool/report/ReportModel.h"
#include "tidepool/report/ReportWriter.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>

#include "CliSupport.h"
#include "Commands.h"
#include <fmt/format.h>

namespace tidepool::cli {
namespace {

struct ReportCommandOptions {
    std::string manifest = "reports/out/manifest/manifest.json";
    std::string results = "reports/out/render/results.json";
    std::string name = "default";
    std::string out = "reports/out";
};

std::string UtcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    char buffer[32] = {0};
    std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buffer;
}

// Loads the inputs, builds and writes the report, prints the table; returns the exit code.
}  // namespace

int BuildAndWriteReport(const std::filesystem::path& manifest, const std::filesystem::path& results,
                        const std::string& name, const std::filesystem::path& out) {
    using namespace tidepool::report;
    const auto start = std::chrono::steady_clock::now();
    ReportInputsResult loaded = LoadReportInputs(manifest, results);
    if (!loaded.inputs) {
        std::fprintf(stderr, "error: %s\n", loaded.error.c_str());
        return kExitUsage;
    }
    if (!loaded.inputs->stability_error.empty()) {
        std::fprintf(stderr, "warning: %s (the report says so)\n",
                     loaded.inputs->stability_error.c_str());
    }
    if (!loaded.inputs->plans_error.empty()) {
        std::fprintf(stderr, "warning: %s (the report says so)\n",
                     loaded.inputs->plans_error.c_str());
    }
    ReportOptions options;
    options.name = name;
    options.generated_utc = UtcNow();
    ReportModelResult model = BuildReportModel(*loaded.inputs, options);
    const double model_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!model.model) {
        std::fprintf(stderr, "error: %s\n", model.error.c_str());
        return kExitUsage;
    }
    const WrittenReport written = WriteReport(*model.model, out);
    if (!written.error.empty()) {
        std::fprintf(stderr, "error: %s\n", written.error.c_str());
        return written.refused ? kExitUsage : kExitEnvironment;
    }
    std::printf("%s", WhitepaperTableText(*model.model).c_str());
    const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf(
            "report: %zu configurations (%d failed), %zu on the Pareto frontier, static-cost "
            "Spearman rho %.3f; written in %.1f s to %s/ (index.html %.1f MB%s, report.md, "
            "data.json, %zu files; reading and comparing images %.1f s)\n",
            model.model->accuracy.size(), model.model->failed_configurations,
            model.model->frontier.size(), model.model->static_cost.spearman_rho, seconds,
            written.folder.c_str(), static_cast<double>(written.html_bytes) / 1e6,
            written.image_downscale > 1
                    ? fmt::format(", images downscaled {}x", written.image_downscale).c_str()
                    : "",
            written.files.size(), model_seconds);
    return model.model->failed_configurations > 0 ? kExitShaderErrors : kExitOk;
}

namespace {

int RunReport(const ReportCommandOptions& options) {
    return BuildAndWriteReport(options.manifest, options.results, options.name, options.out);
}

}  // namespace

void RegisterReportCommand(CLI::App& app, int& exit_code) {
    auto report_options = std::make_shared<ReportCommandOptions>();
    CLI::App* report =
            app.add_subcommand("report",
                               "build the report (whitepaper table, accuracy vs time, static cost, "
                               "validation, images, method) from a saved manifest and results");
    report->add_option("--manifest", report_options->manifest,
                       "manifest.json written by `tidepool validate --out DIR`")
            ->capture_default_str();
    report->add_option("--results", report_options->results,
                       "results.json written by `tidepool render`")
            ->capture_default_str();
    report->add_option("--name", report_options->name, "report folder name under --out")
            ->capture_default_str();
    report->add_option("--out", report_options->out, "folder that receives <name>/")
            ->transform(NormaliseOutPath)
            ->capture_default_str();
    report->callback([report_options, &exit_code] { exit_code = RunReport(*report_options); });
}

}  // namespace tidepool::cli
