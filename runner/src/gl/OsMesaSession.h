// A GL-header-free view of an OSMesa context, so that desktop GL/gl.h (pulled in by
// GL/osmesa.h) and the GLES headers of GlApi.h never meet in one translation unit.
#pragma once

#include <string>

namespace tidepool::runner::gl {

/// An OSMesa compatibility-profile context with its tiny colour buffer.
struct OsMesaSession;

/// Creates a session; null with `failure` set when OSMesa refuses.
OsMesaSession* CreateOsMesaSession(std::string* failure);

/// Makes the session current on this thread; false when OSMesa refuses.
bool MakeOsMesaSessionCurrent(OsMesaSession* session);

/// Destroys the session and its context.
void DestroyOsMesaSession(OsMesaSession* session);

/// OSMesaGetProcAddress.
void* OsMesaProc(const char* name);

}  // namespace tidepool::runner::gl
