// Expansion of a program's features and axes into every combination, pruned by its rules.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tidepool/Diagnostic.h"
#include "tidepool/VariantConfig.h"

namespace tidepool {

/// One permutation of a program: its name and its define set, kept sorted so that the order in
/// which defines are written never changes identity.
struct Variant {
    std::string program;
    std::vector<std::string> defines;  // sorted, unique

    /// `program:DEF_A,DEF_B` (just `program:` when there are no defines).
    std::string Id() const;
    bool operator==(const Variant& other) const = default;
};

/// Builds a variant with its defines sorted and de-duplicated.
Variant MakeVariant(std::string program, std::vector<std::string> defines);

/// A combination the rules removed, and the first rule that removed it.
struct PrunedCombination {
    Variant combination;
    std::string rule;       // Rule::Describe() of the rule
    SourceLocation where;   // where that rule is written
};

/// Limits for ExpandVariants.
struct ExpansionOptions {
    std::uint64_t max_variants = 4096;  // refuse larger matrices before enumerating them
};

/// Every surviving variant of every program, in a stable order, with what was pruned and why.
struct ExpansionResult {
    std::vector<Variant> variants;
    std::vector<PrunedCombination> pruned;
    std::vector<Diagnostic> diagnostics;
};

/// The number of combinations a program's features and axes produce before pruning
/// (saturates at UINT64_MAX instead of overflowing).
std::uint64_t CountCombinations(const ProgramConfig& program);

/// The first rule a define set breaks, or nullptr when it satisfies every rule.
const Rule* FirstBrokenRule(const ProgramConfig& program, const std::vector<std::string>& defines);

/// Enumerates and prunes every program; fails with diagnostics (and no variants) when the total
/// number of combinations exceeds `options.max_variants`, or when a program is left with none.
ExpansionResult ExpandVariants(const VariantConfig& config, const ExpansionOptions& options);

}  // namespace tidepool
