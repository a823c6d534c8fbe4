// The report as a document: sections of paragraphs, tables, charts and image panels, built once
// from the ReportModel (ReportDocumentBuilder) and rendered by an HTML writer and a Markdown
// writer. The writers know only how to render each kind of node; every word of the report lives
// in the builder, so the two formats cannot drift apart.
#pragma once

#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace tidepool::report::doc {

/// A run of inline text: plain, strongly emphasised, or code.
struct Span {
    enum class Kind { kText, kStrong, kCode };
    Kind kind = Kind::kText;
    std::string text;
};

/// Plain text spans, with `quoted` parts (Markdown inline code) as code spans. Never fails; an
/// unclosed backtick makes the rest code.
std::vector<Span> SpansWithCode(std::string_view text);

/// How a paragraph stands out. HTML: <p>, <p class="note">, <p class="warn"> and a bold <p>;
/// Markdown writes every style as a plain paragraph (emphasis lives in the spans).
enum class ParagraphStyle { kBody, kNote, kWarning, kLead };

struct Paragraph {
    ParagraphStyle style = ParagraphStyle::kBody;
    std::vector<Span> spans;
};

/// A third-level heading inside a section; `id` is the HTML anchor ("" for none).
struct Heading {
    std::string text;
    std::string id;
};

/// A table of text cells. Cells are plain text: each writer escapes what its format needs.
struct Table {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    /// An HTML class per row ("" or missing for none): colours rows and lets tools find them.
    std::vector<std::string> row_classes;
    /// When not empty, the table is folded under this title: a <details> block in HTML, a
    /// heading above the table in Markdown.
    std::string folded_under;
};

/// A chart: inline SVG in HTML, an image link to `file` (the same SVG, written beside the page)
/// in Markdown.
struct Figure {
    std::string svg;
    std::string file;  // relative to the report folder, e.g. "charts/accuracy.svg"
    std::string alt;   // the Markdown image text
};

/// One image of a panel: the full-size file beside the page and, for HTML, an embedded copy.
struct PanelImage {
    std::string caption;
    std::string alt;
    std::string file;      // relative to the report folder; HTML links to it
    std::string data_uri;  // HTML shows this; "" shows `file`
};

/// Images side by side under a heading, with the figures that describe them; a panel with a
/// `warning` shows it instead of images.
struct ImagePanel {
    std::string title;
    std::string subtitle;  // after the title, e.g. "view grazing"
    std::string label;     // shown as code, e.g. the configuration id
    std::string summary;   // the figures, e.g. "PSNR 31.2 dB, ..."
    std::string warning;
    std::vector<PanelImage> images;
};

using Block = std::variant<Paragraph, Heading, Table, Figure, ImagePanel>;

/// A numbered top-level section; `id` anchors it and `nav_label` names it in the HTML page's
/// navigation bar.
struct Section {
    std::string title;
    std::string id;
    std::string nav_label;
    std::vector<Block> blocks;
};

/// The whole report: a title, the line saying where it came from, the blocks before the first
/// section, and the sections.
struct Document {
    std::string title;
    Paragraph byline;
    std::vector<Block> lead;
    std::vector<Section> sections;
};

/// The document as one self-contained HTML page (styles inline, no external resource but the
/// images' full-size links). Never fails.
std::string HtmlPage(const Document& document);

/// One section as HTML, as HtmlPage writes it. Never fails.
std::string HtmlSection(const Section& section);

/// The document as Markdown (GitHub flavour: tables, images linked to files). Never fails.
std::string MarkdownPage(const Document& document);

/// One section as Markdown, as MarkdownPage writes it. Never fails.
std::string MarkdownSection(const Section& section);

/// Every figure of the document in order, so its SVG file can be written beside the pages.
std::vector<const Figure*> Figures(const Document& document);

}  // namespace tidepool::report::doc
