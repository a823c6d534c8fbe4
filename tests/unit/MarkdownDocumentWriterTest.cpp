// The report document in Markdown (reports/include/tidepool/report/ReportDocument.h,
// MarkdownSection and MarkdownPage): each node kind, and what a table cell must escape.
#include "tidepool/report/ReportDocument.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tidepool::report::doc {
namespace {

Section MarkdownSection(std::vector<Block> blocks) {
    return Section{"1. Title", "first", "First", std::move(blocks)};
}

TEST(MarkdownDocumentWriterTest, TableRendersAsAPipeTable) {
    const Section section =
            MarkdownSection({Table{{"a", "b"}, {{"1", "2"}, {"3", "4"}}, {"", "bad"}, ""}});
    EXPECT_EQ(MarkdownSection(section),
              "## 1. Title\n\n| a | b |\n|---|---|\n| 1 | 2 |\n| 3 | 4 |\n\n");
}

TEST(MarkdownDocumentWriterTest, TableCellEscapesPipesAndJoinsLines) {
    const Section section = MarkdownSection({Table{{"x|y"}, {{"a|b\nc"}}, {}, ""}});
    EXPECT_EQ(MarkdownSection(section), "## 1. Title\n\n| x\\|y |\n|---|\n| a\\|b c |\n\n");
}

// Markdown text stays as written, unlike HTML's: a repository viewer renders it.
TEST(MarkdownDocumentWriterTest, TextAndHeadingsAreNotEscaped) {
    const Section section =
            MarkdownSection({Heading{"a < b", ""},
                             Paragraph{ParagraphStyle::kBody, {{Span::Kind::kText, "x & \"y\""}}}});
    EXPECT_EQ(MarkdownSection(section), "## 1. Title\n\n### a < b\n\nx & \"y\"\n\n");
}

// Names and messages from the inputs cannot make structure (found by a hostile-input review:
// an id holding a newline and `# H [l](javascript:x)` became a heading with a link).
TEST(MarkdownDocumentWriterTest, TextFromTheInputsCannotMakeStructure) {
    const Paragraph p{ParagraphStyle::kBody,
                      {{Span::Kind::kText, "a\n# H [l](javascript:x) <script>x</script>\r\x1b!"},
                       {Span::Kind::kCode, "c`d\n"}}};
    EXPECT_EQ(MarkdownSection(MarkdownSection({p, Heading{"h\n- item", ""}})),
              "## 1. Title\n\na # H [l]\\(javascript:x) &lt;script>x&lt;/script> \xEF\xBF\xBD!"
              "``c`d ``\n\n### h - item\n\n");
    const Section table = MarkdownSection({Table{{"a\\|b"}, {{"`x`"}}, {}, ""}});
    EXPECT_EQ(MarkdownSection(table), "## 1. Title\n\n| a\\\\\\|b |\n|---|\n| `x` |\n\n");
}

TEST(MarkdownDocumentWriterTest, InlineSpansRenderAsStrongAndCode) {
    const Paragraph p{ParagraphStyle::kNote,
                      {{Span::Kind::kText, "run "},
                       {Span::Kind::kCode, "a<b"},
                       {Span::Kind::kText, ", got "},
                       {Span::Kind::kStrong, "3"}}};
    EXPECT_EQ(MarkdownSection(MarkdownSection({p})), "## 1. Title\n\nrun `a<b`, got **3**\n\n");
}

TEST(MarkdownDocumentWriterTest, FoldedTableIsAHeadingAndItsTable) {
    const Section section = MarkdownSection({Table{{"a"}, {{"1"}}, {}, "All"}});
    EXPECT_EQ(MarkdownSection(section), "## 1. Title\n\n### All\n\n| a |\n|---|\n| 1 |\n\n");
}

TEST(MarkdownDocumentWriterTest, FigureIsALinkToItsFile) {
    const Section section = MarkdownSection({Figure{"<svg></svg>", "charts/a.svg", "a chart"}});
    EXPECT_EQ(MarkdownSection(section), "## 1. Title\n\n![a chart](charts/a.svg)\n\n");
}

TEST(MarkdownDocumentWriterTest, ImagePanelLinksTheFilesInATable) {
    ImagePanel panel{"fog & more", "view top", "water:FOG", "PSNR 30.0 dB", "", {}};
    panel.images = {{"this", "fog this", "images/a.png", "data:image/png;base64,AA"},
                    {"ref|erence", "fog ref", "images/r.png", ""}};
    const std::string md = MarkdownSection(MarkdownSection({panel}));
    EXPECT_NE(md.find("### fog & more — view top\n\n`water:FOG` — PSNR 30.0 dB\n\n"
                      "| this | ref\\|erence |\n|---|---|\n| ![](images/a.png) | ![](images/r.png) "
                      "|\n"),
              std::string::npos)
            << md;
}

TEST(MarkdownDocumentWriterTest, PanelWithWarningShowsItInsteadOfImages) {
    const ImagePanel panel{"t", "view v", "(missing)", "", "MISSING", {{"c", "a", "f.png", ""}}};
    EXPECT_EQ(MarkdownSection(MarkdownSection({panel})),
              "## 1. Title\n\n### t — view v\n\n`(missing)`: **MISSING**\n\n");
}

TEST(MarkdownDocumentWriterTest, PageHasTitleBylineAndLeadInOrder) {
    Document document;
    document.title = "report: a<b";
    document.byline = {ParagraphStyle::kNote, {{Span::Kind::kText, "made today"}}};
    document.lead = {Paragraph{ParagraphStyle::kLead, {{Span::Kind::kText, "in short"}}}};
    document.sections = {MarkdownSection({}), Section{"2. Second", "second", "", {}}};
    EXPECT_EQ(MarkdownPage(document),
              "# report: a&lt;b\n\nmade today\n\nin short\n\n## 1. Title\n\n## 2. Second\n\n");
}

}  // namespace
}  // namespace tidepool::report::doc
