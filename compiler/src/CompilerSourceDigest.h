// The SHA-256 of this library's sources, generated at build time
// (compiler/cmake/SourceDigest.cmake): part of every validation cache key, so that a tidepool whose
// validation code changed never reuses results of the old code.
#pragma once

namespace tidepool {

/// 64 hex digits.
extern const char* const kCompilerSourceDigest;

}  // namespace tidepool
