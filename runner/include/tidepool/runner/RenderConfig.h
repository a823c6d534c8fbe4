// Render configurations: a variant plus the pass options it is rendered with, and how the
// default set, the filters and the file names of a run are derived from variants.yaml.
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/runner/ShaderFeatures.h"

#include <string>
#include <string_view>
#include <vector>

namespace tidepool::runner {

/// The program whose variants make the default matrix.
inline constexpr std::string_view kWaterProgram = "water";
/// The program that switches the water effects with uniform bools instead of defines.
inline constexpr std::string_view kWaterUniformProgram = "water_uniform";

/// One thing the runner renders and times: a water variant and its pass options.
struct RenderConfiguration {
    std::string id;   // variant id plus the pass suffix, e.g. `water:ENABLE_FOG@lowres`
    Variant variant;  // the program and the defines it is compiled with
    std::vector<std::string> effects;  // water effects in force (define names, sorted); for
                                       // water_uniform the uniform bools that are set
    PassOptions passes;
    std::vector<std::string> presets;  // the presets that asked for this configuration

    /// True for water_uniform: effects are uniform bools, not defines.
    bool UsesUniformBools() const { return variant.program == kWaterUniformProgram; }
    /// True when `effect` (a define name such as ENABLE_REFRACTION) is in force.
    bool Has(std::string_view effect) const;
    /// True when the define of `feature` is in force.
    bool Has(ShaderFeature feature) const { return Has(DefineName(feature)); }
};

/// The suffix of non-default pass options in a configuration id: "@refl128", "@refr128",
/// "@lowres", "@discard", "@nodepthfog", "@nocull" in that order, "" for the defaults. Never
/// fails.
std::string PassSuffix(const PassOptions& passes);

/// `variant.Id()` followed by PassSuffix(passes). Never fails.
std::string ConfigurationId(const Variant& variant, const PassOptions& passes);

/// The water_uniform bool for a water define: ENABLE_ drops, the words become CamelCase after a
/// "b" (ENABLE_SCALE_DISTORTION → bScaleDistortion, FRESNEL_EXACT → bFresnelExact). Never fails.
std::string UniformBoolName(std::string_view define);

/// The default set and any problems building it.
struct ConfigurationSet {
    std::vector<RenderConfiguration> configurations;
    std::vector<Diagnostic> diagnostics;
};

/// Every variant of program `water` in `variants` with default passes, then every preset of
/// `config` (presets carry pass options; a water_uniform preset's runtime_features, and its
/// defines, are the effects its bools switch on; its id lists them like a define variant's),
/// de-duplicated by id (a preset equal to a default configuration adds its name to it). Fails
/// through diagnostics when a preset names a program other than water or water_uniform.
ConfigurationSet BuildDefaultConfigurations(const VariantConfig& config,
                                            const std::vector<Variant>& variants);

/// What to keep of a configuration set: globs on ids and preset names, either one matching keeps
/// a configuration; with neither, everything is kept.
struct ConfigurationFilter {
    std::vector<std::string> id_globs;
    std::vector<std::string> presets;
};

/// The configurations `filter` keeps, in their order; a preset name that exists in no
/// configuration is a diagnostic (and keeps nothing).
ConfigurationSet FilterConfigurations(const ConfigurationSet& all,
                                      const ConfigurationFilter& filter);

/// Shell-style glob match (`*`, `?`, `[...]`) of a whole id. Never fails.
bool GlobMatch(std::string_view pattern, std::string_view text);

/// A file-name stem from an id: letters, digits, '-', '.' and '_' stay; ':' becomes "__", ','
/// becomes '+', '@' becomes '-' and anything else '_' (so different ids give different names).
std::string SanitiseFileName(std::string_view id);

}  // namespace tidepool::runner
