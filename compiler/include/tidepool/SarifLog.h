// Validation diagnostics as a SARIF 2.1.0 log: the format code-scanning services (GitHub code
// scanning, GitLab, Azure DevOps) read to show each message on the shader line it is about.
#pragma once

#include "tidepool/GlslValidator.h"

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace tidepool {

/// The SARIF version written, and the schema its `$schema` names.
inline constexpr const char* kSarifVersion = "2.1.0";
inline constexpr const char* kSarifSchema = "https://json.schemastore.org/sarif-2.1.0.json";

/// Builds a SARIF 2.1.0 log of `report` with one run of the tool "tidepool" `tool_version`. Each
/// distinct message is one result, however many variants share it (a stage error common to forty
/// variants is one alert naming them in `properties.variants`); its ruleId is the step that
/// produced it ("vertex", "fragment", "link"), or "input" for a problem not tied to a variant (an
/// unreadable shader file). Locations are the user's file and line: a relative shader path is
/// taken relative to `base_dir` (the configuration's folder; "" for files named on the command
/// line), so that a log made in the repository's root points into it. Never fails.
nlohmann::json BuildSarifLog(const ValidationReport& report, const std::filesystem::path& base_dir,
                             const std::string& tool_version);

/// A file path as a SARIF artifact URI: a relative path stays relative (each byte outside
/// RFC 3986's unreserved set and '/' percent-encoded, so a non-UTF-8 name survives), an absolute
/// one becomes a file:// URI.
std::string ArtifactUri(const std::filesystem::path& path);

}  // namespace tidepool
