#include "tidepool/pipeline/BuildOutputs.h"
#include "tidepool/pipeline/MatrixLoading.h"

#include <gtest/gtest.h>

#include <cctype>
#include <chrono>

#include "FileContents.h"
#include "PipelineFixture.h"

namespace tidepool::pipeline {
namespace {

using testing::Formatted;
using testing::ReadText;
using testing::SmallMatrix;

TEST(BuildOutputsTest, DepfileEscapesSpacesHashesColonsAndDollars) {
    EXPECT_EQ(DepfileText("/o/m.json", {"/a b/c#d.yaml", "/x$y.vsh", "/c:d.fsh"}),
              "/o/m.json: \\\n  /a\\ b/c\\#d.yaml \\\n  /x$$y.vsh \\\n  /c\\:d.fsh\n");
}

// Each refused name was read wrongly by GNU Make 4.3 or Ninja 1.11 however it was escaped: a
// newline ends the rule, a tab or '\\' stays in Ninja's name, ';' starts Make's recipe, '|' its
// order-only list, '*' and '[' are Make's wildcards, '=' makes an assignment, a quote or '&' splits
// Ninja's name, and "a(b)" is Make's archive member.
TEST(BuildOutputsTest, DepfileRefusesNamesMakeOrNinjaWouldMisread) {
    for (const char* name : {"/s/n\nl.vsh", "/s/t\tb.vsh", "/s/e\\ f.vsh", "/s/a;b.vsh",
                             "/s/a|b.vsh", "/s/a*.vsh", "/s/a[1].vsh", "/s/a=b.vsh", "/s/it's.vsh",
                             "/s/a\"b.vsh", "/s/a&b.vsh", "/s/lib(a.vsh)"}) {
        EXPECT_NE(DepfileRefusal(name), "") << name;
    }
    for (const char* name : {"/s/a b#c:d$e.vsh", "/s/wave (copy)/a.vsh", "/s/a+b,c@d!e~f%g.vsh",
                             "/s/{x}-y_z.vsh", "/s/m\xc3\xa9r.vsh"}) {
        EXPECT_EQ(DepfileRefusal(name), "") << name;
    }
    EXPECT_EQ(DepfileRefusal("/s/t\tb.vsh"),
              "\"/s/t\\tb.vsh\" has a tab in its name, which Make or Ninja would read as "
              "something else in a depfile");
}

TEST(BuildOutputsTest, DepfileNamesAreCheckedBeforeAnyWorkAsAUsageError) {
    Outcome outcome;
    EXPECT_TRUE(CheckDepfileNames("/o/manifest.json", {"/s/a b.vsh"}, &outcome));
    EXPECT_FALSE(CheckDepfileNames("/o/manifest.json", {"/s/a.vsh", "/s/a;b.fsh"}, &outcome));
    EXPECT_EQ(outcome.status, Status::kUsage);
    EXPECT_EQ(Formatted(outcome.diagnostics),
              "error: --depfile: \"/s/a;b.fsh\" has ';' in its name, which Make or Ninja would "
              "read as something else in a depfile; rename it, or leave out --depfile\n");
}

TEST(BuildOutputsTest, FilesReadNamesTheConfigurationAndEachShaderOnce) {
    const SmallMatrix matrix;
    const LoadedMatrix loaded = LoadMatrix(matrix.Config());
    ASSERT_TRUE(loaded.config.has_value());
    const std::vector<std::filesystem::path> files = FilesRead(*loaded.config);
    ASSERT_EQ(files.size(), 3U);  // both programs share s.vsh and s.fsh
    EXPECT_EQ(files[0], std::filesystem::absolute(matrix.Config()));
    EXPECT_EQ(files[1].filename(), "s.vsh");
    EXPECT_EQ(files[2].filename(), "s.fsh");
}

TEST(BuildOutputsTest, VariantSourcePathMakesTheIdASafeFileName) {
    Variant variant;
    variant.program = "p";
    variant.defines = {"A", "B"};
    const std::filesystem::path path =
            VariantSourcePath(GlslTarget::kEs100, variant, Stage::kFragment);
    EXPECT_EQ(path.parent_path(), std::filesystem::path(TargetName(GlslTarget::kEs100)) / "p");
    EXPECT_EQ(path.extension(), ".frag");
    for (const char c : path.stem().string()) {
        EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')
                << path;
    }
}

TEST(BuildOutputsTest, WritesEachStageAsTheDriverReceivesItAndKeepsUnchangedFiles) {
    const SmallMatrix matrix;
    const LoadedMatrix loaded = LoadMatrix(matrix.Config());
    ASSERT_TRUE(loaded.config.has_value());
    const std::filesystem::path out = matrix.Dir().Path() / "out";
    Outcome outcome;
    ASSERT_TRUE(WriteVariantSources(*loaded.config, loaded.expansion.variants, out, &outcome))
            << Formatted(outcome.diagnostics);
    const Variant& first = loaded.expansion.variants.front();
    const std::filesystem::path vertex =
            out / VariantSourcePath(GlslTarget::kEs100, first, Stage::kVertex);
    EXPECT_NE(ReadText(vertex).find("#line 2"), std::string::npos);
    const auto written = std::filesystem::last_write_time(vertex);
    std::filesystem::last_write_time(vertex, written - std::chrono::hours(1));
    ASSERT_TRUE(WriteVariantSources(*loaded.config, loaded.expansion.variants, out, &outcome));
    EXPECT_EQ(std::filesystem::last_write_time(vertex), written - std::chrono::hours(1));
}

TEST(BuildOutputsTest, AnUnreadableShaderIsAUsageErrorAtItsPath) {
    const SmallMatrix matrix;
    LoadedMatrix loaded = LoadMatrix(matrix.Config());
    ASSERT_TRUE(loaded.config.has_value());
    std::filesystem::remove(matrix.Dir().Path() / "s.vsh");
    Outcome outcome;
    EXPECT_FALSE(WriteVariantSources(*loaded.config, loaded.expansion.variants,
                                     matrix.Dir().Path() / "out", &outcome));
    EXPECT_EQ(outcome.status, Status::kUsage);
    EXPECT_EQ(Formatted(outcome.diagnostics).rfind("s.vsh: error: cannot read shader file: ", 0),
              0U)
            << Formatted(outcome.diagnostics);
}

TEST(BuildOutputsTest, AddSourcePathsNamesBothStagesOfEveryVariant) {
    Variant variant;
    variant.program = "p";
    stagefiles::ManifestFile manifest;
    stagefiles::ManifestVariant& entry = manifest.variants.emplace_back();
    entry.id = variant.Id();
    entry.program = "p";
    entry.target = "100";
    AddSourcePaths({variant}, &manifest);
    ASSERT_TRUE(manifest.variants[0].sources);
    EXPECT_EQ(manifest.variants[0].sources->vertex,
              VariantSourcePath(GlslTarget::kEs100, variant, Stage::kVertex).generic_string());
    EXPECT_EQ(manifest.variants[0].sources->fragment,
              VariantSourcePath(GlslTarget::kEs100, variant, Stage::kFragment).generic_string());
}

}  // namespace
}  // namespace tidepool::pipeline
