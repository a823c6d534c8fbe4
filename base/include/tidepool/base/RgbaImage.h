// The one in-memory image every part shares (the renderer's read-back and textures, the
// planner's and the report's comparisons) and its PNG reading, encoding and atomic writing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tidepool::base {

/// Largest width or height ReadPng accepts: 16384 is the largest render target Mesa's llvmpipe
/// offers (and above any view we render), so a larger header is a corrupt or foreign file and
/// must not make us allocate gigabytes.
inline constexpr int kMaxPngDimension = 16384;

/// An 8-bit RGBA image, rows top to bottom, 4 bytes per pixel, no padding between rows. Uploaded
/// as-is with glTexImage2D, row 0 is texture coordinate t = 0.
struct RgbaImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;  // width * height * 4 bytes

    /// width * height; meaningful only for a well-formed image (see IsWellFormed).
    std::size_t PixelCount() const {
        return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    }
    /// Whether the image has pixels and exactly width * height * 4 bytes of them.
    bool IsWellFormed() const {
        return width > 0 && height > 0 && pixels.size() == PixelCount() * 4;
    }
};

/// What ReadPng found: an image, or an error message naming the file.
struct ImageResult {
    std::optional<RgbaImage> image;  // set on success
    std::string error;               // "" on success
};

/// Reads any PNG (palette, gray, gray+alpha, RGB, RGBA; 8 or 16 bits; 16-bit files without a
/// gAMA or sRGB chunk are taken as sRGB-encoded, not linear) into RGBA8 with libpng's simplified
/// API, which reports errors through its struct, so a truncated file is an error, not a crash.
/// Fails (no image, `error` starting with the path) when the file is missing, unreadable, not a
/// PNG, corrupt or truncated, or wider or taller than kMaxPngDimension.
ImageResult ReadPng(const std::filesystem::path& path);

/// How an encoder trades time for size: kSmall for bytes that count against a budget (images
/// embedded in index.html), kFast for files on disk (libpng's fast setting: a run writes about
/// 600 images, and at the default setting encoding took a fifth of the render's CPU time for
/// files only about a quarter smaller).
enum class PngEncoding { kSmall, kFast };

/// Encodes `image` as an RGBA PNG into `encoded`. Returns "" or what went wrong (a malformed
/// image, or libpng's message).
std::string EncodePng(const RgbaImage& image, std::string* encoded,
                      PngEncoding encoding = PngEncoding::kSmall);

/// Writes `image` as an 8-bit RGBA PNG at `path` (encoded kFast), creating parent folders,
/// through a temporary file in the same folder renamed over `path`, so a reader never sees half
/// a file. Returns "" on success, otherwise a message naming the file; fails when the image is
/// empty or its pixel count does not match its size, or the file cannot be written.
std::string WritePngAtomically(const std::filesystem::path& path, const RgbaImage& image);

}  // namespace tidepool::base
