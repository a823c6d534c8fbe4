#include "tidepool/pipeline/Outcome.h"

#include <utility>

namespace tidepool::pipeline {

void Outcome::Fail(Status stop, std::string message) {
    diagnostics.push_back(Message(Severity::kError, std::move(message)));
    status = stop;
}

void Outcome::Add(const std::vector<Diagnostic>& more) {
    diagnostics.insert(diagnostics.end(), more.begin(), more.end());
}

Diagnostic Message(Severity severity, std::string message) {
    Diagnostic diagnostic;
    diagnostic.severity = severity;
    diagnostic.message = std::move(message);
    return diagnostic;
}

}  // namespace tidepool::pipeline
