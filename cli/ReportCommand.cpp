// `tidepool report`: build the report from a saved manifest and results: flags → options →
// pipeline::BuildReport → print → exit code. Needs no GL, so it lives in the `tidepool` front end.
#include "tidepool/pipeline/ReportStage.h"

#include <cstdio>
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

}  // namespace

int BuildAndWriteReport(const std::filesystem::path& manifest, const std::filesystem::path& results,
                        const std::string& name, const std::filesystem::path& out) {
    const pipeline::ReportResult result = pipeline::BuildReport({manifest, results, name, out});
    const int code = PrintOutcome(result.outcome);
    if (result.outcome.Stopped()) {
        return code;
    }
    const report::ReportModel& model = *result.model;
    const report::WrittenReport& written = result.written;
    std::printf("%s", report::WhitepaperTableText(model).c_str());
    std::printf(
            "report: %zu configurations (%d failed), %zu on the Pareto frontier, static-cost "
            "Spearman rho %.3f; written in %.1f s to %s/ (index.html %.1f MB%s, report.md, "
            "data.json, %zu files; reading and comparing images %.1f s)\n",
            model.accuracy.size(), model.failed_configurations, model.frontier.size(),
            model.static_cost.spearman_rho, result.seconds, written.folder.c_str(),
            static_cast<double>(written.html_bytes) / 1e6,
            written.image_downscale > 1
                    ? fmt::format(", images downscaled {}x", written.image_downscale).c_str()
                    : "",
            written.files.size(), result.model_seconds);
    return code;
}

namespace {

int RunReport(const ReportCommandOptions& options) {
    if (!CheckReportName(options.name)) {
        return kExitUsage;
    }
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
