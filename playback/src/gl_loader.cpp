#include "nearshore/playback/gl_loader.hpp"

#include <glad/gl.h>

#include <string>

#include "nearshore/core/error.hpp"

namespace nearshore::playback {

void load_opengl(GlProcAddressFunction get_proc_address) {
  if (!get_proc_address)
    throw Error("load_opengl", "get_proc_address is null",
                "pass the windowing library's loader, e.g. glfwGetProcAddress or SDL_GL_GetProcAddress");
  const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(get_proc_address));
  if (version == 0 || GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 33)
    throw Error("the current OpenGL context",
                version == 0 ? std::string("offers no OpenGL functions (is a context current on this thread?)")
                             : "is OpenGL " + std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                                   std::to_string(GLAD_VERSION_MINOR(version)) + ", nearshore needs 3.3 core",
                "make an OpenGL 3.3+ core context current before creating the renderer");
}

}  // namespace nearshore::playback
