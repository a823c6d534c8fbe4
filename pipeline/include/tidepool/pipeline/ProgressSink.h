// The one way a long pipeline stage says how far it is while it runs; the CLI implements it once
// (a line rewritten on a terminal, plain lines in a log). Results never go through it: they are
// returned.
#pragma once

#include "tidepool/Diagnostic.h"

#include <string>
#include <utility>
#include <vector>

namespace tidepool::pipeline {

/// How far a long stage is.
struct StageProgress {
    std::string stage;  // the part of the stage at work ("images", "comparisons", "waiting for")
    std::string item;   // what it works on (a configuration id, a comparison's label)
    long done = 0;      // units of work finished
    long total = 0;     // units of work expected (may be re-estimated as the stage goes)
    double elapsed_seconds = 0;
    double eta_seconds = 0;  // 0 until something is done
    double percent = 0;      // share of the work done
    // The figures behind the ETA, by name (runner::RunProgress::parts), for a progress log.
    std::vector<std::pair<std::string, double>> parts;
};

/// Receives a long stage's progress; the stage calls it from one thread at a time.
class ProgressSink {
public:
    virtual ~ProgressSink() = default;

    /// A long stage starts: one line saying what it is about to do ("render: 54 configurations x
    /// 4 views at 640x480 on llvmpipe ..."). Must not throw.
    virtual void Begin(const std::string& line) = 0;

    /// The stage advanced; called after every unit of work. Must not throw.
    virtual void Progress(const StageProgress& progress) = 0;

    /// The stage is done: whatever Progress left open (a terminal line) is ended. Must not throw.
    virtual void Finish() = 0;
    /// A line for the user while a composite stage goes on (`run`: "validate: 163 variants,
    /// ..."), told when it happens rather than returned at the end. Must not throw.
    virtual void Line(const std::string& line) = 0;
    /// Diagnostics a composite stage found, told as it finds them. Must not throw.
    virtual void Tell(const std::vector<Diagnostic>& diagnostics) = 0;
};

}  // namespace tidepool::pipeline
