// Image comparison for the report and the scene planner: PSNR, SSIM, the share of visibly
// different pixels, and a difference heat map. A configuration's image at a view is
// compared with the reference configuration's image at the same view, so the two images always
// have the same size; a size mismatch is reported as a failure value, never thrown.
//
// All metrics work on the 8-bit sRGB-encoded values as stored, ignore alpha (renders are
// composited opaque, so alpha differences are never seen), and measure differences in 8-bit
// code values (0..255).
#pragma once

#include "tidepool/base/RgbaImage.h"

#include <vector>

namespace tidepool::base {

/// Default `threshold` for ShareAboveThreshold, in 8-bit code values: 8 / 255, about 3% of full
/// scale. sRGB encoding is roughly perceptually uniform, and for typical mid-tone content a step
/// of 2-3% of full scale is about where a difference becomes just noticeable on a normal display;
/// it is also well above the 1-2 code rounding differences that precision variants and driver
/// rounding produce, so the share counts what a viewer could see, not rounding noise.
inline constexpr double kVisibleDifferenceThreshold = 8.0;

/// A suggested `full_scale` for DifferenceHeatMap, in 8-bit code values: 32 (12.5% of full
/// scale) puts the just-visible difference (kVisibleDifferenceThreshold) a quarter of the way up
/// the ramp, clearly off black, while any difference past 32 codes is glaring and may saturate
/// to white.
inline constexpr double kHeatMapFullScale = 32.0;

/// Side of the Gaussian window Ssim uses (sigma 1.5, 11 x 11, as Wang et al. 2004).
inline constexpr int kSsimWindow = 11;

/// Peak signal-to-noise ratio in dB over R, G and B with peak 255: 10 log10(255^2 / MSE).
/// Returns +infinity for identical colour channels. Fails (returns NaN) when the sizes differ or
/// an image is empty or malformed (pixel count not width * height * 4).
double Psnr(const RgbaImage& a, const RgbaImage& b);

/// Mean structural similarity (Wang et al. 2004) on Rec. 601 luma (Y = 0.299 R + 0.587 G +
/// 0.114 B of the encoded values), with an 11 x 11 Gaussian window (sigma 1.5), C1 = (0.01 *
/// 255)^2, C2 = (0.03 * 255)^2, averaged over every position where the window lies wholly inside
/// the image (no padding; no downsampling). Gives 1 for identical images, less the more the
/// local structure differs (can be negative), and is symmetric in a and b. The Gaussian window
/// rather than 8 x 8 blocks because it is the published standard (MATLAB's ssim, scikit-image
/// with gaussian_weights) so figures compare with others', and it has no block artefacts. Fails
/// (returns NaN) when the sizes differ, an image is malformed, or it is smaller than
/// kSsimWindow in either direction.
double Ssim(const RgbaImage& a, const RgbaImage& b);

/// Ssim against one fixed reference: its luma and windowed local moments are computed once, so
/// comparing many images with it (every configuration of a run against the reference, at each
/// view) costs three of the five windowed moments each. Compare(image) equals
/// Ssim(image, reference) to the bit; it fails (NaN) as Ssim does.
class SsimReference {
public:
    /// Prepares `reference`; an unusable one (malformed, smaller than the window) makes every
    /// Compare NaN.
    explicit SsimReference(const RgbaImage& reference);
    /// The mean SSIM of `image` against the reference.
    double Compare(const RgbaImage& image) const;

private:
    int width_ = 0;
    int height_ = 0;
    bool usable_ = false;
    std::vector<double> luma_;         // the reference's luma
    std::vector<double> mean_;         // its windowed mean at every window position
    std::vector<double> mean_square_;  // its windowed mean of squares
};

/// Fraction (0..1) of pixels whose largest absolute R, G or B difference exceeds `threshold`
/// code values (strictly greater; see kVisibleDifferenceThreshold for a default). Fails
/// (returns NaN) when the sizes differ, an image is empty or malformed, or threshold is NaN.
double ShareAboveThreshold(const RgbaImage& a, const RgbaImage& b, double threshold);

/// How far an image is from a reference: what the report's accuracy axis shows.
struct ImageAccuracy {
    double psnr_db = 0;        // +infinity when identical
    double ssim = 0;           // mean SSIM
    double share_visible = 0;  // share of pixels above kVisibleDifferenceThreshold, 0..1
};

/// `image` against `reference`, whose SSIM moments `reference_ssim` holds. The render measures
/// each image this way while it is in memory, and the report for images it reads back, so the
/// two give the same bits. Fails (NaN fields) as Psnr, Ssim and ShareAboveThreshold do.
ImageAccuracy MeasureAccuracy(const RgbaImage& image, const RgbaImage& reference,
                              const SsimReference& reference_ssim);

/// An opaque image of the same size whose pixels show the largest absolute R, G or B difference
/// d as t = min(d / full_scale, 1) on a black -> red -> yellow -> white ramp (t = 0 black, 1/3
/// red, 2/3 yellow, 1 white). Fails (returns an empty image, width and height 0) when the sizes
/// differ, an image is empty or malformed, or full_scale is not finite and positive.
RgbaImage DifferenceHeatMap(const RgbaImage& a, const RgbaImage& b, double full_scale);

}  // namespace tidepool::base
