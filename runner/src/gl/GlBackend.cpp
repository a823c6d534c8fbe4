// Backend selection, the "no GL" message and what a context reports about itself.
#include "tidepool/runner/GlBackend.h"

#include <atomic>
#include <cstring>
#include <regex>
#include <thread>

#include "gl/GlApi.h"
#include "gl/GlContextImpl.h"
#include "gl/OsMesaSession.h"
#include <fmt/format.h>

namespace tidepool::runner {

const char* BackendName(BackendKind kind) {
    switch (kind) {
        case BackendKind::kAuto:
            return "auto";
        case BackendKind::kEgl:
            return "egl";
        case BackendKind::kOsMesa:
            return "osmesa";
    }
    return "auto";
}

bool ParseBackendKind(std::string_view text, BackendKind* kind) {
    for (BackendKind k : {BackendKind::kAuto, BackendKind::kEgl, BackendKind::kOsMesa}) {
        if (text == BackendName(k)) {
            *kind = k;
            return true;
        }
    }
    return false;
}

std::string DescribeMissingGl(const std::vector<BackendAttempt>& attempts) {
    std::string message = "no GL context could be created";
    bool tried_egl = false;
    bool tried_osmesa = false;
    for (const BackendAttempt& attempt : attempts) {
        message += fmt::format("\n  {}: {}", BackendName(attempt.kind),
                               attempt.failure.empty() ? "ok" : attempt.failure);
        tried_egl = tried_egl || attempt.kind == BackendKind::kEgl;
        tried_osmesa = tried_osmesa || attempt.kind == BackendKind::kOsMesa;
    }
    if (tried_egl) {
        message +=
                "\n  EGL needs Mesa's EGL vendor library (Debian package libegl-mesa0) and the "
                "llvmpipe/swrast driver (libgl1-mesa-dri); check that EGL_PLATFORM, "
                "__EGL_VENDOR_LIBRARY_FILENAMES, MESA_LOADER_DRIVER_OVERRIDE and "
                "LIBGL_ALWAYS_SOFTWARE are unset or point at installed drivers";
    }
    if (tried_osmesa) {
        message += "\n  OSMesa needs libOSMesa.so.8 (Debian package libosmesa6)";
    }
    message += "\n  try --backend egl or --backend osmesa to see one backend's error alone";
    return message;
}

GlContext::GlContext(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

GlContext::~GlContext() {
    if (impl_ && impl_->destroy) {
        impl_->destroy();
    }
}

const GlEnvironment& GlContext::Environment() const {
    return impl_->environment;
}

bool GlContext::MakeCurrent() {
    return impl_->make_current && impl_->make_current();
}

GlContextResult CreateGlContext(BackendKind kind) {
    GlContextResult result;
    auto try_backend = [&](BackendKind backend) {
        std::string failure;
        std::unique_ptr<GlContext::Impl> impl = backend == BackendKind::kEgl
                                                        ? gl::CreateEglContext(&failure)
                                                        : gl::CreateOsMesaContext(&failure);
        result.attempts.push_back(BackendAttempt{backend, impl ? "" : failure});
        if (impl) {
            result.context = std::make_unique<GlContext>(std::move(impl));
        }
    };
    if (kind == BackendKind::kAuto || kind == BackendKind::kEgl) {
        try_backend(BackendKind::kEgl);
    }
    if (!result.context && (kind == BackendKind::kAuto || kind == BackendKind::kOsMesa)) {
        try_backend(BackendKind::kOsMesa);
    }
    if (!result.context) {
        result.error = DescribeMissingGl(result.attempts);
    }
    return result;
}

int RunOnRenderingThreads(GlContext& context, const GlContextFactory& make_context, int threads,
                          const std::function<void(GlContext&)>& body) {
    std::atomic<int> started{1};
    std::vector<std::thread> others;
    for (int t = 1; t < threads && make_context; ++t) {
        others.emplace_back([&] {
            std::unique_ptr<GlContext> own = make_context();
            if (!own || !own->MakeCurrent()) {
                return;  // the threads that have a context do this one's share
            }
            ++started;
            body(*own);
        });
    }
    context.MakeCurrent();
    body(context);
    for (std::thread& t : others) {
        t.join();
    }
    context.MakeCurrent();
    return started.load();
}

namespace gl {

std::string LoadGlApi(ProcLoader loader, GlApi* api) {
#define TIDEPOOL_GL_LOAD(name, type)                   \
    api->name = reinterpret_cast<type>(loader(#name)); \
    if (api->name == nullptr) {                        \
        return #name;                                  \
    }
    TIDEPOOL_GL_FUNCTIONS(TIDEPOOL_GL_LOAD)
#undef TIDEPOOL_GL_LOAD
    return "";
}

std::unique_ptr<GlContext::Impl> CreateOsMesaContext(std::string* failure) {
    OsMesaSession* session = CreateOsMesaSession(failure);
    if (session == nullptr) {
        return nullptr;
    }
    auto impl = std::make_unique<GlContext::Impl>();
    const std::string missing = LoadGlApi(&OsMesaProc, &impl->api);
    if (!missing.empty()) {
        *failure = fmt::format("the OSMesa context lacks {}", missing);
        DestroyOsMesaSession(session);
        return nullptr;
    }
    impl->environment.backend = "osmesa";
    impl->make_current = [session] { return MakeOsMesaSessionCurrent(session); };
    impl->destroy = [session] { DestroyOsMesaSession(session); };
    QueryEnvironment(impl.get(), false, &OsMesaProc);
    return impl;
}

void QueryEnvironment(GlContext::Impl* impl, bool is_gles, ProcLoader loader) {
    const GlApi& api = impl->api;
    auto text = [&](GLenum name) {
        const GLubyte* value = api.glGetString(name);
        return value ? std::string(reinterpret_cast<const char*>(value)) : std::string();
    };
    GlEnvironment& env = impl->environment;
    env.context_api = is_gles ? "OpenGL ES" : "OpenGL compatibility";
    env.renderer = text(GL_RENDERER);
    env.version = text(GL_VERSION);
    env.shading_language = text(GL_SHADING_LANGUAGE_VERSION);
    std::smatch match;
    if (std::regex_search(env.version, match, std::regex(R"(Mesa ([0-9][^ ]*))"))) {
        env.mesa_version = match[1];
    }
    const std::string extensions = text(GL_EXTENSIONS);
    GLint major = 0;
    api.glGetIntegerv(GL_MAJOR_VERSION, &major);
    api.glGetError();  // GL_MAJOR_VERSION is unknown to a GLES 2.0 context: ignore that error
    // A GLES context renders to RGBA32F only with GLES 3 and EXT_color_buffer_float; desktop GL
    // 3.0 and later always can.
    env.float_render_target =
            is_gles ? (major >= 3 &&
                       extensions.find("GL_EXT_color_buffer_float") != std::string::npos)
                    : major >= 3;
    LoadTimerQueryApi(loader, extensions, &impl->timer_query);
    env.timer_query = impl->timer_query.Available();
}

void LoadTimerQueryApi(ProcLoader loader, const std::string& extensions, GlTimerQueryApi* api) {
    *api = GlTimerQueryApi{};
    if ((" " + extensions + " ").find(" GL_EXT_disjoint_timer_query ") == std::string::npos) {
        return;
    }
    api->glGenQueriesEXT = reinterpret_cast<PFNGLGENQUERIESEXTPROC>(loader("glGenQueriesEXT"));
    api->glDeleteQueriesEXT =
            reinterpret_cast<PFNGLDELETEQUERIESEXTPROC>(loader("glDeleteQueriesEXT"));
    api->glBeginQueryEXT = reinterpret_cast<PFNGLBEGINQUERYEXTPROC>(loader("glBeginQueryEXT"));
    api->glEndQueryEXT = reinterpret_cast<PFNGLENDQUERYEXTPROC>(loader("glEndQueryEXT"));
    api->glGetQueryObjectui64vEXT =
            reinterpret_cast<PFNGLGETQUERYOBJECTUI64VEXTPROC>(loader("glGetQueryObjectui64vEXT"));
    if (!api->Available()) {
        *api = GlTimerQueryApi{};
    }
}

}  // namespace gl
}  // namespace tidepool::runner
