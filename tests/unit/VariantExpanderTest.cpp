#include "tidepool/VariantExpander.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "AddressSanitizer.h"
#include "ExpandOneByOne.h"
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace tidepool {
namespace {

ProgramConfig Program(std::vector<std::string> features, std::vector<Rule> rules = {},
                      std::vector<Axis> axes = {}) {
    ProgramConfig program;
    program.name = "p";
    for (std::string& f : features) {
        program.features.push_back(Feature{std::move(f), {}});
    }
    program.rules = std::move(rules);
    program.axes = std::move(axes);
    program.where = SourceLocation{"v.yaml", 2, 3};
    return program;
}

VariantConfig Config(std::vector<ProgramConfig> programs) {
    VariantConfig config;
    config.path = "v.yaml";
    config.programs = std::move(programs);
    return config;
}

Rule Requires(std::string subject, std::vector<std::string> others, int line = 0) {
    return Rule{
            RuleKind::kRequires, std::move(subject), std::move(others), {}, {"v.yaml", line, 1}};
}
Rule Excludes(std::string subject, std::vector<std::string> others) {
    return Rule{RuleKind::kExcludes, std::move(subject), std::move(others), {}, {}};
}
Rule ExcludeCombination(std::vector<std::string> others) {
    return Rule{RuleKind::kExcludeCombination, {}, std::move(others), {}, {}};
}

// Options that list every pruned combination (the small matrices here have a few dozen).
ExpansionOptions ListingEveryPruned() {
    ExpansionOptions options;
    options.pruned_limit = kVariantCeiling;
    return options;
}

std::set<std::string> Ids(const std::vector<Variant>& variants) {
    std::set<std::string> ids;
    for (const Variant& v : variants) {
        ids.insert(v.Id());
    }
    return ids;
}

TEST(VariantExpanderTest, IdIsIndependentOfDefineOrder) {
    EXPECT_EQ(MakeVariant("water", {"ENABLE_FOG", "ENABLE_REFRACTION", "ENABLE_DISTORTION"}).Id(),
              MakeVariant("water", {"ENABLE_DISTORTION", "ENABLE_REFRACTION", "ENABLE_FOG"}).Id());
    EXPECT_EQ(MakeVariant("water", {"ENABLE_REFRACTION", "ENABLE_FOG", "ENABLE_DISTORTION"}).Id(),
              "water:ENABLE_DISTORTION,ENABLE_FOG,ENABLE_REFRACTION");
    EXPECT_EQ(MakeVariant("water", {"B", "A", "B"}).Id(), "water:A,B");
    EXPECT_EQ(MakeVariant("water", {}).Id(), "water:");
}

TEST(VariantExpanderTest, WithoutRulesEverySubsetIsEmittedOnce) {
    const ExpansionResult result =
            ExpandVariants(Config({Program({"A", "B", "C", "D"})}), ExpansionOptions{});
    ASSERT_TRUE(result.diagnostics.empty());
    EXPECT_EQ(result.variants.size(), 16U);
    EXPECT_EQ(Ids(result.variants).size(), 16U);
    EXPECT_TRUE(result.pruned.empty());
}

// Exhaustive check of each rule kind: the expansion keeps exactly the subsets a brute-force
// predicate accepts, and prunes the rest with the rule that removed them.
TEST(VariantExpanderTest, EachRuleKindKeepsExactlyTheSubsetsItAllows) {
    const std::vector<std::string> names = {"A", "B", "C", "D"};
    struct Case {
        Rule rule;
        bool (*allowed)(const std::set<std::string>&);
    };
    const std::vector<Case> cases = {
            {Requires("B", {"A", "C"}),
             [](const std::set<std::string>& s) {
                 return s.count("B") == 0 || (s.count("A") != 0 && s.count("C") != 0);
             }},
            {Excludes("A", {"C", "D"}),
             [](const std::set<std::string>& s) {
                 return s.count("A") == 0 || (s.count("C") == 0 && s.count("D") == 0);
             }},
            {ExcludeCombination({"B", "D"}),
             [](const std::set<std::string>& s) {
                 return !(s.count("B") != 0 && s.count("D") != 0);
             }},
    };
    for (const Case& c : cases) {
        const ExpansionResult result =
                ExpandVariants(Config({Program(names, {c.rule})}), ListingEveryPruned());
        std::set<std::string> expected_kept;
        std::set<std::string> expected_pruned;
        for (unsigned mask = 0; mask < 16; ++mask) {
            std::set<std::string> subset;
            for (unsigned bit = 0; bit < 4; ++bit) {
                if ((mask & (1U << bit)) != 0) {
                    subset.insert(names[bit]);
                }
            }
            const std::string id =
                    MakeVariant("p", std::vector<std::string>(subset.begin(), subset.end())).Id();
            (c.allowed(subset) ? expected_kept : expected_pruned).insert(id);
        }
        EXPECT_EQ(Ids(result.variants), expected_kept) << c.rule.Describe();
        std::set<std::string> pruned;
        for (const PrunedCombination& p : result.pruned) {
            pruned.insert(p.combination.Id());
            EXPECT_EQ(p.rule, c.rule.Describe());
        }
        EXPECT_EQ(pruned, expected_pruned) << c.rule.Describe();
    }
}

TEST(VariantExpanderTest, PrunedCombinationNamesTheFirstRuleBrokenAndWhereItIsWritten) {
    const ExpansionResult result = ExpandVariants(
            Config({Program({"A", "B"}, {Requires("B", {"A"}, 7)})}), ListingEveryPruned());
    ASSERT_EQ(result.pruned.size(), 1U);
    EXPECT_EQ(result.pruned[0].combination.Id(), "p:B");
    EXPECT_EQ(result.pruned[0].rule, "B requires A");
    EXPECT_EQ(result.pruned[0].where.line, 7);
}

TEST(VariantExpanderTest, AxisContributesExactlyOneValueDefinePerVariant) {
    const ExpansionResult result =
            ExpandVariants(Config({Program({"A"}, {ExcludeCombination({"A", "MODE_EXACT"})},
                                           {Axis{"MODE", {"fast", "exact", "off"}, {}}})}),
                           ListingEveryPruned());
    EXPECT_EQ(Ids(result.variants),
              (std::set<std::string>{"p:MODE_EXACT", "p:MODE_FAST", "p:MODE_OFF", "p:A,MODE_FAST",
                                     "p:A,MODE_OFF"}));
    ASSERT_EQ(result.pruned.size(), 1U);
    EXPECT_EQ(result.pruned[0].combination.Id(), "p:A,MODE_EXACT");
}

// REFLECTION: { values: [planar, cubemap, fourier], default: planar }
Axis ReflectionWithPlanarDefault() {
    return Axis{"REFLECTION", {"planar", "cubemap", "fourier"}, SourceLocation{}, "planar"};
}

TEST(VariantExpanderTest, AxisDefaultValueAddsNoDefineAndStillCountsAsACombination) {
    const ProgramConfig program = Program({"A"}, {}, {ReflectionWithPlanarDefault()});
    EXPECT_EQ(CountCombinations(program), 6U);
    const ExpansionResult result = ExpandVariants(Config({program}), ExpansionOptions{});
    ASSERT_TRUE(result.diagnostics.empty());
    // The default-valued variants carry no REFLECTION_* define: their ids are those of a program
    // without the axis.
    EXPECT_EQ(Ids(result.variants),
              (std::set<std::string>{"p:", "p:A", "p:REFLECTION_CUBEMAP", "p:REFLECTION_FOURIER",
                                     "p:A,REFLECTION_CUBEMAP", "p:A,REFLECTION_FOURIER"}));
    EXPECT_TRUE(result.pruned.empty());
}

TEST(VariantExpanderTest, CountMultipliesByEveryAxisValueIncludingTheDefault) {
    const ProgramConfig program = Program(
            {"A", "B"}, {}, {Axis{"QUALITY", {"low", "high"}, {}}, ReflectionWithPlanarDefault()});
    EXPECT_EQ(CountCombinations(program), 24U);
    const ExpansionResult result = ExpandVariants(Config({program}), ExpansionOptions{});
    EXPECT_EQ(result.variants.size(), 24U);
    EXPECT_EQ(Ids(result.variants).size(), 24U);
    // Every variant has exactly one QUALITY define and at most one REFLECTION define.
    for (const Variant& v : result.variants) {
        auto count = [&](const std::string& prefix) {
            return std::count_if(v.defines.begin(), v.defines.end(),
                                 [&](const std::string& d) { return d.rfind(prefix, 0) == 0; });
        };
        EXPECT_EQ(count("QUALITY_"), 1) << v.Id();
        EXPECT_LE(count("REFLECTION_"), 1) << v.Id();
    }
}

TEST(VariantExpanderTest, RuleOverTheOtherValuesOfAnAxisWithDefaultPrunesOnlyThoseValues) {
    const ExpansionResult result =
            ExpandVariants(Config({Program({"A"}, {Requires("REFLECTION_FOURIER", {"A"}, 4)},
                                           {ReflectionWithPlanarDefault()})}),
                           ListingEveryPruned());
    EXPECT_EQ(Ids(result.variants),
              (std::set<std::string>{"p:", "p:A", "p:REFLECTION_CUBEMAP", "p:A,REFLECTION_CUBEMAP",
                                     "p:A,REFLECTION_FOURIER"}));
    ASSERT_EQ(result.pruned.size(), 1U);
    EXPECT_EQ(result.pruned[0].combination.Id(), "p:REFLECTION_FOURIER");
}

std::vector<std::string> Features(int count) {
    std::vector<std::string> names;
    for (int i = 0; i < count; ++i) {
        names.push_back(std::string("F").append(std::to_string(i)));
    }
    return names;
}

TEST(VariantExpanderTest, MatrixOverTheLimitIsRefusedAtTheProgramOnceItsValidVariantsPassIt) {
    // 2^40 valid variants: the walk stops at the 4097th, so this returns at once.
    const ExpansionResult result =
            ExpandVariants(Config({Program(Features(40))}), ExpansionOptions{4096});
    EXPECT_TRUE(result.variants.empty());
    ASSERT_EQ(result.diagnostics.size(), 1U);
    EXPECT_EQ(FormatDiagnostic(result.diagnostics[0]),
              "v.yaml:2:3: error: program 'p' takes the matrix over 4096 valid variants, the "
              "limit set by the default max_variants; add rules, remove features, or raise the "
              "limit");
}

#if !defined(TIDEPOOL_TEST_ADDRESS_SANITIZER)  // ASan reserves terabytes of address space
// The walk counts the valid variants before it keeps any: a refusal at a high limit used to keep
// every variant up to it first (at the --allow-large-matrix ceiling, 16 million of them: 5 GB and
// over 20 s). Here 2 million would take about 1 GB; the refusal must come within 256 MB.
TEST(VariantExpanderTest, AMatrixOverAHighLimitIsRefusedWithoutKeepingItsVariants) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        const rlimit quarter_gigabyte{std::size_t{256} << 20, std::size_t{256} << 20};
        if (::setrlimit(RLIMIT_AS, &quarter_gigabyte) != 0) {
            ::_exit(2);
        }
        try {
            ExpansionOptions options{std::uint64_t{2} << 20};
            options.allow_large_matrix = true;
            const ExpansionResult result = ExpandVariants(Config({Program(Features(40))}), options);
            ::_exit(result.variants.empty() && HasErrors(result.diagnostics) ? 0 : 1);
        } catch (...) {
            ::_exit(3);  // std::bad_alloc: the variants were kept
        }
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 0) << "1: not refused; 2: setrlimit; 3: out of memory";
}
#endif

TEST(VariantExpanderTest, LimitSetInTheFileIsNamedAtItsLine) {
    ExpansionOptions options;
    options.max_variants = 8;
    options.limit_origin = "max_variants";
    options.limit_where = SourceLocation{"v.yaml", 1, 15};
    const ExpansionResult result = ExpandVariants(Config({Program(Features(4))}), options);
    ASSERT_EQ(result.diagnostics.size(), 1U);
    EXPECT_EQ(FormatDiagnostic(result.diagnostics[0]),
              "v.yaml:1:15: error: program 'p' takes the matrix over 8 valid variants, the limit "
              "set by max_variants; add rules, remove features, or raise the limit");
}

TEST(VariantExpanderTest, LimitCountsValidVariantsNotCombinations) {
    // A chain where each feature requires the one before: 41 valid of 2^40 combinations.
    std::vector<Rule> chain;
    const std::vector<std::string> names = Features(40);
    for (std::size_t i = 1; i < names.size(); ++i) {
        chain.push_back(Requires(names[i], {names[i - 1]}, static_cast<int>(i)));
    }
    const ExpansionResult result =
            ExpandVariants(Config({Program(names, chain)}), ExpansionOptions{41});
    ASSERT_TRUE(result.diagnostics.empty());
    EXPECT_EQ(result.variants.size(), 41U);
    EXPECT_EQ(result.pruned_total, (std::uint64_t{1} << 40U) - 41U);
    ASSERT_EQ(result.pruned_by_rule.size(), 39U);
    // Rule i (F_i requires F_{i-1}) is the first broken rule of i * 2^(39-i) combinations: the
    // i valid chains of F_0..F_{i-1} ending without F_{i-1}, with F_i, anything after.
    for (std::size_t i = 1; i <= 39; ++i) {
        EXPECT_EQ(result.pruned_by_rule[i - 1].count, i * (std::uint64_t{1} << (39U - i))) << i;
        EXPECT_EQ(result.pruned_by_rule[i - 1].where.line, static_cast<int>(i));
    }
    EXPECT_TRUE(HasErrors(
            ExpandVariants(Config({Program(names, chain)}), ExpansionOptions{40}).diagnostics));
}

TEST(VariantExpanderTest, LimitAboveTheCeilingNeedsAllowLargeMatrix) {
    ExpansionOptions options;
    options.max_variants = kVariantCeiling + 1;
    options.limit_origin = "max_variants";
    options.limit_where = SourceLocation{"v.yaml", 1, 15};
    const ExpansionResult refused = ExpandVariants(Config({Program({"A"})}), options);
    ASSERT_EQ(refused.diagnostics.size(), 1U);
    EXPECT_EQ(FormatDiagnostic(refused.diagnostics[0]),
              "v.yaml:1:15: error: max_variants of 65537 is over the ceiling of 65536 valid "
              "variants; lower it, or pass --allow-large-matrix to allow up to 16777216");
    options.allow_large_matrix = true;
    EXPECT_EQ(ExpandVariants(Config({Program({"A"})}), options).variants.size(), 2U);
}

TEST(VariantExpanderTest, LimitOutOfRangeIsRefusedEvenWithAllowLargeMatrix) {
    for (const std::uint64_t limit : {std::uint64_t{0}, kLargeVariantCeiling + 1}) {
        ExpansionOptions options;
        options.max_variants = limit;
        options.allow_large_matrix = true;
        options.limit_origin = "--max-variants";
        const ExpansionResult refused = ExpandVariants(Config({Program({"A"})}), options);
        ASSERT_EQ(refused.diagnostics.size(), 1U);
        EXPECT_EQ(FormatDiagnostic(refused.diagnostics[0]),
                  "v.yaml: error: --max-variants must be from 1 to 16777216 valid variants, not " +
                          std::to_string(limit));
        EXPECT_TRUE(refused.variants.empty());
    }
}

TEST(VariantExpanderTest, RaisedLimitAdmitsTheMatrix) {
    std::vector<std::string> thirteen;
    for (int i = 0; i < 13; ++i) {
        thirteen.push_back(std::string("F").append(std::to_string(i)));
    }
    // 2^13 = 8192 combinations: refused at the default limit, admitted when it is raised.
    EXPECT_TRUE(HasErrors(ExpandVariants(Config({Program(thirteen)}), {4096}).diagnostics));
    EXPECT_EQ(ExpandVariants(Config({Program(thirteen)}), {8192}).variants.size(), 8192U);
}

TEST(VariantExpanderTest, RulesThatLeaveNoVariantAreAnErrorAtTheProgram) {
    const ExpansionResult result =
            ExpandVariants(Config({Program({"A"}, {ExcludeCombination({"A", "MODE_X"})},
                                           {Axis{"MODE", {"x", "y"}, {}}}),
                                   Program({}, {}, {})}),
                           ExpansionOptions{});
    EXPECT_FALSE(HasErrors(result.diagnostics));

    ProgramConfig impossible = Program({"A"}, {Requires("A", {"A"})});
    impossible.rules.push_back(ExcludeCombination({"MODE_X", "A"}));
    impossible.axes.push_back(Axis{"MODE", {"x"}, {}});
    impossible.rules.push_back(Requires("MODE_X", {"A"}));
    const ExpansionResult none = ExpandVariants(Config({impossible}), ExpansionOptions{});
    ASSERT_EQ(none.diagnostics.size(), 1U);
    EXPECT_EQ(FormatDiagnostic(none.diagnostics[0]),
              "v.yaml:2:3: error: the rules leave program 'p' with no variant; relax a rule");
    EXPECT_TRUE(none.variants.empty());
}

// A random program: up to 12 features, up to 2 axes (some with a default), and up to 10 rules of
// every kind over its define names, written as a user might (repeats and self-references too).
ProgramConfig RandomProgram(std::mt19937& random) {
    auto below = [&](int n) { return std::uniform_int_distribution<int>(0, n - 1)(random); };
    ProgramConfig program = Program({});
    const int feature_count = below(13);
    // append, not "F" + std::to_string(f): GCC 12 at -O3 reports a false -Wstringop-overflow
    // in the inlined insert of `const char* + std::string` when this file is compiled together
    // with other test files (the unity build of the tests, cmake/TidepoolPrecompiledHeaders.cmake).
    for (int f = 0; f < feature_count; ++f) {
        program.features.push_back(Feature{std::string("F").append(std::to_string(f)), {}});
    }
    // At most 4096 * 9 combinations, so the brute force stays quick under the sanitizers.
    const int axis_count = feature_count > 10 ? below(2) : below(3);
    for (int a = 0; a < axis_count; ++a) {
        Axis axis{std::string("X").append(std::to_string(a)), {}, {}};
        const int value_count = 1 + below(3);
        for (int v = 0; v < value_count; ++v) {
            axis.values.push_back(std::string(1, static_cast<char>('a' + v)));
        }
        if (below(2) == 0) {
            axis.default_value = axis.values[static_cast<std::size_t>(below(value_count))];
        }
        program.axes.push_back(std::move(axis));
    }
    const std::vector<std::string> names = program.AllDefines();
    if (names.empty()) {
        return program;
    }
    auto name = [&] {
        return names[static_cast<std::size_t>(below(static_cast<int>(names.size())))];
    };
    const int rule_count = below(11);
    for (int r = 0; r < rule_count; ++r) {
        std::vector<std::string> others;
        const int other_count = 1 + below(3);
        for (int o = 0; o < other_count; ++o) {
            others.push_back(name());
        }
        Rule rule{static_cast<RuleKind>(below(3)),
                  name(),
                  std::move(others),
                  {},
                  SourceLocation{"v.yaml", 10 + r, 5}};
        if (rule.kind == RuleKind::kExcludeCombination) {
            rule.subject.clear();
        }
        program.rules.push_back(std::move(rule));
    }
    return program;
}

TEST(VariantExpanderTest, PrunedCountsPerRuleEqualABruteForceOnRandomConfigs) {
    std::mt19937 random(20261123);  // fixed: a failure must reproduce
    for (int trial = 0; trial < 200; ++trial) {
        const ProgramConfig program = RandomProgram(random);
        const testing::BruteForceExpansion expected = testing::ExpandOneByOne(program);
        ExpansionOptions options = ListingEveryPruned();
        options.max_variants = kVariantCeiling;
        const ExpansionResult result = ExpandVariants(Config({program}), options);
        std::string described;
        for (const Rule& rule : program.rules) {
            described += rule.Describe() + "; ";
        }
        SCOPED_TRACE("trial " + std::to_string(trial) + ": " +
                     std::to_string(program.features.size()) + " features, " +
                     std::to_string(program.axes.size()) + " axes, rules: " + described);

        EXPECT_EQ(result.variants.empty(), expected.variants.empty());
        if (!expected.variants.empty()) {
            EXPECT_EQ(result.variants, expected.variants);
        }
        ASSERT_EQ(result.pruned_by_rule.size(), program.rules.size());
        std::uint64_t total = 0;
        for (std::size_t r = 0; r < program.rules.size(); ++r) {
            EXPECT_EQ(result.pruned_by_rule[r].count, expected.counts[r]) << "rule " << r;
            EXPECT_EQ(result.pruned_by_rule[r].rule, program.rules[r].Describe());
            EXPECT_EQ(result.pruned_by_rule[r].where.line, program.rules[r].where.line);
            total += expected.counts[r];
        }
        EXPECT_EQ(result.pruned_total, total);
        std::set<std::pair<std::string, std::string>> listed;
        for (const PrunedCombination& p : result.pruned) {
            listed.emplace(p.combination.Id(), p.rule);
        }
        EXPECT_EQ(listed.size(), result.pruned.size()) << "a combination listed twice";
        EXPECT_EQ(listed, expected.pruned);
    }
}

TEST(VariantExpanderTest, PrunedListStopsAtItsLimitWhileCountsStayComplete) {
    const ExpansionResult result = ExpandVariants(
            Config({Program({"A", "B", "C"}, {Requires("B", {"A"}, 4), Requires("C", {"A"}, 5)})}),
            ExpansionOptions{.max_variants = 4096, .pruned_limit = 2});
    EXPECT_EQ(result.variants.size(), 5U);
    EXPECT_EQ(result.pruned.size(), 2U);
    EXPECT_EQ(result.pruned_total, 3U);
    ASSERT_EQ(result.pruned_by_rule.size(), 2U);
    EXPECT_EQ(result.pruned_by_rule[0].count, 2U);  // B, B+C
    EXPECT_EQ(result.pruned_by_rule[1].count, 1U);  // C
}

}  // namespace
}  // namespace tidepool
