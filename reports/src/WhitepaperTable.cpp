#include "tidepool/report/WhitepaperTable.h"

namespace tidepool::report {

const std::vector<WhitepaperRow>& WhitepaperRows() {
    // Figures and wording from ../shared/seeds/README.md ("The whitepaper's cost figures"); the
    // notes explain the mechanism on llvmpipe (a tiled software rasteriser on 2 CPU cores, no
    // TBDR hidden-surface removal, shaders JIT-compiled to SIMD, texture sampling in software).
    static const std::vector<WhitepaperRow> rows = {
            {1, "add a refraction render pass (reflection only -> reflection + refraction)",
             "performance reduced by 60%", FigureKind::kPercent, -60.0, -1, "reflection_only",
             "reflection_refraction",
             "The extra 256x256 scene pass is CPU rasterisation on llvmpipe, but the 640x480 "
             "main pass with software texture sampling dominates the frame, so the pass costs a "
             "smaller share than SGX's 60%."},
            {2, "mix the reflection with a constant water colour", "performance reduced by 9%",
             FigureKind::kPercent, -9.0, -1, "reflection_only", "reflection_water_colour",
             "One mix() per water pixel is a few SIMD instructions in the JIT-compiled shader; "
             "next to the passes it is a small cost, close to the noise of a 2-core run."},
            {3, "alpha-blend the water so objects below can be seen", "performance reduced by 11%",
             FigureKind::kPercent, -11.0, -1, "reflection_only", "reflection_alpha_blend",
             "Blending on llvmpipe is a software read-modify-write of each tile's colour, cheap "
             "next to the passes; SGX paid for the lost hidden-surface removal, llvmpipe has none."},
            {4, "disable the fog", "performance increased by 3.5%", FigureKind::kPercent, 3.5, +1,
             "full", "full_no_fog",
             "Fog is per-pixel arithmetic in the water, skybox and model shaders of every pass; "
             "llvmpipe pays all of it on 2 CPU cores, so disabling it saves more than on SGX."},
            {5, "Fresnel term instead of a constant reflection/refraction mix",
             "performance reduced by 22%", FigureKind::kPercent, -22.0, -1, "full_constant_mix",
             "full",
             "Schlick's pow() and the eye-vector normalize() are JIT-compiled to SIMD code on 2 "
             "cores; they touch only water pixels, a small share of llvmpipe's frame."},
            {6, "scale the distortion by the fragment's distance from the camera",
             "performance reduced by <1%", FigureKind::kNegligible, -1.0, -1,
             "full_unscaled_distortion", "full",
             "One division per water pixel: negligible on both, as the whitepaper says."},
            {7, "render the water to a 256x256 texture and apply it to the final plane at 640x480",
             "performance increased by ~18%", FigureKind::kPercent, 18.0, +1, "full",
             "full_low_res_water",
             "Shading the water at 256x256 instead of 640x480 saves llvmpipe most of the water's "
             "software shading and texture fetches; applying it is one cheap textured draw."},
            {8, "normalise with a normalisation cube map instead of arithmetic",
             "\"can halve the number of cycles required to normalise a vector\"",
             FigureKind::kDirection, std::numeric_limits<double>::quiet_NaN(), +1, "full",
             "full_cubemap_normalise",
             "llvmpipe samples textures in software (address, filter, fetch), which costs far "
             "more than the rsqrt and multiplies of normalize() on SIMD; SGX had a texture unit."},
            {9, "#define code paths instead of uniform bool branches",
             "\"at least an extra cycle for each decision point\" saved",
             FigureKind::kDirection, std::numeric_limits<double>::quiet_NaN(), +1,
             "full_uniform_bools", "full",
             "With #defines LLVM compiles one straight-line path and optimises across it; the "
             "uniform-bool program keeps every test and the masked SIMD control flow around it, "
             "which costs llvmpipe far more than SGX's cycle per decision."},
            {10, "clip with the modified (oblique) projection matrix instead of `discard`",
             "\"significantly faster\", clipping \"for almost no additional cost\"",
             FigureKind::kDirection, std::numeric_limits<double>::quiet_NaN(), +1,
             "full_clip_discard", "full",
             "On llvmpipe discard only masks SIMD lanes and no TBDR early-depth optimisation is "
             "lost, while the oblique matrix culls clipped geometry before rasterisation."},
            {11, "reflection texture 256x256 -> 128x128",
             "\"75% lower resolution\"; 256x256 \"proven effective\"", FigureKind::kDirection,
             std::numeric_limits<double>::quiet_NaN(), +1, "full", "full_reflection_128",
             "A quarter of the reflection pass's pixels is a quarter of its software "
             "rasterisation and shading, so llvmpipe gains as the GPU did."},
    };
    return rows;
}

}  // namespace tidepool::report
