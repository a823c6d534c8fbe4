// Renders a report document as Markdown for repository viewers: one paragraph per line pair,
// GitHub tables, images and charts linked to the files beside report.md.
#include "tidepool/report/ReportDocument.h"

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>

namespace tidepool::report::doc {
namespace {

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD

// Text from the inputs (names, messages) as Markdown text that stays as written where it can
// ("a < b" is left alone) but cannot make structure: a line break would start a block (a
// heading, a list), `<` before a letter, `/`, `!` or `?` would open raw HTML or an autolink,
// and `](` a link or an image; a control character would drive a terminal showing the file.
std::string MarkdownText(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        const char next = i + 1 < text.size() ? text[i + 1] : '\0';
        if (c == '\n' || c == '\r') {
            out += ' ';
        } else if (static_cast<unsigned char>(c) < 0x20 && c != '\t') {
            out += kReplacement;
        } else if (c == '<' && (std::isalpha(static_cast<unsigned char>(next)) != 0 ||
                                next == '/' || next == '!' || next == '?')) {
            out += "&lt;";
        } else if (c == ']' && next == '(') {
            out += "]\\";
        } else {
            out += c;
        }
    }
    return out;
}

// A table cell: MarkdownText, and a pipe would end the cell. A backslash is escaped too, or one
// before a pipe would escape the pipe's own backslash and end the cell after all.
std::string MarkdownCell(std::string_view text) {
    std::string out;
    for (char c : MarkdownText(text)) {
        if (c == '|' || c == '\\') {
            out += '\\';
        }
        out += c;
    }
    return out;
}

// A code span holding `text` as it is: fenced by one backtick more than its longest run of them,
// padded where it starts or ends with one; lines joined, control characters replaced.
std::string CodeSpan(std::string_view text) {
    std::string content;
    std::size_t run = 0;
    std::size_t longest = 0;
    for (const char c : text) {
        run = c == '`' ? run + 1 : 0;
        longest = std::max(longest, run);
        if (c == '\n' || c == '\r') {
            content += ' ';
        } else if (static_cast<unsigned char>(c) < 0x20 && c != '\t') {
            content += kReplacement;
        } else {
            content += c;
        }
    }
    const std::string fence(longest + 1, '`');
    const bool pad = !content.empty() && (content.front() == '`' || content.back() == '`');
    return fence + (pad ? " " : "") + content + (pad ? " " : "") + fence;
}

std::string Row(const std::vector<std::string>& cells) {
    std::string out = "|";
    for (const std::string& c : cells) {
        out.append(" ").append(MarkdownCell(c)).append(" |");
    }
    return out + "\n";
}

std::string Rule(std::size_t columns) {
    std::string out = "|";
    for (std::size_t i = 0; i < columns; ++i) {
        out += "---|";
    }
    return out + "\n";
}

std::string SpansToMarkdown(const std::vector<Span>& spans) {
    std::string out;
    for (const Span& span : spans) {
        switch (span.kind) {
            case Span::Kind::kText:
                out += MarkdownText(span.text);
                break;
            case Span::Kind::kStrong:
                out += "**" + MarkdownText(span.text) + "**";
                break;
            case Span::Kind::kCode:
                out += CodeSpan(span.text);
                break;
        }
    }
    return out;
}

std::string ToMarkdown(const Paragraph& paragraph) {
    return SpansToMarkdown(paragraph.spans) + "\n\n";
}

std::string ToMarkdown(const Heading& heading) {
    return "### " + MarkdownText(heading.text) + "\n\n";
}

std::string ToMarkdown(const Table& table) {
    std::string out = table.folded_under.empty()
                              ? std::string()
                              : "### " + MarkdownText(table.folded_under) + "\n\n";
    out += Row(table.header) + Rule(table.header.size());
    for (const std::vector<std::string>& row : table.rows) {
        out += Row(row);
    }
    return out + "\n";
}

std::string ToMarkdown(const Figure& figure) {
    return "![" + MarkdownText(figure.alt) + "](" + figure.file + ")\n\n";
}

// Heading, the label and its figures on one line, then the images as one table row.
std::string ToMarkdown(const ImagePanel& panel) {
    std::string out = "### " + MarkdownText(panel.title) + " — " + MarkdownText(panel.subtitle) +
                      "\n\n" + CodeSpan(panel.label);
    if (!panel.warning.empty()) {
        return out + ": **" + MarkdownText(panel.warning) + "**\n\n";
    }
    out += " — " + MarkdownText(panel.summary) + "\n\n";
    std::vector<std::string> captions;
    std::string images = "|";
    for (const PanelImage& image : panel.images) {
        captions.push_back(image.caption);
        images += " ![](" + image.file + ") |";
    }
    return out + Row(captions) + Rule(captions.size()) + images + "\n\n";
}

}  // namespace

std::string MarkdownSection(const Section& section) {
    std::string out = "## " + MarkdownText(section.title) + "\n\n";
    for (const Block& block : section.blocks) {
        out += std::visit([](const auto& node) { return ToMarkdown(node); }, block);
    }
    return out;
}

std::string MarkdownPage(const Document& document) {
    std::string out = "# " + MarkdownText(document.title) + "\n\n" + ToMarkdown(document.byline);
    for (const Block& block : document.lead) {
        out += std::visit([](const auto& node) { return ToMarkdown(node); }, block);
    }
    for (const Section& section : document.sections) {
        out += MarkdownSection(section);
    }
    return out;
}

}  // namespace tidepool::report::doc
