// What the expander's depth-first walk must agree with: every combination of a program visited
// one by one, as the expander did before it walked only valid variants. Slow on purpose; for
// tests over small matrices only.
#pragma once

#include "tidepool/VariantExpander.h"

#include <algorithm>
#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace tidepool::testing {

/// A program's expansion worked out one combination at a time.
struct BruteForceExpansion {
    std::vector<Variant> variants;                         // sorted by id
    std::vector<std::uint64_t> counts;                     // per rule: combinations it is first for
    std::set<std::pair<std::string, std::string>> pruned;  // (id, rule description)
};

/// Decodes every combination index in mixed radix (low bits choose features, the rest choose
/// axis values) and asks FirstBrokenRule where it belongs.
inline BruteForceExpansion ExpandOneByOne(const ProgramConfig& program) {
    BruteForceExpansion expected;
    expected.counts.assign(program.rules.size(), 0);
    for (std::uint64_t index = 0; index < CountCombinations(program); ++index) {
        std::vector<std::string> defines;
        std::uint64_t rest = index;
        for (const Feature& feature : program.features) {
            if ((rest & 1U) != 0) {
                defines.push_back(feature.name);
            }
            rest >>= 1U;
        }
        for (const Axis& axis : program.axes) {
            if (std::string define = axis.DefineFor(axis.values[rest % axis.values.size()]);
                !define.empty()) {
                defines.push_back(std::move(define));
            }
            rest /= axis.values.size();
        }
        Variant variant = MakeVariant(program.name, std::move(defines));
        if (const Rule* rule = FirstBrokenRule(program, variant.defines)) {
            ++expected.counts[static_cast<std::size_t>(rule - program.rules.data())];
            expected.pruned.emplace(variant.Id(), rule->Describe());
        } else {
            expected.variants.push_back(std::move(variant));
        }
    }
    std::sort(expected.variants.begin(), expected.variants.end(),
              [](const Variant& a, const Variant& b) { return a.Id() < b.Id(); });
    return expected;
}

}  // namespace tidepool::testing
