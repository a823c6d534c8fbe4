// PSNR, SSIM, share of visibly different pixels, heat maps.
#include "tidepool/base/ImageMetrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "TestImages.h"

namespace tidepool::base {
namespace {

// --- PSNR ------------------------------------------------------------------------------------

TEST(ImageMetricsTest, PsnrOfIdenticalImagesIsInfinite) {
    EXPECT_EQ(Psnr(PatternImage(), PatternImage()), std::numeric_limits<double>::infinity());
}

TEST(ImageMetricsTest, PsnrOfConstantOffsetOfTenIs28Point13Decibels) {
    const RgbaImage a = MakeImage(8, 8, [](int, int) { return Rgba{100, 150, 200, 255}; });
    const RgbaImage b = MakeImage(8, 8, [](int, int) { return Rgba{110, 140, 210, 255}; });
    // MSE = 100, so 10 log10(255^2 / 100) = 20 log10(25.5) = 28.1308 dB.
    EXPECT_NEAR(Psnr(a, b), 20 * std::log10(255.0 / 10.0), 1e-12);
    EXPECT_NEAR(Psnr(a, b), 28.1308, 1e-4);
}

TEST(ImageMetricsTest, PsnrIgnoresAlpha) {
    const RgbaImage a = MakeImage(4, 4, [](int, int) { return Rgba{1, 2, 3, 255}; });
    const RgbaImage b = MakeImage(4, 4, [](int, int) { return Rgba{1, 2, 3, 0}; });
    EXPECT_EQ(Psnr(a, b), std::numeric_limits<double>::infinity());
}

TEST(ImageMetricsTest, PsnrOfDifferentSizesOrMalformedImagesIsNaN) {
    const RgbaImage a = MakeImage(4, 4, [](int, int) { return Rgba{0, 0, 0, 255}; });
    const RgbaImage b = MakeImage(4, 5, [](int, int) { return Rgba{0, 0, 0, 255}; });
    RgbaImage short_pixels = a;
    short_pixels.pixels.pop_back();
    EXPECT_TRUE(std::isnan(Psnr(a, b)));
    EXPECT_TRUE(std::isnan(Psnr(a, short_pixels)));
    EXPECT_TRUE(std::isnan(Psnr(RgbaImage{}, RgbaImage{})));
}

// --- SSIM ------------------------------------------------------------------------------------

TEST(ImageMetricsTest, SsimOfIdenticalImagesIsOne) {
    EXPECT_DOUBLE_EQ(Ssim(PatternImage(), PatternImage()), 1.0);
}

TEST(ImageMetricsTest, SsimOfAnImageAndItsInverseIsFarBelowOne) {
    const RgbaImage inverse = MakeImage(40, 30, [](int x, int y) {
        const Rgba c = Pattern(x, y);
        return Rgba{255 - c.r, 255 - c.g, 255 - c.b, 255};
    });
    EXPECT_LT(Ssim(PatternImage(), inverse), 0.0);  // anti-correlated structure
}

TEST(ImageMetricsTest, SsimIsSymmetric) {
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
// The render (image in memory) and the report (image read back) both measure accuracy this
// way: it must be the three metrics to the bit, and an identical image is infinitely close.
TEST(ImageMetricsTest, AccuracyIsPsnrSsimAndVisibleShareAgainstTheReference) {
    const RgbaImage noisy = MakeImage(40, 30, [](int x, int y) {
        const Rgba c = Pattern(x, y);
        const int d = (x * 7 + y * 11) % 25 - 12;
        return Rgba{c.r + d, c.g + d, c.b + d, 255};
    });
    const RgbaImage reference = PatternImage();
    const SsimReference moments(reference);
    const ImageAccuracy a = MeasureAccuracy(noisy, reference, moments);
    EXPECT_EQ(a.psnr_db, Psnr(noisy, reference));
    EXPECT_EQ(a.ssim, Ssim(noisy, reference));
    EXPECT_EQ(a.share_visible, ShareAboveThreshold(noisy, reference, kVisibleDifferenceThreshold));
    EXPECT_GT(a.share_visible, 0.0);
    const ImageAccuracy same = MeasureAccuracy(reference, reference, moments);
    EXPECT_TRUE(std::isinf(same.psnr_db));
    EXPECT_DOUBLE_EQ(same.ssim, 1.0);
    EXPECT_EQ(same.share_visible, 0.0);
}

TEST(ImageMetricsTest, SsimMatchesScikitImageOnANoisyImage) {
    const RgbaImage noisy = MakeImage(40, 30, [](int x, int y) {
        const Rgba c = Pattern(x, y);
        const int d = (x * 5 + y * 3) % 21 - 10;
        return Rgba{c.r + d, c.g + d, c.b + d, 255};  // MakeImage clamps to 0..255
    });
    EXPECT_NEAR(Ssim(PatternImage(), noisy), 0.9848782336163907, 1e-9);
}

TEST(ImageMetricsTest, SsimMatchesScikitImageOnAContrastReduction) {
    const RgbaImage flat = MakeImage(40, 30, [](int x, int y) {
        const Rgba c = Pattern(x, y);
        return Rgba{c.r / 2 + 40, c.g / 2 + 40, c.b / 2 + 40, 255};
    });
    EXPECT_NEAR(Ssim(PatternImage(), flat), 0.790398673606695, 1e-9);
}

TEST(ImageMetricsTest, SsimOfFlatImagesIsTheLuminanceTerm) {
    // No variance on either side, so only (2 mu_x mu_y + C1) / (mu_x^2 + mu_y^2 + C1) remains.
    const RgbaImage a = MakeImage(16, 16, [](int, int) { return Rgba{100, 100, 100, 255}; });
    const RgbaImage b = MakeImage(16, 16, [](int, int) { return Rgba{110, 110, 110, 255}; });
    const double c1 = (0.01 * 255) * (0.01 * 255);
    // 1e-9: the Gaussian weights sum to 1 only up to rounding, leaving ~1e-13 variance.
    EXPECT_NEAR(Ssim(a, b), (2 * 100.0 * 110.0 + c1) / (100.0 * 100.0 + 110.0 * 110.0 + c1), 1e-9);
}

TEST(ImageMetricsTest, SsimFailsOnDifferentSizesAndImagesSmallerThanTheWindow) {
    const RgbaImage small = MakeImage(10, 40, [](int, int) { return Rgba{0, 0, 0, 255}; });
    EXPECT_TRUE(std::isnan(Ssim(small, small)));
    EXPECT_TRUE(std::isnan(Ssim(PatternImage(), MakeImage(30, 40, Pattern))));
    const RgbaImage smallest = MakeImage(11, 11, [](int, int) { return Rgba{9, 9, 9, 255}; });
    EXPECT_DOUBLE_EQ(Ssim(smallest, smallest), 1.0);  // exactly one window position
}

// --- Share above threshold -------------------------------------------------------------------

TEST(ImageMetricsTest, ShareAboveThresholdCountsPixelsStrictlyAboveIt) {
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

TEST(ImageMetricsTest, ShareAboveThresholdFailsOnDifferentSizesOrNaNThreshold) {
    EXPECT_TRUE(std::isnan(ShareAboveThreshold(PatternImage(), MakeImage(4, 4, Pattern), 8.0)));
    EXPECT_TRUE(std::isnan(ShareAboveThreshold(PatternImage(), PatternImage(), std::nan(""))));
}

// --- Heat map --------------------------------------------------------------------------------

TEST(ImageMetricsTest, HeatMapRampsFromBlackThroughRedAndYellowToWhite) {
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

TEST(ImageMetricsTest, HeatMapFailsWithAnEmptyImage) {
    EXPECT_EQ(DifferenceHeatMap(PatternImage(), MakeImage(4, 4, Pattern), 32.0).width, 0);
    EXPECT_TRUE(DifferenceHeatMap(PatternImage(), PatternImage(), 0.0).pixels.empty());
    EXPECT_TRUE(DifferenceHeatMap(PatternImage(), PatternImage(), std::nan("")).pixels.empty());
}

}  // namespace
}  // namespace tidepool::base
