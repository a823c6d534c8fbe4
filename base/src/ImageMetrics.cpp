// The image metrics, all over 8-bit code values with alpha ignored.
#include "tidepool/base/ImageMetrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace tidepool::base {
namespace {

constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

// Two images the metrics can compare: both well formed and of the same size.
bool AreComparable(const RgbaImage& a, const RgbaImage& b) {
    return a.IsWellFormed() && b.IsWellFormed() && a.width == b.width && a.height == b.height;
}

// The largest absolute R, G or B difference of pixel `index` (alpha ignored).
int MaxColourDifference(const RgbaImage& a, const RgbaImage& b, std::size_t index) {
    const std::size_t first = index * 4;
    int largest = 0;
    for (std::size_t channel = 0; channel < 3; ++channel) {
        largest = std::max(
                largest, std::abs(int{a.pixels[first + channel]} - int{b.pixels[first + channel]}));
    }
    return largest;
}

// Rec. 601 luma of every pixel, on the encoded 0..255 values as SSIM is usually applied.
std::vector<double> Luma(const RgbaImage& image) {
    std::vector<double> luma(image.PixelCount());
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

double Psnr(const RgbaImage& a, const RgbaImage& b) {
    if (!AreComparable(a, b)) {
        return kUndefined;
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
            static_cast<double>(squared_error) / (3.0 * static_cast<double>(a.PixelCount()));
    return 10 * std::log10(255.0 * 255.0 / mean_squared_error);
}

namespace {

constexpr double kSsimC1 = (0.01 * 255) * (0.01 * 255);  // Wang et al.'s K1 = 0.01, L = 255
constexpr double kSsimC2 = (0.03 * 255) * (0.03 * 255);  // K2 = 0.03
constexpr std::size_t kTaps = kSsimWindow;

// The per-pixel quantities whose windowed means SSIM needs: x is the compared image's luma,
// y the reference's.
enum class Moment { kX, kY, kXX, kYY, kXY };

// The filtering loops are built twice, for AVX2 and for any x86-64, and the loader picks one:
// a report filters hundreds of images, and 4 doubles per instruction instead of 2 nearly halve
// its time. AVX2 alone does not fuse multiply and add, so both give the same bits.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TIDEPOOL_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define TIDEPOOL_VECTOR_CLONES
#endif

// One row of one moment filtered horizontally: out[c] = sum over k of w[k] * q(c + k), the taps
// added in order k = 0..10. Each loop sweeps contiguous columns, which the compiler vectorises
// (a report computes hundreds of these).
TIDEPOOL_VECTOR_CLONES
void FilterRow(Moment moment, const double* x, const double* y, std::size_t out_width,
               const std::array<double, kSsimWindow>& weights, double* out) {
    std::fill(out, out + out_width, 0.0);
    for (std::size_t k = 0; k < kTaps; ++k) {
        const double w = weights[k];
        const double* xs = x + k;
        const double* ys = y + k;
        switch (moment) {
            case Moment::kX:
                for (std::size_t c = 0; c < out_width; ++c)
                    out[c] += w * xs[c];
                break;
            case Moment::kY:
                for (std::size_t c = 0; c < out_width; ++c)
                    out[c] += w * ys[c];
                break;
            case Moment::kXX:
                for (std::size_t c = 0; c < out_width; ++c)
                    out[c] += w * (xs[c] * xs[c]);
                break;
            case Moment::kYY:
                for (std::size_t c = 0; c < out_width; ++c)
                    out[c] += w * (ys[c] * ys[c]);
                break;
            case Moment::kXY:
                // w * (x * y), not (w * x) * y: keeps Ssim(a, b) == Ssim(b, a) bit for bit.
                for (std::size_t c = 0; c < out_width; ++c)
                    out[c] += w * (xs[c] * ys[c]);
                break;
        }
    }
}

// The horizontally filtered rows[0..10] filtered vertically: out[c] = sum over k of
// w[k] * rows[k][c], the taps added in order.
TIDEPOOL_VECTOR_CLONES
void FilterColumns(const std::array<const double*, kTaps>& rows,
                   const std::array<double, kSsimWindow>& weights, std::size_t out_width,
                   double* out) {
    std::fill(out, out + out_width, 0.0);
    for (std::size_t k = 0; k < kTaps; ++k) {
        const double w = weights[k];
        const double* in = rows[k];
        for (std::size_t c = 0; c < out_width; ++c) {
            out[c] += w * in[c];
        }
    }
}

// Filters `moments` over every position where the window fits: rows horizontally into a ring
// of the last kTaps rows, then the ring vertically, so memory stays a few rows whatever the
// image size; calls emit(top, filtered) with one out_width row per moment, in `moments`' order.
template <typename Emit>
void FilterWindows(const std::vector<Moment>& moments, const std::vector<double>& x,
                   const std::vector<double>& y, std::size_t width, std::size_t height,
                   const Emit& emit) {
    const std::array<double, kSsimWindow> weights = GaussianWindow();
    const std::size_t out_width = width - kTaps + 1;
    const std::size_t out_height = height - kTaps + 1;
    const std::size_t count = moments.size();
    std::vector<double> ring(count * kTaps * out_width);
    const auto ring_row = [&](std::size_t m, std::size_t row) {
        return ring.data() + (m * kTaps + row % kTaps) * out_width;
    };
    const auto filter_row = [&](std::size_t row) {
        for (std::size_t m = 0; m < count; ++m) {
            FilterRow(moments[m], x.data() + row * width, y.data() + row * width, out_width,
                      weights, ring_row(m, row));
        }
    };
    for (std::size_t row = 0; row + 1 < kTaps; ++row) {
        filter_row(row);
    }
    std::vector<double> filtered(count * out_width);
    for (std::size_t top = 0; top < out_height; ++top) {
        filter_row(top + kTaps - 1);
        for (std::size_t m = 0; m < count; ++m) {
            std::array<const double*, kTaps> rows{};
            for (std::size_t k = 0; k < kTaps; ++k) {
                rows[k] = ring_row(m, top + k);
            }
            FilterColumns(rows, weights, out_width, filtered.data() + m * out_width);
        }
        emit(top, filtered.data());
    }
}

}  // namespace

SsimReference::SsimReference(const RgbaImage& reference)
    : width_(reference.width), height_(reference.height) {
    if (!reference.IsWellFormed() || width_ < kSsimWindow || height_ < kSsimWindow) {
        return;
    }
    luma_ = Luma(reference);
    const auto width = static_cast<std::size_t>(width_);
    const auto height = static_cast<std::size_t>(height_);
    const std::size_t out_width = width - kTaps + 1;
    mean_.resize(out_width * (height - kTaps + 1));
    mean_square_.resize(mean_.size());
    FilterWindows({Moment::kY, Moment::kYY}, luma_, luma_, width, height,
                  [&](std::size_t top, const double* filtered) {
                      std::copy(filtered, filtered + out_width,
                                mean_.begin() + static_cast<std::ptrdiff_t>(top * out_width));
                      std::copy(
                              filtered + out_width, filtered + 2 * out_width,
                              mean_square_.begin() + static_cast<std::ptrdiff_t>(top * out_width));
                  });
    usable_ = true;
}

double SsimReference::Compare(const RgbaImage& image) const {
    if (!usable_ || !image.IsWellFormed() || image.width != width_ || image.height != height_) {
        return kUndefined;
    }
    const std::vector<double> x = Luma(image);
    const auto width = static_cast<std::size_t>(width_);
    const auto height = static_cast<std::size_t>(height_);
    const std::size_t out_width = width - kTaps + 1;
    const std::size_t out_height = height - kTaps + 1;
    double total = 0;
    FilterWindows({Moment::kX, Moment::kXX, Moment::kXY}, x, luma_, width, height,
                  [&](std::size_t top, const double* filtered) {
                      const double* m0 = filtered;
                      const double* m2 = filtered + out_width;
                      const double* m4 = filtered + 2 * out_width;
                      const double* m1 = mean_.data() + top * out_width;
                      const double* m3 = mean_square_.data() + top * out_width;
                      for (std::size_t c = 0; c < out_width; ++c) {
                          const double mean_xy = m0[c] * m1[c];
                          const double variance_x = m2[c] - m0[c] * m0[c];
                          const double variance_y = m3[c] - m1[c] * m1[c];
                          const double covariance = m4[c] - mean_xy;
                          total += ((2 * mean_xy + kSsimC1) * (2 * covariance + kSsimC2)) /
                                   ((m0[c] * m0[c] + m1[c] * m1[c] + kSsimC1) *
                                    (variance_x + variance_y + kSsimC2));
                      }
                  });
    return total / static_cast<double>(out_width * out_height);
}

double Ssim(const RgbaImage& a, const RgbaImage& b) {
    if (!AreComparable(a, b)) {
        return kUndefined;
    }
    return SsimReference(b).Compare(a);
}

double ShareAboveThreshold(const RgbaImage& a, const RgbaImage& b, double threshold) {
    if (!AreComparable(a, b) || std::isnan(threshold)) {
        return kUndefined;
    }
    const std::size_t pixels = a.PixelCount();
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
    for (std::size_t i = 0; i < a.PixelCount(); ++i) {
        const auto& colour = ramp[static_cast<std::size_t>(MaxColourDifference(a, b, i))];
        std::copy(colour.begin(), colour.end(),
                  heat.pixels.begin() + static_cast<std::ptrdiff_t>(i * 4));
        heat.pixels[i * 4 + 3] = 255;
    }
    return heat;
}

ImageAccuracy MeasureAccuracy(const RgbaImage& image, const RgbaImage& reference,
                              const SsimReference& reference_ssim) {
    return {Psnr(image, reference), reference_ssim.Compare(image),
            ShareAboveThreshold(image, reference, kVisibleDifferenceThreshold)};
}

}  // namespace tidepool::base
