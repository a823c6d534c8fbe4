// OSMesa: Mesa's off-screen desktop GL (compatibility profile) context, the fallback when EGL is
// unavailable. The GLSL ES 1.00 shaders compile there because Mesa's desktop GL exposes
// ARB_ES2_compatibility, which accepts `#version 100` (checked by the backend GL test).
//
// This file includes GL/osmesa.h (which pulls in desktop GL/gl.h) and no GLES header.
//
// libOSMesa is opened when the first OSMesa context is asked for, not linked: it loads Mesa's
// LLVM (libLLVM-15, about 100 MB), and every process that links the runner, each unit test
// included, would otherwise pay for loading and relocating it at start-up (most under ASan).
#include <GL/osmesa.h>

#include <vector>

#include "gl/OsMesaSession.h"
#include <dlfcn.h>

namespace tidepool::runner::gl {
namespace {

// OSMesa needs a colour buffer to make a context current; the renderer draws into framebuffer
// objects, so a tiny one suffices.
constexpr int kBufferSize = 4;

// The four OSMesa entry points the backend calls, from libOSMesa.so.8 (Debian's libosmesa6).
struct OsMesaLibrary {
    decltype(&OSMesaCreateContextAttribs) create_context_attribs = nullptr;
    decltype(&OSMesaMakeCurrent) make_current = nullptr;
    decltype(&OSMesaDestroyContext) destroy_context = nullptr;
    decltype(&OSMesaGetProcAddress) get_proc_address = nullptr;
    std::string error;  // why the library or one of its functions could not be loaded
};

// Loads `name` unless an earlier function is missing, so that `error` names the first one.
template <typename Function>
void LoadSymbol(void* library, const char* name, Function* function, std::string* error) {
    if (!error->empty()) {
        return;
    }
    *function = reinterpret_cast<Function>(dlsym(library, name));
    if (*function == nullptr) {
        *error = std::string("libOSMesa.so.8 lacks ") + name;
    }
}

// Opened once per process and never closed: contexts may live until exit. RTLD_GLOBAL, as
// linking it did, so that Mesa's libraries see one another's symbols as before.
const OsMesaLibrary& Library() {
    static const OsMesaLibrary library = [] {
        OsMesaLibrary loaded;
        void* handle = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_GLOBAL);
        if (handle == nullptr) {
            const char* reason = dlerror();
            loaded.error = std::string("cannot load libOSMesa.so.8: ") +
                           (reason != nullptr ? reason : "unknown reason");
            return loaded;
        }
        LoadSymbol(handle, "OSMesaCreateContextAttribs", &loaded.create_context_attribs,
                   &loaded.error);
        LoadSymbol(handle, "OSMesaMakeCurrent", &loaded.make_current, &loaded.error);
        LoadSymbol(handle, "OSMesaDestroyContext", &loaded.destroy_context, &loaded.error);
        LoadSymbol(handle, "OSMesaGetProcAddress", &loaded.get_proc_address, &loaded.error);
        return loaded;
    }();
    return library;
}

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
    const OsMesaLibrary& library = Library();
    if (!library.error.empty()) {
        *failure = library.error;
        return nullptr;
    }
    OSMesaContext context = library.create_context_attribs(attributes, nullptr);
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
    return Library().make_current(session->context, session->buffer.data(), GL_UNSIGNED_BYTE,
                                  kBufferSize, kBufferSize) == GL_TRUE;
}

void DestroyOsMesaSession(OsMesaSession* session) {
    Library().destroy_context(session->context);
    delete session;
}

void* OsMesaProc(const char* name) {
    return reinterpret_cast<void*>(Library().get_proc_address(name));
}

}  // namespace tidepool::runner::gl
