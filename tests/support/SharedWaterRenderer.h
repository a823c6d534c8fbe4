// One water renderer over the shared GL context for a whole gl test binary, and the
// configurations the renderer's, timer's and render loop's tests build: creating a renderer
// costs more than most tests.
#pragma once

#include "tidepool/VariantConfig.h"
#include "tidepool/VariantExpander.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/Renderer.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "GlTestEnvironment.h"

namespace tidepool::test_support {

// Small enough that the whole gl suite renders in seconds on llvmpipe, large enough that the
// scene's objects cover several pixels at the default views.
constexpr int kRendererWidth = 128;
constexpr int kRendererHeight = 96;

// The shared context and configuration, the default matrix's variants and a renderer (and one
// with a float target where the driver has it); `error` says what is missing.
struct SharedRenderer {
    runner::GlContext* context = nullptr;
    const VariantConfig* config = nullptr;
    std::vector<Variant> variants;
    std::unique_ptr<runner::WaterRenderer> renderer;
    std::unique_ptr<runner::WaterRenderer> float_renderer;
    std::string error;
};

inline SharedRenderer& SharedWaterRenderer() {
    static SharedRenderer shared = [] {
        SharedRenderer s;
        GlTestEnvironment& environment = SharedGlEnvironment();
        if (!environment.error.empty()) {
            s.error = environment.error;
            return s;
        }
        s.context = environment.context.get();
        s.config = &*environment.config;
        s.variants = ExpandVariants(*s.config, ExpansionOptions{s.config->max_variants}).variants;
        runner::RenderSettings settings;
        settings.width = kRendererWidth;
        settings.height = kRendererHeight;
        s.renderer = runner::WaterRenderer::Create(*s.context, *s.config, settings, &s.error);
        if (s.renderer && s.context->Environment().float_render_target) {
            settings.float_target = true;
            s.float_renderer =
                    runner::WaterRenderer::Create(*s.context, *s.config, settings, &s.error);
        }
        return s;
    }();
    return shared;
}

/// A water configuration with `defines`, named as the renderer names it.
inline runner::RenderConfiguration WaterConfiguration(std::vector<std::string> defines,
                                                      PassOptions passes = {}) {
    runner::RenderConfiguration c;
    c.variant = MakeVariant("water", std::move(defines));
    c.effects = c.variant.defines;
    // The renderer tests' checks are sized for 256x256 targets magnified onto a 128x96 image, as at
    // 640x480; the demo's rule would give 64x64 here (FramePlanTest covers the rule).
    passes.reflection_size = passes.reflection_size > 0 ? passes.reflection_size : 256;
    passes.refraction_size = passes.refraction_size > 0 ? passes.refraction_size : 256;
    c.passes = passes;
    c.id = runner::ConfigurationId(c.variant, passes);
    return c;
}

}  // namespace tidepool::test_support
