#include "tidepool/VariantExpander.h"

#include <algorithm>
#include <iterator>
#include <limits>
#include <map>
#include <utility>

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
                if (has(rule.subject) &&
                    !std::all_of(rule.others.begin(), rule.others.end(), has)) {
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

namespace {

// Kleene's three-valued logic over a partial choice: a define is present, absent, or not yet
// known. The order lets AND be min, OR be max and NOT be 2 - x.
enum Truth : int { kFalse = 0, kUnknown = 1, kTrue = 2 };

// Marks "no decision" (a name no decision defines), "undecided" and "no rule".
constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

// One decision of the walk: a feature (absent or present) or an axis (one of its values).
struct Decision {
    std::vector<std::string> defines;  // per choice; "" where the choice adds none
    std::vector<std::size_t> rules;    // the rules naming one of its defines, ascending
};

// "Decision `decision` took choice `choice`"; a name no decision defines is always absent.
struct Literal {
    std::size_t decision = kNone;
    std::size_t choice = 0;
};

struct CompiledRule {
    RuleKind kind = RuleKind::kRequires;
    Literal subject;
    std::vector<Literal> others;
};

// The walk over one program. A branch is cut as soon as some rule fails for every completion of
// the choices made so far; then every combination below it is pruned, and CountCut works out
// exactly which rule is the first each of them breaks, without visiting them one by one.
class ProgramExpansion {
public:
    // With `keep_variants` false the walk only counts the valid variants (up to the budget) and
    // the pruned ones, and lists none.
    ProgramExpansion(const ProgramConfig& program, std::uint64_t valid_budget,
                     std::uint64_t list_budget, bool keep_variants = true)
        : program_(program),
          valid_budget_(valid_budget),
          list_budget_(keep_variants ? list_budget : 0),
          keep_variants_(keep_variants) {
        Compile();
        counts_.assign(program.rules.size(), 0);
    }

    // Walks every valid variant; stops early once more than `valid_budget` were found.
    void Run() {
        const std::size_t failing = FirstFailingRule();
        if (failing != kNone) {
            Cut(0, failing);
        } else {
            Walk(0);
        }
    }

    bool OverBudget() const { return over_budget_; }
    std::vector<Variant>& Variants() { return variants_; }
    std::vector<PrunedCombination>& Listed() { return listed_; }
    const std::vector<std::uint64_t>& Counts() const { return counts_; }

private:
    void Compile() {
        std::map<std::string, Literal> literal_of;
        auto add_decision = [&](std::vector<std::string> defines) {
            for (std::size_t c = 0; c < defines.size(); ++c) {
                if (!defines[c].empty()) {
                    literal_of[defines[c]] = Literal{decisions_.size(), c};
                }
            }
            decisions_.push_back(Decision{std::move(defines), {}});
        };
        for (const Feature& feature : program_.features) {
            add_decision({"", feature.name});
        }
        for (const Axis& axis : program_.axes) {
            std::vector<std::string> defines;
            for (const std::string& value : axis.values) {
                defines.push_back(axis.DefineFor(value));
            }
            add_decision(std::move(defines));
        }
        auto literal = [&](const std::string& name) {
            auto it = literal_of.find(name);
            return it == literal_of.end() ? Literal{} : it->second;
        };
        for (std::size_t r = 0; r < program_.rules.size(); ++r) {
            const Rule& rule = program_.rules[r];
            CompiledRule compiled{rule.kind, literal(rule.subject), {}};
            for (const std::string& other : rule.others) {
                compiled.others.push_back(literal(other));
            }
            for (std::size_t d : NamedDecisions(compiled)) {
                if (d != kNone &&
                    (decisions_[d].rules.empty() || decisions_[d].rules.back() != r)) {
                    decisions_[d].rules.push_back(r);
                }
            }
            rules_.push_back(std::move(compiled));
        }
        // Decide the names of earlier rules first: a rule is then settled soon after its names
        // are chosen, branches die young, and when a rule fails the rules declared before it
        // are mostly settled already, which keeps CountCut shallow.
        std::vector<bool> placed(decisions_.size(), false);
        auto place = [&](std::size_t d) {
            if (d != kNone && !placed[d]) {
                placed[d] = true;
                order_.push_back(d);
            }
        };
        for (const CompiledRule& rule : rules_) {
            for (std::size_t d : NamedDecisions(rule)) {
                place(d);
            }
        }
        for (std::size_t d = 0; d < decisions_.size(); ++d) {
            place(d);
        }
        chosen_.assign(decisions_.size(), kNone);
    }

    // The decisions a rule reads, subject first (kNone for names no decision defines).
    static std::vector<std::size_t> NamedDecisions(const CompiledRule& rule) {
        std::vector<std::size_t> named;
        if (rule.kind != RuleKind::kExcludeCombination) {
            named.push_back(rule.subject.decision);
        }
        for (const Literal& other : rule.others) {
            named.push_back(other.decision);
        }
        return named;
    }

    Truth Value(const Literal& literal) const {
        if (literal.decision == kNone) {
            return kFalse;
        }
        const std::size_t choice = chosen_[literal.decision];
        if (choice == kNone) {
            return kUnknown;
        }
        return choice == literal.choice ? kTrue : kFalse;
    }

    // Whether rule `r` is broken: kTrue for every completion of the current choices, kFalse for
    // none, kUnknown when that depends on choices not made yet. Same formulas as FirstBrokenRule.
    Truth Broken(std::size_t r) const {
        const CompiledRule& rule = rules_[r];
        auto all_others = [&] {
            Truth all = kTrue;
            for (const Literal& other : rule.others) {
                all = std::min(all, Value(other));
            }
            return all;
        };
        switch (rule.kind) {
            case RuleKind::kRequires:
                return std::min(Value(rule.subject), static_cast<Truth>(kTrue - all_others()));
            case RuleKind::kExcludes: {
                Truth any = kFalse;
                for (const Literal& other : rule.others) {
                    any = std::max(any, Value(other));
                }
                return std::min(Value(rule.subject), any);
            }
            case RuleKind::kExcludeCombination:
                return all_others();
        }
        return kFalse;
    }

    // The first rule broken for every completion of the current choices, or kNone.
    std::size_t FirstFailingRule() const {
        for (std::size_t r = 0; r < rules_.size(); ++r) {
            if (Broken(r) == kTrue) {
                return r;
            }
        }
        return kNone;
    }

    void Walk(std::size_t depth) {
        if (depth == order_.size()) {
            if (keep_variants_) {
                variants_.push_back(CurrentVariant());
            }
            ++found_;
            over_budget_ = found_ > valid_budget_;
            return;
        }
        const std::size_t d = order_[depth];
        for (std::size_t c = 0; c < decisions_[d].defines.size() && !over_budget_; ++c) {
            chosen_[d] = c;
            // No rule was broken before this choice, so only the rules naming it can be now.
            std::size_t failing = kNone;
            for (std::size_t r : decisions_[d].rules) {
                if (Broken(r) == kTrue) {
                    failing = r;
                    break;
                }
            }
            if (failing != kNone) {
                Cut(depth + 1, failing);
            } else {
                Walk(depth + 1);
            }
        }
        chosen_[d] = kNone;
    }

    // Every completion of the choices made before `depth` breaks rule `failing`, the first rule
    // to do so for all of them; lists the first completions when asked, and counts them all.
    void Cut(std::size_t depth, std::size_t failing) {
        if (listed_.size() < list_budget_) {
            List(depth);
        }
        CountCut(failing);
    }

    // Credits every completion of the current choices to the first rule it breaks, knowing that
    // all of them break rule `bound`. When every earlier rule is unbroken for all completions,
    // `bound` is first for the whole subtree, which then counts at once; an earlier rule still
    // undecided may be first for some completions, so the count splits on one of its names.
    // Only names of such earlier rules are ever chosen here, never the rest of the subtree.
    void CountCut(std::size_t bound) {
        std::size_t open = kNone;
        for (std::size_t r = 0; r < bound; ++r) {
            const Truth broken = Broken(r);
            if (broken == kTrue) {
                bound = r;
                break;
            }
            if (broken == kUnknown && open == kNone) {
                open = r;
            }
        }
        if (open == kNone) {
            counts_[bound] = SaturatingAdd(counts_[bound], Completions());
            return;
        }
        const std::size_t d = UndecidedNameOf(open);
        for (std::size_t c = 0; c < decisions_[d].defines.size(); ++c) {
            chosen_[d] = c;
            CountCut(bound);
        }
        chosen_[d] = kNone;
    }

    // A decision named by rule `r` that is not made yet (an undecided rule has one).
    std::size_t UndecidedNameOf(std::size_t r) const {
        const CompiledRule& rule = rules_[r];
        if (rule.kind != RuleKind::kExcludeCombination && Value(rule.subject) == kUnknown) {
            return rule.subject.decision;
        }
        for (const Literal& other : rule.others) {
            if (Value(other) == kUnknown) {
                return other.decision;
            }
        }
        return kNone;  // unreachable for an undecided rule
    }

    // The number of ways to make the decisions not made yet.
    std::uint64_t Completions() const {
        std::uint64_t count = 1;
        for (std::size_t d = 0; d < decisions_.size(); ++d) {
            if (chosen_[d] == kNone) {
                count = SaturatingMultiply(count, decisions_[d].defines.size());
            }
        }
        return count;
    }

    // Lists completions of the current choices (all pruned) until the list budget is spent.
    void List(std::size_t depth) {
        if (depth == order_.size()) {
            Variant combination = CurrentVariant();
            const Rule* rule = FirstBrokenRule(program_, combination.defines);
            listed_.push_back(
                    PrunedCombination{std::move(combination), rule->Describe(), rule->where});
            return;
        }
        const std::size_t d = order_[depth];
        for (std::size_t c = 0; c < decisions_[d].defines.size() && listed_.size() < list_budget_;
             ++c) {
            chosen_[d] = c;
            List(depth + 1);
        }
        chosen_[d] = kNone;
    }

    Variant CurrentVariant() const {
        std::vector<std::string> defines;
        for (std::size_t d = 0; d < decisions_.size(); ++d) {
            if (const std::string& define = decisions_[d].defines[chosen_[d]]; !define.empty()) {
                defines.push_back(define);
            }
        }
        return MakeVariant(program_.name, std::move(defines));
    }

    const ProgramConfig& program_;
    std::uint64_t valid_budget_;
    std::uint64_t list_budget_;
    bool keep_variants_;
    std::uint64_t found_ = 0;          // valid variants walked
    std::vector<Decision> decisions_;  // features, then axes, as declared
    std::vector<CompiledRule> rules_;  // as declared
    std::vector<std::size_t> order_;   // the order decisions are made in
    std::vector<std::size_t> chosen_;  // per decision: the choice, or kNone while undecided
    std::vector<Variant> variants_;
    std::vector<PrunedCombination> listed_;
    std::vector<std::uint64_t> counts_;  // per rule
    bool over_budget_ = false;
};

// The error for a limit out of range, or "" when `options` can be used.
std::string LimitError(const ExpansionOptions& options) {
    if (options.max_variants == 0 || options.max_variants > kLargeVariantCeiling) {
        return fmt::format("{} must be from 1 to {} valid variants, not {}", options.limit_origin,
                           kLargeVariantCeiling, options.max_variants);
    }
    if (options.max_variants > kVariantCeiling && !options.allow_large_matrix) {
        return fmt::format(
                "{} of {} is over the ceiling of {} valid variants; lower it, or pass "
                "--allow-large-matrix to allow up to {}",
                options.limit_origin, options.max_variants, kVariantCeiling, kLargeVariantCeiling);
    }
    return {};
}

}  // namespace

ExpansionResult ExpandVariants(const VariantConfig& config, const ExpansionOptions& options) {
    ExpansionResult result;
    const SourceLocation& limit_where = options.limit_where;
    if (const std::string error = LimitError(options); !error.empty()) {
        result.diagnostics.push_back(
                limit_where.file.empty()
                        ? MakeError(config.path, 0, 0, error)
                        : MakeError(limit_where.file, limit_where.line, limit_where.column, error));
        return result;
    }
    for (const ProgramConfig& program : config.programs) {
        const std::uint64_t valid_budget = options.max_variants - result.variants.size();
        // A program over the limit is found by counting first: a variant kept costs about 500
        // bytes, and a refusal at the ceiling of --allow-large-matrix kept 16 million of them
        // (5 GB, over 20 s) before it could say no. Counting is cheap beside keeping them.
        ProgramExpansion counted(program, valid_budget, 0, /*keep_variants=*/false);
        counted.Run();
        if (counted.OverBudget()) {
            // Stop at once: the rest of the matrix would only make the refusal more expensive.
            const SourceLocation& where = limit_where.file.empty() ? program.where : limit_where;
            result.diagnostics.push_back(MakeError(
                    where.file, where.line, where.column,
                    fmt::format("program '{}' takes the matrix over {} valid variants, the limit "
                                "set by {}; add rules, remove features, or raise the limit",
                                program.name, options.max_variants, options.limit_origin)));
            break;
        }
        ProgramExpansion expansion(
                program, valid_budget,
                options.pruned_limit -
                        std::min<std::uint64_t>(options.pruned_limit, result.pruned.size()));
        expansion.Run();
        if (expansion.Variants().empty()) {
            result.diagnostics.push_back(MakeError(
                    program.where.file, program.where.line, program.where.column,
                    fmt::format("the rules leave program '{}' with no variant; relax a rule",
                                program.name)));
        }
        std::move(expansion.Variants().begin(), expansion.Variants().end(),
                  std::back_inserter(result.variants));
        std::move(expansion.Listed().begin(), expansion.Listed().end(),
                  std::back_inserter(result.pruned));
        for (std::size_t r = 0; r < program.rules.size(); ++r) {
            const Rule& rule = program.rules[r];
            result.pruned_by_rule.push_back(RulePruneCount{program.name, rule.Describe(),
                                                           rule.where, expansion.Counts()[r]});
            result.pruned_total = SaturatingAdd(result.pruned_total, expansion.Counts()[r]);
        }
    }
    // A stable order independent of the order decisions were made in: by id (each id made
    // once, not once per comparison).
    std::vector<std::pair<std::string, Variant>> by_id;
    by_id.reserve(result.variants.size());
    for (Variant& variant : result.variants) {
        std::string id = variant.Id();
        by_id.emplace_back(std::move(id), std::move(variant));
    }
    std::sort(by_id.begin(), by_id.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < by_id.size(); ++i) {
        result.variants[i] = std::move(by_id[i].second);
    }
    if (HasErrors(result.diagnostics)) {
        result.variants.clear();
    }
    return result;
}

}  // namespace tidepool
