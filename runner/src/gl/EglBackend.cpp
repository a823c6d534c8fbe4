// EGL on Mesa's surfaceless platform: no window system, no config, a GLES context that renders
// into framebuffer objects only.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>

#include "gl/GlContextImpl.h"
#include <fmt/format.h>

namespace tidepool::runner::gl {
namespace {

bool HasExtension(const char* list, const char* name) {
    if (list == nullptr) {
        return false;
    }
    const std::string padded = std::string(" ") + list + " ";
    return padded.find(std::string(" ") + name + " ") != std::string::npos;
}

void* EglProc(const char* name) {
    return reinterpret_cast<void*>(eglGetProcAddress(name));
}

}  // namespace

std::unique_ptr<GlContext::Impl> CreateEglContext(std::string* failure) {
    const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!HasExtension(client_extensions, "EGL_MESA_platform_surfaceless")) {
        *failure =
                "EGL_MESA_platform_surfaceless is not offered (is Mesa's EGL, package "
                "libegl-mesa0, installed and chosen by libglvnd?)";
        return nullptr;
    }
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
            eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display == nullptr) {
        *failure = "eglGetPlatformDisplayEXT is missing";
        return nullptr;
    }
    EGLDisplay display =
            get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) {
        *failure = fmt::format("eglGetPlatformDisplayEXT(surfaceless) failed (EGL error 0x{:x})",
                               eglGetError());
        return nullptr;
    }
    EGLint major = 0;
    EGLint minor = 0;
    if (eglInitialize(display, &major, &minor) != EGL_TRUE) {
        *failure = fmt::format(
                "eglInitialize failed (EGL error 0x{:x}): no usable Mesa driver "
                "(package libgl1-mesa-dri)",
                eglGetError());
        return nullptr;
    }
    const char* display_extensions = eglQueryString(display, EGL_EXTENSIONS);
    if (!HasExtension(display_extensions, "EGL_KHR_no_config_context") &&
        !HasExtension(display_extensions, "EGL_MESA_configless_context")) {
        *failure = "neither EGL_KHR_no_config_context nor EGL_MESA_configless_context is offered";
        return nullptr;
    }
    if (!HasExtension(display_extensions, "EGL_KHR_surfaceless_context")) {
        *failure = "EGL_KHR_surfaceless_context is not offered";
        return nullptr;
    }
    if (eglBindAPI(EGL_OPENGL_ES_API) != EGL_TRUE) {
        *failure = "eglBindAPI(EGL_OPENGL_ES_API) failed";
        return nullptr;
    }
    // GLES 2.0 is what the shaders target; Mesa returns the highest compatible version (3.2 on
    // llvmpipe), which the NaN check uses for float render targets when it is there.
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 2, EGL_NONE};
    EGLContext context =
            eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, context_attributes);
    if (context == EGL_NO_CONTEXT) {
        *failure = fmt::format("eglCreateContext(GLES 2, no config) failed (EGL error 0x{:x})",
                               eglGetError());
        return nullptr;
    }
    if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) != EGL_TRUE) {
        *failure =
                fmt::format("eglMakeCurrent(surfaceless) failed (EGL error 0x{:x})", eglGetError());
        eglDestroyContext(display, context);
        return nullptr;
    }
    auto impl = std::make_unique<GlContext::Impl>();
    const std::string missing = LoadGlApi(&EglProc, &impl->api);
    if (!missing.empty()) {
        *failure = fmt::format("the GLES context lacks {}", missing);
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
        return nullptr;
    }
    impl->environment.backend = "egl";
    impl->make_current = [display, context] {
        return eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) == EGL_TRUE;
    };
    // The display is not terminated: Mesa returns the same display to every caller in the
    // process, so terminating it would pull it from under other live contexts.
    impl->destroy = [display, context] {
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
    };
    QueryEnvironment(impl.get(), true, &EglProc);
    return impl;
}

}  // namespace tidepool::runner::gl
