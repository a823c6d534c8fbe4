#include "StderrProgressSink.h"

#include <cerrno>
#include <cstring>

#include "CliSupport.h"
#include "GlCliSupport.h"
#include <fcntl.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

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
    if (log_ != nullptr && log_pid_ == ::getpid()) {
        std::fclose(log_);
    }
}

bool StderrProgressSink::OpenLog(const std::string& path) {
    // Emptied, and written at its end by every process: a process forked from this one appends
    // its own lines, and a write at this one's own offset would then land over them.
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0644);
    std::FILE* log = fd >= 0 ? ::fdopen(fd, "a") : nullptr;
    if (log == nullptr) {
        const int error = errno;
        if (fd >= 0) {
            ::close(fd);
        }
        errno = error;
        std::fprintf(stderr,
                     "error: --progress-log %s: cannot write it (%s); give a file in a folder "
                     "that exists and that you may write to\n",
                     path.c_str(), std::strerror(errno));
        return false;
    }
    if (log_ != nullptr && log_pid_ == ::getpid()) {
        std::fclose(log_);
    }
    log_ = log;
    log_path_ = path;
    log_pid_ = ::getpid();
    return true;
}

double StderrProgressSink::Seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void StderrProgressSink::Log(const std::string& text) {
    if (log_ != nullptr && log_pid_ != ::getpid()) {
        // Forked: the descriptor is closed here and its number may now be another file's, so the
        // stream is left as it is, not closed.
        log_ = std::fopen(log_path_.c_str(), "a");
        log_pid_ = ::getpid();
    }
    if (log_ != nullptr) {
        std::fwrite(text.data(), 1, text.size(), log_);
        std::fflush(log_);
    }
}

void StderrProgressSink::Begin(const std::string& line) {
    std::fprintf(stderr, "%s\n", line.c_str());
    if (log_ != nullptr) {
        Log(LogText({{"t", Seconds()}, {"line", line}}));
    }
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
    Log(LogText({{"t", Seconds()},
                 {"stage", p.stage},
                 {"item", p.item},
                 {"done", p.done},
                 {"total", p.total},
                 {"elapsed_seconds", p.elapsed_seconds},
                 {"eta_seconds", p.eta_seconds},
                 {"percent", p.percent},
                 {"parts", std::move(parts)}}));
}

void StderrProgressSink::Finish() {
    FinishProgress();
}

void StderrProgressSink::Line(const std::string& line) {
    std::fprintf(stderr, "%s\n", line.c_str());
    if (log_ != nullptr) {
        Log(LogText({{"t", Seconds()}, {"line", line}}));
    }
}

void StderrProgressSink::Tell(const std::vector<Diagnostic>& diagnostics) {
    PrintDiagnostics(diagnostics);
}

}  // namespace tidepool::cli
