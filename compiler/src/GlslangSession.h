// The one place that talks to glslang: process initialisation, preprocessing, parsing and
// linking, with glslang's text log turned into Diagnostics. Private to the compiler library.
#pragma once

#include "tidepool/DeviceLimits.h"
#include "tidepool/Diagnostic.h"
#include "tidepool/SourceAssembler.h"
#include "tidepool/VariantConfig.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ConformanceRules.h"
#include "DefineRelevance.h"
#include "KeywordRenaming.h"

namespace glslang {
class TShader;
class TIntermediate;
}  // namespace glslang

namespace tidepool {

/// One stage as the user wrote it plus what to compile it with. With no target, the file's own
/// `#version` decides (GLSL ES only); with a target, a `#version 100` file is compiled for it
/// (a WebGL target also adds the WebGL rules) unless `keep_version` is set. `limits`, when given,
/// are the device's.
struct GlslangStageInput {
    std::string file;
    const std::string& text;
    Stage stage;
    std::optional<GlslTarget> target;
    const std::vector<std::string>& defines;
    const DeviceLimits* limits = nullptr;
    /// Plain files: the file's own `#version` is validated whatever the target's version, so a
    /// GLSL ES 1.00 file under webgl2 is a 1.00 shader with the rules WebGL gives 1.00 shaders
    /// (WebGL 2.0 §4.3 "Supported GLSL Constructs"). Variant configs leave it unset: their
    /// shaders are written once and compiled as each target's version.
    bool keep_version = false;
    /// Lines of `text` that glslang's preprocessor skips under `defines`, as DefineRelevance's
    /// walk found them; ParseStage gives glslang those of them WithSkippedLinesBlanked empties
    /// as empty lines. Null: none known.
    const std::vector<LineSpan>* skipped_lines = nullptr;
};

/// The preprocessed text of a stage (defines applied, comments and inactive blocks gone).
struct PreprocessResult {
    bool ok = false;
    std::string text;
};

/// A parsed stage; `intermediate` lives as long as this object.
struct StageParse {
    StageParse();
    StageParse(StageParse&&) noexcept;
    StageParse& operator=(StageParse&&) noexcept;
    ~StageParse();

    bool ok = false;
    std::vector<Diagnostic> diagnostics;
    std::unique_ptr<glslang::TShader> shader;
    const glslang::TIntermediate* intermediate = nullptr;
    /// The words renamed for glslang (see KeywordRenaming.h), and the text glslang parsed (the
    /// user's, line for line), where the names in `intermediate` are found.
    KeywordRenaming renaming;
    std::string text;
    /// What the stage declares invariant beyond glslang's qualifiers, for the link's rules.
    InvarianceDeclarations invariance;
};

/// The outcome of a link.
struct LinkResult {
    bool ok = false;
    std::vector<Diagnostic> diagnostics;
};

/// What, besides a stage's text, decides glslang's verdict on it: glslang's version and the
/// default resource limits, as text for cache keys. Never fails.
std::string GlslangIdentity();

/// `text` with every `//` comment taken out up to its line's end, which is what glslang is given:
/// a comment is one space to the language (the "Comments" section of GLSL ES 1.00 and 3.00), and
/// nothing follows a line comment on its line, so no token, line or column of code moves, while
/// glslang's preprocessor reads comments a character at a time (half the bytes of
/// shaders/water.fsh). Block comments stay, and so does a `//` after a `"` on its line (it may be
/// inside a string); a text with a `\` at a line's end is returned as it is.
std::string WithoutLineComments(std::string_view text);

/// Whether glslang's preprocessor can skip `line` (one line, no line break) without a message:
/// only names of at most 255 characters, white space (space, tab, a `\r` ending the line),
/// punctuation other than `#`,
/// `"`, `'`, `\` and a comment's `/*`, `*/` or `//`, and decimal numbers it cannot refuse: no
/// leading zero before a digit, at most nine digits before an optional dot, an exponent of at
/// most two digits, and no letter or digit run on after them (a suffix). glslang scans skipped
/// text token by token and reports what its scanner refuses there (a bad hexadecimal digit, a
/// suffix its version lacks, a literal too long), so any other line is kept.
bool IsQuietWhenSkipped(std::string_view line);

/// IsQuietWhenSkipped of each line of `text` (lines end at `\n`).
std::vector<bool> QuietWhenSkippedLines(std::string_view text);

/// `text` with every line of `skipped` that `quiet` (by line, 0-based, as QuietWhenSkippedLines
/// gives it for the same lines) marks made empty, its line break kept: glslang's preprocessor
/// otherwise reads skipped lines a character at a time (a sixth of glslang's parsing of the
/// default matrix), and an empty line gives it the same text, messages, lines and columns
/// everywhere else. Directives are never in `skipped`.
std::string WithSkippedLinesBlanked(std::string_view text, const std::vector<LineSpan>& skipped,
                                    const std::vector<bool>& quiet);

/// Initialises glslang once per process (thread-safe); every function below calls it.
void EnsureGlslangInitialized();

/// Builds glslang's built-in symbol tables for `targets` in this process by parsing a trivial
/// program of each stage, so that worker processes forked afterwards inherit them instead of each
/// building them again (about a tenth of a second per worker and version).
void WarmUpGlslang(const std::vector<GlslTarget>& targets);

/// Runs glslang's preprocessor only; fails when the preprocessor reports an error.
PreprocessResult PreprocessStage(const GlslangStageInput& input);

/// Parses one stage with the defines as glslang's preamble; desktop GLSL is an error.
StageParse ParseStage(const GlslangStageInput& input);

/// Parses a vertex and a fragment stage and links them into one program (all link-time checks).
LinkResult LinkStages(const GlslangStageInput& vertex, const GlslangStageInput& fragment);

/// Links stages ParseStage parsed from `inputs` (`parses[i]` from `inputs[i]`): a vertex and a
/// fragment stage, or one stage alone for the link-time errors that need no second stage. The
/// parses stay usable: one that ReusableForLink accepts afterwards may serve another link
/// exactly as a new parse of the same input would.
LinkResult LinkParsed(const std::vector<const GlslangStageInput*>& inputs,
                      const std::vector<StageParse*>& parses);

/// Whether a parse may serve another link: it parsed, and no link recorded an error in its tree
/// (glslang counts a link's errors in the trees it linked).
bool ReusableForLink(const StageParse& parsed);

/// Turns a glslang info log into Diagnostics for `file`; `source` supplies columns (the first
/// place on the line where the quoted token of the message appears).
std::vector<Diagnostic> ParseGlslangLog(const std::string& log, const std::string& file,
                                        const std::string& source);

}  // namespace tidepool
