// Turning a Mesa GLSL compiler or linker info log into diagnostics at the user's file and line.
#pragma once

#include "tidepool/Diagnostic.h"

#include <string>
#include <string_view>
#include <vector>

namespace tidepool::runner {

/// Parses Mesa's info log, lines like `0:42(7): error: message` (source string 0, line 42 as the
/// `#line 2` directive of AssembleDriverSource leaves it: the user's own line), into diagnostics
/// for `file` tagged with `variant`. Mesa's column is 1-based but counted after its preprocessor
/// has collapsed every run of blanks to one space (checked in tests/gl/GlBackendGlTest.cpp); given
/// the user's source, the column is mapped back to the user's text, otherwise it is kept as Mesa
/// wrote it. Lines without a position (`error: ...`, link messages) keep line 0; other non-empty
/// lines are appended to the previous message. Never fails: unrecognised text becomes one
/// diagnostic.
std::vector<Diagnostic> ParseMesaInfoLog(std::string_view log, const std::string& file,
                                         const std::string& variant,
                                         std::string_view user_source = {});

/// Maps Mesa's column on a line (1-based, blank runs counted as one) to the 1-based column in
/// `line_text`; returns `mesa_column` unchanged when the line is shorter than that.
int MapMesaColumn(std::string_view line_text, int mesa_column);

}  // namespace tidepool::runner
