// The CLI's one progress sink: what a long pipeline stage is doing, on stderr. Built into
// `tidepool-gl` only (the stages that report progress render).
#pragma once

#include "tidepool/pipeline/ProgressSink.h"
#include "tidepool/runner/Results.h"

#include <string>

namespace tidepool::cli {

/// Prints a stage's first line as it is, and its progress as MakeProgressPrinter does: on a
/// terminal one line rewritten in place, in a log a plain line on every change of stage and at
/// most every 10 seconds. Never fails.
class StderrProgressSink : public pipeline::ProgressSink {
public:
    StderrProgressSink();

    void Begin(const std::string& line) override;
    void Progress(const pipeline::StageProgress& progress) override;
    void Finish() override;
    void Line(const std::string& line) override;
    void Tell(const std::vector<Diagnostic>& diagnostics) override;

private:
    runner::ProgressCallback printer_;
};

}  // namespace tidepool::cli
