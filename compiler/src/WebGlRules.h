// The rules the WebGL specifications add to GLSL ES, as browsers' shader translators (ANGLE)
// apply them before a driver sees the shader. Each check cites its section of WebGL 1.0 or 2.0
// (the Khronos editor's drafts). Private to the compiler library.
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/VariantConfig.h"

#include <string>
#include <string_view>
#include <vector>

namespace tidepool {

/// The longest token a WebGL target accepts: 256 characters for WebGL 1 (WebGL 1.0 §6.20
/// "Maximum GLSL Token Size"), 1024 for WebGL 2 (WebGL 2.0 follows GLSL ES 3.00 §3.8, which
/// limits identifiers to 1024 characters).
int MaxWebGlTokenLength(GlslTarget target);

/// Checks the user's text (comments left out, every line, preprocessor directives and inactive
/// blocks included) for a token longer than MaxWebGlTokenLength and for an identifier that starts
/// with `webgl_` or `_webgl_` (WebGL 1.0 §6.17 "GLSL Constructs": reserved for use by WebGL).
std::vector<Diagnostic> CheckWebGlTokens(std::string_view text, GlslTarget target,
                                         const std::string& file);

/// Checks glslang's preprocessed text of a stage (comments and inactive blocks gone, lines kept)
/// for a character outside the GLSL ES source character set (GLSL ES 1.00 §3.1, 3.00 §3.1),
/// which WebGL makes a compile error (WebGL 1.0 §6.21 "Characters Outside the GLSL Source
/// Character Set"). Columns are found on the same line of `source`, the user's text.
std::vector<Diagnostic> CheckWebGlCharacters(std::string_view preprocessed, std::string_view source,
                                             const std::string& file);

}  // namespace tidepool
