// Mesa's info log format: `<string>:<line>(<column>): <severity>: <message>`.
#include "tidepool/runner/MesaInfoLog.h"

#include <regex>

namespace tidepool::runner {
namespace {

Severity SeverityFrom(const std::string& word) {
    return word == "warning" ? Severity::kWarning : Severity::kError;
}

std::string Trim(std::string_view text) {
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos) {
        return "";
    }
    const auto last = text.find_last_not_of(" \t\r\n");
    return std::string(text.substr(first, last - first + 1));
}

}  // namespace

int MapMesaColumn(std::string_view line_text, int mesa_column) {
    int collapsed = 0;
    bool in_blank = false;
    for (std::size_t i = 0; i < line_text.size(); ++i) {
        const bool blank = line_text[i] == ' ' || line_text[i] == '\t';
        if (blank && in_blank) {
            continue;  // the rest of a blank run: Mesa counted the run once
        }
        in_blank = blank;
        ++collapsed;
        if (collapsed == mesa_column) {
            return static_cast<int>(i) + 1;
        }
    }
    return mesa_column;
}

std::vector<Diagnostic> ParseMesaInfoLog(std::string_view log, const std::string& file,
                                         const std::string& variant, std::string_view user_source) {
    // The user's lines, to map columns back (index 0 is line 1).
    std::vector<std::string_view> source_lines;
    for (std::size_t start = 0; !user_source.empty() && start <= user_source.size();) {
        std::size_t end = user_source.find('\n', start);
        if (end == std::string_view::npos) {
            end = user_source.size();
        }
        source_lines.push_back(user_source.substr(start, end - start));
        start = end + 1;
    }
    static const std::regex positioned(R"(^\s*\d+:(\d+)\((\d+)\):\s*(error|warning)\s*:\s*(.*)$)");
    static const std::regex plain(R"(^\s*(error|warning)\s*:\s*(.*)$)");
    std::vector<Diagnostic> diagnostics;
    std::size_t start = 0;
    while (start <= log.size()) {
        std::size_t end = log.find('\n', start);
        if (end == std::string_view::npos) {
            end = log.size();
        }
        const std::string line = Trim(log.substr(start, end - start));
        start = end + 1;
        if (line.empty()) {
            continue;
        }
        std::smatch match;
        Diagnostic diagnostic;
        diagnostic.file = file;
        diagnostic.variant = variant;
        if (std::regex_match(line, match, positioned)) {
            diagnostic.line = std::stoi(match[1]);
            diagnostic.column = std::stoi(match[2]);
            const auto index = static_cast<std::size_t>(diagnostic.line - 1);
            if (diagnostic.line >= 1 && index < source_lines.size()) {
                diagnostic.column = MapMesaColumn(source_lines[index], diagnostic.column);
            }
            diagnostic.severity = SeverityFrom(match[3]);
            diagnostic.message = match[4];
        } else if (std::regex_match(line, match, plain)) {
            diagnostic.severity = SeverityFrom(match[1]);
            diagnostic.message = match[2];
        } else if (!diagnostics.empty()) {
            diagnostics.back().message += " " + line;
            continue;
        } else {
            diagnostic.message = line;
        }
        diagnostics.push_back(std::move(diagnostic));
    }
    return diagnostics;
}

}  // namespace tidepool::runner
