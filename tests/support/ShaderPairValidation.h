// Validates shader files written for a test, as `tidepool validate VERT FRAG` does, and gives the
// verdict with the first error, for tables of {shaders, expected first error}.
#pragma once

#include "tidepool/GlslValidator.h"

#include <optional>
#include <string>
#include <vector>

#include "TempDir.h"

namespace tidepool::testing {

/// The verdict on one vertex + fragment pair (or a lone stage).
struct PairVerdict {
    std::size_t verdicts = 0;  // how many verdicts validation gave (1 for a pair or a lone stage)
    bool valid = false;
    std::string first_error;    // "a.fsh:4:7: error: ...", the test's folder left out; "" if none
    std::string first_warning;  // the same for the first warning
};

/// Writes `vertex` to a.vsh and `fragment` to a.fsh (a file is left out when its text is
/// nullopt) in a fresh folder and validates them together with `options`.
inline PairVerdict ValidatePair(const std::optional<std::string>& vertex,
                                const std::optional<std::string>& fragment,
                                const ShaderFileOptions& options = {}) {
    TempDir dir;
    std::vector<ShaderFile> files;
    if (vertex) {
        files.push_back({dir.Write("a.vsh", *vertex).string(), Stage::kVertex});
    }
    if (fragment) {
        files.push_back({dir.Write("a.fsh", *fragment).string(), Stage::kFragment});
    }
    const ValidationReport report = ValidateShaderFiles(files, {}, options);
    PairVerdict verdict;
    verdict.verdicts = report.verdicts.size();
    if (report.verdicts.empty()) {
        return verdict;
    }
    verdict.valid = report.verdicts[0].valid;
    for (const Diagnostic& d : report.verdicts[0].diagnostics) {
        if (d.severity == Severity::kError && verdict.first_error.empty()) {
            verdict.first_error = FormatDiagnostic(d);
        }
        if (d.severity == Severity::kWarning && verdict.first_warning.empty()) {
            verdict.first_warning = FormatDiagnostic(d);
        }
    }
    const std::string folder = dir.Path().string() + "/";
    for (std::string* text : {&verdict.first_error, &verdict.first_warning}) {
        for (std::size_t at = text->find(folder); at != std::string::npos;
             at = text->find(folder)) {
            text->erase(at, folder.size());
        }
    }
    return verdict;
}

}  // namespace tidepool::testing
