// One message about the user's input: a YAML file, a shader file or the command line.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tidepool {

/// How bad a diagnostic is; only errors change a verdict or an exit code.
enum class Severity { kError, kWarning, kNote };

/// A message at a place in a file the user wrote (never an expanded copy); line and column are
/// 1-based, 0 when unknown. `variant` is the variant id the message belongs to, empty when none.
struct Diagnostic {
    Severity severity = Severity::kError;
    std::string file;
    int line = 0;
    int column = 0;
    std::string message;
    std::string variant;
};

/// Formats a diagnostic in GCC form, `file:line:col: error: message [variant id]`, leaving out
/// the parts that are unknown so editors can still jump to the line.
std::string FormatDiagnostic(const Diagnostic& diagnostic);

/// Returns the lower-case name GCC uses for a severity ("error", "warning", "note").
const char* SeverityName(Severity severity);
/// The severity SeverityName gives `name`; nothing for any other text.
std::optional<Severity> SeverityFromName(std::string_view name);

/// True when any diagnostic is an error.
bool HasErrors(const std::vector<Diagnostic>& diagnostics);

/// Builds an error diagnostic; a shorthand used by every stage of the compiler.
Diagnostic MakeError(std::string file, int line, int column, std::string message);

}  // namespace tidepool
