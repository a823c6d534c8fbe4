// The CLI's one progress sink: what a long pipeline stage is doing, on stderr, and on request
// every progress state in a log other tools can read. Built into `tidepool-gl` only (the stages
// that report progress render).
#pragma once

#include "tidepool/pipeline/ProgressSink.h"
#include "tidepool/runner/Results.h"

#include <chrono>
#include <cstdio>
#include <string>

#include <sys/types.h>

namespace tidepool::cli {

/// Prints a stage's first line as it is, and its progress as MakeProgressPrinter does: on a
/// terminal one line rewritten in place, in a log a plain line on every change of stage and at
/// most every 10 seconds. With a progress log open, also writes every line and every progress
/// state, with the figures its ETA was worked out from, to the log. Never fails.
class StderrProgressSink : public pipeline::ProgressSink {
public:
    StderrProgressSink();
    ~StderrProgressSink() override;
    StderrProgressSink(const StderrProgressSink&) = delete;
    StderrProgressSink& operator=(const StderrProgressSink&) = delete;

    /// Starts the progress log at `path` (replacing a file there): one JSON object a line, each
    /// written whole and flushed as it happens, so a log read while the stage runs, or left by a
    /// stage that was killed, holds whole lines. Every object has "t", the seconds since this
    /// sink was made; a line the stage told has "line"; a progress state has "stage", "item",
    /// "done", "total", "elapsed_seconds", "eta_seconds", "percent" and "parts" (an object of
    /// the figures behind the ETA, runner::RunProgress::parts). A process forked from this one
    /// (`run` renders in one, with the stability catalogue and the plans in another) opens the
    /// file again to append: its workers close every descriptor they did not make. False, with
    /// the reason printed, when the file cannot be written.
    bool OpenLog(const std::string& path);

    void Begin(const std::string& line) override;
    void Progress(const pipeline::StageProgress& progress) override;
    void Finish() override;
    void Line(const std::string& line) override;
    void Tell(const std::vector<Diagnostic>& diagnostics) override;

private:
    // Seconds since this sink was made.
    double Seconds() const;
    // Appends `text` (whole lines) to the open log.
    void Log(const std::string& text);

    runner::ProgressCallback printer_;
    std::string log_path_;
    std::FILE* log_ = nullptr;
    pid_t log_pid_ = 0;  // the process that opened log_
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace tidepool::cli
