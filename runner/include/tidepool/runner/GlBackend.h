// Headless GL contexts through Mesa: EGL on the surfaceless platform (a GLES context, configless,
// rendering into framebuffer objects only) or OSMesa (a desktop compatibility context) as the
// fallback. No GL header appears here; the renderer reaches the context through runner/src/gl/.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace tidepool::runner {

/// Which backend to create a context with; kAuto tries EGL first, then OSMesa.
enum class BackendKind { kAuto, kEgl, kOsMesa };

/// "auto", "egl" or "osmesa".
const char* BackendName(BackendKind kind);

/// Parses "auto", "egl" or "osmesa"; false (and `kind` untouched) for anything else.
bool ParseBackendKind(std::string_view text, BackendKind* kind);

/// What the context reports about itself, recorded in every result file.
struct GlEnvironment {
    std::string backend;               // "egl" or "osmesa"
    std::string context_api;           // "OpenGL ES" (EGL) or "OpenGL compatibility" (OSMesa)
    std::string renderer;              // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string version;               // GL_VERSION
    std::string shading_language;      // GL_SHADING_LANGUAGE_VERSION
    std::string mesa_version;          // the "Mesa x.y.z" part of GL_VERSION, "" when not Mesa
    bool float_render_target = false;  // RGBA32F colour attachments render (NaN/Inf checks)
    bool timer_query = false;          // GL_EXT_disjoint_timer_query is offered and loaded
};

/// One backend that was tried and why it failed ("" when it worked).
struct BackendAttempt {
    BackendKind kind = BackendKind::kEgl;
    std::string failure;
};

/// Builds the message for "no GL context": what each backend reported, then what is typically
/// missing (the Debian packages libegl-mesa0, libgl1-mesa-dri, libosmesa6) and which environment
/// variables can break Mesa's driver choice (EGL_PLATFORM, LIBGL_ALWAYS_SOFTWARE,
/// MESA_LOADER_DRIVER_OVERRIDE, __EGL_VENDOR_LIBRARY_FILENAMES). Never fails.
std::string DescribeMissingGl(const std::vector<BackendAttempt>& attempts);

/// An owned, current GL context with its entry points loaded. Create with CreateGlContext.
class GlContext {
public:
    /// Backend-specific state, defined under runner/src/gl/.
    struct Impl;

    /// Takes ownership of a created backend context.
    explicit GlContext(std::unique_ptr<Impl> impl);
    /// Destroys the backend context.
    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    /// What the context reported when it was created.
    const GlEnvironment& Environment() const;
    /// Makes this context current on the calling thread; false when the backend refuses.
    bool MakeCurrent();
    /// The backend state, for the renderer under runner/src/gl/.
    Impl& Internal() { return *impl_; }

private:
    std::unique_ptr<Impl> impl_;
};

/// A context, or why there is none.
struct GlContextResult {
    std::unique_ptr<GlContext> context;    // null on failure
    std::vector<BackendAttempt> attempts;  // every backend tried, in order
    std::string error;                     // DescribeMissingGl(attempts) on failure, "" otherwise
};

/// Creates a context with `kind` and makes it current. Fails (null context, `error` naming what is
/// missing) when no requested backend gives a context with the entry points the runner needs.
/// llvmpipe reads LP_NUM_THREADS when the first context is created, so the caller sets it first.
GlContextResult CreateGlContext(BackendKind kind);

/// Makes a new context for a rendering thread of its own; null when none can be made.
using GlContextFactory = std::function<std::unique_ptr<GlContext>()>;

/// Runs `body` on `threads` rendering threads at once (at least 1): the calling thread with
/// `context`, each other thread with a context of its own from `make_context`, current on that
/// thread. A thread whose context cannot be made runs nothing, so callers share work through a
/// queue `body` drains, never by thread index. Returns how many threads ran `body`; `context` is
/// current on the calling thread again when it returns. Never fails.
int RunOnRenderingThreads(GlContext& context, const GlContextFactory& make_context, int threads,
                          const std::function<void(GlContext&)>& body);

}  // namespace tidepool::runner
