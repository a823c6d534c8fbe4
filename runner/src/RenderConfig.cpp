// Render configurations from variants.yaml.
#include "tidepool/runner/RenderConfig.h"

#include <algorithm>
#include <cctype>
#include <set>

#include <fmt/format.h>
#include <fnmatch.h>

namespace tidepool::runner {

bool RenderConfiguration::Has(std::string_view effect) const {
    return std::find(effects.begin(), effects.end(), effect) != effects.end();
}

std::string PassSuffix(const PassOptions& passes) {
    const PassOptions defaults;
    std::string suffix;
    if (passes.reflection_size != defaults.reflection_size) {
        suffix += fmt::format("@refl{}", passes.reflection_size);
    }
    if (passes.refraction_size != defaults.refraction_size) {
        suffix += fmt::format("@refr{}", passes.refraction_size);
    }
    if (passes.low_res_water) {
        suffix += "@lowres";
    }
    if (passes.clip == "discard") {
        suffix += "@discard";
    }
    if (!passes.depth_fog) {
        suffix += "@nodepthfog";
    }
    if (!passes.culling) {
        suffix += "@nocull";
    }
    return suffix;
}

std::string ConfigurationId(const Variant& variant, const PassOptions& passes) {
    return variant.Id() + PassSuffix(passes);
}

std::string UniformBoolName(std::string_view define) {
    constexpr std::string_view kPrefix = "ENABLE_";
    if (define.substr(0, kPrefix.size()) == kPrefix) {
        define.remove_prefix(kPrefix.size());
    }
    std::string name = "b";
    bool start_of_word = true;
    for (char c : define) {
        if (c == '_') {
            start_of_word = true;
            continue;
        }
        const auto byte = static_cast<unsigned char>(c);
        name += static_cast<char>(start_of_word ? std::toupper(byte) : std::tolower(byte));
        start_of_word = false;
    }
    return name;
}

ConfigurationSet BuildDefaultConfigurations(const VariantConfig& config,
                                            const std::vector<Variant>& variants) {
    ConfigurationSet set;
    auto add = [&](RenderConfiguration configuration, const std::string& preset) {
        for (RenderConfiguration& existing : set.configurations) {
            if (existing.id == configuration.id) {
                if (!preset.empty()) {
                    existing.presets.push_back(preset);
                }
                return;
            }
        }
        if (!preset.empty()) {
            configuration.presets.push_back(preset);
        }
        set.configurations.push_back(std::move(configuration));
    };
    for (const Variant& variant : variants) {
        if (variant.program != kWaterProgram) {
            continue;
        }
        RenderConfiguration configuration;
        configuration.variant = variant;
        configuration.effects = variant.defines;
        configuration.id = ConfigurationId(variant, configuration.passes);
        add(std::move(configuration), "");
    }
    for (const Preset& preset : config.presets) {
        if (preset.program != kWaterProgram && preset.program != kWaterUniformProgram) {
            set.diagnostics.push_back(Diagnostic{
                    Severity::kError, preset.where.file, preset.where.line, preset.where.column,
                    fmt::format(
                            "preset '{}' uses program '{}'; the renderer draws only '{}' and '{}' "
                            "as the water",
                            preset.name, preset.program, kWaterProgram, kWaterUniformProgram),
                    ""});
            continue;
        }
        RenderConfiguration configuration;
        configuration.variant = MakeVariant(preset.program, preset.defines);
        // Effects in force: the defines plus, for water_uniform, the bools switched on. The id
        // names the effects, so a uniform-bool configuration reads like its define twin.
        std::vector<std::string> effects = preset.defines;
        effects.insert(effects.end(), preset.runtime_features.begin(),
                       preset.runtime_features.end());
        const Variant named = MakeVariant(preset.program, effects);
        configuration.effects = named.defines;
        configuration.passes = preset.passes;
        configuration.id = ConfigurationId(named, configuration.passes);
        add(std::move(configuration), preset.name);
    }
    return set;
}

bool GlobMatch(std::string_view pattern, std::string_view text) {
    return fnmatch(std::string(pattern).c_str(), std::string(text).c_str(), 0) == 0;
}

ConfigurationSet FilterConfigurations(const ConfigurationSet& all,
                                      const ConfigurationFilter& filter) {
    ConfigurationSet kept;
    kept.diagnostics = all.diagnostics;
    for (const std::string& preset : filter.presets) {
        const bool known = std::any_of(all.configurations.begin(), all.configurations.end(),
                                       [&](const RenderConfiguration& c) {
                                           return std::find(c.presets.begin(), c.presets.end(),
                                                            preset) != c.presets.end();
                                       });
        if (!known) {
            kept.diagnostics.push_back(
                    MakeError("", 0, 0,
                              fmt::format("unknown preset '{}'; see the presets in "
                                          "variants.yaml",
                                          preset)));
        }
    }
    const bool keep_all = filter.id_globs.empty() && filter.presets.empty();
    for (const RenderConfiguration& configuration : all.configurations) {
        bool keep = keep_all;
        for (const std::string& glob : filter.id_globs) {
            keep = keep || GlobMatch(glob, configuration.id);
        }
        for (const std::string& preset : filter.presets) {
            keep = keep || std::find(configuration.presets.begin(), configuration.presets.end(),
                                     preset) != configuration.presets.end();
        }
        if (keep) {
            kept.configurations.push_back(configuration);
        }
    }
    return kept;
}

std::string SanitiseFileName(std::string_view id) {
    std::string name;
    for (char c : id) {
        const auto byte = static_cast<unsigned char>(c);
        if (std::isalnum(byte) || c == '-' || c == '.' || c == '_') {
            name += c;
        } else if (c == ':') {
            name += "__";
        } else if (c == ',') {
            name += '+';
        } else if (c == '@') {
            name += '-';
        } else {
            name += '_';
        }
    }
    return name;
}

}  // namespace tidepool::runner
