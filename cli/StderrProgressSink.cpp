#include "StderrProgressSink.h"

#include <cstdio>

#include "CliSupport.h"
#include "GlCliSupport.h"

namespace tidepool::cli {

StderrProgressSink::StderrProgressSink() : printer_(MakeProgressPrinter()) {}

void StderrProgressSink::Begin(const std::string& line) {
    std::fprintf(stderr, "%s\n", line.c_str());
}

void StderrProgressSink::Progress(const pipeline::StageProgress& p) {
    printer_({p.stage, p.item, p.done, p.total, p.elapsed_seconds, p.eta_seconds, p.percent});
}

void StderrProgressSink::Finish() {
    FinishProgress();
}

void StderrProgressSink::Line(const std::string& line) {
    std::fprintf(stderr, "%s\n", line.c_str());
}

void StderrProgressSink::Tell(const std::vector<Diagnostic>& diagnostics) {
    PrintDiagnostics(diagnostics);
}

}  // namespace tidepool::cli
