// PNG reading and atomic writing, PSNR, SSIM, share of visibly different pixels, heat maps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "TempDir.h"
#include "tidepool/report/ImageMetrics.h"

namespace tidepool::report {
namespace {

using testing::TempDir;

struct Rgba {
    int r, g, b, a;
};

RgbaImage MakeImage(int width, int height, const std::function<Rgba(int, int)>& colour) {
    RgbaImage image;
    image.width = width;
    image.height = height;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const Rgba c = colour(x, y);
            for (const int v : {c.r, c.g, c.b, c.a}) {
                image.pixels.push_back(static_cast<std::uint8_t>(std::clamp(v, 0, 255)));
            }
        }
    }
    return image;
}

Rgba PixelAt(const RgbaImage& image, int x, int y) {
    const int pixel = y * image.width + x;
    const auto i = static_cast<std::size_t>(pixel) * 4;
    return {image.pixels[i], image.pixels[i + 1], image.pixels[i + 2], image.pixels[i + 3]};
}

// A 40 x 30 test pattern with structure at several scales; the scikit-image reference values
// below were computed on exactly these formulas.
Rgba Pattern(int x, int y) {
    return {(x * 7 + y * 13) % 256, (x * x + 3 * y) % 256, (x * y) % 256, 255};
}
RgbaImage PatternImage() {
    return MakeImage(40, 30, Pattern);
}

std::string FileContents(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void ExpectPixel(const RgbaImage& image, int x, int y, Rgba expected) {
    const Rgba actual = PixelAt(image, x, y);
    EXPECT_EQ(actual.r, expected.r) << "at " << x << "," << y;
    EXPECT_EQ(actual.g, expected.g) << "at " << x << "," << y;
    EXPECT_EQ(actual.b, expected.b) << "at " << x << "," << y;
    EXPECT_EQ(actual.a, expected.a) << "at " << x << "," << y;
}

// --- PSNR ------------------------------------------------------------------------------------

TEST(ReportImageMetricsTest, PsnrOfIdenticalImagesIsInfinite) {
    EXPECT_EQ(Psnr(PatternImage(), PatternImage()), std::numeric_limits<double>::infinity());
}

TEST(ReportImageMetricsTest, PsnrOfConstantOffsetOfTenIs28Point13Decibels) {
    const RgbaImage a = MakeImage(8, 8, [](int, int) { return Rgba{100, 150, 200, 255}; });
    const RgbaImage b = MakeImage(8, 8, [](int, int) { return Rgba{110, 140, 210, 255}; });
    // MSE = 100, so 10 log10(255^2 / 100) = 20 log10(25.5) = 28.1308 dB.
    EXPECT_NEAR(Psnr(a, b), 20 * std::log10(255.0 / 10.0), 1e-12);
    EXPECT_NEAR(Psnr(a, b), 28.1308, 1e-4);
}

TEST(ReportImageMetricsTest, PsnrIgnoresAlpha) {
    const RgbaImage a = MakeImage(4, 4, [](int, int) { return Rgba{1, 2, 3, 255}; });
    const RgbaImage b = MakeImage(4, 4, [](int, int) { return Rgba{1, 2, 3, 0}; });
    EXPECT_EQ(Psnr(a, b), std::numeric_limits<double>::infinity());
}

TEST(ReportImageMetricsTest, PsnrOfDifferentSizesOrMalformedImagesIsNaN) {
    const RgbaImage a = MakeImage(4, 4, [](int, int) { return Rgba{0, 0, 0, 255}; });
    const RgbaImage b = MakeImage(4, 5, [](int, int) { return Rgba{0, 0, 0, 255}; });
    RgbaImage short_pixels = a;
    short_pixels.pixels.pop_back();
    EXPECT_TRUE(std::isnan(Psnr(a, b)));
    EXPECT_TRUE(std::isnan(Psnr(a, short_pixels)));
    EXPECT_TRUE(std::isnan(Psnr(RgbaImage{}, RgbaImage{})));
}

// --- SSIM ------------------------------------------------------------------------------------

TEST(ReportImageMetricsTest, SsimOfIdenticalImagesIsOne) {
    EXPECT_DOUBLE_EQ(Ssim(PatternImage(), PatternImage()), 1.0);
}

TEST(ReportImageMetricsTest, SsimOfAnImageAndItsInverseIsFarBelowOne) {
    const RgbaImage inverse = MakeImage(40, 30, [](int x, int y) {
        const Rgba c = Pattern(x, y);
        return Rgba{255 - c.r, 255 - c.g, 255 - c.b, 255};
    });
    EXPECT_LT(Ssim(PatternImage(), inverse), 0.0);  // anti-correlated structure
}

TEST(ReportImageMetricsTest, SsimIsSymmetric) {
    const RgbaImage noisy = MakeImage(40, 30, [](int x, int y) {
        const Rgba c = Pattern(x, y);
        const int d = (x * 5 + y * 3) % 21 - 10;
        return Rgba{c.r + d, c.g + d, c.b + d, 255};
    });
    EXPECT_EQ(Ssim(PatternImage(), noisy), Ssim(noisy, PatternImage()));
}

// Reference values from scikit-image 0.19.3, structural_similarity(luma_a, luma_b,
// gaussian_weights=True, sigma=1.5, use_sample_covariance=False, data_range=255) on the float64
// Rec. 601 luma of the same images: that is Wang et al.'s definition, as Ssim implements it.
// 1e-9: the two sum the same terms in a different order.
TEST(ReportImageMetricsTest, SsimMatchesScikitImageOnANoisyImage) {
    const RgbaImage noisy = MakeImage(40, 30, [](int x, int y) {
        const Rgba c = Pattern(x, y);
        const int d = (x * 5 + y * 3) % 21 - 10;
        return Rgba{c.r + d, c.g + d, c.b + d, 255};  // MakeImage clamps to 0..255
    });
    EXPECT_NEAR(Ssim(PatternImage(), noisy), 0.9848782336163907, 1e-9);
}

TEST(ReportImageMetricsTest, SsimMatchesScikitImageOnAContrastReduction) {
    const RgbaImage flat = MakeImage(40, 30, [](int x, int y) {
        const Rgba c = Pattern(x, y);
        return Rgba{c.r / 2 + 40, c.g / 2 + 40, c.b / 2 + 40, 255};
    });
    EXPECT_NEAR(Ssim(PatternImage(), flat), 0.790398673606695, 1e-9);
}

TEST(ReportImageMetricsTest, SsimOfFlatImagesIsTheLuminanceTerm) {
    // No variance on either side, so only (2 mu_x mu_y + C1) / (mu_x^2 + mu_y^2 + C1) remains.
    const RgbaImage a = MakeImage(16, 16, [](int, int) { return Rgba{100, 100, 100, 255}; });
    const RgbaImage b = MakeImage(16, 16, [](int, int) { return Rgba{110, 110, 110, 255}; });
    const double c1 = (0.01 * 255) * (0.01 * 255);
    // 1e-9: the Gaussian weights sum to 1 only up to rounding, leaving ~1e-13 variance.
    EXPECT_NEAR(Ssim(a, b), (2 * 100.0 * 110.0 + c1) / (100.0 * 100.0 + 110.0 * 110.0 + c1), 1e-9);
}

TEST(ReportImageMetricsTest, SsimFailsOnDifferentSizesAndImagesSmallerThanTheWindow) {
    const RgbaImage small = MakeImage(10, 40, [](int, int) { return Rgba{0, 0, 0, 255}; });
    EXPECT_TRUE(std::isnan(Ssim(small, small)));
    EXPECT_TRUE(std::isnan(Ssim(PatternImage(), MakeImage(30, 40, Pattern))));
    const RgbaImage smallest = MakeImage(11, 11, [](int, int) { return Rgba{9, 9, 9, 255}; });
    EXPECT_DOUBLE_EQ(Ssim(smallest, smallest), 1.0);  // exactly one window position
}

// --- Share above threshold -------------------------------------------------------------------

TEST(ReportImageMetricsTest, ShareAboveThresholdCountsPixelsStrictlyAboveIt) {
    // 10 x 10 pixels: the first 25 differ by 9 in green (above 8), the next 10 by exactly 8 in
    // blue (not above), the next 10 only in alpha (ignored), the rest not at all.
    const RgbaImage a = MakeImage(10, 10, [](int, int) { return Rgba{50, 50, 50, 255}; });
    const RgbaImage b = MakeImage(10, 10, [](int x, int y) {
        const int i = y * 10 + x;
        if (i < 25) {
            return Rgba{50, 59, 50, 255};
        }
        if (i < 35) {
            return Rgba{50, 50, 42, 255};
        }
        if (i < 45) {
            return Rgba{50, 50, 50, 0};
        }
        return Rgba{50, 50, 50, 255};
    });
    EXPECT_DOUBLE_EQ(ShareAboveThreshold(a, b, kVisibleDifferenceThreshold), 0.25);
    EXPECT_DOUBLE_EQ(ShareAboveThreshold(a, b, 7.0), 0.35);
    EXPECT_DOUBLE_EQ(ShareAboveThreshold(a, a, 0.0), 0.0);
}

TEST(ReportImageMetricsTest, ShareAboveThresholdFailsOnDifferentSizesOrNaNThreshold) {
    EXPECT_TRUE(std::isnan(ShareAboveThreshold(PatternImage(), MakeImage(4, 4, Pattern), 8.0)));
    EXPECT_TRUE(std::isnan(ShareAboveThreshold(PatternImage(), PatternImage(), std::nan(""))));
}

// --- Heat map --------------------------------------------------------------------------------

TEST(ReportImageMetricsTest, HeatMapRampsFromBlackThroughRedAndYellowToWhite) {
    // Row 0 differs from `a` by 0, 10, 20, 30 and 100 codes in red; full scale is 30.
    const RgbaImage a = MakeImage(5, 2, [](int, int) { return Rgba{0, 0, 0, 255}; });
    const RgbaImage b = MakeImage(5, 2, [](int x, int y) {
        const int differences[] = {0, 10, 20, 30, 100};
        return Rgba{y == 0 ? differences[x] : 0, 0, 0, 128};
    });
    const RgbaImage heat = DifferenceHeatMap(a, b, 30.0);
    ASSERT_EQ(heat.width, 5);
    ASSERT_EQ(heat.height, 2);
    ASSERT_EQ(heat.pixels.size(), 5u * 2u * 4u);
    ExpectPixel(heat, 0, 0, {0, 0, 0, 255});        // no difference: black, opaque
    ExpectPixel(heat, 1, 0, {255, 0, 0, 255});      // a third of full scale: red
    ExpectPixel(heat, 2, 0, {255, 255, 0, 255});    // two thirds: yellow
    ExpectPixel(heat, 3, 0, {255, 255, 255, 255});  // full scale: white
    ExpectPixel(heat, 4, 0, {255, 255, 255, 255});  // beyond full scale saturates
    ExpectPixel(heat, 4, 1, {0, 0, 0, 255});        // an alpha-only difference is not shown
}

TEST(ReportImageMetricsTest, HeatMapFailsWithAnEmptyImage) {
    EXPECT_EQ(DifferenceHeatMap(PatternImage(), MakeImage(4, 4, Pattern), 32.0).width, 0);
    EXPECT_TRUE(DifferenceHeatMap(PatternImage(), PatternImage(), 0.0).pixels.empty());
    EXPECT_TRUE(DifferenceHeatMap(PatternImage(), PatternImage(), std::nan("")).pixels.empty());
}

// --- PNG input and output --------------------------------------------------------------------

TEST(ReportImageMetricsTest, PngRoundTripIsByteIdenticalIncludingAlpha) {
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

TEST(ReportImageMetricsTest, WritingOverAnExistingPngReplacesIt) {
    TempDir dir;
    const std::filesystem::path path = dir.Path() / "image.png";
    EXPECT_EQ(WritePngAtomically(path, MakeImage(2, 2, Pattern)), "");
    const RgbaImage second = MakeImage(3, 1, [](int x, int) { return Rgba{x, x, x, 255}; });
    EXPECT_EQ(WritePngAtomically(path, second), "");
    const ImageResult read = ReadPng(path);
    ASSERT_TRUE(read.image.has_value()) << read.error;
    EXPECT_EQ(read.image->pixels, second.pixels);
}

TEST(ReportImageMetricsTest, WritingAMalformedImageFailsNamingTheFile) {
    TempDir dir;
    const std::filesystem::path path = dir.Path() / "bad.png";
    RgbaImage image = MakeImage(2, 2, Pattern);
    image.pixels.pop_back();
    EXPECT_EQ(WritePngAtomically(path, image),
              path.string() + ": cannot write PNG: a 2x2 image needs 16 bytes of pixels, not 15");
    EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(ReportImageMetricsTest, WritingUnderARegularFileFailsNamingTheFolder) {
    TempDir dir;
    const std::filesystem::path blocker = dir.Write("blocker", "not a folder");
    const std::string error = WritePngAtomically(blocker / "image.png", MakeImage(2, 2, Pattern));
    EXPECT_EQ(error.rfind(blocker.string(), 0), 0u) << error;
}

TEST(ReportImageMetricsTest, ReadingAMissingFileFailsNamingTheFile) {
    TempDir dir;
    const std::filesystem::path path = dir.Path() / "missing.png";
    const ImageResult read = ReadPng(path);
    EXPECT_FALSE(read.image.has_value());
    EXPECT_EQ(read.error, path.string() + ": cannot read PNG: No such file or directory");
}

TEST(ReportImageMetricsTest, ReadingATruncatedPngFailsNamingTheFile) {
    TempDir dir;
    const std::filesystem::path whole = dir.Path() / "whole.png";
    ASSERT_EQ(WritePngAtomically(whole, PatternImage()), "");
    const std::string bytes = FileContents(whole);
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

TEST(ReportImageMetricsTest, ReadingAFileThatIsNotAPngFailsNamingTheFile) {
    TempDir dir;
    const std::filesystem::path path = dir.Write("notes.png", "this is text, not an image\n");
    const ImageResult read = ReadPng(path);
    EXPECT_FALSE(read.image.has_value());
    EXPECT_EQ(read.error.rfind(path.string() + ": cannot read PNG: ", 0), 0u) << read.error;
}

TEST(ReportImageMetricsTest, ReadingAPngWithCorruptImageDataFailsNamingTheFile) {
    TempDir dir;
    const std::filesystem::path whole = dir.Path() / "whole.png";
    ASSERT_EQ(WritePngAtomically(whole, PatternImage()), "");
    std::string bytes = FileContents(whole);
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

TEST(ReportImageMetricsTest, EightBitGreyIsReadAsOpaqueRgba) {
    TempDir dir;
    const ImageResult read = ReadPng(dir.Write("grey8.png", Bytes(kGray8)));
    ASSERT_TRUE(read.image.has_value()) << read.error;
    ExpectPixel(*read.image, 0, 0, {0, 0, 0, 255});
    ExpectPixel(*read.image, 1, 0, {128, 128, 128, 255});
    ExpectPixel(*read.image, 0, 1, {200, 200, 200, 255});
    ExpectPixel(*read.image, 1, 1, {255, 255, 255, 255});
}

TEST(ReportImageMetricsTest, UntaggedSixteenBitGreyIsTakenAsSrgbNotLinear) {
    TempDir dir;
    const ImageResult read = ReadPng(dir.Write("grey16.png", Bytes(kGray16)));
    ASSERT_TRUE(read.image.has_value()) << read.error;
    // Read as linear, 0x8080 would be re-encoded to about 188; as sRGB it is 0x80.
    ExpectPixel(*read.image, 0, 0, {128, 128, 128, 255});
    ExpectPixel(*read.image, 1, 0, {255, 255, 255, 255});
}

TEST(ReportImageMetricsTest, PaletteWithTransparencyIsReadAsRgba) {
    TempDir dir;
    const ImageResult read = ReadPng(dir.Write("palette.png", Bytes(kPalette)));
    ASSERT_TRUE(read.image.has_value()) << read.error;
    ExpectPixel(*read.image, 0, 0, {255, 0, 0, 255});
    ExpectPixel(*read.image, 1, 0, {0, 0, 255, 128});
}

TEST(ReportImageMetricsTest, ReadingAPngLargerThanTheLimitFailsBeforeAllocating) {
    TempDir dir;
    const std::filesystem::path path = dir.Write("wide.png", Bytes(kTooWide));
    const ImageResult read = ReadPng(path);
    EXPECT_FALSE(read.image.has_value());
    EXPECT_EQ(read.error,
              path.string() + ": PNG is 20000x1, larger than the 16384x16384 this reader accepts");
}

}  // namespace
}  // namespace tidepool::report
