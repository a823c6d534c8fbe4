#include "tidepool/VariantExpander.h"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

namespace tidepool {

std::string Variant::Id() const {
    return fmt::format("{}:{}", program, fmt::join(defines, ","));
}

Variant MakeVariant(std::string program, std::vector<std::string> defines) {
    std::sort(defines.begin(), defines.end());
    defines.erase(std::unique(defines.begin(), defines.end()), defines.end());
    return Variant{std::move(program), std::move(defines)};
}

namespace {

std::uint64_t SaturatingMultiply(std::uint64_t a, std::uint64_t b) {
    if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) {
        return std::numeric_limits<std::uint64_t>::max();
    }
    return a * b;
}

std::uint64_t SaturatingAdd(std::uint64_t a, std::uint64_t b) {
    return b > std::numeric_limits<std::uint64_t>::max() - a
                   ? std::numeric_limits<std::uint64_t>::max()
                   : a + b;
}

}  // namespace

std::uint64_t CountCombinations(const ProgramConfig& program) {
    std::uint64_t count = 1;
    for (std::size_t i = 0; i < program.features.size(); ++i) {
        count = SaturatingMultiply(count, 2);
    }
    for (const Axis& axis : program.axes) {
        count = SaturatingMultiply(count, axis.values.size());
    }
    return count;
}

const Rule* FirstBrokenRule(const ProgramConfig& program, const std::vector<std::string>& defines) {
    auto has = [&](const std::string& name) {
        return std::find(defines.begin(), defines.end(), name) != defines.end();
    };
    for (const Rule& rule : program.rules) {
        switch (rule.kind) {
            case RuleKind::kRequires:
                if (has(rule.subject) && !std::all_of(rule.others.begin(), rule.others.end(), has)) {
                    return &rule;
                }
                break;
            case RuleKind::kExcludes:
                if (has(rule.subject) && std::any_of(rule.others.begin(), rule.others.end(), has)) {
                    return &rule;
                }
                break;
            case RuleKind::kExcludeCombination:
                if (std::all_of(rule.others.begin(), rule.others.end(), has)) {
                    return &rule;
                }
                break;
        }
    }
    return nullptr;
}

ExpansionResult ExpandVariants(const VariantConfig& config, const ExpansionOptions& options) {
    ExpansionResult result;

    // Refuse before enumerating: a 40-feature matrix must not be allocated to find out it is big.
    std::uint64_t total = 0;
    for (const ProgramConfig& program : config.programs) {
        total = SaturatingAdd(total, CountCombinations(program));
    }
    if (total > options.max_variants) {
        const std::string count = total == std::numeric_limits<std::uint64_t>::max()
                                          ? std::string("more than 18446744073709551615")
                                          : fmt::format("{}", total);
        result.diagnostics.push_back(MakeError(
                config.path, 0, 0,
                fmt::format("the matrix has {} combinations, over the limit of {}; add rules, "
                            "remove features, or raise the limit with --max-variants",
                            count, options.max_variants)));
        return result;
    }

    for (const ProgramConfig& program : config.programs) {
        const std::size_t feature_count = program.features.size();
        const std::uint64_t combinations = CountCombinations(program);
        std::size_t kept = 0;
        for (std::uint64_t index = 0; index < combinations; ++index) {
            // Mixed-radix decoding: the low bits choose features, the rest choose axis values.
            std::vector<std::string> defines;
            std::uint64_t rest = index;
            for (std::size_t f = 0; f < feature_count; ++f) {
                if ((rest & 1U) != 0) {
                    defines.push_back(program.features[f].name);
                }
                rest >>= 1U;
            }
            for (const Axis& axis : program.axes) {
                // An axis default is a combination of its own that adds no define.
                std::string define = axis.DefineFor(axis.values[rest % axis.values.size()]);
                if (!define.empty()) {
                    defines.push_back(std::move(define));
                }
                rest /= axis.values.size();
            }
            Variant variant = MakeVariant(program.name, std::move(defines));
            if (const Rule* rule = FirstBrokenRule(program, variant.defines)) {
                result.pruned.push_back(PrunedCombination{std::move(variant), rule->Describe(),
                                                          rule->where});
            } else {
                result.variants.push_back(std::move(variant));
                ++kept;
            }
        }
        if (kept == 0) {
            result.diagnostics.push_back(MakeError(
                    program.where.file, program.where.line, program.where.column,
                    fmt::format("the rules leave program '{}' with no variant; relax a rule",
                                program.name)));
        }
    }
    // A stable order independent of how the combinations were counted: by id.
    std::sort(result.variants.begin(), result.variants.end(),
              [](const Variant& a, const Variant& b) { return a.Id() < b.Id(); });
    if (HasErrors(result.diagnostics)) {
        result.variants.clear();
    }
    return result;
}

}  // namespace tidepool
