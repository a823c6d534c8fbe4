// PNG reading and atomic writing.
#include "tidepool/base/RgbaImage.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "FileContents.h"
#include "TempDir.h"
#include "TestImages.h"

namespace tidepool::base {
namespace {

using testing::ReadText;
using testing::TempDir;

// --- PNG input and output --------------------------------------------------------------------

TEST(RgbaImageTest, PngRoundTripIsByteIdenticalIncludingAlpha) {
    TempDir dir;
    const RgbaImage image = MakeImage(37, 23, [](int x, int y) {
        return Rgba{(x * 7 + y) % 256, (y * 11) % 256, (x * y) % 256, (x * 13 + y * 5) % 256};
    });
    const std::filesystem::path path = dir.Path() / "views" / "top.png";
    EXPECT_EQ(WritePngAtomically(path, image), "");
    const ImageResult read = ReadPng(path);
    ASSERT_TRUE(read.image.has_value()) << read.error;
    EXPECT_EQ(read.error, "");
    EXPECT_EQ(read.image->width, image.width);
    EXPECT_EQ(read.image->height, image.height);
    EXPECT_EQ(read.image->pixels, image.pixels);
    // Only the destination is left in the folder: the temporary file was renamed over it.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(path.parent_path()),
                            std::filesystem::directory_iterator()),
              1);
}

TEST(RgbaImageTest, WritingOverAnExistingPngReplacesIt) {
    TempDir dir;
    const std::filesystem::path path = dir.Path() / "image.png";
    EXPECT_EQ(WritePngAtomically(path, MakeImage(2, 2, Pattern)), "");
    const RgbaImage second = MakeImage(3, 1, [](int x, int) { return Rgba{x, x, x, 255}; });
    EXPECT_EQ(WritePngAtomically(path, second), "");
    const ImageResult read = ReadPng(path);
    ASSERT_TRUE(read.image.has_value()) << read.error;
    EXPECT_EQ(read.image->pixels, second.pixels);
}

TEST(RgbaImageTest, WritingAMalformedImageFailsNamingTheFile) {
    TempDir dir;
    const std::filesystem::path path = dir.Path() / "bad.png";
    RgbaImage image = MakeImage(2, 2, Pattern);
    image.pixels.pop_back();
    EXPECT_EQ(WritePngAtomically(path, image),
              path.string() + ": cannot write PNG: a 2x2 image needs 16 bytes of pixels, not 15");
    EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(RgbaImageTest, WritingUnderARegularFileFailsNamingTheFolder) {
    TempDir dir;
    const std::filesystem::path blocker = dir.Write("blocker", "not a folder");
    const std::string error = WritePngAtomically(blocker / "image.png", MakeImage(2, 2, Pattern));
    EXPECT_EQ(error.rfind(blocker.string(), 0), 0u) << error;
}

TEST(RgbaImageTest, ReadingAMissingFileFailsNamingTheFile) {
    TempDir dir;
    const std::filesystem::path path = dir.Path() / "missing.png";
    const ImageResult read = ReadPng(path);
    EXPECT_FALSE(read.image.has_value());
    EXPECT_EQ(read.error, path.string() + ": cannot read PNG: No such file or directory");
}

TEST(RgbaImageTest, ReadingATruncatedPngFailsNamingTheFile) {
    TempDir dir;
    const std::filesystem::path whole = dir.Path() / "whole.png";
    ASSERT_EQ(WritePngAtomically(whole, PatternImage()), "");
    const std::string bytes = ReadText(whole);
    // Cut inside the header, inside the image data, and inside the last IDAT's checksum (the
    // 12-byte IEND chunk follows it). A file missing only IEND has all its pixels and is read.
    for (const std::size_t keep : {std::size_t{20}, bytes.size() / 2, bytes.size() - 14}) {
        SCOPED_TRACE(keep);
        const std::filesystem::path cut =
                dir.Write("cut" + std::to_string(keep) + ".png", bytes.substr(0, keep));
        const ImageResult read = ReadPng(cut);
        EXPECT_FALSE(read.image.has_value());
        EXPECT_EQ(read.error.rfind(cut.string() + ": ", 0), 0u) << read.error;
    }
}

TEST(RgbaImageTest, ReadingAFileThatIsNotAPngFailsNamingTheFile) {
    TempDir dir;
    const std::filesystem::path path = dir.Write("notes.png", "this is text, not an image\n");
    const ImageResult read = ReadPng(path);
    EXPECT_FALSE(read.image.has_value());
    EXPECT_EQ(read.error.rfind(path.string() + ": cannot read PNG: ", 0), 0u) << read.error;
}

TEST(RgbaImageTest, ReadingAPngWithCorruptImageDataFailsNamingTheFile) {
    TempDir dir;
    const std::filesystem::path whole = dir.Path() / "whole.png";
    ASSERT_EQ(WritePngAtomically(whole, PatternImage()), "");
    std::string bytes = ReadText(whole);
    const std::size_t data = bytes.find("IDAT");
    ASSERT_NE(data, std::string::npos);
    for (std::size_t i = data + 8; i < data + 40; ++i) {
        bytes[i] = static_cast<char>(bytes[i] ^ 0x5a);
    }
    const std::filesystem::path path = dir.Write("corrupt.png", bytes);
    const ImageResult read = ReadPng(path);
    EXPECT_FALSE(read.image.has_value());
    EXPECT_EQ(read.error.rfind(path.string() + ": corrupt or truncated PNG: ", 0), 0u)
            << read.error;
}

// Hand-made PNGs (generated with Python's zlib and struct) in the formats the runner never
// writes, to check that ReadPng converts them to RGBA8.

// 2 x 2, 8-bit grey: rows [0, 128] and [200, 255].
constexpr unsigned char kGray8[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
        0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x00, 0x00, 0x00, 0x00, 0x57,
        0xdd, 0x52, 0xf8, 0x00, 0x00, 0x00, 0x0e, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x60,
        0x68, 0x60, 0x38, 0xf1, 0x1f, 0x00, 0x04, 0x95, 0x02, 0x48, 0x11, 0xa8, 0xf6, 0xe3, 0x00,
        0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
// 2 x 1, 16-bit grey without gAMA or sRGB: 0x8080 and 0xffff.
constexpr unsigned char kGray16[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
        0x44, 0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x01, 0x10, 0x00, 0x00, 0x00,
        0x00, 0x81, 0xd9, 0xfc, 0x15, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x44, 0x41, 0x54, 0x78,
        0x9c, 0x63, 0x68, 0x68, 0xf8, 0xff, 0x1f, 0x00, 0x06, 0x82, 0x02, 0xff, 0xb3, 0xbe,
        0x51, 0x33, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
// 2 x 1, palette: entry 0 opaque red, entry 1 blue with tRNS alpha 128.
constexpr unsigned char kPalette[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
        0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x01, 0x08, 0x03, 0x00, 0x00, 0x00, 0xc3,
        0xfc, 0x8f, 0xb8, 0x00, 0x00, 0x00, 0x06, 0x50, 0x4c, 0x54, 0x45, 0xff, 0x00, 0x00, 0x00,
        0x00, 0xff, 0x6c, 0xa1, 0xfd, 0x8e, 0x00, 0x00, 0x00, 0x02, 0x74, 0x52, 0x4e, 0x53, 0xff,
        0x80, 0x08, 0x0f, 0xb3, 0x6a, 0x00, 0x00, 0x00, 0x0b, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c,
        0x63, 0x60, 0x60, 0x04, 0x00, 0x00, 0x04, 0x00, 0x02, 0xbf, 0x7a, 0x3f, 0x4a, 0x00, 0x00,
        0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
// An IHDR claiming 20000 x 1 RGBA, a 16-byte IDAT and IEND.
constexpr unsigned char kTooWide[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
        0x44, 0x52, 0x00, 0x00, 0x4e, 0x20, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00,
        0x00, 0x3b, 0xb4, 0x9e, 0x8e, 0x00, 0x00, 0x00, 0x0b, 0x49, 0x44, 0x41, 0x54, 0x78,
        0x9c, 0x63, 0x60, 0x40, 0x05, 0x00, 0x00, 0x10, 0x00, 0x01, 0x39, 0xbd, 0x8f, 0x65,
        0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

template <std::size_t N>
std::string_view Bytes(const unsigned char (&bytes)[N]) {
    return {reinterpret_cast<const char*>(bytes), N};
}

TEST(RgbaImageTest, EightBitGreyIsReadAsOpaqueRgba) {
    TempDir dir;
    const ImageResult read = ReadPng(dir.Write("grey8.png", Bytes(kGray8)));
    ASSERT_TRUE(read.image.has_value()) << read.error;
    ExpectPixel(*read.image, 0, 0, {0, 0, 0, 255});
    ExpectPixel(*read.image, 1, 0, {128, 128, 128, 255});
    ExpectPixel(*read.image, 0, 1, {200, 200, 200, 255});
    ExpectPixel(*read.image, 1, 1, {255, 255, 255, 255});
}

TEST(RgbaImageTest, UntaggedSixteenBitGreyIsTakenAsSrgbNotLinear) {
    TempDir dir;
    const ImageResult read = ReadPng(dir.Write("grey16.png", Bytes(kGray16)));
    ASSERT_TRUE(read.image.has_value()) << read.error;
    // Read as linear, 0x8080 would be re-encoded to about 188; as sRGB it is 0x80.
    ExpectPixel(*read.image, 0, 0, {128, 128, 128, 255});
    ExpectPixel(*read.image, 1, 0, {255, 255, 255, 255});
}

TEST(RgbaImageTest, PaletteWithTransparencyIsReadAsRgba) {
    TempDir dir;
    const ImageResult read = ReadPng(dir.Write("palette.png", Bytes(kPalette)));
    ASSERT_TRUE(read.image.has_value()) << read.error;
    ExpectPixel(*read.image, 0, 0, {255, 0, 0, 255});
    ExpectPixel(*read.image, 1, 0, {0, 0, 255, 128});
}

TEST(RgbaImageTest, ReadingAPngLargerThanTheLimitFailsBeforeAllocating) {
    TempDir dir;
    const std::filesystem::path path = dir.Write("wide.png", Bytes(kTooWide));
    const ImageResult read = ReadPng(path);
    EXPECT_FALSE(read.image.has_value());
    EXPECT_EQ(read.error,
              path.string() + ": PNG is 20000x1, larger than the 16384x16384 this reader accepts");
}

}  // namespace
}  // namespace tidepool::base
