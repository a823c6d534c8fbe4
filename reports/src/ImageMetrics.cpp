// PNG input/output through libpng's simplified API (png_image), which catches libpng's longjmp
// errors internally and reports them through its struct, so no longjmp ever crosses our C++
// frames; and the image metrics, all over 8-bit code values with alpha ignored.
#include "tidepool/report/ImageMetrics.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>

#include <fmt/format.h>

#include "tidepool/base/AtomicFile.h"

namespace tidepool::report {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::size_t PixelCount(const RgbaImage& image) {
    return static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
}

bool IsWellFormed(const RgbaImage& image) {
    return image.width > 0 && image.height > 0 && image.pixels.size() == PixelCount(image) * 4;
}

// Two images the metrics can compare: both well formed and of the same size.
bool AreComparable(const RgbaImage& a, const RgbaImage& b) {
    return IsWellFormed(a) && IsWellFormed(b) && a.width == b.width && a.height == b.height;
}

// The largest absolute R, G or B difference of pixel `index` (alpha ignored).
int MaxColourDifference(const RgbaImage& a, const RgbaImage& b, std::size_t index) {
    const std::size_t base = index * 4;
    int largest = 0;
    for (std::size_t channel = 0; channel < 3; ++channel) {
        largest = std::max(largest,
                           std::abs(int{a.pixels[base + channel]} - int{b.pixels[base + channel]}));
    }
    return largest;
}

// Rec. 601 luma of every pixel, on the encoded 0..255 values as SSIM is usually applied.
std::vector<double> Luma(const RgbaImage& image) {
    std::vector<double> luma(PixelCount(image));
    for (std::size_t i = 0; i < luma.size(); ++i) {
        const std::uint8_t* pixel = &image.pixels[i * 4];
        luma[i] = 0.299 * pixel[0] + 0.587 * pixel[1] + 0.114 * pixel[2];
    }
    return luma;
}

// Normalised 1-D Gaussian of sigma 1.5 over kSsimWindow taps; the 2-D window is its outer
// product, which is what fspecial('gaussian', 11, 1.5) gives in Wang et al.'s reference code.
std::array<double, kSsimWindow> GaussianWindow() {
    constexpr double kSigma = 1.5;
    std::array<double, kSsimWindow> weights{};
    double total = 0;
    for (std::size_t k = 0; k < weights.size(); ++k) {
        const double offset = static_cast<double>(k) - (kSsimWindow - 1) / 2.0;
        weights[k] = std::exp(-offset * offset / (2 * kSigma * kSigma));
        total += weights[k];
    }
    for (double& weight : weights) {
        weight /= total;
    }
    return weights;
}

}  // namespace

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

std::string WritePngAtomically(const std::filesystem::path& path, const RgbaImage& image) {
    if (!IsWellFormed(image)) {
        return fmt::format("{}: cannot write PNG: a {}x{} image needs {} bytes of pixels, not {}",
                           path.string(), image.width, image.height,
                           image.width > 0 && image.height > 0 ? PixelCount(image) * 4 : 0,
                           image.pixels.size());
    }
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(image.width);
    png.height = static_cast<png_uint_32>(image.height);
    png.format = PNG_FORMAT_RGBA;
    png_alloc_size_t size = 0;
    if (png_image_write_get_memory_size(png, size, 0, image.pixels.data(), 0, nullptr) == 0) {
        return fmt::format("{}: cannot encode PNG: {}", path.string(), png.message);
    }
    std::string encoded(size, '\0');
    if (png_image_write_to_memory(&png, encoded.data(), &size, 0, image.pixels.data(), 0,
                                  nullptr) == 0) {
        return fmt::format("{}: cannot encode PNG: {}", path.string(), png.message);
    }
    encoded.resize(size);
    return base::WriteFileAtomically(path, encoded);
}

double Psnr(const RgbaImage& a, const RgbaImage& b) {
    if (!AreComparable(a, b)) {
        return kNaN;
    }
    // Exact in 64 bits: at most 255^2 * 3 * 16384^2 (about 5e13) for the largest image.
    std::uint64_t squared_error = 0;
    for (std::size_t i = 0; i < a.pixels.size(); i += 4) {
        for (std::size_t channel = 0; channel < 3; ++channel) {
            const int difference = int{a.pixels[i + channel]} - int{b.pixels[i + channel]};
            squared_error += static_cast<std::uint64_t>(difference * difference);
        }
    }
    if (squared_error == 0) {
        return std::numeric_limits<double>::infinity();
    }
    const double mean_squared_error =
            static_cast<double>(squared_error) / (3.0 * static_cast<double>(PixelCount(a)));
    return 10 * std::log10(255.0 * 255.0 / mean_squared_error);
}

double Ssim(const RgbaImage& a, const RgbaImage& b) {
    if (!AreComparable(a, b) || a.width < kSsimWindow || a.height < kSsimWindow) {
        return kNaN;
    }
    constexpr double kC1 = (0.01 * 255) * (0.01 * 255);  // Wang et al.'s K1 = 0.01, L = 255
    constexpr double kC2 = (0.03 * 255) * (0.03 * 255);  // K2 = 0.03
    constexpr std::size_t kTaps = kSsimWindow;
    constexpr std::size_t kMoments = 5;  // E[x], E[y], E[x^2], E[y^2], E[xy]
    const std::array<double, kSsimWindow> weights = GaussianWindow();
    const std::vector<double> x = Luma(a);
    const std::vector<double> y = Luma(b);
    const auto width = static_cast<std::size_t>(a.width);
    const auto height = static_cast<std::size_t>(a.height);
    const std::size_t out_width = width - kTaps + 1;  // positions where the window fits
    const std::size_t out_height = height - kTaps + 1;

    // The window is separable: filter rows horizontally into a ring of the last kTaps rows,
    // then filter that ring vertically, so memory stays a few rows whatever the image size.
    std::vector<double> ring(kMoments * kTaps * out_width);
    const auto slot = [&](std::size_t moment, std::size_t row, std::size_t column) -> double& {
        return ring[(moment * kTaps + row % kTaps) * out_width + column];
    };
    const auto filter_row = [&](std::size_t row) {
        for (std::size_t column = 0; column < out_width; ++column) {
            std::array<double, kMoments> sums{};
            for (std::size_t k = 0; k < kTaps; ++k) {
                const double xv = x[row * width + column + k];
                const double yv = y[row * width + column + k];
                const double w = weights[k];
                // w * (xv * yv), not (w * xv) * yv: keeps Ssim(a, b) == Ssim(b, a) bit for bit.
                sums[0] += w * xv;
                sums[1] += w * yv;
                sums[2] += w * (xv * xv);
                sums[3] += w * (yv * yv);
                sums[4] += w * (xv * yv);
            }
            for (std::size_t moment = 0; moment < kMoments; ++moment) {
                slot(moment, row, column) = sums[moment];
            }
        }
    };

    for (std::size_t row = 0; row + 1 < kTaps; ++row) {
        filter_row(row);
    }
    double total = 0;
    for (std::size_t top = 0; top < out_height; ++top) {
        filter_row(top + kTaps - 1);
        for (std::size_t column = 0; column < out_width; ++column) {
            std::array<double, kMoments> m{};
            for (std::size_t k = 0; k < kTaps; ++k) {
                for (std::size_t moment = 0; moment < kMoments; ++moment) {
                    m[moment] += weights[k] * slot(moment, top + k, column);
                }
            }
            const double mean_xy = m[0] * m[1];
            const double variance_x = m[2] - m[0] * m[0];
            const double variance_y = m[3] - m[1] * m[1];
            const double covariance = m[4] - mean_xy;
            total += ((2 * mean_xy + kC1) * (2 * covariance + kC2)) /
                     ((m[0] * m[0] + m[1] * m[1] + kC1) * (variance_x + variance_y + kC2));
        }
    }
    return total / static_cast<double>(out_width * out_height);
}

double ShareAboveThreshold(const RgbaImage& a, const RgbaImage& b, double threshold) {
    if (!AreComparable(a, b) || std::isnan(threshold)) {
        return kNaN;
    }
    const std::size_t pixels = PixelCount(a);
    std::size_t above = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
        if (MaxColourDifference(a, b, i) > threshold) {
            ++above;
        }
    }
    return static_cast<double>(above) / static_cast<double>(pixels);
}

RgbaImage DifferenceHeatMap(const RgbaImage& a, const RgbaImage& b, double full_scale) {
    if (!AreComparable(a, b) || !std::isfinite(full_scale) || full_scale <= 0) {
        return {};
    }
    // Differences are whole code values, so the ramp is a 256-entry table.
    std::array<std::array<std::uint8_t, 3>, 256> ramp{};
    for (std::size_t d = 0; d < ramp.size(); ++d) {
        const double t = std::min(static_cast<double>(d) / full_scale, 1.0);
        for (std::size_t channel = 0; channel < 3; ++channel) {
            // Red rises over the first third, green over the second, blue over the last.
            const double level = std::clamp(3 * t - static_cast<double>(channel), 0.0, 1.0);
            ramp[d][channel] = static_cast<std::uint8_t>(std::lround(level * 255));
        }
    }
    RgbaImage heat;
    heat.width = a.width;
    heat.height = a.height;
    heat.pixels.resize(a.pixels.size());
    for (std::size_t i = 0; i < PixelCount(a); ++i) {
        const auto& colour = ramp[static_cast<std::size_t>(MaxColourDifference(a, b, i))];
        std::copy(colour.begin(), colour.end(),
                  heat.pixels.begin() + static_cast<std::ptrdiff_t>(i * 4));
        heat.pixels[i * 4 + 3] = 255;
    }
    return heat;
}

}  // namespace tidepool::report
