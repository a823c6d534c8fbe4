// KeywordRenaming (compiler/src/KeywordRenaming.h): which words are renamed, whole tokens only,
// and the way back for glslang's messages.
#include <gtest/gtest.h>

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "KeywordRenaming.h"

namespace tidepool {
namespace {

TEST(KeywordRenamingTest, RenamesOnlyTheWordsAShaderUses) {
    const KeywordRenaming renaming = PlanEs100Renaming({"float filter; int case_count;", ""});
    ASSERT_EQ(renaming.names.size(), 1U);
    EXPECT_EQ(renaming.names[0].first, "tp_es100_filter");
    EXPECT_EQ(renaming.names[0].second, "filter");
}

TEST(KeywordRenamingTest, ReplacesWholeIdentifiersOnlyAndNotNumbers) {
    const KeywordRenaming renaming = PlanEs100Renaming({"case filter", ""});
    EXPECT_EQ(renaming.Apply("float filter = x.filter + filters + my_case + case; // case\n"
                             "int n = 0xcase;"),
              "float tp_es100_filter = x.tp_es100_filter + filters + my_case + tp_es100_case; "
              "// tp_es100_case\nint n = 0xcase;");
}

TEST(KeywordRenamingTest, RestoresTheUsersWordsInMessages) {
    const KeywordRenaming renaming = PlanEs100Renaming({"filter", ""});
    EXPECT_EQ(renaming.Restore("ERROR: 0:4: 'tp_es100_filter' : redefinition"),
              "ERROR: 0:4: 'filter' : redefinition");
}

TEST(KeywordRenamingTest, DefinesInThePreambleAreRenamedAlike) {
    const KeywordRenaming renaming = PlanEs100Renaming({"float x = active;", "#define active 1\n"});
    EXPECT_EQ(renaming.Apply("#define active 1\n"), "#define tp_es100_active 1\n");
}

TEST(KeywordRenamingTest, AWordWhoseStandInTheShaderSpellsIsLeftForGlslang) {
    const KeywordRenaming renaming = PlanEs100Renaming({"float filter, tp_es100_filter;", ""});
    EXPECT_TRUE(renaming.names.empty());
}

TEST(KeywordRenamingTest, LengthIsRenamedOnlyWhereItNamesAMember) {
    const std::string shader =
            "struct Wave { float length; };\n"
            "uniform Tide { float length; vec4 h[2]; } tide;\n"
            "float f(Wave w) { return w.length + w . length + length(tide.h[0]) +\n"
            "                  float(tide.h.length()); }\n";
    EXPECT_TRUE(PlanLengthMemberRenaming({shader, ""}));
    KeywordRenaming renaming;
    renaming.length_members = true;
    EXPECT_EQ(renaming.Apply(shader),
              "struct Wave { float tp_member_length; };\n"
              "uniform Tide { float tp_member_length; vec4 h[2]; } tide;\n"
              "float f(Wave w) { return w.tp_member_length + w . tp_member_length + "
              "length(tide.h[0]) +\n"
              "                  float(tide.h.length()); }\n");
    EXPECT_EQ(renaming.Restore("'tp_member_length' : no such field in structure"),
              "'length' : no such field in structure");
}

TEST(KeywordRenamingTest, NoMemberNamedLengthOrTheStandInSpelledMeansNoRenaming) {
    EXPECT_FALSE(PlanLengthMemberRenaming({"float f(vec2 v) { return length(v); }", ""}));
    EXPECT_FALSE(PlanLengthMemberRenaming({"float g(Wave w) { return w.length; }", ""}));
    EXPECT_FALSE(PlanLengthMemberRenaming(
            {"struct Wave { float length; float tp_member_length; };", ""}));
}

TEST(KeywordRenamingTest, AScanKeepsOnlyTheWholeWordsAndStandInsThePlanAsksAbout) {
    const RenamingScan scan =
            ScanForRenaming("float filter; int filters, case_count, tp_es100_x; // common\n");
    EXPECT_EQ(scan.es100_tokens,
              (std::set<std::string, std::less<>>{"common", "filter", "tp_es100_x"}));
    EXPECT_FALSE(scan.spells_length_stand_in);
    EXPECT_FALSE(scan.declares_length_member);
}

TEST(KeywordRenamingTest, AStandInSpelledInAnotherTextOfTheStageBlocksTheWord) {
    // The scans of a stage's texts are planned together, as PlanEs100Renaming plans its texts.
    const std::vector<RenamingScan> scans = {ScanForRenaming("float filter;"),
                                             ScanForRenaming("#define tp_es100_filter 1\n")};
    EXPECT_TRUE(PlanRenaming(scans, /*es100=*/true).names.empty());
    const std::vector<RenamingScan> member = {ScanForRenaming("struct S { float length; };"),
                                              ScanForRenaming("#define tp_member_length 1\n")};
    EXPECT_FALSE(PlanRenaming(member, /*es100=*/true).length_members);
}

TEST(KeywordRenamingTest, OnlyAnEs100StageRenamesWordsButEveryStageRenamesLengthMembers) {
    const std::vector<RenamingScan> scans = {
            ScanForRenaming("struct S { float length; }; float filter;"), ScanForRenaming("")};
    const KeywordRenaming es300 = PlanRenaming(scans, /*es100=*/false);
    EXPECT_TRUE(es300.names.empty());
    EXPECT_TRUE(es300.length_members);
    const KeywordRenaming es100 = PlanRenaming(scans, /*es100=*/true);
    ASSERT_EQ(es100.names.size(), 1U);
    EXPECT_EQ(es100.names[0].second, "filter");
    EXPECT_TRUE(es100.length_members);
}

}  // namespace
}  // namespace tidepool
