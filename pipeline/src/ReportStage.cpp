#include "tidepool/pipeline/ReportStage.h"

#include <chrono>
#include <ctime>
#include <utility>

namespace tidepool::pipeline {
namespace {

std::string UtcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    char buffer[32] = {0};
    std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buffer;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

ReportResult BuildReport(const ReportRequest& request) {
    using namespace tidepool::report;
    const auto start = std::chrono::steady_clock::now();
    ReportResult result;
    ReportInputsResult loaded = LoadReportInputs(request.manifest, request.results);
    if (!loaded.inputs) {
        result.outcome.Fail(Status::kUsage, loaded.error);
        return result;
    }
    result.inputs = std::make_unique<ReportInputs>(std::move(*loaded.inputs));
    for (const std::string* error :
         {&result.inputs->stability_error, &result.inputs->plans_error}) {
        if (!error->empty()) {
            result.outcome.diagnostics.push_back(
                    Message(Severity::kWarning, *error + " (the report says so)"));
        }
    }
    ReportOptions options;
    options.name = request.name;
    options.generated_utc = UtcNow();
    ReportModelResult model = BuildReportModel(*result.inputs, options);
    result.model_seconds = SecondsSince(start);
    if (!model.model) {
        result.outcome.Fail(Status::kUsage, model.error);
        return result;
    }
    result.model = std::move(model.model);
    result.written = WriteReport(*result.model, request.out);
    if (!result.written.error.empty()) {
        result.outcome.Fail(result.written.refused ? Status::kUsage : Status::kEnvironment,
                            result.written.error);
        return result;
    }
    result.seconds = SecondsSince(start);
    result.outcome.status =
            result.model->failed_configurations > 0 ? Status::kInvalid : Status::kOk;
    return result;
}

}  // namespace tidepool::pipeline
