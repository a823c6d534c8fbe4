// PNG input/output through libpng's simplified API (png_image), which catches libpng's longjmp
// errors internally and reports them through its struct, so no longjmp ever crosses our C++
// frames.
#include "tidepool/base/RgbaImage.h"

#include "tidepool/base/AtomicFile.h"

#include <new>
#include <utility>

#include <fmt/format.h>
#include <png.h>

namespace tidepool::base {

ImageResult ReadPng(const std::filesystem::path& path) {
    ImageResult result;
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (png_image_begin_read_from_file(&png, path.c_str()) == 0) {
        result.error = fmt::format("{}: cannot read PNG: {}", path.string(), png.message);
        png_image_free(&png);  // safe when libpng already freed it
        return result;
    }
    if (png.width > static_cast<png_uint_32>(kMaxPngDimension) ||
        png.height > static_cast<png_uint_32>(kMaxPngDimension)) {
        result.error = fmt::format("{}: PNG is {}x{}, larger than the {}x{} this reader accepts",
                                   path.string(), png.width, png.height, kMaxPngDimension,
                                   kMaxPngDimension);
        png_image_free(&png);
        return result;
    }
    png.format = PNG_FORMAT_RGBA;
    // Without this, libpng takes untagged 16-bit data as linear and re-encodes it to sRGB.
    png.flags |= PNG_IMAGE_FLAG_16BIT_sRGB;
    RgbaImage image;
    image.width = static_cast<int>(png.width);
    image.height = static_cast<int>(png.height);
    try {
        image.pixels.assign(PNG_IMAGE_SIZE(png), 0);
    } catch (const std::bad_alloc&) {
        result.error = fmt::format("{}: out of memory for a {}x{} image", path.string(), png.width,
                                   png.height);
        png_image_free(&png);
        return result;
    }
    if (png_image_finish_read(&png, nullptr, image.pixels.data(), 0, nullptr) == 0) {
        result.error = fmt::format("{}: corrupt or truncated PNG: {}", path.string(), png.message);
        png_image_free(&png);
        return result;
    }
    result.image = std::move(image);
    return result;
}

std::string EncodePng(const RgbaImage& image, std::string* encoded, PngEncoding encoding) {
    if (!image.IsWellFormed()) {
        return fmt::format("cannot write PNG: a {}x{} image needs {} bytes of pixels, not {}",
                           image.width, image.height,
                           image.width > 0 && image.height > 0 ? image.PixelCount() * 4 : 0,
                           image.pixels.size());
    }
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(image.width);
    png.height = static_cast<png_uint_32>(image.height);
    png.format = PNG_FORMAT_RGBA;
    png.flags = encoding == PngEncoding::kFast ? PNG_IMAGE_FLAG_FAST : 0;
    // Encoded once into a buffer of libpng's own upper bound, not sized by a first encoding:
    // the report encodes a hundred images, and that halves its time.
    png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
    encoded->assign(size, '\0');
    if (png_image_write_to_memory(&png, encoded->data(), &size, 0, image.pixels.data(), 0,
                                  nullptr) == 0) {
        return fmt::format("cannot encode PNG: {}", png.message);
    }
    encoded->resize(size);
    return "";
}

std::string WritePngAtomically(const std::filesystem::path& path, const RgbaImage& image) {
    std::string encoded;
    if (std::string error = EncodePng(image, &encoded, PngEncoding::kFast); !error.empty()) {
        return path.string() + ": " + error;
    }
    return WriteFileAtomically(path, encoded);
}

}  // namespace tidepool::base
