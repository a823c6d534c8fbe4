// KeywordRenaming (compiler/src/KeywordRenaming.h): which words are renamed, whole tokens only,
// and the way back for glslang's messages.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace tidepool
