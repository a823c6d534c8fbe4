#include "tidepool/SourceAssembler.h"

#include <fmt/format.h>

namespace tidepool {

const char* StageName(Stage stage) {
    return stage == Stage::kVertex ? "vertex" : "fragment";
}

std::string DefinePreamble(const std::vector<std::string>& defines) {
    std::string preamble;
    for (const std::string& define : defines) {
        // "NAME=VALUE" (plain-file validation's -D) defines NAME as VALUE; a bare name as 1.
        const std::size_t equals = define.find('=');
        if (equals == std::string::npos) {
            preamble += fmt::format("#define {} 1\n", define);
        } else {
            preamble += fmt::format("#define {} {}\n", define.substr(0, equals),
                                    define.substr(equals + 1));
        }
    }
    return preamble;
}

namespace {

// The first line of a file, and where the line after it starts.
struct FirstLine {
    std::string_view text;
    std::size_t next = 0;
};

FirstLine SplitFirstLine(std::string_view source) {
    const std::size_t end = source.find('\n');
    if (end == std::string_view::npos) {
        return {source, source.size()};
    }
    return {source.substr(0, end), end + 1};
}

std::string_view Trim(std::string_view text) {
    const std::size_t begin = text.find_first_not_of(" \t\r");
    if (begin == std::string_view::npos) {
        return {};
    }
    const std::size_t end = text.find_last_not_of(" \t\r");
    return text.substr(begin, end - begin + 1);
}

// GLSL ES 3.00 dropped the 1.00 storage keywords and texture functions; these macros let the
// project's 1.00 shaders compile unchanged as 3.00 (gl_FragColor becomes a declared output).
std::string Es300Compatibility(Stage stage) {
    if (stage == Stage::kVertex) {
        return "#define attribute in\n#define varying out\n#define texture2D texture\n"
               "#define textureCube texture\n";
    }
    return "#define varying in\n#define texture2D texture\n#define textureCube texture\n"
           "out highp vec4 tp_FragColor;\n#define gl_FragColor tp_FragColor\n";
}

}  // namespace

std::string FindVersionLine(std::string_view user_source) {
    const FirstLine first = SplitFirstLine(user_source);
    const std::string_view line = Trim(first.text);
    return line.rfind("#version", 0) == 0 ? std::string(line) : std::string();
}

std::string AssembleDriverSource(std::string_view user_source,
                                 const std::vector<std::string>& defines, Stage stage,
                                 GlslTarget target) {
    std::string out = VersionDirective(target) + "\n";
    if (TargetVersion(target) == 300) {
        out += Es300Compatibility(stage);
    }
    out += DefinePreamble(defines);
    // GLSL ES gives `#line N` C semantics (the next line is N), in glslang and in Mesa alike.
    if (!FindVersionLine(user_source).empty()) {
        out += "#line 2\n";
        out += user_source.substr(SplitFirstLine(user_source).next);
    } else {
        out += "#line 1\n";
        out += user_source;
    }
    return out;
}

}  // namespace tidepool
