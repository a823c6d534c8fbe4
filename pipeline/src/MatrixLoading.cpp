#include "tidepool/pipeline/MatrixLoading.h"

#include <algorithm>
#include <charconv>
#include <utility>

#include <fmt/format.h>

namespace tidepool::pipeline {

bool ParseWholeNumber(std::string_view text, std::uint64_t min, std::uint64_t max,
                      std::uint64_t* value) {
    // Digits only: CLI11 and strtoull would wrap "-1" into 2^64-1 and accept "1e3" as 1.
    std::uint64_t parsed = 0;
    const char* end = text.data() + text.size();
    const bool digits = !text.empty() && std::all_of(text.begin(), text.end(),
                                                     [](char c) { return c >= '0' && c <= '9'; });
    if (digits && std::from_chars(text.data(), end, parsed).ec == std::errc() && parsed >= min &&
        parsed <= max) {
        *value = parsed;
        return true;
    }
    return false;
}

std::string WholeNumberError(std::string_view flag, std::string_view text, std::uint64_t min,
                             std::uint64_t max, std::string_view hint) {
    return fmt::format("{} must be a whole number from {} to {}{}{}, not '{}'", flag, min, max,
                       hint.empty() ? "" : " ", hint, text);
}

LoadedMatrix LoadMatrix(const std::string& config_path, const MatrixLimits& limits) {
    LoadedMatrix loaded;
    ExpansionOptions expansion_options;
    expansion_options.allow_large_matrix = limits.allow_large_matrix;
    expansion_options.pruned_limit = limits.pruned_limit;
    if (limits.max_variants) {
        const std::uint64_t ceiling =
                limits.allow_large_matrix ? kLargeVariantCeiling : kVariantCeiling;
        const std::string hint =
                limits.allow_large_matrix
                        ? std::string()
                        : fmt::format("(up to {} with --allow-large-matrix)", kLargeVariantCeiling);
        if (!ParseWholeNumber(*limits.max_variants, 1, ceiling, &expansion_options.max_variants)) {
            loaded.outcome.Fail(
                    Status::kUsage,
                    WholeNumberError("--max-variants", *limits.max_variants, 1, ceiling, hint));
            return loaded;
        }
        expansion_options.limit_origin = "--max-variants";
    }
    ConfigResult config = LoadVariantConfig(config_path);
    loaded.outcome.Add(config.diagnostics);
    if (!config.config) {
        loaded.outcome.status = Status::kUsage;
        return loaded;
    }
    if (!limits.max_variants) {
        expansion_options.max_variants = config.config->max_variants;
        if (!config.config->max_variants_where.file.empty()) {
            expansion_options.limit_origin = "max_variants";
            expansion_options.limit_where = config.config->max_variants_where;
        }
    }
    loaded.expansion = ExpandVariants(*config.config, expansion_options);
    loaded.outcome.Add(loaded.expansion.diagnostics);
    if (HasErrors(loaded.expansion.diagnostics)) {
        loaded.outcome.status = Status::kUsage;
        return loaded;
    }
    loaded.config = std::move(config.config);
    return loaded;
}

void KeepOnlyProgram(LoadedMatrix* loaded, const std::string& name) {
    VariantConfig& config = *loaded->config;
    if (config.FindProgram(name) == nullptr) {
        std::vector<std::string> names;
        for (const ProgramConfig& program : config.programs) {
            names.push_back(program.name);
        }
        loaded->outcome.Fail(Status::kUsage,
                             fmt::format("--program {}: {} has no such program; it has {}", name,
                                         config.path, fmt::join(names, ", ")));
        loaded->config.reset();
        return;
    }
    auto other = [&name](const auto& item) { return item.program != name; };
    std::erase_if(config.programs,
                  [&name](const ProgramConfig& program) { return program.name != name; });
    std::erase_if(config.presets, other);
    ExpansionResult& expansion = loaded->expansion;
    std::erase_if(expansion.variants, other);
    std::erase_if(expansion.pruned_by_rule, other);
    std::erase_if(expansion.pruned,
                  [&name](const PrunedCombination& p) { return p.combination.program != name; });
    expansion.pruned_total = 0;
    for (const RulePruneCount& rule : expansion.pruned_by_rule) {
        // Saturating, as the expander's own total.
        expansion.pruned_total = rule.count > UINT64_MAX - expansion.pruned_total
                                         ? UINT64_MAX
                                         : expansion.pruned_total + rule.count;
    }
}

}  // namespace tidepool::pipeline
