// Small images for the image tests (RgbaImageTest, ImageMetricsTest): made from a colour
// function, read back pixel by pixel, and a fixed pattern with structure at several scales.
#pragma once

#include "tidepool/base/RgbaImage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>

// In base's namespace, beside the type they make, so the image tests use them unqualified.
namespace tidepool::base {

struct Rgba {
    int r, g, b, a;
};

inline RgbaImage MakeImage(int width, int height, const std::function<Rgba(int, int)>& colour) {
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

inline Rgba PixelAt(const RgbaImage& image, int x, int y) {
    const int pixel = y * image.width + x;
    const auto i = static_cast<std::size_t>(pixel) * 4;
    return {image.pixels[i], image.pixels[i + 1], image.pixels[i + 2], image.pixels[i + 3]};
}

// A 40 x 30 test pattern with structure at several scales; the scikit-image reference values
// in ImageMetricsTest were computed on exactly these formulas.
inline Rgba Pattern(int x, int y) {
    return {(x * 7 + y * 13) % 256, (x * x + 3 * y) % 256, (x * y) % 256, 255};
}
inline RgbaImage PatternImage() {
    return MakeImage(40, 30, Pattern);
}

inline void ExpectPixel(const RgbaImage& image, int x, int y, Rgba expected) {
    const Rgba actual = PixelAt(image, x, y);
    EXPECT_EQ(actual.r, expected.r) << "at " << x << "," << y;
    EXPECT_EQ(actual.g, expected.g) << "at " << x << "," << y;
    EXPECT_EQ(actual.b, expected.b) << "at " << x << "," << y;
    EXPECT_EQ(actual.a, expected.a) << "at " << x << "," << y;
}

}  // namespace tidepool::base
