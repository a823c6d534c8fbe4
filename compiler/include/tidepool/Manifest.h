// The manifest: every variant with its defines, stage hashes, verdict, diagnostics and static
// cost, as versioned JSON (schema "tidepool.manifest", version 1; README.md documents it).
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/GlslValidator.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/stagefiles/ManifestFile.h"
#include "tidepool/stagefiles/StageFile.h"  // JsonText

#include <nlohmann/json.hpp>

namespace tidepool {

/// A diagnostic as a stage file holds it (no `text`). Never fails.
stagefiles::DiagnosticEntry ToEntry(const Diagnostic& diagnostic);
/// A diagnostic as a JSON object {severity, file, line, column, message, variant}.
nlohmann::json ToJson(const Diagnostic& diagnostic);

/// What each step of a variant's validation came to, as the JSON fields every verdict carries:
/// "steps" {vertex, fragment, link: "valid" | "invalid" | "not run"} and "failed_steps", the
/// names of the steps that are invalid, in that order (empty when the variant is valid).
nlohmann::json StepsJson(const VariantVerdict& verdict);

/// Builds the manifest; `validation` may be null (then verdicts and costs are left out, as for
/// `tidepool expand`). Never fails.
stagefiles::ManifestFile BuildManifestFile(const VariantConfig& config,
                                           const ExpansionResult& expansion,
                                           const ValidationReport* validation);
/// ToJson(BuildManifestFile(...)): the one writer's JSON. Never fails.
nlohmann::json BuildManifest(const VariantConfig& config, const ExpansionResult& expansion,
                             const ValidationReport* validation);

}  // namespace tidepool
