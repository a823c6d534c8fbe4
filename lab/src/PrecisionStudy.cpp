#include "tidepool/lab/PrecisionStudy.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <type_traits>
#include <utility>

namespace tidepool::lab {

double RoundToHalf(double value) {
    if (!std::isfinite(value) || value == 0.0) {
        return value;
    }
    // 65504 is the largest half; everything from halfway to the next binade step (65520) up
    // rounds to infinity.
    const double magnitude = std::abs(value);
    if (magnitude >= 65520.0) {
        return std::copysign(std::numeric_limits<double>::infinity(), value);
    }
    // 11 significant bits; below 2^-14 the spacing stays 2^-24 (subnormals).
    const int exponent = std::max(static_cast<int>(std::floor(std::log2(magnitude))), -14);
    const double spacing = std::ldexp(1.0, exponent - 10);
    return std::nearbyint(value / spacing) * spacing;  // ties to even in the default mode
}

Half operator+(Half a, Half b) {
    return Half(a.value + b.value);
}
Half operator-(Half a, Half b) {
    return Half(a.value - b.value);
}
Half operator-(Half a) {
    return Half(-a.value);
}
Half operator*(Half a, Half b) {
    return Half(a.value * b.value);
}
Half operator/(Half a, Half b) {
    return Half(a.value / b.value);
}
bool operator<(Half a, Half b) {
    return a.value < b.value;
}
bool operator>(Half a, Half b) {
    return a.value > b.value;
}

namespace {

double ToDouble(float v) {
    return static_cast<double>(v);
}
double ToDouble(double v) {
    return v;
}
double ToDouble(Half v) {
    return v.value;
}

float Sqrt(float v) {
    return std::sqrt(v);
}
double Sqrt(double v) {
    return std::sqrt(v);
}
Half Sqrt(Half v) {
    return Half(std::sqrt(v.value));
}
// inversesqrt as one rounded operation, as GPUs implement it.
float InverseSqrt(float v) {
    return 1.0F / std::sqrt(v);
}
double InverseSqrt(double v) {
    return 1.0 / std::sqrt(v);
}
Half InverseSqrt(Half v) {
    return Half(1.0 / std::sqrt(v.value));
}

template <typename S>
S Max(S a, S b) {
    return a < b ? b : a;
}
template <typename S>
S Min(S a, S b) {
    return b < a ? b : a;
}
template <typename S>
S Abs(S a) {
    return a < S(0) ? -a : a;
}
template <typename S>
S Clamp(S v, S low, S high) {
    return Min(Max(v, low), high);
}

template <typename S>
struct V3 {
    S x, y, z;
};
template <typename S>
S Dot(const V3<S>& a, const V3<S>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename S>
V3<S> Scale(const V3<S>& a, S s) {
    return {a.x * s, a.y * s, a.z * s};
}

using Inputs = std::vector<double>;
using Outputs = std::vector<double>;

template <typename S>
V3<S> In3(const Inputs& in, std::size_t first) {
    return {S(in[first]), S(in[first + 1]), S(in[first + 2])};
}
template <typename S>
Outputs Out3(const V3<S>& v) {
    return {ToDouble(v.x), ToDouble(v.y), ToDouble(v.z)};
}

// ---- The expressions, as water.fsh writes them (S is the precision) -------------------------

// Constants of the default settings (Renderer.h): WaveDistortion 100 (texture units, the
// demo's), a 640-wide target, water fog reaching 1 at 2000 units, bump layer 1 at 1/15 per unit.
constexpr double kWaveDistortion = 100.0;
constexpr double kRcpWidth = 1.0 / 640.0;
constexpr double kRcpFogDistance = 1.0 / 2000.0;
constexpr double kBumpScale = 1.0 / 15.0;
constexpr double kMinEyeDistance = 1e-3;

template <typename S>
S EyeLengthUnscaled(const V3<S>& e) {
    return Sqrt(Dot(e, e));
}

template <typename S>
std::pair<S, V3<S>> EyeScaled(const V3<S>& e) {
    const S scale = Max(Max(Abs(e.x), Abs(e.y)), Max(Abs(e.z), S(kMinEyeDistance)));
    const S rcp = S(1) / scale;  // a vector divide: one reciprocal, three multiplies
    return {scale, Scale(e, rcp)};
}

template <typename S>
S EyeLengthScaled(const V3<S>& e) {
    const auto [scale, scaled] = EyeScaled(e);
    return Max(scale * Sqrt(Dot(scaled, scaled)), S(kMinEyeDistance));
}

template <typename S>
V3<S> EyeDirectionUnscaled(const V3<S>& e) {
    return Scale(e, InverseSqrt(Max(Dot(e, e), S(1e-8))));
}

template <typename S>
V3<S> EyeDirectionScaled(const V3<S>& e) {
    const auto [scale, scaled] = EyeScaled(e);
    return Scale(scaled, InverseSqrt(Max(Dot(scaled, scaled), S(1e-4))));
}

template <typename S>
S Schlick(S cos_incidence) {
    const S r0 = S(0.02037);
    const S m = S(1) - cos_incidence;
    const S m2 = m * m;
    return r0 + (S(1) - r0) * (m2 * m2 * m);
}

template <typename S>
S ExactFresnel(S cos_i) {
    const S n1 = S(1.000293);
    const S n2 = S(1.333333);
    const S eta = n1 / n2;
    const S sin_t2 = eta * eta * (S(1) - cos_i * cos_i);
    const S cos_t = Sqrt(Max(S(1) - sin_t2, S(0)));
    const S rs = (n1 * cos_i - n2 * cos_t) / Max(n1 * cos_i + n2 * cos_t, S(1e-4));
    const S rp = (n1 * cos_t - n2 * cos_i) / Max(n1 * cos_t + n2 * cos_i, S(1e-4));
    return S(0.5) * (rs * rs + rp * rp);
}

template <typename S>
V3<S> NormaliseBump(const V3<S>& n) {
    return Scale(n, InverseSqrt(Max(Dot(n, n), S(1e-4))));
}

// The whole Fresnel chain of the full variant: bump normal and eye direction normalised, cos
// clamped, Schlick.
template <typename S>
S FresnelChain(const V3<S>& bump, const V3<S>& eye) {
    return Schlick(Clamp(Dot(NormaliseBump(bump), EyeDirectionScaled(eye)), S(0), S(1)));
}

template <typename S>
S DistortionOffset(S bump_x, const V3<S>& eye) {
    return bump_x * Min(S(kWaveDistortion) / EyeLengthScaled(eye), S(16));  // cMaxDistortion
}

// The seed's glare power as the seed writes it: pow(dot(m, s) * 0.5 + 0.5, 512), with pow as
// GPUs evaluate it, exp2(512 * log2(x)), each step rounded.
template <typename S>
S GlarePow(const V3<S>& m, const V3<S>& s) {
    const S x = Clamp(Dot(m, s) * S(0.5) + S(0.5), S(0), S(1));
    if (!(x > S(0))) {
        return S(0);
    }
    const S log = S(std::log2(ToDouble(x)));
    return S(std::exp2(ToDouble(S(512) * log)));
}

// water.fsh's form: u = |m - s|^2 / 4 = 1 - dotSpec, then exp2(-738.65 (u + u^2 / 2)).
template <typename S>
S GlareComplement(const V3<S>& m, const V3<S>& s) {
    const V3<S> d{m.x - s.x, m.y - s.y, m.z - s.z};
    const S u = Min(Dot(d, d) * S(0.25), S(1));
    return S(std::exp2(ToDouble(S(-738.65) * (u + S(0.5) * u * u))));
}

// clamp(depth / divisor, 0, 1) as ENABLE_EXTINCTION wrote it, and floored as it does now; the
// reference treats a divisor of 0 as "reached at once", as WaterMath.h's ExtinctionColour does.
template <typename S>
S ExtinctionRatio(S depth, S divisor, bool floored) {
    if constexpr (std::is_same_v<S, double>) {
        if (!(divisor > 0.0)) {
            return depth > 0.0 ? 1.0 : 0.0;
        }
    }
    return Clamp(depth / (floored ? Max(divisor, S(1e-3)) : divisor), S(0), S(1));
}

// The depth optics' path length a^2 * MaxWaterDepth / max(cos, 0.05), where a is the stored
// sqrt(D / MaxWaterDepth); `clamped` applies the renderer's upload clamp (MediumpMaxWaterDepth).
template <typename S>
S DepthPath(double stored, double max_depth, double cos_view, bool clamped) {
    const S depth_max = S(clamped ? std::min(max_depth, 3000.0) : max_depth);
    const S a = S(stored);
    return a * a * depth_max / Max(S(cos_view), S(0.05));
}

template <typename S>
S FogFactor(const V3<S>& eye) {
    return Clamp(EyeLengthScaled(eye) * S(kRcpFogDistance), S(0), S(1));
}

// ---- Sweeps ---------------------------------------------------------------------------------

// Eye vectors: 60 log-spaced distances per decade-ish from `nearest` to `farthest`, over 64
// directions of the upper hemisphere (the camera above the water) and a few below.
std::vector<Inputs> EyeSweep(double nearest, double farthest) {
    std::vector<Inputs> samples;
    constexpr int kDistances = 120;
    for (int d = 0; d < kDistances; ++d) {
        const double t = d / static_cast<double>(kDistances - 1);
        const double distance = nearest * std::pow(farthest / nearest, t);
        for (int i = 0; i < 8; ++i) {
            const double elevation = -0.2 + 1.7 * i / 7.0;  // radians, -11° .. 86°
            for (int j = 0; j < 8; ++j) {
                const double azimuth = 0.37 + j * 0.785398;
                samples.push_back({distance * std::cos(elevation) * std::cos(azimuth),
                                   distance * std::sin(elevation),
                                   distance * std::cos(elevation) * std::sin(azimuth)});
            }
        }
    }
    return samples;
}

// Summed bump normals (two unit normals tilted up to 60°, z-major swizzled to y up) with eye
// vectors at grazing to steep angles.
std::vector<Inputs> BumpEyeSweep() {
    std::vector<Inputs> samples;
    auto normal = [](double tilt, double azimuth) {
        return std::array<double, 3>{std::sin(tilt) * std::cos(azimuth), std::cos(tilt),
                                     std::sin(tilt) * std::sin(azimuth)};
    };
    for (int a = 0; a < 12; ++a) {
        for (int b = 0; b < 12; ++b) {
            const auto n0 = normal(1.05 * a / 11.0, 0.3 + a * 0.9);
            const auto n1 = normal(1.05 * b / 11.0, 2.1 + b * 1.3);
            for (int e = 0; e < 24; ++e) {
                const double elevation = 1e-4 + 1.5 * e / 23.0;  // grazing to 86°
                const double distance = 5.0 + 80.0 * e;
                samples.push_back({n0[0] + n1[0], n0[1] + n1[1], n0[2] + n1[2],
                                   distance * std::cos(elevation), distance * std::sin(elevation),
                                   distance * 0.3 * std::cos(elevation)});
            }
        }
    }
    return samples;
}

struct Expression {
    std::string text;
    std::vector<Inputs> sweep;
    std::function<Outputs(const Inputs&)> as_double;
    std::function<Outputs(const Inputs&)> as_float;
    std::function<Outputs(const Inputs&)> as_half;
    double relative_floor;  // |reference| below this counts as this (relative error denominator)
    double bound;           // relative error above which fp16 "loses precision"
    std::string note;
    // Coordinates: the error counts in units of relative_floor (a texel, a pixel) whatever the
    // coordinate's size, because a texel off is a texel off at coordinate 0 or 100.
    bool absolute = false;
};

// Builds the three evaluations of one templated expression.
template <typename F>
Expression Make(std::string text, std::vector<Inputs> sweep, F f, double relative_floor,
                double bound, std::string note, bool absolute = false) {
    return Expression{std::move(text),
                      std::move(sweep),
                      [f](const Inputs& in) { return f(std::type_identity<double>{}, in); },
                      [f](const Inputs& in) { return f(std::type_identity<float>{}, in); },
                      [f](const Inputs& in) { return f(std::type_identity<Half>{}, in); },
                      relative_floor,
                      bound,
                      std::move(note),
                      absolute};
}

PrecisionRow Evaluate(const Expression& e) {
    PrecisionRow row;
    row.expression = e.text;
    row.bound_fp16 = e.bound;
    row.note = e.note;
    for (const Inputs& in : e.sweep) {
        const Outputs reference = e.as_double(in);
        const Outputs single = e.as_float(in);
        const Outputs half = e.as_half(in);
        for (std::size_t k = 0; k < reference.size(); ++k) {
            const double denominator = e.absolute
                                               ? e.relative_floor
                                               : std::max(std::abs(reference[k]), e.relative_floor);
            row.max_abs_error_float =
                    std::max(row.max_abs_error_float, std::abs(single[k] - reference[k]));
            if (!std::isfinite(half[k])) {
                ++row.non_finite_fp16;
                continue;
            }
            const double error = std::abs(half[k] - reference[k]);
            row.max_abs_error_fp16 = std::max(row.max_abs_error_fp16, error);
            row.max_rel_error_fp16 = std::max(row.max_rel_error_fp16, error / denominator);
        }
    }
    row.loses_precision = row.non_finite_fp16 > 0 || row.max_rel_error_fp16 > row.bound_fp16;
    return row;
}

}  // namespace

std::vector<PrecisionRow> RunPrecisionStudy() {
    // The default far plane is 2000; a mediump varying itself holds up to 65504.
    const std::vector<Inputs> eyes = EyeSweep(1e-3, 2000.0);
    const std::vector<Inputs> bumps = BumpEyeSweep();
    // fp16 rounds each operation to within 2^-11 (4.9e-4) relative; an expression of about ten
    // operations that stays within 10 such steps (5e-3) is "as precise as mediump can be", so
    // anything beyond 1e-2 relative is a real loss.
    constexpr double kBound = 1e-2;
    std::vector<Expression> expressions;
    expressions.push_back(Make(
            "length(EyeVector) = sqrt(dot(E, E))", eyes,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(EyeLengthUnscaled(In3<S>(in, 0)))};
            },
            kMinEyeDistance, kBound,
            "dot(E, E) overflows fp16's 65504 beyond 256 units (Inf) and loses its bits below "
            "0.01; the shaders no longer use this form"));
    expressions.push_back(Make(
            "eyeScale * sqrt(dot(E / eyeScale, E / eyeScale)), eyeScale = max |E_i|", eyes,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(EyeLengthScaled(In3<S>(in, 0)))};
            },
            kMinEyeDistance, kBound,
            "the guarded form in water.fsh and water_uniform.fsh: the scaled square lies in "
            "[1, 3], so fp16 keeps ~11 bits at every distance"));
    expressions.push_back(Make(
            "E * inversesqrt(max(dot(E, E), 1e-8))", eyes,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return Out3(EyeDirectionUnscaled(In3<S>(in, 0)));
            },
            1.0, kBound,
            "the pre-guard eye direction: 0 beyond 256 units (Inf squared length) and 1e-8 "
            "underflows to 0 in fp16; replaced by the scaled form"));
    expressions.push_back(Make(
            "(E / eyeScale) * inversesqrt(max(dot(E / eyeScale, E / eyeScale), 1e-4))", eyes,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return Out3(EyeDirectionScaled(In3<S>(in, 0)));
            },
            1.0, kBound, "the guarded eye direction (error relative to unit length)"));
    std::vector<Inputs> cosines;
    for (int i = 0; i <= 4000; ++i) {
        cosines.push_back({i / 4000.0});
    }
    expressions.push_back(Make(
            "Schlick: R0 + (1 - R0) * (1 - cos)^5", cosines,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(Schlick(S(in[0])))};
            },
            0.02037, kBound, "reflectance never falls below R(0), so relative to R(0)"));
    expressions.push_back(Make(
            "exact Fresnel: (rs^2 + rp^2) / 2", cosines,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(ExactFresnel(S(in[0])))};
            },
            0.02037, kBound,
            "n1 / n2 and the differences n1 cos - n2 cos_t cancel; fp16 keeps them to ~1e-3 "
            "of R(0)"));
    expressions.push_back(Make(
            "bump * inversesqrt(max(dot(bump, bump), 1e-4))", bumps,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return Out3(NormaliseBump(In3<S>(in, 0)));
            },
            1.0, kBound,
            "summed bump normals of length 0..2 (not unit, as the whitepaper "
            "assumes); error relative to unit length"));
    expressions.push_back(Make(
            "Fresnel chain: Schlick(clamp(dot(normalised bump, eye direction), 0, 1))", bumps,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(FresnelChain(In3<S>(in, 0), In3<S>(in, 3)))};
            },
            0.02037, kBound, "grazing angles included (cos -> 0, clamped below 0)"));
    expressions.push_back(Make(
            "bumpNormal.x * min(WaveDistortion / eyeDistance, 16)", eyes,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(DistortionOffset(S(0.7), In3<S>(in, 0)))};
            },
            kRcpWidth, kBound,
            "texture-space offset; the demo's 100 over an eye distance below 1.5e-3 overflows "
            "fp16, so water.fsh caps the factor at 16 (past the texture's edge anyway); "
            "relative to one pixel of a 640-wide target"));
    expressions.push_back(Make(
            "clamp(eyeDistance * RcpMaxFogDepth, 0, 1)", eyes,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(FogFactor(In3<S>(in, 0)))};
            },
            1.0 / 255.0, kBound, "relative to one 8-bit colour step"));
    std::vector<Inputs> coordinates;
    for (int i = 0; i <= 2000; ++i) {
        coordinates.push_back({-2000.0 + 2.0 * i, 0.613});
    }
    expressions.push_back(Make(
            "BumpCoord = inVertex.xz * BumpScale + BumpTranslation (wrapped)", coordinates,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(S(in[0]) * S(kBumpScale) + S(in[1]))};
            },
            1.0 / 256.0, 0.5,
            "in texels of the 256 normal map, bound half a texel of the 256 normal map: fp16 "
            "spacing reaches 0.0625 (16 "
            "texels) at 2000 units, so the varyings are highp where the fragment stage has it "
            "(HIGHP_OR_MEDIUMP); the mediump fallback blurs only far water, which the mip chain "
            "blurs anyway",
            true));
    std::vector<Inputs> long_run;
    for (int i = 0; i <= 200; ++i) {
        long_run.push_back({-200.0 + 2.0 * i, 0.013 * 1e6});
    }
    expressions.push_back(Make(
            "BumpCoord with BumpTranslation unwrapped after 1e6 s (13000)", long_run,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(S(in[0]) * S(kBumpScale) + S(in[1]))};
            },
            1.0 / 256.0, 0.5,
            "in texels, bound half a texel: fp16 spacing at 13000 is 8 texture units: the ripples "
            "freeze or jump; this is why "
            "the renderer wraps the translation (whitepaper 2.2) and BumpTranslation can stay "
            "mediump",
            true));
    std::vector<Inputs> fragments;
    for (const double width : {640.0, 1920.0}) {
        for (int x = 0; x < static_cast<int>(width); x += 3) {
            fragments.push_back({x + 0.5, 1.0 / width, width});
        }
    }
    expressions.push_back(Make(
            "gl_FragCoord.x * RcpWindowSize.x", fragments,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                // Error in pixels of the window it addresses.
                return {ToDouble(S(in[0]) * S(in[1])) * in[2]};
            },
            1.0, 0.5,
            "in pixels, bound half a pixel: gl_FragCoord is only mediump in GLSL ES 1.00, so "
            "from 1024 pixels on its x.5 centres round to whole pixels; no qualifier fixes a "
            "built-in, so on wide mediump-only screens the lookup is off by up to a pixel, which "
            "linear filtering and the distortion hide",
            true));
    // The sun glare within 12 degrees of the highlight (beyond, the power is below 1/255).
    std::vector<Inputs> glare;
    for (int i = 0; i <= 2400; ++i) {
        const double angle = 0.21 * i / 2400.0;
        glare.push_back(
                {std::sin(angle) * 0.6, std::cos(angle), std::sin(angle) * 0.8, 0.0, 1.0, 0.0});
    }
    expressions.push_back(Make(
            "pow(dot(m, s) * 0.5 + 0.5, 512)", glare,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(GlarePow(In3<S>(in, 0), In3<S>(in, 3)))};
            },
            1.0 / 255.0, kBound,
            "the seed's glare: dotSpec near 1 has fp16 spacing 2^-11, one step moves the power "
            "by 22%, so the highlight bands into rings; water.fsh no longer uses this form"));
    expressions.push_back(Make(
            "exp2(-738.65 (u + u^2 / 2)), u = |m - s|^2 / 4", glare,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(GlareComplement(In3<S>(in, 0), In3<S>(in, 3)))};
            },
            1.0 / 255.0, kBound,
            "the guarded glare in water.fsh: 1 - dotSpec from the difference vector keeps its "
            "relative precision near the highlight; relative to one 8-bit step"));
    std::vector<Inputs> extinction;
    for (const double divisor : {0.0, 4.5, 75.0, 300.0}) {
        for (int i = 0; i <= 400; ++i) {
            extinction.push_back({i == 0 ? 0.0 : 0.01 * std::pow(8000.0, i / 400.0), divisor});
        }
    }
    expressions.push_back(Make(
            "clamp(D / Extinction, 0, 1)", extinction,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(ExtinctionRatio(S(in[0]), S(in[1]), false))};
            },
            1.0 / 255.0, kBound,
            "extinction or visibility 0 gives 0/0 = NaN at the water line (depth 0)"));
    expressions.push_back(Make(
            "clamp(D / max(Extinction, 1e-3), 0, 1)", extinction,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(ExtinctionRatio(S(in[0]), S(in[1]), true))};
            },
            1.0 / 255.0, kBound,
            "the guarded form in water.fsh: 0 depth stays clear, any depth above 1e-3 is opaque, "
            "as the CPU reference has it"));
    std::vector<Inputs> paths;
    for (const double max_depth : {80.0, 3000.0, 1e5}) {
        for (int i = 0; i <= 100; ++i) {
            for (const double cos_view : {0.01, 0.05, 0.3, 1.0}) {
                paths.push_back({i / 100.0, max_depth, cos_view});
            }
        }
    }
    expressions.push_back(Make(
            "a^2 * MaxWaterDepth / max(cos, 0.05), MaxWaterDepth as given", paths,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(DepthPath<S>(in[0], in[1], in[2], false))};
            },
            1.0, kBound,
            "MaxWaterDepth 1e5 is Inf in mediump, and Inf x 0 at the water line is NaN"));
    expressions.push_back(Make(
            "a^2 * min(MaxWaterDepth, 3000) / max(cos, 0.05)", paths,
            [](auto tag, const Inputs& in) -> Outputs {
                using S = typename decltype(tag)::type;
                return {ToDouble(DepthPath<S>(in[0], in[1], in[2], true))};
            },
            1.0, kBound,
            "the renderer clamps MaxWaterDepth to [0.5, 3000] on upload (MediumpMaxWaterDepth): "
            "the longest path, 20 x 3000, stays below 65504"));
    std::vector<PrecisionRow> rows;
    rows.reserve(expressions.size());
    for (const Expression& e : expressions) {
        rows.push_back(Evaluate(e));
    }
    return rows;
}

}  // namespace tidepool::lab
