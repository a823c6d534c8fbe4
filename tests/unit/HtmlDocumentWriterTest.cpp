// The report document in HTML (reports/include/tidepool/report/ReportDocument.h, HtmlSection and
// HtmlPage): each node kind, and the markup it must escape.
#include "tidepool/report/ReportDocument.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tidepool::report::doc {
namespace {

Section SectionOf(std::vector<Block> blocks) {
    return Section{"1. Title", "first", "First", std::move(blocks)};
}

TEST(HtmlDocumentWriterTest, TableRendersWithItsRowClasses) {
    const Section section =
            SectionOf({Table{{"a", "b"}, {{"1", "2"}, {"3", "4"}}, {"", "bad"}, ""}});
    EXPECT_EQ(HtmlSection(section),
              "<h2 id=\"first\">1. Title</h2><table class=\"wide\"><thead><tr><th>a</th><th>b</th>"
              "</tr></thead><tbody><tr><td>1</td><td>2</td></tr><tr class=\"bad\"><td>3</td>"
              "<td>4</td></tr></tbody></table>\n");
}

TEST(HtmlDocumentWriterTest, EscapesMarkupInCellsTextAndHeadings) {
    const Section section =
            SectionOf({Heading{"a < b", ""},
                       Paragraph{ParagraphStyle::kBody, {{Span::Kind::kText, "x & \"y\""}}},
                       Table{{"<th>"}, {{"a&b"}}, {}, ""}});
    const std::string html = HtmlSection(section);
    EXPECT_NE(html.find("<h3>a &lt; b</h3>"), std::string::npos) << html;
    EXPECT_NE(html.find("<p>x &amp; &quot;y&quot;</p>"), std::string::npos) << html;
    EXPECT_NE(html.find("<th>&lt;th&gt;</th>"), std::string::npos) << html;
    EXPECT_NE(html.find("<td>a&amp;b</td>"), std::string::npos) << html;
}

TEST(HtmlDocumentWriterTest, LetsCommaJoinedCellsWrap) {
    const std::string html = HtmlSection(SectionOf({Table{{"id"}, {{"water:A,B,C"}}, {}, ""}}));
    EXPECT_NE(html.find("<td>water:A,<wbr>B,<wbr>C</td>"), std::string::npos) << html;
}

TEST(HtmlDocumentWriterTest, InlineSpansRenderAsBoldAndCode) {
    const Paragraph p{ParagraphStyle::kNote,
                      {{Span::Kind::kText, "run "},
                       {Span::Kind::kCode, "a<b"},
                       {Span::Kind::kText, ", got "},
                       {Span::Kind::kStrong, "3"}}};
    EXPECT_EQ(HtmlSection(SectionOf({p})),
              "<h2 id=\"first\">1. Title</h2><p class=\"note\">run <code>a&lt;b</code>, got "
              "<b>3</b></p>");
}

TEST(HtmlDocumentWriterTest, FoldedTableIsDetails) {
    const Section section = SectionOf({Table{{"a"}, {{"1"}}, {}, "All"}});
    EXPECT_NE(HtmlSection(section).find("<details><summary>All</summary><table"),
              std::string::npos);
}

TEST(HtmlDocumentWriterTest, FigureIsInlineSvg) {
    const Section section = SectionOf({Figure{"<svg></svg>", "charts/a.svg", "a chart"}});
    EXPECT_EQ(HtmlSection(section), "<h2 id=\"first\">1. Title</h2><svg></svg>");
}

TEST(HtmlDocumentWriterTest, ImagePanelEmbedsTheImagesAndLinksTheFiles) {
    ImagePanel panel{"fog & more", "view top", "water:FOG", "PSNR 30.0 dB", "", {}};
    panel.images = {{"this", "fog this", "images/a.png", "data:image/png;base64,AA"},
                    {"ref|erence", "fog ref", "images/r.png", ""}};
    const std::string html = HtmlSection(SectionOf({panel}));
    EXPECT_NE(html.find("<h3>fog &amp; more <small>— view top</small></h3><code>water:FOG</code>"),
              std::string::npos)
            << html;
    EXPECT_NE(html.find("<a href=\"images/a.png\"><img src=\"data:image/png;base64,AA\" "
                        "alt=\"fog this\"></a><figcaption>this</figcaption>"),
              std::string::npos)
            << html;
    // Without an embedded copy the page shows the file.
    EXPECT_NE(html.find("<img src=\"images/r.png\""), std::string::npos) << html;
}

TEST(HtmlDocumentWriterTest, PanelWithWarningShowsItInsteadOfImages) {
    const ImagePanel panel{"t", "view v", "(missing)", "", "MISSING", {{"c", "a", "f.png", ""}}};
    const std::string html = HtmlSection(SectionOf({panel}));
    EXPECT_NE(html.find("<p class=\"warn\">MISSING</p></div>"), std::string::npos) << html;
    EXPECT_EQ(html.find("<img"), std::string::npos) << html;
}

TEST(HtmlDocumentWriterTest, PageHasTitleBylineNavigationAndLeadInOrder) {
    Document document;
    document.title = "report: a<b";
    document.byline = {ParagraphStyle::kNote, {{Span::Kind::kText, "made today"}}};
    document.lead = {Paragraph{ParagraphStyle::kLead, {{Span::Kind::kText, "in short"}}}};
    document.sections = {SectionOf({}), Section{"2. Second", "second", "", {}}};
    const std::string html = HtmlPage(document);
    EXPECT_NE(html.find("<title>report: a&lt;b</title>"), std::string::npos);
    EXPECT_NE(html.find("<h1>report: a&lt;b</h1><p class=\"note\">made today</p>"
                        "<nav><a href=\"#first\">First</a></nav><p><b>in short</b></p>"
                        "<h2 id=\"first\">1. Title</h2><h2 id=\"second\">2. Second</h2>"
                        "</body></html>\n"),
              std::string::npos)
            << html;
}

}  // namespace
}  // namespace tidepool::report::doc
