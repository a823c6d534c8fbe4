// Expansion of a program's features and axes into its valid variants: a depth-first walk that
// applies the rules while choosing, so its cost follows the valid variants, not every combination.
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/VariantConfig.h"

#include <cstdint>
#include <string>
#include <vector>

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
    std::string rule;      // Rule::Describe() of the rule
    SourceLocation where;  // where that rule is written
};

/// How many combinations one rule pruned: those whose first broken rule it is.
struct RulePruneCount {
    std::string program;
    std::string rule;         // Rule::Describe() of the rule
    SourceLocation where;     // where that rule is written
    std::uint64_t count = 0;  // saturates at UINT64_MAX
};

/// Limits and listing for ExpandVariants.
struct ExpansionOptions {
    std::uint64_t max_variants = 4096;  // refuse more valid variants than this (all programs)
    // What set `max_variants`, named in the messages: "--max-variants", "max_variants" or
    // "the default max_variants".
    std::string limit_origin = "the default max_variants";
    // Where the file sets it (its diagnostics point there); empty when set on the command line
    // or by default, and the over-the-limit error then points at the program.
    SourceLocation limit_where = {};  // "= {}": `ExpansionOptions{n}` leaves it out unwarned
    bool allow_large_matrix = false;  // permit max_variants above kVariantCeiling
    std::uint64_t pruned_limit = 0;   // list at most this many pruned combinations (0: none)
};

/// Every valid variant of every program, in a stable order, with how many combinations each
/// rule pruned and, when asked for, the first of them.
struct ExpansionResult {
    std::vector<Variant> variants;
    std::vector<RulePruneCount> pruned_by_rule;  // every rule of every program, declaration order
    std::uint64_t pruned_total = 0;              // saturates at UINT64_MAX
    std::vector<PrunedCombination> pruned;       // at most ExpansionOptions::pruned_limit
    std::vector<Diagnostic> diagnostics;
};

/// The number of combinations a program's features and axes produce before pruning
/// (saturates at UINT64_MAX instead of overflowing).
std::uint64_t CountCombinations(const ProgramConfig& program);

/// The first rule a define set breaks, or nullptr when it satisfies every rule.
const Rule* FirstBrokenRule(const ProgramConfig& program, const std::vector<std::string>& defines);

/// Enumerates the valid variants of every program, counting pruned combinations per rule
/// without visiting them one by one; fails with diagnostics (and no variants) when
/// `options.max_variants` is 0, above kLargeVariantCeiling, or above kVariantCeiling without
/// `allow_large_matrix`; when the valid variants exceed it (enumeration stops there); or when a
/// program is left with none.
ExpansionResult ExpandVariants(const VariantConfig& config, const ExpansionOptions& options);

}  // namespace tidepool
