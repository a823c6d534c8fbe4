// `tidepool validate`'s output: the summary line, the JSON and SARIF reports.
#include "ValidateOutput.h"

#include "tidepool/Manifest.h"
#include "tidepool/SarifLog.h"
#include "tidepool/base/AtomicFile.h"

#include <cstdio>
#include <utility>

#include "Commands.h"
#include <fmt/format.h>

namespace tidepool::cli {
namespace {

// Prints `text` (a JSON or SARIF report) on stdout, or writes it to --output-file atomically.
int EmitReport(const ValidateCommandOptions& options, const std::string& text) {
    if (options.output_file.empty()) {
        std::printf("%s\n", text.c_str());
        return kExitOk;
    }
    if (const std::string error = base::WriteFileAtomically(options.output_file, text + "\n");
        !error.empty()) {
        std::fprintf(stderr, "error: --output-file: %s\n", error.c_str());
        return kExitEnvironment;
    }
    return kExitOk;
}

}  // namespace

int ReportFiles(const ValidateCommandOptions& options,
                const pipeline::ValidateFilesResult& result) {
    nlohmann::json json = nlohmann::json::array();
    for (const VariantVerdict& verdict : result.report.verdicts) {
        nlohmann::json diagnostics = nlohmann::json::array();
        for (const Diagnostic& d : verdict.diagnostics) {
            diagnostics.push_back(ToJson(d));
        }
        nlohmann::json entry = {{"files", verdict.variant.program},
                                {"valid", verdict.valid},
                                {"diagnostics", diagnostics}};
        entry.update(StepsJson(verdict));
        json.push_back(std::move(entry));
    }
    int code = kExitOk;
    if (options.Format() == "sarif") {
        code = EmitReport(options, JsonText(BuildSarifLog(result.report, "", TIDEPOOL_VERSION), 2));
    } else if (options.Format() == "json") {
        code = EmitReport(options, JsonText(json, 2));
    } else {
        std::printf("%zu file(s): %s\n", options.files.files.size(),
                    result.outcome.status == pipeline::Status::kOk ? "valid" : "INVALID");
    }
    return code != kExitOk ? code : pipeline::ExitCode(result.outcome.status);
}

MatrixReport RenderMatrixReport(const ValidateCommandOptions& options,
                                const pipeline::ValidateResult& result) {
    const VariantConfig& config = *result.matrix.config;
    const ValidationReport& report = result.report;
    std::string text;
    if (options.Format() == "sarif") {
        text = JsonText(BuildSarifLog(report, config.base_dir, TIDEPOOL_VERSION), 2) + "\n";
    } else if (options.Format() == "json") {
        text = JsonText(result.manifest, 2) + "\n";
    } else {
        const int invalid = report.InvalidCount();
        return {fmt::format("{} variants ({} pruned combinations) x {} target(s): {} stage slots "
                            "-> {} distinct stage programs ({} shared), {} links; {}\n",
                            result.matrix.expansion.variants.size(),
                            result.matrix.expansion.pruned_total, config.targets.size(),
                            report.stage_slots, report.stage_programs.size(),
                            report.SharedStageSlots(), report.links,
                            invalid == 0 ? "all valid" : fmt::format("{} INVALID", invalid)),
                std::nullopt};
    }
    if (options.output_file.empty()) {
        return {std::move(text), std::nullopt};
    }
    return {"", std::move(text)};
}

}  // namespace tidepool::cli
