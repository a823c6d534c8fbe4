// PNG files of rendered images (libpng).
#pragma once

#include <filesystem>
#include <string>

#include "tidepool/runner/ProceduralScene.h"

namespace tidepool::runner {

/// Writes `image` (rows top to bottom, RGBA8) as an 8-bit RGBA PNG at `path` atomically, creating
/// parent folders. Returns "" on success, otherwise what went wrong (unwritable path, libpng error).
std::string WritePng(const std::filesystem::path& path, const ImageRgba8& image);

/// Reads an 8-bit RGB or RGBA PNG into RGBA8 rows top to bottom. Returns "" on success, otherwise
/// what went wrong (missing file, not a PNG, an unsupported bit depth).
std::string ReadPng(const std::filesystem::path& path, ImageRgba8* image);

}  // namespace tidepool::runner
