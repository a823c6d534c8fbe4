// libpng's simplified API (png_image), which reports errors through its struct, not longjmp.
#include "tidepool/runner/ImageIo.h"

#include <png.h>

#include <string>

#include "tidepool/base/AtomicFile.h"

namespace tidepool::runner {

std::string WritePng(const std::filesystem::path& path, const ImageRgba8& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != static_cast<std::size_t>(image.width) *
                                    static_cast<std::size_t>(image.height) * 4) {
        return "image has no pixels or a size that does not match its pixel count";
    }
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(image.width);
    png.height = static_cast<png_uint_32>(image.height);
    png.format = PNG_FORMAT_RGBA;
    // libpng's fast setting: a run writes about 600 images, and at the default setting encoding
    // took a fifth of the render's CPU time for files only about a quarter smaller.
    png.flags = PNG_IMAGE_FLAG_FAST;
    // Encoded in memory into libpng's upper bound (asking for the exact size first encodes
    // twice), then written whole: a failed or killed write never leaves a short PNG.
    png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
    std::string encoded(size, '\0');
    if (png_image_write_to_memory(&png, encoded.data(), &size, 0, image.pixels.data(), 0,
                                  nullptr) == 0) {
        return "cannot encode " + path.string() + ": " + png.message;
    }
    encoded.resize(size);
    return base::WriteFileAtomically(path, encoded);
}

std::string ReadPng(const std::filesystem::path& path, ImageRgba8* image) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (png_image_begin_read_from_file(&png, path.c_str()) == 0) {
        return "cannot read " + path.string() + ": " + png.message;
    }
    png.format = PNG_FORMAT_RGBA;
    image->width = static_cast<int>(png.width);
    image->height = static_cast<int>(png.height);
    image->pixels.assign(PNG_IMAGE_SIZE(png), 0);
    if (png_image_finish_read(&png, nullptr, image->pixels.data(), 0, nullptr) == 0) {
        return "cannot decode " + path.string() + ": " + png.message;
    }
    return "";
}

}  // namespace tidepool::runner
