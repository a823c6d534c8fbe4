// Turning a user's shader file plus a variant's defines into the text a compiler receives,
// without moving the user's line numbers.
#pragma once

#include "tidepool/VariantConfig.h"

#include <string>
#include <string_view>
#include <vector>

namespace tidepool {

/// The pipeline stage of a shader file.
enum class Stage { kVertex, kFragment };

/// "vertex" or "fragment".
const char* StageName(Stage stage);

/// The preamble glslang receives through TShader::setPreamble: one `#define NAME 1` per define,
/// or `#define NAME VALUE` for a define written "NAME=VALUE".
std::string DefinePreamble(const std::vector<std::string>& defines);

/// The source a GL driver receives: `#version` for the target, the defines, then a `#line`
/// directive so that the user's next line keeps its own number, then the rest of the file.
/// If the file starts with its own `#version` line, that line is replaced (and `#line 2` follows);
/// otherwise `#line 1` precedes the whole file. For the 300 es target, a compatibility block maps
/// the 1.00 keywords (attribute, varying, texture2D, textureCube, gl_FragColor) to 3.00 ones.
std::string AssembleDriverSource(std::string_view user_source,
                                 const std::vector<std::string>& defines, Stage stage,
                                 GlslTarget target);

/// The `#version` line of a user's file, if its first non-blank line is one; "" otherwise.
std::string FindVersionLine(std::string_view user_source);

}  // namespace tidepool
