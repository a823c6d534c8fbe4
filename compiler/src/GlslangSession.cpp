#include "GlslangSession.h"

#include <algorithm>
#include <cctype>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "BuiltInResources.h"
#include "ConformanceRules.h"
#include "GlslEsRules.h"
#include "KeywordRenaming.h"
#include "WebGlRules.h"
#include <fmt/format.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <glslang/Include/PoolAlloc.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/build_info.h>
#pragma GCC diagnostic pop

namespace tidepool {

std::string WithoutLineComments(std::string_view text) {
    // A `\` line continuation (in GLSL ES 3.00 it carries a line comment on to the next line).
    if (text.find("\\\n") != std::string_view::npos ||
        text.find("\\\r") != std::string_view::npos) {
        return std::string(text);
    }
    std::string out;
    out.reserve(text.size());
    std::size_t i = 0;
    while (i < text.size()) {
        const std::size_t slash = text.find('/', i);
        if (slash == std::string_view::npos || slash + 1 >= text.size()) {
            break;
        }
        if (text[slash + 1] == '*') {
            // A block comment stays as written: it may span lines, and inside a directive a
            // newline would end the directive where the comment does not.
            const std::size_t end = text.find("*/", slash + 2);
            const std::size_t stop = end == std::string_view::npos ? text.size() : end + 2;
            out.append(text.substr(i, stop - i));
            i = stop;
        } else if (text[slash + 1] == '/') {
            // After a `"` on the same line, the `//` may be inside a string (glslang's #include
            // and #line extensions take strings): the line stays as written.
            const std::size_t line = text.rfind('\n', slash);
            const std::size_t line_start = line == std::string_view::npos ? 0 : line + 1;
            const bool after_quote =
                    text.substr(line_start, slash - line_start).find('"') != std::string_view::npos;
            if (after_quote) {
                std::size_t end = text.find('\n', slash);
                end = end == std::string_view::npos ? text.size() : end;
                out.append(text.substr(i, end - i));
                i = end;
                continue;
            }
            out.append(text.substr(i, slash - i));
            std::size_t end = text.find('\n', slash);
            end = end == std::string_view::npos ? text.size() : end;
            if (end > slash && text[end - 1] == '\r') {
                --end;  // the line's own ending stays
            }
            i = end;
        } else {
            out.append(text.substr(i, slash + 1 - i));
            i = slash + 1;
        }
    }
    out.append(text.substr(std::min(i, text.size())));
    return out;
}

bool IsQuietWhenSkipped(std::string_view line) {
    constexpr std::size_t kLongestName = 255;
    constexpr std::size_t kMostDigits = 9;          // before the dot, and after it
    constexpr std::size_t kMostExponentDigits = 2;  // 1e99 is no message even as a float
    constexpr std::string_view kPunctuation = "+-*/%<>=!&|^~?:;,.(){}[]";
    auto digit = [](char c) { return c >= '0' && c <= '9'; };
    auto name_part = [&](char c) {
        return digit(c) || c == '_' || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
    };
    std::size_t i = 0;
    auto digits = [&] {
        const std::size_t start = i;
        while (i < line.size() && digit(line[i])) {
            ++i;
        }
        return i - start;
    };
    while (i < line.size()) {
        const char c = line[i];
        const char next = i + 1 < line.size() ? line[i + 1] : '\0';
        if (name_part(c) && !digit(c)) {
            const std::size_t start = i;
            while (i < line.size() && name_part(line[i])) {
                ++i;
            }
            if (i - start > kLongestName) {
                return false;
            }
        } else if (digit(c) || (c == '.' && digit(next))) {
            if (c == '0' && digit(next)) {
                return false;  // octal: glslang checks its digits
            }
            if (digits() > kMostDigits) {
                return false;
            }
            if (i < line.size() && line[i] == '.') {
                ++i;
                if (digits() > kMostDigits) {
                    return false;
                }
            }
            if (i < line.size() && (line[i] == 'e' || line[i] == 'E')) {
                ++i;
                if (i < line.size() && (line[i] == '+' || line[i] == '-')) {
                    ++i;
                }
                const std::size_t exponent = digits();
                if (exponent == 0 || exponent > kMostExponentDigits) {
                    return false;
                }
            }
            if (i < line.size() && (name_part(line[i]) || line[i] == '.')) {
                return false;  // a suffix, a hexadecimal `x`, or a number run on
            }
        } else if (c == ' ' || c == '\t' || (c == '\r' && i + 1 == line.size()) ||
                   (kPunctuation.find(c) != std::string_view::npos &&
                    !(c == '/' && (next == '*' || next == '/')) && !(c == '*' && next == '/'))) {
            ++i;  // white space, or punctuation that starts no comment
        } else {
            return false;
        }
    }
    return true;
}

std::vector<bool> QuietWhenSkippedLines(std::string_view text) {
    std::vector<bool> quiet;
    std::size_t start = 0;
    for (;;) {
        const std::size_t end = text.find('\n', start);
        quiet.push_back(IsQuietWhenSkipped(text.substr(start, end - start)));
        if (end == std::string_view::npos) {
            return quiet;
        }
        start = end + 1;
    }
}

std::string WithSkippedLinesBlanked(std::string_view text, const std::vector<LineSpan>& skipped,
                                    const std::vector<bool>& quiet) {
    std::string out;
    out.reserve(text.size());
    auto span = skipped.begin();
    std::size_t index = 0;  // of the line, 0-based
    std::size_t start = 0;
    for (;;) {
        std::size_t end = text.find('\n', start);
        end = end == std::string_view::npos ? text.size() : end;
        const auto number = static_cast<int>(index + 1);
        while (span != skipped.end() && span->last < number) {
            ++span;
        }
        const bool blank = span != skipped.end() && span->first <= number && index < quiet.size() &&
                           quiet[index];
        if (!blank) {
            out.append(text.substr(start, end - start));
        }
        if (end == text.size()) {
            return out;
        }
        out.push_back('\n');
        start = end + 1;
        ++index;
    }
}

StageParse::StageParse() = default;
StageParse::StageParse(StageParse&&) noexcept = default;
StageParse& StageParse::operator=(StageParse&&) noexcept = default;
StageParse::~StageParse() = default;

void EnsureGlslangInitialized() {
    // glslang's process-wide tables are built once and never torn down: worker threads may still
    // use them when main returns, and FinalizeProcess would race with them.
    static std::once_flag once;
    std::call_once(once, [] { glslang::InitializeProcess(); });
}

namespace {

EShLanguage Language(Stage stage) {
    return stage == Stage::kVertex ? EShLangVertex : EShLangFragment;
}

bool IsTarget(const GlslangStageInput& input, GlslTarget target) {
    return input.target.has_value() && *input.target == target;
}

// True for a GLSL ES 1.00 stage a browser compiles, under WebGL 1 or WebGL 2: WebGL 2 runs 1.00
// shaders too (WebGL 2.0 §4.3 "Supported GLSL Constructs"), and WebGL 1's rules for them hold
// there as well (Appendix A's loops and indexing, packing, global initializers), as ANGLE
// applies them to every 1.00 shader of a WebGL context.
bool IsWebGlEs100(const GlslangStageInput& input, int version) {
    return input.target.has_value() && IsWebGlTarget(*input.target) && version == 100;
}

struct TextScan;

// What glslang is given for one stage: the text (with the version line possibly rewritten in
// place, which keeps the line count), the preamble and the default version.
struct PreparedStage {
    std::shared_ptr<const TextScan> scan;  // of the input's text (ScanOf): looked up once
    std::string text;
    std::string preamble;
    // The preamble and the declarations only a parse gets: the preprocessed text, which checks
    // read line by line against the user's, stays free of them.
    std::string parse_preamble;
    int default_version = 100;
    bool force_version = false;
    std::vector<Diagnostic> diagnostics;  // a desktop #version, found before glslang runs
    KeywordRenaming renaming;             // applied to `text` and `preamble`
};

std::string Es300Preamble(Stage stage) {
    if (stage == Stage::kVertex) {
        return "#define attribute in\n#define varying out\n#define texture2D texture\n"
               "#define textureCube texture\n";
    }
    return "#define varying in\n#define texture2D texture\n#define textureCube texture\n"
           "out highp vec4 tp_FragColor;\n#define gl_FragColor tp_FragColor\n";
}

// What the text scans around glslang find in one text. They depend on the text alone, and a
// validation gives glslang the same few files hundreds of times (each preprocessing group, both
// stages of each link); scanning them every time was a quarter of a cold validation of the
// default matrix.
struct TextScan {
    std::string without_line_comments;
    RenamingScan renaming;
    bool may_have_late_extension = false;
    std::vector<UnaryPlus> unary_pluses;
    // Whether a GLSL ES 3.00 reserved word may be used (MayUseEs300ReservedWord): worked out the
    // first time a 3.00 stage asks, since a 1.00 stage never does and the scan is a whole
    // tokenisation (5 ms of a cold validation of the default matrix, all 1.00, when made for
    // every text).
    mutable std::once_flag reserved_word_once;
    mutable bool may_use_es300_reserved_word = false;
    // QuietWhenSkippedLines of without_line_comments: worked out the first time a stage of the
    // text has lines glslang skips.
    mutable std::once_flag quiet_once;
    mutable std::vector<bool> quiet_when_skipped;
};

// The scan of `text`, from the texts this process scanned last (a worker keeps its own after
// fork). Thread-safe.
std::shared_ptr<const TextScan> ScanOf(const std::string& text) {
    // Enough for every file of a configuration; a plain-file run over a corpus sees each text
    // once, so a full memo is dropped rather than grown.
    constexpr std::size_t kTexts = 64;
    // Never destroyed, like glslang's tables: a thread may still parse while main returns.
    static auto* const mutex = new std::mutex;
    static auto* const scans = new std::unordered_map<std::string, std::shared_ptr<const TextScan>>;
    {
        const std::lock_guard<std::mutex> lock(*mutex);
        if (const auto it = scans->find(text); it != scans->end()) {
            return it->second;
        }
    }
    auto scan = std::make_shared<TextScan>();
    scan->without_line_comments = WithoutLineComments(text);
    scan->renaming = ScanForRenaming(text);
    scan->may_have_late_extension = MayHaveLateExtension(text);
    scan->unary_pluses = FindUnaryPluses(text);
    const std::lock_guard<std::mutex> lock(*mutex);
    if (scans->size() >= kTexts) {
        scans->clear();
    }
    scans->emplace(text, scan);
    return scan;
}

// A `#version` directive after comments and white space, with its 1-based line; "" when the text
// has none there. GLSL ES lets comments come first (1.00 and 3.00 §3.4); glslang 12 refuses
// that for an ES version itself, but takes a desktop one after a comment as desktop GLSL.
std::pair<std::string, int> VersionAfterComments(std::string_view text) {
    std::size_t i = 0;
    while (i < text.size()) {
        if (text.find_first_of(" \t\r\n\f\v", i) == i) {
            ++i;
        } else if (text.compare(i, 2, "//") == 0) {
            i = text.find('\n', i);
        } else if (text.compare(i, 2, "/*") == 0) {
            const std::size_t close = text.find("*/", i + 2);
            i = close == std::string_view::npos ? close : close + 2;
        } else {
            break;
        }
    }
    if (i >= text.size() || text.compare(i, 9, "#version ") != 0) {
        return {"", 0};
    }
    const std::size_t end = std::min(text.find('\n', i), text.size());
    std::string line(text.substr(i, end - i));
    line.erase(line.find_last_not_of(" \t\r") + 1);
    return {line, 1 + static_cast<int>(
                              std::count(text.begin(), text.begin() + static_cast<long>(i), '\n'))};
}

PreparedStage Prepare(const GlslangStageInput& input) {
    PreparedStage prepared;
    prepared.scan = ScanOf(input.text);
    prepared.text = prepared.scan->without_line_comments;
    // The version and whether it is GLSL ES, from a `#version` line.
    auto read_version = [](const std::string& line) {
        std::istringstream words(line.substr(std::string("#version").size()));
        int number = 100;
        std::string profile;
        words >> number >> profile;
        return std::make_pair(number, number == 100 || profile == "es");
    };
    std::string version_line = FindVersionLine(input.text);
    int version_line_number = 1;
    if (version_line.empty()) {
        // Only a desktop version counts from there: glslang refuses an ES one after comments.
        const auto [later, line] = VersionAfterComments(input.text);
        if (!later.empty() && !read_version(later).second) {
            version_line = later;
            version_line_number = line;
        }
    }
    int version = 100;
    bool es = true;
    if (!version_line.empty()) {
        std::tie(version, es) = read_version(version_line);
        if (!es) {
            prepared.diagnostics.push_back(
                    MakeError(input.file, version_line_number, 1,
                              fmt::format("'{}' is desktop GLSL; tidepool validates GLSL ES: use "
                                          "'#version 100' or '#version 300 es'",
                                          version_line)));
        }
    }
    if (IsTarget(input, GlslTarget::kWebGl1) && es && version != 100) {
        prepared.diagnostics.push_back(MakeError(
                input.file, 1, 1,
                fmt::format("'{}': WebGL 1 runs GLSL ES 1.00 shaders only (WebGL 1.0 §4.3 "
                            "\"Supported GLSL Constructs\"); use '#version 100', or the webgl2 "
                            "target for a GLSL ES 3.00 shader",
                            version_line)));
    }
    if (input.target && TargetVersion(*input.target) == 300 && version == 100 &&
        !input.keep_version) {
        // Compile the 1.00 file as 3.00 without moving a line: rewrite its first line in place.
        if (!version_line.empty()) {
            const std::size_t end = prepared.text.find('\n');
            prepared.text.replace(0, end, "#version 300 es");
        } else {
            prepared.force_version = true;
        }
        prepared.default_version = 300;
        prepared.preamble = Es300Preamble(input.stage);
    } else {
        prepared.default_version = version;
    }
    if (IsWebGlEs100(input, prepared.default_version) &&
        prepared.text.find('\\') != std::string::npos) {
        prepared.text = JoinContinuedLines(prepared.text);
    }
    prepared.preamble += DefinePreamble(input.defines);
    // GLSL ES 1.00 §3.7: words glslang 12 wrongly refuses in 1.00 are given to it renamed.
    // GLSL ES 1.00 and 3.00 §4.1.8: a member may be named `length`; glslang 12 refuses its use.
    prepared.renaming =
            PlanRenaming({ScanOf(prepared.text)->renaming, ScanForRenaming(prepared.preamble)},
                         /*es100=*/prepared.default_version == 100);
    prepared.text = prepared.renaming.Apply(prepared.text);
    prepared.preamble = prepared.renaming.Apply(prepared.preamble);
    prepared.parse_preamble = prepared.preamble;
    if (IsTarget(input, GlslTarget::kWebGl2) && prepared.default_version == 300) {
        // WebGL 2 supports only the std140 layout for uniform blocks (WebGL 2.0 "Only std140
        // layout supported in uniform blocks"), so a block without a layout qualifier is std140
        // there, not GLSL ES 3.00's default of shared (as ANGLE lays it out for WebGL).
        prepared.parse_preamble += "layout(std140) uniform;\n";
    }
    return prepared;
}

enum class ShaderUse { kPreprocess, kParse };

std::unique_ptr<glslang::TShader> MakeShader(const GlslangStageInput& input,
                                             const PreparedStage& prepared, const char* const* text,
                                             ShaderUse use) {
    auto shader = std::make_unique<glslang::TShader>(Language(input.stage));
    shader->setStrings(text, 1);
    shader->setPreamble(use == ShaderUse::kParse ? prepared.parse_preamble.c_str()
                                                 : prepared.preamble.c_str());
    return shader;
}

constexpr auto kMessages = static_cast<EShMessages>(EShMsgDefault);

// Gives the thread's glslang pool allocator back to what it was when this was made: every
// glslang shader takes it over for its own pool, and a parsed tree must be used with the pool
// it lives in, not with one freed by a shader made and destroyed after it.
class KeepThreadPool {
public:
    KeepThreadPool() : saved_(glslang::GetThreadPoolAllocator()) {}
    ~KeepThreadPool() { glslang::SetThreadPoolAllocator(&saved_); }
    KeepThreadPool(const KeepThreadPool&) = delete;
    KeepThreadPool& operator=(const KeepThreadPool&) = delete;

private:
    glslang::TPoolAllocator& saved_;
};

TBuiltInResource ResourcesOf(const GlslangStageInput& input, int version) {
    return ResourcesFor(version, input.limits, IsWebGlEs100(input, version));
}

}  // namespace

std::string GlslangIdentity() {
    // The ES 1.00 adjustments of ResourcesFor are code, covered by the compiler's source digest.
    return fmt::format("glslang {}.{}.{}{}\n{}", GLSLANG_VERSION_MAJOR, GLSLANG_VERSION_MINOR,
                       GLSLANG_VERSION_PATCH, GLSLANG_VERSION_FLAVOR,
                       GetDefaultTBuiltInResourceString());
}

void WarmUpGlslang(const std::vector<GlslTarget>& targets) {
    static const std::string vertex_source =
            "#version 100\nvoid main() { gl_Position = vec4(0.0); }\n";
    static const std::string fragment_source =
            "#version 100\nprecision mediump float;\nvoid main() { gl_FragColor = vec4(0.0); }\n";
    static const std::vector<std::string> no_defines;
    for (GlslTarget target : targets) {
        static_cast<void>(
                ParseStage({"warm-up", vertex_source, Stage::kVertex, target, no_defines}));
        static_cast<void>(
                ParseStage({"warm-up", fragment_source, Stage::kFragment, target, no_defines}));
    }
}

PreprocessResult PreprocessStage(const GlslangStageInput& input) {
    EnsureGlslangInitialized();
    const PreparedStage prepared = Prepare(input);
    const char* text = prepared.text.c_str();
    auto shader = MakeShader(input, prepared, &text, ShaderUse::kPreprocess);
    PreprocessResult result;
    glslang::TShader::ForbidIncluder includer;
    const TBuiltInResource resources = ResourcesOf(input, prepared.default_version);
    result.ok =
            shader->preprocess(&resources, prepared.default_version, EEsProfile,
                               prepared.force_version, false, kMessages, &result.text, includer);
    return result;
}

StageParse ParseStage(const GlslangStageInput& input) {
    EnsureGlslangInitialized();
    StageParse result;
    const PreparedStage prepared = Prepare(input);
    if (HasErrors(prepared.diagnostics)) {
        result.diagnostics = prepared.diagnostics;
        return result;
    }
    const char* text = prepared.text.c_str();
    const int version = prepared.default_version;
    const TBuiltInResource resources = ResourcesOf(input, version);
    const bool webgl = input.target.has_value() && IsWebGlTarget(*input.target);
    std::vector<Diagnostic> webgl_errors;
    if (webgl) {
        webgl_errors = CheckWebGlTokens(input.text, *input.target, input.file);
        // A character glslang's preprocessor refuses still leaves the text up to it.
        const PreprocessResult preprocessed = PreprocessStage(input);
        {
            const std::vector<Diagnostic> characters =
                    CheckWebGlCharacters(preprocessed.text, input.text, input.file);
            webgl_errors.insert(webgl_errors.end(), characters.begin(), characters.end());
            if (IsTarget(input, GlslTarget::kWebGl2)) {
                const std::vector<Diagnostic> layouts =
                        CheckWebGl2BlockLayouts(preprocessed.text, input.text, input.file);
                webgl_errors.insert(webgl_errors.end(), layouts.begin(), layouts.end());
            }
        }
    }
    // Before the parse: a glslang shader sets the thread's pool allocator to its own, so one
    // destroyed after the parse would leave the parsed tree's thread pointing at freed memory.
    std::vector<Diagnostic> late_extensions;
    // WebGL 1.0 §6.35: in a WebGL shader of GLSL ES 1.00, #extension may follow other tokens.
    if (!IsWebGlEs100(input, version) && prepared.scan->may_have_late_extension) {
        // Only the user's defines go with the text: Es300Preamble declares an output, which
        // would count as a token before the user's own #extension lines.
        const std::string defines = DefinePreamble(input.defines);
        auto shader = std::make_unique<glslang::TShader>(Language(input.stage));
        shader->setStrings(&text, 1);
        shader->setPreamble(defines.c_str());
        std::string preprocessed;
        glslang::TShader::ForbidIncluder includer;
        if (shader->preprocess(&resources, version, EEsProfile, prepared.force_version, false,
                               kMessages, &preprocessed, includer)) {
            late_extensions = CheckExtensionPlacement(preprocessed, input.file);
        }
    }
    // What glslang parses: lines its preprocessor skips are empty where that changes nothing.
    // The lines are judged before the renaming, which only swaps names for names a few
    // characters longer: well inside what IsQuietWhenSkipped leaves to glslang's 1024.
    std::string blanked;
    const char* parse_chars = text;
    if (input.skipped_lines != nullptr && !input.skipped_lines->empty()) {
        const std::shared_ptr<const TextScan>& scan = prepared.scan;
        std::call_once(scan->quiet_once, [&] {
            scan->quiet_when_skipped = QuietWhenSkippedLines(scan->without_line_comments);
        });
        blanked = WithSkippedLinesBlanked(prepared.text, *input.skipped_lines,
                                          scan->quiet_when_skipped);
        parse_chars = blanked.c_str();
    }
    auto parse = [&](EShMessages messages) {
        auto shader = MakeShader(input, prepared, &parse_chars, ShaderUse::kParse);
        const bool ok = shader->parse(&resources, version, EEsProfile, prepared.force_version,
                                      false, messages);
        return std::make_pair(ok, std::move(shader));
    };
    const KeywordRenaming& renaming = prepared.renaming;
    result.renaming = renaming;
    result.text = prepared.text;
    std::tie(result.ok, result.shader) = parse(kMessages);
    result.diagnostics =
            ParseGlslangLog(renaming.Restore(result.shader->getInfoLog()), input.file, input.text);
    std::set<int> switch_lines;
    if (!result.ok && version >= 300 && MentionsEmptyLastCase(result.diagnostics)) {
        const KeepThreadPool keep;
        const PreprocessResult preprocessed = PreprocessStage(input);
        if (preprocessed.ok) {
            switch_lines = SwitchesWithStatementAfterLastLabel(preprocessed.text);
        }
    }
    if (!result.ok &&
        FailedOnlyForRelaxableReasons(result.diagnostics, version, webgl, switch_lines)) {
        // glslang's relaxed mode turns exactly these errors into warnings (and others too, which
        // RestoreDemotedErrors turns back), so the second parse is the specification's verdict.
        auto [ok, shader] = parse(static_cast<EShMessages>(kMessages | EShMsgRelaxedErrors));
        // Any other error relaxed mode demoted is an error again; the relaxed log, unlike the
        // first one, goes past the relaxable error to the real one.
        result.diagnostics = RestoreDemotedErrors(
                ParseGlslangLog(renaming.Restore(shader->getInfoLog()), input.file, input.text),
                switch_lines, webgl && version == 100);
        if (ok && !HasErrors(result.diagnostics)) {
            result.ok = true;
            result.shader = std::move(shader);
        }
    }
    if (!result.ok && version == 100 && FailedOnlyForConstantExpressions(result.diagnostics)) {
        // GLSL ES 1.00 §5.10: matrixCompMult and the sequence operator of constant expressions
        // are constant expressions, which glslang 12 does not fold; the preprocessed text is
        // parsed again with them rewritten into expressions it does fold.
        PreprocessResult preprocessed;
        {
            const KeepThreadPool keep;
            preprocessed = PreprocessStage(input);
        }
        std::set<int> rewritten_lines;
        const std::string folded =
                preprocessed.ok ? FoldEs100ConstantExpressions(preprocessed.text, &rewritten_lines)
                                : std::string();
        if (!folded.empty()) {
            const char* folded_text = folded.c_str();
            auto shader = std::make_unique<glslang::TShader>(Language(input.stage));
            shader->setStrings(&folded_text, 1);
            shader->setPreamble(kEs100FoldingPreamble);
            const bool ok = shader->parse(&resources, version, EEsProfile, prepared.force_version,
                                          false, kMessages);
            std::vector<Diagnostic> diagnostics =
                    ParseGlslangLog(renaming.Restore(shader->getInfoLog()), input.file, input.text);
            // Errors away from the rewritten lines are the shader's own, found now that the
            // constants fold (an index past an array sized by one); others stay glslang's first.
            const bool own_errors =
                    std::none_of(diagnostics.begin(), diagnostics.end(), [&](const Diagnostic& d) {
                        return d.severity == Severity::kError &&
                               (d.line == 0 || rewritten_lines.count(d.line) != 0);
                    });
            if (ok && !HasErrors(diagnostics)) {
                result.ok = true;
                result.shader = std::move(shader);
                result.diagnostics = std::move(diagnostics);
            } else if (own_errors) {
                result.diagnostics = std::move(diagnostics);
            }
        }
    }
    if (!webgl_errors.empty()) {
        // Reported first: a browser refuses the shader before its driver parses it.
        result.ok = false;
        result.diagnostics.insert(result.diagnostics.begin(), webgl_errors.begin(),
                                  webgl_errors.end());
    }
    if (result.ok && !late_extensions.empty()) {
        result.ok = false;
        result.diagnostics.insert(result.diagnostics.end(), late_extensions.begin(),
                                  late_extensions.end());
    }
    if (result.ok) {
        result.intermediate = result.shader->getIntermediate();
        std::vector<Diagnostic> broken =
                CheckStageRules(*result.intermediate, resources, input.file, prepared.text);
        const std::vector<Diagnostic> conformance =
                CheckStageConformance(*result.intermediate, input.file);
        broken.insert(broken.end(), conformance.begin(), conformance.end());
        std::vector<Diagnostic> warnings;  // reported whether or not the stage is valid
        if (webgl) {
            const std::vector<Diagnostic> nesting =
                    CheckWebGlStructNesting(*result.intermediate, input.file, prepared.text);
            broken.insert(broken.end(), nesting.begin(), nesting.end());
        }
        if (IsTarget(input, GlslTarget::kWebGl2)) {
            const std::vector<Diagnostic> operators =
                    CheckWebGl2Operators(*result.intermediate, input.file, prepared.text);
            broken.insert(broken.end(), operators.begin(), operators.end());
        }
        if (webgl && version == 100) {
            const std::vector<Diagnostic> initializers =
                    CheckWebGlGlobalInitializers(*result.intermediate, input.file);
            broken.insert(broken.end(), initializers.begin(), initializers.end());
            // A uniform too large on its own is reported above; packing would only repeat it.
            if (broken.empty()) {
                broken = CheckWebGlUniformPacking(*result.intermediate, resources, input.file,
                                                  prepared.text);
            }
        }
        // The glslang work below must leave the thread's pool allocator to the parsed tree.
        const KeepThreadPool keep;
        // A macro may hold a unary '+': then the expanded text (lines kept) is the one scanned;
        // otherwise the stage text's scan, made once per process (ScanOf).
        std::string expanded;
        if (MacroMayHoldUnaryPlus(prepared.text)) {
            if (PreprocessResult preprocessed = PreprocessStage(input); preprocessed.ok) {
                expanded = std::move(preprocessed.text);
            }
        }
        const std::string_view scanned = expanded.empty() ? prepared.text : expanded;
        const std::vector<UnaryPlus> pluses =
                expanded.empty() ? ScanOf(prepared.text)->unary_pluses : FindUnaryPluses(scanned);
        if (!pluses.empty()) {
            // glslang drops unary '+' unchecked; the same text with '-' in its place shows which
            // operand types it would refuse (GLSL ES 1.00 §5.9, 3.00 §5.9).
            const std::string negated = NegateUnaryPluses(scanned, pluses);
            const char* negated_text = negated.c_str();
            auto shader = MakeShader(input, prepared, &negated_text, ShaderUse::kParse);
            shader->parse(&resources, version, EEsProfile, prepared.force_version, false,
                          kMessages);
            // Reported where the user wrote it: renaming lengthens words, never moves a '+'
            // to another place among the '+'s.
            std::vector<UnaryPlus> shown = ScanOf(input.text)->unary_pluses;
            if (shown.size() != pluses.size()) {
                shown = pluses;
            }
            const std::vector<Diagnostic> plus_errors = UnaryPlusErrors(
                    ParseGlslangLog(renaming.Restore(shader->getInfoLog()), input.file, negated),
                    shown, input.file);
            broken.insert(broken.end(), plus_errors.begin(), plus_errors.end());
        }
        const std::shared_ptr<const TextScan> scan = ScanOf(input.text);
        if (version >= 300) {
            std::call_once(scan->reserved_word_once, [&] {
                scan->may_use_es300_reserved_word = MayUseEs300ReservedWord(input.text);
            });
        }
        if (version >= 300 && scan->may_use_es300_reserved_word) {
            if (const PreprocessResult preprocessed = PreprocessStage(input); preprocessed.ok) {
                for (Diagnostic& d :
                     CheckEs300ReservedWords(preprocessed.text, input.text, input.file, webgl)) {
                    (d.severity == Severity::kError ? broken : warnings).push_back(std::move(d));
                }
            }
        }
        if (MayRedeclareInvariant(input.text)) {
            const PreprocessResult preprocessed = PreprocessStage(input);
            if (preprocessed.ok) {
                result.invariance = FindInvarianceDeclarations(preprocessed.text, input.text);
                const std::vector<Diagnostic> invariance =
                        CheckInvariantBuiltIns(*result.intermediate, result.invariance, input.file);
                broken.insert(broken.end(), invariance.begin(), invariance.end());
            }
        }
        for (Diagnostic& d : broken) {
            d.message = renaming.Restore(d.message);
        }
        if (!broken.empty()) {
            result.ok = false;
            result.intermediate = nullptr;
            result.diagnostics.insert(result.diagnostics.end(), broken.begin(), broken.end());
        }
        for (Diagnostic& d : warnings) {
            d.message = renaming.Restore(d.message);
            result.diagnostics.push_back(std::move(d));
        }
    }
    return result;
}

namespace {

// A pool allocator of the thread's own for the length of a link. A link's checks allocate glslang
// strings from the thread's pool, and when both stages were parsed before (LinkParsed) that may
// still be the pool of a shader destroyed since.
class ScratchThreadPool {
public:
    ScratchThreadPool() : saved_(glslang::GetThreadPoolAllocator()) {
        glslang::SetThreadPoolAllocator(&pool_);
    }
    ~ScratchThreadPool() { glslang::SetThreadPoolAllocator(&saved_); }
    ScratchThreadPool(const ScratchThreadPool&) = delete;
    ScratchThreadPool& operator=(const ScratchThreadPool&) = delete;

private:
    glslang::TPoolAllocator pool_;
    glslang::TPoolAllocator& saved_;
};

// Links the parsed stages `parses[i]` of `inputs[i]`. glslang keeps the uncalled functions
// (EShMsgKeepUncalled; it reports the same errors either way), so a tree no link found an error
// in is still the tree ParseStage made and may serve another link (ReusableForLink).
// The variable or block a glslang link message is about, from the fragment side of its detail
// (`fragment stage: " vec2 uv[2]"`, `fragment stage: k ""`, `fragment stage: Block: B, ...`);
// "" when it names none.
std::string NameInLinkMessage(std::string_view message) {
    constexpr std::string_view kSide = "fragment stage: ";
    const std::size_t at = message.rfind(kSide);
    if (at == std::string_view::npos) {
        return {};
    }
    std::string_view detail = message.substr(at + kSide.size());
    if (detail.rfind("Block: ", 0) == 0) {
        detail.remove_prefix(std::string_view("Block: ").size());
    } else if (!detail.empty() && detail.front() == '"') {
        // The declaration, quoted: the name is its last word, before any array size.
        detail = detail.substr(1, detail.find('"', 1) - 1);
        detail = detail.substr(0, detail.find('['));
        detail = detail.substr(detail.find_last_of(' ') + 1);
    }
    auto is_word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    const auto end = std::find_if_not(detail.begin(), detail.end(), is_word);
    return std::string(detail.begin(), end);
}

LinkResult Link(const std::vector<const GlslangStageInput*>& inputs,
                const std::vector<StageParse*>& parses) {
    LinkResult result;
    const ScratchThreadPool scratch;
    glslang::TProgram program;  // declared after the shaders it links, so destroyed before them
    for (const StageParse* parse : parses) {
        if (!parse->ok) {
            result.diagnostics = parse->diagnostics;
            return result;
        }
        program.addShader(parse->shader.get());
    }
    // Both stages rename a word to the same stand-in, so each stage's renaming restores it.
    auto restore = [&](std::string text) {
        for (const StageParse* parse : parses) {
            text = parse->renaming.Restore(text);
        }
        return text;
    };
    if (inputs.size() == 2) {
        const StageParse& vertex = *parses[0];
        const StageParse& fragment = *parses[1];
        result.diagnostics = CheckLinkRules(*vertex.shader->getIntermediate(), inputs[0]->file,
                                            *fragment.shader->getIntermediate(), inputs[1]->file);
        if (!HasErrors(result.diagnostics)) {
            result.diagnostics = CheckLinkConformance(
                    LinkedStage{*vertex.shader->getIntermediate(), inputs[0]->file, vertex.text,
                                vertex.invariance},
                    LinkedStage{*fragment.shader->getIntermediate(), inputs[1]->file, fragment.text,
                                fragment.invariance});
        }
        if (!HasErrors(result.diagnostics) &&
            IsWebGlEs100(*inputs[1], fragment.shader->getIntermediate()->getVersion())) {
            result.diagnostics = CheckWebGlVaryingPacking(*fragment.shader->getIntermediate(),
                                                          ResourcesOf(*inputs[1], 100),
                                                          inputs[1]->file, fragment.text);
        }
        for (Diagnostic& d : result.diagnostics) {
            d.message = restore(d.message);
        }
        if (HasErrors(result.diagnostics)) {
            return result;  // glslang's own link would only add confusion to these
        }
    }
    result.ok = program.link(static_cast<EShMessages>(kMessages | EShMsgKeepUncalled));
    // Link messages carry no line; attach them to the stage they name, else the last file.
    const std::string log = restore(program.getInfoLog());
    bool dropped_offset_errors = false;
    for (Diagnostic d : ParseGlslangLog(log, inputs.back()->file, inputs.back()->text)) {
        // GLSL ES 3.00 has no `offset` layout qualifier (3.10 brought it), yet glslang 12 compares
        // the member offsets it works out for a block declared std140 with those of the same
        // block made std140 by a default `layout(std140) uniform;`, which it leaves without
        // offsets. A real difference of layout has messages of its own (packing, matrix order,
        // member types), and the checks after this one ran (TProgram::crossStageCheck goes on).
        if (d.message.find("Interface block member layout offset qualifier must match") !=
            std::string::npos) {
            dropped_offset_errors = true;
            continue;
        }
        // glslang 12 merges the uniforms of all stages under no stage and then names that side of
        // a clash "unknown stage"; in a vertex + fragment program the unnamed side is the vertex.
        for (std::size_t at = d.message.find("unknown stage");
             inputs.size() == 2 && at != std::string::npos; at = d.message.find("unknown stage")) {
            d.message.replace(at, std::string_view("unknown stage").size(), "vertex");
        }
        if (d.line == 0 && inputs.size() == 2 &&
            d.message.find("vertex stage") != std::string::npos &&
            d.message.find("fragment") == std::string::npos) {
            d.file = inputs.front()->file;
        }
        // The rest, where the fragment stage declares what the message names.
        if (d.line == 0 && inputs.size() == 2 && d.file == inputs.back()->file) {
            if (const std::string name = NameInLinkMessage(d.message); !name.empty()) {
                std::tie(d.line, d.column) = FirstMention(parses.back()->text, name);
            }
        }
        result.diagnostics.push_back(std::move(d));
    }
    if (!result.ok && dropped_offset_errors && !HasErrors(result.diagnostics)) {
        result.ok = true;
    }
    if (!result.ok && !HasErrors(result.diagnostics)) {
        result.diagnostics.push_back(
                MakeError(inputs.back()->file, 0, 0, "link failed (glslang gave no message)"));
    }
    return result;
}

}  // namespace

LinkResult LinkStages(const GlslangStageInput& vertex, const GlslangStageInput& fragment) {
    EnsureGlslangInitialized();
    // Parsed in this order and destroyed after the link, its program first.
    StageParse vertex_parsed = ParseStage(vertex);
    StageParse fragment_parsed = vertex_parsed.ok ? ParseStage(fragment) : StageParse{};
    return Link({&vertex, &fragment}, {&vertex_parsed, &fragment_parsed});
}

LinkResult LinkParsed(const std::vector<const GlslangStageInput*>& inputs,
                      const std::vector<StageParse*>& parses) {
    EnsureGlslangInitialized();
    return Link(inputs, parses);
}

bool ReusableForLink(const StageParse& parsed) {
    return parsed.ok && parsed.shader != nullptr &&
           parsed.shader->getIntermediate()->getNumErrors() == 0;
}

namespace {

std::string_view TrimView(std::string_view text) {
    const std::size_t begin = text.find_first_not_of(" \t\r");
    if (begin == std::string_view::npos) {
        return {};
    }
    return text.substr(begin, text.find_last_not_of(" \t\r") - begin + 1);
}

std::vector<std::string> SplitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        lines.push_back(line);
    }
    return lines;
}

// glslang names a column nowhere in its log; the quoted token at the start of most messages
// ('foo' : undeclared identifier) is searched for on the reported line instead.
int ColumnOfToken(const std::string& message, const std::vector<std::string>& source_lines,
                  int line) {
    if (line <= 0 || static_cast<std::size_t>(line) > source_lines.size() || message.empty() ||
        message.front() != '\'') {
        return 0;
    }
    const std::size_t close = message.find('\'', 1);
    if (close == std::string::npos || close == 1) {
        return 0;
    }
    const std::string token = message.substr(1, close - 1);
    const std::string& text = source_lines[static_cast<std::size_t>(line) - 1];
    const std::size_t at = text.find(token);
    return at == std::string::npos ? 0 : static_cast<int>(at) + 1;
}

// Whether 1-based line `line` of `lines` is an `#extension` directive.
bool IsExtensionDirective(const std::vector<std::string>& lines, int line) {
    if (line <= 0 || static_cast<std::size_t>(line) > lines.size()) {
        return false;
    }
    const std::string_view text = TrimView(lines[static_cast<std::size_t>(line) - 1]);
    return !text.empty() && text.front() == '#' &&
           TrimView(text.substr(1)).rfind("extension", 0) == 0;
}

// Mends glslang's message `d` about an `#extension` directive; false when it is to be dropped.
// glslang reads past the end of a directive that stops early (`#extension` alone is reported on
// the next line), and after an error in a directive it adds "extra tokens -- expected newline"
// for tokens the line does not have.
bool PlaceExtensionMessage(const std::vector<std::string>& lines,
                           const std::vector<Diagnostic>& earlier, Diagnostic& d) {
    if (!IsExtensionDirective(lines, d.line) && IsExtensionDirective(lines, d.line - 1)) {
        --d.line;
    }
    return d.message.find("extra tokens -- expected newline") == std::string::npos ||
           std::none_of(earlier.begin(), earlier.end(), [&](const Diagnostic& e) {
               return e.line == d.line && e.file == d.file &&
                      e.message.rfind("'#extension' : ", 0) == 0;
           });
}

// The line numbers `source`'s `#line` directives give, as written: the word after "#line".
std::vector<std::string_view> LineDirectiveNumbers(std::string_view source) {
    std::vector<std::string_view> numbers;
    for (std::size_t at = 0; at < source.size();) {
        const std::size_t end = std::min(source.find('\n', at), source.size());
        std::string_view line = TrimView(source.substr(at, end - at));
        at = end + 1;
        if (line.empty() || line.front() != '#') {
            continue;
        }
        line = TrimView(line.substr(1));
        if (line.rfind("line", 0) != 0) {
            continue;
        }
        line = TrimView(line.substr(4));
        numbers.push_back(line.substr(0, std::min(line.find_first_of(" \t"), line.size())));
    }
    return numbers;
}

// Whether `source` has a `#line` directive whose line number is past 2^31 - 1, which glslang's
// count wraps to a negative one.
bool SetsALineCountPast32Bits(std::string_view source) {
    const std::vector<std::string_view> numbers = LineDirectiveNumbers(source);
    return std::any_of(numbers.begin(), numbers.end(), [](std::string_view number) {
        const std::size_t digits = std::min(number.find_first_not_of("0123456789"), number.size());
        constexpr std::string_view kLargest = "2147483647";
        return digits > kLargest.size() ||
               (digits == kLargest.size() && number.substr(0, digits) > kLargest);
    });
}

// Whether `source` has a `#line` directive with a negative line number.
bool SetsANegativeLineCount(std::string_view source) {
    const std::vector<std::string_view> numbers = LineDirectiveNumbers(source);
    return std::any_of(numbers.begin(), numbers.end(),
                       [](std::string_view number) { return number.rfind('-', 0) == 0; });
}

// Where in `line` the first byte past ASCII outside the comments that start on it lies; npos
// when there is none.
std::size_t FirstNonAsciiInCode(std::string_view line) {
    for (std::size_t i = 0; i < line.size(); ++i) {
        if (line.compare(i, 2, "//") == 0) {
            return std::string_view::npos;
        }
        if (line.compare(i, 2, "/*") == 0) {
            const std::size_t end = line.find("*/", i + 2);
            if (end == std::string_view::npos) {
                return std::string_view::npos;
            }
            i = end + 1;
            continue;
        }
        if (static_cast<unsigned char>(line[i]) >= 0x80) {
            return i;
        }
    }
    return std::string_view::npos;
}

// glslang reports every byte past ASCII outside a comment as the one token '\x80' ("unexpected
// token"), which is on no line and is no UTF-8 either. The first such byte in code on the line
// is the one meant: `d` gets its column and a message that says what is wrong.
void PlaceNonAsciiToken(const std::vector<std::string>& source_lines, Diagnostic& d) {
    constexpr std::string_view kToken = "'\x80' : unexpected token";
    if (d.message.rfind(kToken, 0) != 0 || d.line <= 0 ||
        static_cast<std::size_t>(d.line) > source_lines.size()) {
        return;
    }
    const std::string& text = source_lines[static_cast<std::size_t>(d.line) - 1];
    const std::size_t at = FirstNonAsciiInCode(text);
    if (at == std::string_view::npos) {
        return;
    }
    d.column = static_cast<int>(at) + 1;
    d.message = fmt::format(
            "a character outside GLSL ES's character set (byte 0x{:02X}, not ASCII): outside "
            "comments a shader may hold ASCII only (GLSL ES 1.00 and 3.00 section 3.1); remove "
            "it, or move it into a comment",
            static_cast<unsigned char>(text[at]));
}

}  // namespace

std::vector<Diagnostic> ParseGlslangLog(const std::string& log, const std::string& file,
                                        const std::string& source) {
    static const std::pair<std::string_view, Severity> prefixes[] = {
            {"ERROR: ", Severity::kError},         {"INTERNAL ERROR: ", Severity::kError},
            {"UNIMPLEMENTED: ", Severity::kError}, {"WARNING: ", Severity::kWarning},
            {"NOTE: ", Severity::kNote},
    };
    // Split only for a message to place: most logs are empty, and splitting every parsed stage's
    // text was a few per cent of a cold validation.
    std::optional<std::vector<std::string>> source_lines;
    std::vector<Diagnostic> diagnostics;
    for (const std::string& raw : SplitLines(log)) {
        std::string_view line = TrimView(raw);
        if (line.empty()) {
            continue;
        }
        const auto prefix =
                std::find_if(std::begin(prefixes), std::end(prefixes),
                             [&](const auto& p) { return line.rfind(p.first, 0) == 0; });
        if (prefix == std::end(prefixes)) {
            // A continuation line (link logs list the clashing declarations below the message).
            if (!diagnostics.empty()) {
                diagnostics.back().message += fmt::format("; {}", line);
            }
            continue;
        }
        std::string_view rest = line.substr(prefix->first.size());
        // glslang's closing summary repeats what the messages already said.
        if (rest.find("compilation errors.") != std::string_view::npos ||
            rest.find("compilation warnings.") != std::string_view::npos) {
            continue;
        }
        // Without cascading errors glslang stops at the first error; the notes it then adds
        // ("compilation terminated", "missing #endif" of the block it stopped in) are not the
        // user's mistakes.
        if (rest.find("compilation terminated") != std::string_view::npos ||
            (HasErrors(diagnostics) && rest.find("missing #endif") != std::string_view::npos)) {
            continue;
        }
        Diagnostic d;
        d.severity = prefix->second;
        d.file = file;
        // Location form "<string>:<line>: message", where <string> is 0 for the user's file.
        const std::size_t first_colon = rest.find(':');
        if (first_colon != std::string_view::npos) {
            const std::size_t second_colon = rest.find(':', first_colon + 1);
            const std::string_view string_part = rest.substr(0, first_colon);
            const std::string_view line_part =
                    second_colon == std::string_view::npos
                            ? std::string_view()
                            : rest.substr(first_colon + 1, second_colon - first_colon - 1);
            // A `#line` past 2^31 - 1 wraps glslang's count to a negative line.
            const bool wrapped = line_part.size() > 1 && line_part[0] == '-';
            const std::string_view digits = wrapped ? line_part.substr(1) : line_part;
            const bool numeric =
                    !string_part.empty() && !digits.empty() && digits.size() <= 10 &&
                    string_part.find_first_not_of("0123456789") == std::string_view::npos &&
                    digits.find_first_not_of("0123456789") == std::string_view::npos;
            if (numeric) {
                d.line = wrapped ? 0 : static_cast<int>(std::stoll(std::string(digits)));
                rest = TrimView(rest.substr(second_colon + 1));
            }
            // Negative because the count wrapped, or because a `#line` set it so.
            if (numeric && wrapped && SetsALineCountPast32Bits(source)) {
                d.message = fmt::format(
                        "at an unknown line (a '#line' directive set the count past "
                        "2147483647 and glslang wrapped it to {}; use smaller line numbers): ",
                        line_part);
            } else if (numeric && wrapped && SetsANegativeLineCount(source)) {
                d.message = fmt::format(
                        "at an unknown line (a '#line' directive set the count to {}; use line "
                        "numbers from 1 to 2147483647): ",
                        line_part);
            } else if (numeric && wrapped) {
                d.message = fmt::format(
                        "at an unknown line (a '#line' directive set the count so near "
                        "2147483647 that a later line passed it, and glslang wrapped it to {}; "
                        "use smaller line numbers): ",
                        line_part);
            } else if (string_part == "-1" && second_colon != std::string_view::npos) {
                // Source string -1 is glslang's preamble, which holds the defines: a define's
                // value glslang cannot read, found where the file uses it ("-1:1: '' : bad
                // digit in hexadecimal literal" for -D X=0x).
                d.message =
                        "in a define's value (defines are given to glslang ahead of the "
                        "file; check each -D NAME=VALUE): ";
                rest = TrimView(rest.substr(second_colon + 1));
            }
        }
        d.message += std::string(rest);
        // glslang's parser (bison) says only this when an expression nests deeper than its
        // stack of 10,000 states: 9,000 parentheses pass, 10,000 do not.
        if (d.message.find("memory exhausted") != std::string::npos) {
            d.message =
                    "an expression nests deeper than glslang's parser can follow (its stack "
                    "holds 10000 states, about one for each open parenthesis; glslang says only "
                    "'memory exhausted'): write it with fewer nested parentheses, or split it "
                    "into several statements";
        }
        if (!source_lines) {
            source_lines = SplitLines(source);
        }
        if (d.message.rfind("'#extension' : ", 0) == 0 &&
            !PlaceExtensionMessage(*source_lines, diagnostics, d)) {
            continue;
        }
        d.column = ColumnOfToken(d.message, *source_lines, d.line);
        PlaceNonAsciiToken(*source_lines, d);
        diagnostics.push_back(std::move(d));
    }
    return diagnostics;
}

}  // namespace tidepool
