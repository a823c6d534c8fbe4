#include "tidepool/VariantExpander.h"

#include <algorithm>
#include <set>

#include <gtest/gtest.h>

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
    return Rule{RuleKind::kRequires, std::move(subject), std::move(others), {}, {"v.yaml", line, 1}};
}
Rule Excludes(std::string subject, std::vector<std::string> others) {
    return Rule{RuleKind::kExcludes, std::move(subject), std::move(others), {}, {}};
}
Rule ExcludeCombination(std::vector<std::string> others) {
    return Rule{RuleKind::kExcludeCombination, {}, std::move(others), {}, {}};
}

std::set<std::string> Ids(const std::vector<Variant>& variants) {
    std::set<std::string> ids;
    for (const Variant& v : variants) {
        ids.insert(v.Id());
    }
    return ids;
}

TEST(VariantIdTest, IdIsIndependentOfDefineOrder) {
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
             [](const std::set<std::string>& s) { return !(s.count("B") != 0 && s.count("D") != 0); }},
    };
    for (const Case& c : cases) {
        const ExpansionResult result =
                ExpandVariants(Config({Program(names, {c.rule})}), ExpansionOptions{});
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
            Config({Program({"A", "B"}, {Requires("B", {"A"}, 7)})}), ExpansionOptions{});
    ASSERT_EQ(result.pruned.size(), 1U);
    EXPECT_EQ(result.pruned[0].combination.Id(), "p:B");
    EXPECT_EQ(result.pruned[0].rule, "B requires A");
    EXPECT_EQ(result.pruned[0].where.line, 7);
}

TEST(VariantExpanderTest, AxisContributesExactlyOneValueDefinePerVariant) {
    const ExpansionResult result =
            ExpandVariants(Config({Program({"A"}, {ExcludeCombination({"A", "MODE_EXACT"})},
                                           {Axis{"MODE", {"fast", "exact", "off"}, {}}})}),
                           ExpansionOptions{});
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
    const ProgramConfig program =
            Program({"A", "B"}, {},
                    {Axis{"QUALITY", {"low", "high"}, {}}, ReflectionWithPlanarDefault()});
    EXPECT_EQ(CountCombinations(program), 24U);
    const ExpansionResult result = ExpandVariants(Config({program}), ExpansionOptions{});
    EXPECT_EQ(result.variants.size(), 24U);
    EXPECT_EQ(Ids(result.variants).size(), 24U);
    // Every variant has exactly one QUALITY define and at most one REFLECTION define.
    for (const Variant& v : result.variants) {
        auto count = [&](const std::string& prefix) {
            return std::count_if(v.defines.begin(), v.defines.end(), [&](const std::string& d) {
                return d.rfind(prefix, 0) == 0;
            });
        };
        EXPECT_EQ(count("QUALITY_"), 1) << v.Id();
        EXPECT_LE(count("REFLECTION_"), 1) << v.Id();
    }
}

TEST(VariantExpanderTest, RuleOverTheOtherValuesOfAnAxisWithDefaultPrunesOnlyThoseValues) {
    const ExpansionResult result = ExpandVariants(
            Config({Program({"A"}, {Requires("REFLECTION_FOURIER", {"A"}, 4)},
                            {ReflectionWithPlanarDefault()})}),
            ExpansionOptions{});
    EXPECT_EQ(Ids(result.variants),
              (std::set<std::string>{"p:", "p:A", "p:REFLECTION_CUBEMAP", "p:A,REFLECTION_CUBEMAP",
                                     "p:A,REFLECTION_FOURIER"}));
    ASSERT_EQ(result.pruned.size(), 1U);
    EXPECT_EQ(result.pruned[0].combination.Id(), "p:REFLECTION_FOURIER");
}

TEST(VariantExpanderTest, MatrixOverTheLimitIsRefusedWithItsCountBeforeEnumeration) {
    std::vector<std::string> many;
    for (int i = 0; i < 40; ++i) {
        many.push_back(std::string("F").append(std::to_string(i)));
    }
    const ExpansionResult result = ExpandVariants(Config({Program(many)}), ExpansionOptions{4096});
    EXPECT_TRUE(result.variants.empty());
    ASSERT_EQ(result.diagnostics.size(), 1U);
    EXPECT_EQ(FormatDiagnostic(result.diagnostics[0]),
              "v.yaml: error: the matrix has 1099511627776 combinations, over the limit of 4096; "
              "add rules, remove features, or raise the limit with --max-variants");
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
    const ExpansionResult result = ExpandVariants(
            Config({Program({"A"}, {ExcludeCombination({"A", "MODE_X"})},
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

}  // namespace
}  // namespace tidepool
