// The report document's own helpers (reports/include/tidepool/report/ReportDocument.h): spans
// split at backticks, and the figures a document holds. Its two writers are tested in
// HtmlDocumentWriterTest and MarkdownDocumentWriterTest.
#include "tidepool/report/ReportDocument.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tidepool::report::doc {
namespace {

TEST(ReportDocumentTest, SpansWithCodeSplitsBackticks) {
    const std::vector<Span> spans = SpansWithCode("see `tidepool plan` or `x");
    ASSERT_EQ(spans.size(), 4u);
    EXPECT_EQ(spans[0].kind, Span::Kind::kText);
    EXPECT_EQ(spans[0].text, "see ");
    EXPECT_EQ(spans[1].kind, Span::Kind::kCode);
    EXPECT_EQ(spans[1].text, "tidepool plan");
    EXPECT_EQ(spans[2].text, " or ");
    EXPECT_EQ(spans[3].kind, Span::Kind::kCode);  // unclosed: code to the end
    EXPECT_EQ(spans[3].text, "x");
}

TEST(ReportDocumentTest, FiguresListsEveryFigureOfEverySectionInOrder) {
    Document document;
    document.sections = {Section{"1. A",
                                 "a",
                                 "A",
                                 {Paragraph{ParagraphStyle::kBody, {{Span::Kind::kText, "text"}}},
                                  Figure{"<svg></svg>", "charts/a.svg", "a chart"}}},
                         Section{"2. B", "b", "B", {Table{{"x"}, {{"1"}}, {}, ""}}},
                         Section{"3. C", "c", "C", {Figure{"<svg/>", "charts/c.svg", "c chart"}}}};
    const std::vector<const Figure*> figures = Figures(document);
    ASSERT_EQ(figures.size(), 2u);
    EXPECT_EQ(figures[0]->file, "charts/a.svg");
    EXPECT_EQ(figures[1]->file, "charts/c.svg");
    EXPECT_TRUE(Figures(Document{}).empty());
}

}  // namespace
}  // namespace tidepool::report::doc
