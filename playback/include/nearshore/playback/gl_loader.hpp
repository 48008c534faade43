#pragma once
// Loading OpenGL in a host's context. nearshore calls OpenGL through its own glad2 loader; the
// functions must be loaded once, with the context current, from the host's windowing library
// (glfwGetProcAddress, SDL_GL_GetProcAddress, eglGetProcAddress, ...). GlWindow does it for the
// nearshore viewer; a host that draws with nearshore in its own window calls this first.

namespace nearshore::playback {

/// Returns the address of an OpenGL function by name, or null.
using GlProcAddressFunction = void* (*)(const char* name);

/// Loads the OpenGL 3.3+ core functions of the context current on this thread. Throws
/// nearshore::Error when `get_proc_address` is null or the context offers less than OpenGL 3.3.
void load_opengl(GlProcAddressFunction get_proc_address);

}  // namespace nearshore::playback
