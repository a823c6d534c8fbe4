// The embedded water renderer: the whitepaper's passes (reflection with a mirrored camera,
// refraction, optional low-resolution water, main) over the procedural scene, drawn with the
// variant under test through the real GL driver.
#pragma once

#include "tidepool/Diagnostic.h"
#include "tidepool/SourceAssembler.h"
#include "tidepool/VariantConfig.h"
#include "tidepool/runner/FourierReflection.h"
#include "tidepool/runner/GlBackend.h"
#include "tidepool/runner/ProceduralScene.h"
#include "tidepool/runner/RenderConfig.h"
#include "tidepool/runner/WaterMath.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tidepool::runner {

/// Everything besides the configuration that moves a pixel or a figure; recorded in results.
struct RenderSettings {
    int width = 640;
    int height = 480;
    float animation_time = 2.0F;  // seconds; fixed so every run renders the same pixels
    // Hand the shader only the fractional part of the bump translations (whitepaper 2.2). Off
    // only for the hard case that shows why: after long run times the raw translation is too
    // large for mediump bump coordinates.
    bool wrap_bump_translation = true;
    // Clip planes move this far (world units) "back along the plane's direction" (whitepaper
    // 3.3.4): the reflection keeps a sliver below the water, the refraction a sliver above it,
    // so distorted lookups at objects crossing the water find the object, not the clear colour.
    float clip_plane_offset = 0.5F;
    // The demo's WaveDistortion: the screen-space lookup moves by the bump normal times this,
    // in texture units, divided by the eye distance under ENABLE_SCALE_DISTORTION. Unscaled
    // water uses this over the view's typical water distance (FramePlan.h,
    // DistortionConstant), so both give the same offset there.
    float wave_distortion = 100.0F;
    glm::vec2 bump_scale0{1.0F / 24.0F, 1.0F / 24.0F};  // one normal-map tile per 24 units
    glm::vec2 bump_scale1{1.0F / 15.0F, 1.0F / 15.0F};  // a second, finer layer
    glm::vec2 bump_velocity0{0.013F, 0.021F};           // texture units per second
    glm::vec2 bump_velocity1{-0.017F, 0.009F};
    glm::vec3 fog_colour{0.85F, 0.95F, 1.0F};     // water fog (whitepaper demo)
    float rcp_max_fog_distance = 1.0F / 2000.0F;  // water fog reaches 1 at the far plane (demo)
    glm::vec3 underwater_colour{0.05F, 0.15F, 0.10F};   // refraction clear + depth fog (demo)
    float rcp_max_fog_depth = 1.0F / 80.0F;             // underwater depth fog (demo)
    glm::vec4 water_colour{0.05F, 0.15F, 0.10F, 0.4F};  // ENABLE_WATER_COLOUR rgb and mix factor
    // Low-resolution water texture; 0 follows the demo's rule for the window (FramePlan.h,
    // LowResWaterSize: 256 at 640x480).
    int low_res_water_size = 0;
    int sky_size = 128;               // sky cube-map face size
    int normal_map_size = 256;        // water normal map size
    int normalisation_cube_size = 8;  // per face, the demo's size (whitepaper 3.3.1)
    // Depth-based optics (../shared/seeds/003; shaders/water.fsh). The refraction pass stores
    // depth up to max_water_depth; extinction is the depth at which each channel is gone.
    float max_water_depth = 80.0F;
    ExtinctionModel extinction;  // ENABLE_EXTINCTION (WaterMath.h)
    glm::vec3 foam_colour{0.9F, 0.95F, 0.95F};
    glm::vec2 foam_depth{0.5F, 2.0F};                // foam full up to .x, gone at .y
    glm::vec2 foam_scale{1.0F / 6.0F, 1.0F / 6.0F};  // one foam tile per 6 units
    float shore_hardness = 1.0F;                     // 1 / depth over which the shore blends
    glm::vec3 sun_colour{1.0F, 0.95F, 0.85F};
    float shininess = 0.6F;  // seed: 0.5 to 0.7
    // REFLECTION_FOURIER: the per-vertex coefficients and the tessellated water grid.
    FourierSettings fourier;
    // Render the main pass into an RGBA32F target instead of RGBA8, so NaN and Inf survive to
    // the read-back (needs GlEnvironment::float_render_target).
    bool float_target = false;
};

/// The driver's verdict on one configuration's programs: its water program and the helper
/// programs (skybox, model, water_composite variants) the configuration's passes need.
struct DriverVerdict {
    bool valid = false;            // every program compiled and linked
    bool vertex_compiled = false;  // the water program's stages and link
    bool fragment_compiled = false;
    bool linked = false;
    std::string vertex_log;  // Mesa's info logs of the water program, verbatim
    std::string fragment_log;
    std::string link_log;
    std::vector<Diagnostic> diagnostics;  // parsed from every log, at the user's files
};

/// What one frame did.
struct FrameReport {
    int passes = 0;                       // render passes (framebuffer targets) drawn
    int draw_calls = 0;                   // glDrawArrays/glDrawElements calls
    std::vector<std::string> pass_names;  // "reflection", "refraction", "low_res_water", "main"
    std::vector<int> pass_draw_calls;     // draw calls of each pass, in pass_names' order
    // Pixels of each pass's target: every pass clears and covers its whole target once, so this
    // is an occlusion-free estimate of the fragments it shades (GLES 2 has no occlusion query).
    std::vector<long long> pass_pixels;
    bool oblique_fallback = false;  // the oblique near plane was impossible; discard clipped
    std::string gl_error;           // "" or e.g. "GL_INVALID_OPERATION after pass reflection"
    double plan_seconds = 0;        // CPU time computing the frame (matrices, polygon, culling)
};

/// Called after each pass of a frame is submitted, with the pass's name ("reflection", ...):
/// the timing engine finishes the GL work there and reads its clock, to time each pass.
using PassCallback = std::function<void(const std::string& pass)>;

/// The renderer of one GL context: scene resources, render targets and compiled programs.
class WaterRenderer {
public:
    /// Creates the scene, its textures and render targets on `context` (made current here),
    /// reading shaders through `config`; draws `scene` when given (BuildSceneFromDescription),
    /// the default scene otherwise. Fails (null, `error` set) when a render target is
    /// incomplete or float_target is asked for but the context cannot render to float.
    static std::unique_ptr<WaterRenderer> Create(GlContext& context, const VariantConfig& config,
                                                 const RenderSettings& settings, std::string* error,
                                                 const Scene* scene = nullptr);
    ~WaterRenderer();
    WaterRenderer(const WaterRenderer&) = delete;
    WaterRenderer& operator=(const WaterRenderer&) = delete;

    /// Compiles and links (once; cached) the programs `configuration` needs, in Mesa. Fails
    /// through the verdict (valid false, diagnostics at the user's lines).
    DriverVerdict Prepare(const RenderConfiguration& configuration);

    /// Renders one frame of `configuration` from `view` into the main target. Call Prepare
    /// first (it makes the context current; RenderFrame does not, to keep eglMakeCurrent out of
    /// timed frames, so re-current the context if another was made current since); fails through
    /// FrameReport::gl_error (glGetError after each pass) or, when the programs are invalid, by
    /// drawing nothing and saying so there.
    FrameReport RenderFrame(const RenderConfiguration& configuration, const CameraView& view,
                            const PassCallback& after_pass = {});

    /// Starts a GPU timer query (GL_EXT_disjoint_timer_query) around the commands that follow.
    /// Fails (false) when the context offers no timer queries or one is already running.
    bool BeginGpuTimer();
    /// Ends the query begun by BeginGpuTimer, waits for its result and returns the GPU time in
    /// milliseconds. Fails (NaN) when no query runs or the GPU reported a disjoint interval
    /// (the measurement was disturbed, e.g. by a frequency change).
    double EndGpuTimerMs();

    /// Replaces the settings that only move uniforms and the frame plan (animation time and
    /// wrapping, fog, distortion, bump scales and velocities, colours, clip offset); the sizes
    /// and float_target stay as created, since they decide textures and targets. Never fails.
    void UpdateFrameSettings(const RenderSettings& settings);

    /// Blocks until GL has finished every submitted command (glFinish).
    void Finish();

    /// Reads the main target back as RGBA8 rows top to bottom (converted when it is float).
    base::RgbaImage ReadImage();

    /// Reads the main target back as RGBA floats, rows top to bottom; empty unless the settings
    /// asked for float_target.
    std::vector<float> ReadFloatPixels();

    /// The settings the renderer was created with.
    const RenderSettings& Settings() const;
    /// The scene it draws.
    const Scene& GetScene() const;

    /// Backend state; defined under runner/src/gl/.
    struct Impl;

private:
    explicit WaterRenderer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

/// The verdict of the driver on one shader stage.
struct DriverStageResult {
    bool compiled = false;
    std::string log;
};

/// Compiles one stage's full driver source (as AssembleDriverSource writes it) in the context's
/// GL driver and returns its status and info log; used to check Mesa's line numbers. Fails
/// through `compiled` false.
DriverStageResult CompileDriverStage(GlContext& context, Stage stage, const std::string& source);

}  // namespace tidepool::runner
