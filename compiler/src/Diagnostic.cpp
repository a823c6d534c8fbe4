#include "tidepool/Diagnostic.h"

#include <algorithm>

#include <fmt/format.h>

namespace tidepool {

const char* SeverityName(Severity severity) {
    switch (severity) {
        case Severity::kError:
            return "error";
        case Severity::kWarning:
            return "warning";
        case Severity::kNote:
            return "note";
    }
    return "error";
}

std::optional<Severity> SeverityFromName(std::string_view name) {
    for (Severity severity : {Severity::kError, Severity::kWarning, Severity::kNote}) {
        if (name == SeverityName(severity)) {
            return severity;
        }
    }
    return std::nullopt;
}

std::string FormatDiagnostic(const Diagnostic& diagnostic) {
    std::string out;
    if (!diagnostic.file.empty()) {
        out += diagnostic.file;
        if (diagnostic.line > 0) {
            out += fmt::format(":{}", diagnostic.line);
            if (diagnostic.column > 0) {
                out += fmt::format(":{}", diagnostic.column);
            }
        }
        out += ": ";
    }
    out += fmt::format("{}: {}", SeverityName(diagnostic.severity), diagnostic.message);
    if (!diagnostic.variant.empty()) {
        out += fmt::format(" [{}]", diagnostic.variant);
    }
    return out;
}

bool HasErrors(const std::vector<Diagnostic>& diagnostics) {
    return std::any_of(diagnostics.begin(), diagnostics.end(),
                       [](const Diagnostic& d) { return d.severity == Severity::kError; });
}

Diagnostic MakeError(std::string file, int line, int column, std::string message) {
    return Diagnostic{Severity::kError, std::move(file), line, column, std::move(message), {}};
}

}  // namespace tidepool
