// The SHA-256 of the sources behind what `tidepool validate` prints and writes, generated at
// build time (cli/CMakeLists.txt): part of every run record's key (RunRecordCache.h), so that a
// tidepool whose output code changed never repeats what an older one printed.
#pragma once

namespace tidepool {

/// 64 hex digits.
extern const char* const kRunSourceDigest;

}  // namespace tidepool
