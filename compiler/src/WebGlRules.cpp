#include "WebGlRules.h"

#include <cctype>
#include <cstring>

#include "GlslEsRules.h"
#include <fmt/format.h>

namespace tidepool {
namespace {

bool IsIdentifierChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

// GLSL ES 1.00 §3.1 and 3.00 §3.1: letters, digits, `_`, the punctuation below, space, tab,
// vertical tab, form feed, carriage return and line feed. A backslash is in the 3.00 set only
// (line continuation); glslang reports it in a 1.00 shader itself.
bool InSourceCharacterSet(char c) {
    if (IsIdentifierChar(c)) {
        return true;
    }
    return c != '\0' && std::strchr(".+-/*%<>[](){}^|&~=!:;,?# \t\v\f\r\n\\", c) != nullptr;
}

std::string Shown(char c) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x21 && byte < 0x7f) {
        return fmt::format("'{}'", c);
    }
    return fmt::format("byte 0x{:02X}", byte);
}

}  // namespace

int MaxWebGlTokenLength(GlslTarget target) {
    return target == GlslTarget::kWebGl2 ? 1024 : 256;
}

std::vector<Diagnostic> CheckWebGlTokens(std::string_view text, GlslTarget target,
                                         const std::string& file) {
    std::vector<Diagnostic> errors;
    const std::size_t max_length = static_cast<std::size_t>(MaxWebGlTokenLength(target));
    for (const std::vector<SourceToken>& line : SourceTokenLines(text)) {
        for (const SourceToken& token : line) {
            if (token.text.size() > max_length) {
                errors.push_back(MakeError(
                        file, token.line, token.column,
                        fmt::format("a token of {} characters ('{}...'); {} accepts at most {} "
                                    "(WebGL 1.0 §6.20 \"Maximum GLSL Token Size\"{})",
                                    token.text.size(), token.text.substr(0, 16), TargetName(target),
                                    max_length,
                                    target == GlslTarget::kWebGl2 ? "; GLSL ES 3.00 §3.8" : "")));
            } else if (token.identifier && (token.text.rfind("webgl_", 0) == 0 ||
                                            token.text.rfind("_webgl_", 0) == 0)) {
                errors.push_back(MakeError(
                        file, token.line, token.column,
                        fmt::format("'{}': identifiers starting with 'webgl_' or '_webgl_' are "
                                    "reserved for use by WebGL (WebGL 1.0 §6.17 \"GLSL "
                                    "Constructs\"); rename it",
                                    token.text)));
            }
        }
    }
    return errors;
}

std::vector<Diagnostic> CheckWebGlCharacters(std::string_view preprocessed, std::string_view source,
                                             const std::string& file) {
    std::vector<Diagnostic> errors;
    // The user's lines, to find the character's column in what the user wrote.
    std::vector<std::string_view> source_lines;
    for (std::size_t start = 0; start <= source.size();) {
        const std::size_t end = std::min(source.find('\n', start), source.size());
        source_lines.push_back(source.substr(start, end - start));
        start = end + 1;
    }
    int line = 1;
    for (std::size_t i = 0; i < preprocessed.size(); ++i) {
        const char c = preprocessed[i];
        if (c == '\n') {
            ++line;
            continue;
        }
        if (InSourceCharacterSet(c)) {
            continue;
        }
        int column = 0;
        if (line >= 1 && static_cast<std::size_t>(line) <= source_lines.size()) {
            const std::size_t at = source_lines[static_cast<std::size_t>(line) - 1].find(c);
            column = at == std::string_view::npos ? 0 : static_cast<int>(at) + 1;
        }
        errors.push_back(MakeError(
                file, line, column,
                fmt::format("{} is outside the GLSL ES source character set (GLSL ES §3.1); "
                            "WebGL accepts it only in comments and in blocks the preprocessor "
                            "leaves out (WebGL 1.0 §6.21)",
                            Shown(c))));
        // One message per line is enough: the rest of a UTF-8 sequence is the same mistake.
        while (i + 1 < preprocessed.size() && preprocessed[i + 1] != '\n') {
            ++i;
        }
    }
    return errors;
}

}  // namespace tidepool
