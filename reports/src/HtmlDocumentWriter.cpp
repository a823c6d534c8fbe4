// Renders a report document as one self-contained HTML page: styles and a small image check
// inline, charts as inline SVG, images as the data: URIs the document carries.
#include "tidepool/report/ReportDocument.h"

#include "ReportText.h"

namespace tidepool::report::doc {
namespace {

constexpr const char* kCss = R"css(
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;margin:24px auto;max-width:1400px;padding:0 16px;color:#222;line-height:1.4}
h1{font-size:1.6em}h2{border-bottom:2px solid #ddd;padding-bottom:4px;margin-top:2em}
table{border-collapse:collapse;margin:8px 0 16px;font-size:13px}
th,td{border:1px solid #ccc;padding:4px 6px;vertical-align:top;text-align:left;overflow-wrap:break-word}
table.wide{width:100%}
th{background:#f2f4f4;position:sticky;top:0}
tr.good td:nth-child(7){background:#d5f5e3}tr.fair td:nth-child(7){background:#d6eaf8}
tr.bad td{background:#fadbd8}tr.unknown td:nth-child(7){background:#eaeded}
tr.frontier td{background:#fdf2e9}
.note{color:#555;font-size:13px}.warn{background:#fadbd8;padding:8px;border-left:4px solid #c0392b}
.panel{margin:0 0 18px 0}
.panel img{border:1px solid #999;width:100%;height:auto}
.panel figure{display:inline-block;width:32%;margin:0 1% 0 0;vertical-align:top}.panel figcaption{font-size:12px;color:#555}
code{font-size:12px;background:#f4f6f6;padding:1px 3px}
svg{max-width:100%;height:auto;border:1px solid #eee}
nav a{margin-right:12px}
)css";

// Sets data-images-loaded="loaded/total" on <body> once the page has loaded, so a headless
// browser test can check that every embedded image decoded.
constexpr const char* kImageCheckScript =
        "<script>window.addEventListener('load',function(){var i=document.images,n=0;"
        "for(var k=0;k<i.length;k++){if(i[k].complete&&i[k].naturalWidth>0)n++;}"
        "document.body.setAttribute('data-images-loaded',n+'/'+i.length);});</script>";

std::string SpansToHtml(const std::vector<Span>& spans) {
    std::string out;
    for (const Span& span : spans) {
        switch (span.kind) {
            case Span::Kind::kText:
                out += HtmlEscaped(span.text);
                break;
            case Span::Kind::kStrong:
                out += "<b>" + HtmlEscaped(span.text) + "</b>";
                break;
            case Span::Kind::kCode:
                out += "<code>" + HtmlEscaped(span.text) + "</code>";
                break;
        }
    }
    return out;
}

std::string ToHtml(const Paragraph& paragraph) {
    switch (paragraph.style) {
        case ParagraphStyle::kBody:
            return "<p>" + SpansToHtml(paragraph.spans) + "</p>";
        case ParagraphStyle::kNote:
            return "<p class=\"note\">" + SpansToHtml(paragraph.spans) + "</p>";
        case ParagraphStyle::kWarning:
            return "<p class=\"warn\">" + SpansToHtml(paragraph.spans) + "</p>";
        case ParagraphStyle::kLead:
            return "<p><b>" + SpansToHtml(paragraph.spans) + "</b></p>";
    }
    return "<p>" + SpansToHtml(paragraph.spans) + "</p>";
}

std::string ToHtml(const Heading& heading) {
    const std::string id =
            heading.id.empty() ? std::string() : " id=\"" + HtmlEscaped(heading.id) + "\"";
    return "<h3" + id + ">" + HtmlEscaped(heading.text) + "</h3>";
}

std::string ToHtml(const Table& table) {
    std::string out = "<table class=\"wide\"><thead><tr>";
    for (const std::string& h : table.header) {
        out += "<th>" + HtmlEscaped(h) + "</th>";
    }
    out += "</tr></thead><tbody>";
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        const std::string css = r < table.row_classes.size() ? table.row_classes[r] : "";
        out += css.empty() ? "<tr>" : "<tr class=\"" + HtmlEscaped(css) + "\">";
        for (const std::string& c : table.rows[r]) {
            // Variant ids are long comma-joined define lists: let them wrap after a comma.
            std::string cell = HtmlEscaped(c);
            for (std::size_t at = cell.find(','); at != std::string::npos;
                 at = cell.find(',', at + 6)) {
                cell.insert(at + 1, "<wbr>");
            }
            out += "<td>" + cell + "</td>";
        }
        out += "</tr>";
    }
    out += "</tbody></table>\n";
    if (table.folded_under.empty()) {
        return out;
    }
    return "<details><summary>" + HtmlEscaped(table.folded_under) + "</summary>" + out +
           "</details>";
}

std::string ToHtml(const Figure& figure) {
    return figure.svg;
}

// Heading, label and figures, then each image embedded and linked to its full-size file.
std::string ToHtml(const ImagePanel& panel) {
    std::string out = "<div class=\"panel\"><h3>" + HtmlEscaped(panel.title) + " <small>— " +
                      HtmlEscaped(panel.subtitle) + "</small></h3><code>" +
                      HtmlEscaped(panel.label) + "</code>";
    if (!panel.warning.empty()) {
        return out + "<p class=\"warn\">" + HtmlEscaped(panel.warning) + "</p></div>";
    }
    out += "<p class=\"note\">" + HtmlEscaped(panel.summary) + "</p>";
    for (const PanelImage& image : panel.images) {
        out += "<figure><a href=\"" + HtmlEscaped(image.file) + "\"><img src=\"" +
               (image.data_uri.empty() ? HtmlEscaped(image.file) : image.data_uri) + "\" alt=\"" +
               HtmlEscaped(image.alt) + "\"></a><figcaption>" + HtmlEscaped(image.caption) +
               "</figcaption></figure>";
    }
    return out + "</div>";
}

std::string Blocks(const std::vector<Block>& blocks) {
    std::string out;
    for (const Block& block : blocks) {
        out += std::visit([](const auto& node) { return ToHtml(node); }, block);
    }
    return out;
}

}  // namespace

std::string HtmlSection(const Section& section) {
    const std::string id =
            section.id.empty() ? std::string() : " id=\"" + HtmlEscaped(section.id) + "\"";
    return "<h2" + id + ">" + HtmlEscaped(section.title) + "</h2>" + Blocks(section.blocks);
}

std::string HtmlPage(const Document& document) {
    std::string out =
            "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta name=\"viewport\" content=\"width=device-width,initial-scale=1\">";
    out += "<title>" + HtmlEscaped(document.title) + "</title><style>" + kCss + "</style>" +
           kImageCheckScript + "</head><body>";
    out += "<h1>" + HtmlEscaped(document.title) + "</h1>" + ToHtml(document.byline);
    std::string nav;
    for (const Section& section : document.sections) {
        if (!section.nav_label.empty()) {
            nav += "<a href=\"#" + HtmlEscaped(section.id) + "\">" +
                   HtmlEscaped(section.nav_label) + "</a>";
        }
    }
    if (!nav.empty()) {
        out += "<nav>" + nav + "</nav>";
    }
    out += Blocks(document.lead);
    for (const Section& section : document.sections) {
        out += HtmlSection(section);
    }
    return out + "</body></html>\n";
}

}  // namespace tidepool::report::doc
