#include "tidepool/report/ReportDocument.h"

namespace tidepool::report::doc {

std::vector<Span> SpansWithCode(std::string_view text) {
    std::vector<Span> spans;
    bool code = false;
    while (!text.empty()) {
        const std::size_t tick = text.find('`');
        const std::string_view run = text.substr(0, tick);
        if (!run.empty()) {
            spans.push_back({code ? Span::Kind::kCode : Span::Kind::kText, std::string(run)});
        }
        if (tick == std::string_view::npos) {
            break;
        }
        code = !code;
        text.remove_prefix(tick + 1);
    }
    return spans;
}

std::vector<const Figure*> Figures(const Document& document) {
    std::vector<const Figure*> figures;
    auto collect = [&figures](const std::vector<Block>& blocks) {
        for (const Block& block : blocks) {
            if (const auto* figure = std::get_if<Figure>(&block)) {
                figures.push_back(figure);
            }
        }
    };
    collect(document.lead);
    for (const Section& section : document.sections) {
        collect(section.blocks);
    }
    return figures;
}

}  // namespace tidepool::report::doc
