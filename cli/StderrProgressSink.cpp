#include "StderrProgressSink.h"

#include <cerrno>
#include <cstring>

#include "CliSupport.h"
#include "GlCliSupport.h"
#include <nlohmann/json.hpp>

namespace tidepool::cli {
namespace {

// The log's text for `record`: one line. Text that is not UTF-8 (an id from a hand-written
// file) is written with U+FFFD in its place rather than not at all.
std::string LogText(const nlohmann::json& record) {
    return record.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace

StderrProgressSink::StderrProgressSink() : printer_(MakeProgressPrinter()) {}

StderrProgressSink::~StderrProgressSink() {
    if (log_ != nullptr) {
        std::fclose(log_);
    }
}

bool StderrProgressSink::OpenLog(const std::string& path) {
    std::FILE* log = std::fopen(path.c_str(), "w");
    if (log == nullptr) {
        std::fprintf(stderr,
                     "error: --progress-log %s: cannot write it (%s); give a file in a folder "
                     "that exists and that you may write to\n",
                     path.c_str(), std::strerror(errno));
        return false;
    }
    if (log_ != nullptr) {
        std::fclose(log_);
    }
    log_ = log;
    return true;
}

void StderrProgressSink::LogLine(const std::string& line) {
    if (log_ == nullptr) {
        return;
    }
    const std::string text = LogText(
            {{"t",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count()},
             {"line", line}});
    std::fwrite(text.data(), 1, text.size(), log_);
    std::fflush(log_);
}

void StderrProgressSink::Begin(const std::string& line) {
    std::fprintf(stderr, "%s\n", line.c_str());
    LogLine(line);
}

void StderrProgressSink::Progress(const pipeline::StageProgress& p) {
    printer_({p.stage, p.item, p.done, p.total, p.elapsed_seconds, p.eta_seconds, p.percent, {}});
    if (log_ == nullptr) {
        return;
    }
    nlohmann::json parts = nlohmann::json::object();
    for (const auto& [name, value] : p.parts) {
        parts[name] = value;
    }
    const std::string text = LogText(
            {{"t",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count()},
             {"stage", p.stage},
             {"item", p.item},
             {"done", p.done},
             {"total", p.total},
             {"elapsed_seconds", p.elapsed_seconds},
             {"eta_seconds", p.eta_seconds},
             {"percent", p.percent},
             {"parts", std::move(parts)}});
    std::fwrite(text.data(), 1, text.size(), log_);
    std::fflush(log_);
}

void StderrProgressSink::Finish() {
    FinishProgress();
}

void StderrProgressSink::Line(const std::string& line) {
    std::fprintf(stderr, "%s\n", line.c_str());
    LogLine(line);
}

void StderrProgressSink::Tell(const std::vector<Diagnostic>& diagnostics) {
    PrintDiagnostics(diagnostics);
}

}  // namespace tidepool::cli
