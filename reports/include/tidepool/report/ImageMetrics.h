// Image comparison for the report: PNG reading and atomic writing, PSNR, SSIM, the share of
// visibly different pixels, and a difference heat map. A configuration's image at a view is
// compared with the reference configuration's image at the same view, so the two images always
// have the same size; a size mismatch is reported as a failure value, never thrown.
//
// All metrics work on the 8-bit sRGB-encoded values as stored, ignore alpha (renders are
// composited opaque, so alpha differences are never seen), and measure differences in 8-bit
// code values (0..255).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tidepool::report {

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

/// Largest width or height ReadPng accepts: 16384 is the largest render target Mesa's llvmpipe
/// offers (and above any view we render), so a larger header is a corrupt or foreign file and
/// must not make us allocate gigabytes.
inline constexpr int kMaxPngDimension = 16384;

/// An 8-bit RGBA image, rows top to bottom, 4 bytes per pixel, no padding between rows.
struct RgbaImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;  // width * height * 4 bytes
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
/// embedded in index.html), kFast for files on disk (libpng's fast setting: about a fifth of the
/// time for files about a third larger).
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

/// An opaque image of the same size whose pixels show the largest absolute R, G or B difference
/// d as t = min(d / full_scale, 1) on a black -> red -> yellow -> white ramp (t = 0 black, 1/3
/// red, 2/3 yellow, 1 white). Fails (returns an empty image, width and height 0) when the sizes
/// differ, an image is empty or malformed, or full_scale is not finite and positive.
RgbaImage DifferenceHeatMap(const RgbaImage& a, const RgbaImage& b, double full_scale);

}  // namespace tidepool::report
