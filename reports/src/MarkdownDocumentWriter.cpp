// Renders a report document as Markdown for repository viewers: one paragraph per line pair,
// GitHub tables, images and charts linked to the files beside report.md.
#include "tidepool/report/ReportDocument.h"

#include <string_view>

namespace tidepool::report::doc {
namespace {

// A table cell: pipes would end the cell, newlines the row.
std::string MarkdownCell(std::string_view text) {
    std::string out;
    for (char c : text) {
        if (c == '|') {
            out += "\\|";
        } else if (c == '\n') {
            out += ' ';
        } else {
            out += c;
        }
    }
    return out;
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
                out += span.text;
                break;
            case Span::Kind::kStrong:
                out += "**" + span.text + "**";
                break;
            case Span::Kind::kCode:
                out += "`" + span.text + "`";
                break;
        }
    }
    return out;
}

std::string ToMarkdown(const Paragraph& paragraph) {
    return SpansToMarkdown(paragraph.spans) + "\n\n";
}

std::string ToMarkdown(const Heading& heading) {
    return "### " + heading.text + "\n\n";
}

std::string ToMarkdown(const Table& table) {
    std::string out =
            table.folded_under.empty() ? std::string() : "### " + table.folded_under + "\n\n";
    out += Row(table.header) + Rule(table.header.size());
    for (const std::vector<std::string>& row : table.rows) {
        out += Row(row);
    }
    return out + "\n";
}

std::string ToMarkdown(const Figure& figure) {
    return "![" + figure.alt + "](" + figure.file + ")\n\n";
}

// Heading, the label and its figures on one line, then the images as one table row.
std::string ToMarkdown(const ImagePanel& panel) {
    std::string out = "### " + panel.title + " — " + panel.subtitle + "\n\n`" + panel.label + "`";
    if (!panel.warning.empty()) {
        return out + ": **" + panel.warning + "**\n\n";
    }
    out += " — " + panel.summary + "\n\n";
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
    std::string out = "## " + section.title + "\n\n";
    for (const Block& block : section.blocks) {
        out += std::visit([](const auto& node) { return ToMarkdown(node); }, block);
    }
    return out;
}

std::string MarkdownPage(const Document& document) {
    std::string out = "# " + document.title + "\n\n" + ToMarkdown(document.byline);
    for (const Block& block : document.lead) {
        out += std::visit([](const auto& node) { return ToMarkdown(node); }, block);
    }
    for (const Section& section : document.sections) {
        out += MarkdownSection(section);
    }
    return out;
}

}  // namespace tidepool::report::doc
