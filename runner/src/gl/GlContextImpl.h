// The backend state behind tidepool::runner::GlContext, shared by the EGL and OSMesa backends
// and the renderer.
#pragma once

#include "tidepool/runner/GlBackend.h"

#include <functional>
#include <string>

#include "gl/GlApi.h"

namespace tidepool::runner {

struct GlContext::Impl {
    gl::GlApi api;
    gl::GlTimerQueryApi timer_query;  // null pointers without GL_EXT_disjoint_timer_query
    GlEnvironment environment;
    std::function<bool()> make_current;  // binds the backend context to this thread
    std::function<void()> destroy;       // releases the backend context
};

namespace gl {

/// Creates an EGL surfaceless GLES context; null with `failure` set when that is impossible.
std::unique_ptr<GlContext::Impl> CreateEglContext(std::string* failure);

/// Creates an OSMesa desktop compatibility context; null with `failure` set when impossible.
std::unique_ptr<GlContext::Impl> CreateOsMesaContext(std::string* failure);

/// Fills `impl->environment` from the current context (strings, Mesa version, float targets).
void QueryEnvironment(GlContext::Impl* impl, bool is_gles, ProcLoader loader);

}  // namespace gl
}  // namespace tidepool::runner
