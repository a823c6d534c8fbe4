// KeywordRenaming (compiler/src/KeywordRenaming.h): which words are renamed, whole tokens only,
// and the way back for glslang's messages.
#include <gtest/gtest.h>

#include <string>

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

}  // namespace
}  // namespace tidepool
