// The GL entry points the runner uses, loaded at run time through the backend's GetProcAddress.
//
// Why a table instead of calling libGLESv2 directly: the process may hold an EGL (GLES) context or
// an OSMesa (desktop compatibility) context, and libGLESv2's dispatch only reaches EGL contexts.
// Loading every entry point from the backend that made the context works for both. The functions
// and enum values used here are identical in GLES 2.0/3.0 and desktop GL 4.5 compatibility.
#pragma once

#include <GLES3/gl3.h>

#include <string>

#include <GLES2/gl2ext.h>

namespace tidepool::runner::gl {

// X(name, type) for every entry point; the type is the Khronos PFN typedef.
#define TIDEPOOL_GL_FUNCTIONS(X)                                     \
    X(glGetString, PFNGLGETSTRINGPROC)                               \
    X(glGetError, PFNGLGETERRORPROC)                                 \
    X(glGetIntegerv, PFNGLGETINTEGERVPROC)                           \
    X(glEnable, PFNGLENABLEPROC)                                     \
    X(glDisable, PFNGLDISABLEPROC)                                   \
    X(glViewport, PFNGLVIEWPORTPROC)                                 \
    X(glClearColor, PFNGLCLEARCOLORPROC)                             \
    X(glClear, PFNGLCLEARPROC)                                       \
    X(glDepthFunc, PFNGLDEPTHFUNCPROC)                               \
    X(glDepthMask, PFNGLDEPTHMASKPROC)                               \
    X(glBlendFunc, PFNGLBLENDFUNCPROC)                               \
    X(glFrontFace, PFNGLFRONTFACEPROC)                               \
    X(glCullFace, PFNGLCULLFACEPROC)                                 \
    X(glFinish, PFNGLFINISHPROC)                                     \
    X(glReadPixels, PFNGLREADPIXELSPROC)                             \
    X(glPixelStorei, PFNGLPIXELSTOREIPROC)                           \
    X(glCreateShader, PFNGLCREATESHADERPROC)                         \
    X(glShaderSource, PFNGLSHADERSOURCEPROC)                         \
    X(glCompileShader, PFNGLCOMPILESHADERPROC)                       \
    X(glGetShaderiv, PFNGLGETSHADERIVPROC)                           \
    X(glGetShaderInfoLog, PFNGLGETSHADERINFOLOGPROC)                 \
    X(glDeleteShader, PFNGLDELETESHADERPROC)                         \
    X(glCreateProgram, PFNGLCREATEPROGRAMPROC)                       \
    X(glAttachShader, PFNGLATTACHSHADERPROC)                         \
    X(glBindAttribLocation, PFNGLBINDATTRIBLOCATIONPROC)             \
    X(glLinkProgram, PFNGLLINKPROGRAMPROC)                           \
    X(glGetProgramiv, PFNGLGETPROGRAMIVPROC)                         \
    X(glGetProgramInfoLog, PFNGLGETPROGRAMINFOLOGPROC)               \
    X(glDeleteProgram, PFNGLDELETEPROGRAMPROC)                       \
    X(glUseProgram, PFNGLUSEPROGRAMPROC)                             \
    X(glGetUniformLocation, PFNGLGETUNIFORMLOCATIONPROC)             \
    X(glUniform1i, PFNGLUNIFORM1IPROC)                               \
    X(glUniform1f, PFNGLUNIFORM1FPROC)                               \
    X(glUniform2f, PFNGLUNIFORM2FPROC)                               \
    X(glUniform3f, PFNGLUNIFORM3FPROC)                               \
    X(glUniform4f, PFNGLUNIFORM4FPROC)                               \
    X(glUniformMatrix4fv, PFNGLUNIFORMMATRIX4FVPROC)                 \
    X(glGenBuffers, PFNGLGENBUFFERSPROC)                             \
    X(glBindBuffer, PFNGLBINDBUFFERPROC)                             \
    X(glBufferData, PFNGLBUFFERDATAPROC)                             \
    X(glBufferSubData, PFNGLBUFFERSUBDATAPROC)                       \
    X(glDeleteBuffers, PFNGLDELETEBUFFERSPROC)                       \
    X(glEnableVertexAttribArray, PFNGLENABLEVERTEXATTRIBARRAYPROC)   \
    X(glDisableVertexAttribArray, PFNGLDISABLEVERTEXATTRIBARRAYPROC) \
    X(glVertexAttribPointer, PFNGLVERTEXATTRIBPOINTERPROC)           \
    X(glVertexAttrib3f, PFNGLVERTEXATTRIB3FPROC)                     \
    X(glDrawArrays, PFNGLDRAWARRAYSPROC)                             \
    X(glDrawElements, PFNGLDRAWELEMENTSPROC)                         \
    X(glGenTextures, PFNGLGENTEXTURESPROC)                           \
    X(glBindTexture, PFNGLBINDTEXTUREPROC)                           \
    X(glTexImage2D, PFNGLTEXIMAGE2DPROC)                             \
    X(glTexParameteri, PFNGLTEXPARAMETERIPROC)                       \
    X(glActiveTexture, PFNGLACTIVETEXTUREPROC)                       \
    X(glGenerateMipmap, PFNGLGENERATEMIPMAPPROC)                     \
    X(glDeleteTextures, PFNGLDELETETEXTURESPROC)                     \
    X(glGenFramebuffers, PFNGLGENFRAMEBUFFERSPROC)                   \
    X(glBindFramebuffer, PFNGLBINDFRAMEBUFFERPROC)                   \
    X(glFramebufferTexture2D, PFNGLFRAMEBUFFERTEXTURE2DPROC)         \
    X(glFramebufferRenderbuffer, PFNGLFRAMEBUFFERRENDERBUFFERPROC)   \
    X(glCheckFramebufferStatus, PFNGLCHECKFRAMEBUFFERSTATUSPROC)     \
    X(glDeleteFramebuffers, PFNGLDELETEFRAMEBUFFERSPROC)             \
    X(glGenRenderbuffers, PFNGLGENRENDERBUFFERSPROC)                 \
    X(glBindRenderbuffer, PFNGLBINDRENDERBUFFERPROC)                 \
    X(glRenderbufferStorage, PFNGLRENDERBUFFERSTORAGEPROC)           \
    X(glDeleteRenderbuffers, PFNGLDELETERENDERBUFFERSPROC)

/// A backend's way of finding an entry point by name (eglGetProcAddress, OSMesaGetProcAddress).
using ProcLoader = void* (*)(const char* name);

/// Every GL entry point the runner calls, as function pointers of the current context's backend.
struct GlApi {
#define TIDEPOOL_GL_DECLARE(name, type) type name = nullptr;
    TIDEPOOL_GL_FUNCTIONS(TIDEPOOL_GL_DECLARE)
#undef TIDEPOOL_GL_DECLARE
};

/// GL_EXT_disjoint_timer_query's entry points: optional, for GPU frame times where a hardware
/// driver offers them; every pointer is null when the context lacks one of them.
struct GlTimerQueryApi {
    PFNGLGENQUERIESEXTPROC glGenQueriesEXT = nullptr;
    PFNGLDELETEQUERIESEXTPROC glDeleteQueriesEXT = nullptr;
    PFNGLBEGINQUERYEXTPROC glBeginQueryEXT = nullptr;
    PFNGLENDQUERYEXTPROC glEndQueryEXT = nullptr;
    PFNGLGETQUERYOBJECTUI64VEXTPROC glGetQueryObjectui64vEXT = nullptr;

    /// True when every entry point was found.
    bool Available() const {
        return glGenQueriesEXT != nullptr && glDeleteQueriesEXT != nullptr &&
               glBeginQueryEXT != nullptr && glEndQueryEXT != nullptr &&
               glGetQueryObjectui64vEXT != nullptr;
    }
};

/// Loads every entry point through `loader`; returns the name of the first one missing, or ""
/// when all were found.
std::string LoadGlApi(ProcLoader loader, GlApi* api);

/// Loads the timer-query entry points when `extensions` (GL_EXTENSIONS) lists
/// GL_EXT_disjoint_timer_query; leaves them null otherwise. Never fails.
void LoadTimerQueryApi(ProcLoader loader, const std::string& extensions, GlTimerQueryApi* api);

}  // namespace tidepool::runner::gl
