// OSMesa: Mesa's off-screen desktop GL (compatibility profile) context, the fallback when EGL is
// unavailable. The GLSL ES 1.00 shaders compile there because Mesa's desktop GL exposes
// ARB_ES2_compatibility, which accepts `#version 100` (checked by the backend GL test).
//
// This file includes GL/osmesa.h (which pulls in desktop GL/gl.h) and no GLES header.
#include <GL/osmesa.h>

#include <vector>

#include "gl/OsMesaSession.h"

namespace tidepool::runner::gl {
namespace {

// OSMesa needs a colour buffer to make a context current; the renderer draws into framebuffer
// objects, so a tiny one suffices.
constexpr int kBufferSize = 4;

}  // namespace

struct OsMesaSession {
    OSMesaContext context = nullptr;
    std::vector<unsigned char> buffer =
            std::vector<unsigned char>(static_cast<std::size_t>(kBufferSize * kBufferSize * 4));
};

OsMesaSession* CreateOsMesaSession(std::string* failure) {
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_PROFILE,
                              OSMESA_COMPAT_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              2,
                              0};
    OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (context == nullptr) {
        *failure = "OSMesaCreateContextAttribs(compatibility profile) failed";
        return nullptr;
    }
    auto* session = new OsMesaSession;
    session->context = context;
    if (!MakeOsMesaSessionCurrent(session)) {
        *failure = "OSMesaMakeCurrent failed";
        DestroyOsMesaSession(session);
        return nullptr;
    }
    return session;
}

bool MakeOsMesaSessionCurrent(OsMesaSession* session) {
    return OSMesaMakeCurrent(session->context, session->buffer.data(), GL_UNSIGNED_BYTE,
                             kBufferSize, kBufferSize) == GL_TRUE;
}

void DestroyOsMesaSession(OsMesaSession* session) {
    OSMesaDestroyContext(session->context);
    delete session;
}

void* OsMesaProc(const char* name) {
    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
}

}  // namespace tidepool::runner::gl
