// How a pipeline stage ended, as a value: a status and everything the stage has to say about
// the user's input, its files and the machine, in the order it found them.
#pragma once

#include "tidepool/Diagnostic.h"

#include <string>
#include <vector>

namespace tidepool::pipeline {

/// How a stage ended. The values are the process exit codes of the CLI (README, "Exit codes"),
/// so a command returns a stage's status as it is.
enum class Status : int {
    kOk = 0,           // done, everything valid
    kInvalid = 1,      // done, but a shader, variant, case or plan failed
    kUsage = 2,        // stopped: bad options, configuration or input files
    kEnvironment = 3,  // stopped: no GL context, or a file could not be written
};

/// A status and the diagnostics behind it. Messages without a place in a file (e.g. "error: no
/// configuration matches") are diagnostics with an empty `file`, which FormatDiagnostic prints
/// as "error: ...", so the CLI prints every message of a stage one way.
struct Outcome {
    Status status = Status::kOk;
    std::vector<Diagnostic> diagnostics;

    /// True when the stage stopped before its work was done (usage or environment).
    bool Stopped() const { return status == Status::kUsage || status == Status::kEnvironment; }

    /// Records an error without a place in a file and stops with `status`.
    void Fail(Status stop, std::string message);

    /// Appends `more` in order, keeping this outcome's status.
    void Add(const std::vector<Diagnostic>& more);
};

/// An error, warning or note without a place in a file ("error: MESSAGE" when printed).
Diagnostic Message(Severity severity, std::string message);

/// The exit code of `status`. Never fails.
inline int ExitCode(Status status) {
    return static_cast<int>(status);
}

}  // namespace tidepool::pipeline
