#include "nearshore/playback/window.hpp"

#include <glad/gl.h>
// glad first: GLFW must not pull in the system GL header.
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "nearshore/core/error.hpp"
#include "nearshore/playback/gl_loader.hpp"

namespace nearshore::playback {
namespace {
std::string g_last_glfw_error;
void remember_glfw_error(int, const char* description) { g_last_glfw_error = description ? description : ""; }
}  // namespace

struct GlWindow::Impl {
  GLFWwindow* window = nullptr;
};

GlWindow::GlWindow(int width_px, int height_px, const std::string& title, bool visible) : impl_(new Impl) {
  glfwSetErrorCallback(remember_glfw_error);
  if (!glfwInit())
    throw Error("OpenGL window", "GLFW could not start: " + g_last_glfw_error,
                std::getenv("DISPLAY") ? "check the X display" : "no DISPLAY is set: run under `xvfb-run -a ...`");
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  // 4.5 first (llvmpipe's maximum; 4.6 requests fail there), then 3.3, which the shaders need.
  for (auto [major, minor] : {std::pair{4, 5}, std::pair{3, 3}}) {
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, major);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, minor);
    impl_->window = glfwCreateWindow(width_px, height_px, title.c_str(), nullptr, nullptr);
    if (impl_->window) break;
  }
  if (!impl_->window) {
    glfwTerminate();
    throw Error("OpenGL window", "no OpenGL 3.3 core context: " + g_last_glfw_error,
                "install Mesa (libgl1-mesa-dri) or update the GPU driver");
  }
  glfwMakeContextCurrent(impl_->window);
  glfwSwapInterval(visible ? 1 : 0);
  try {
    load_opengl(reinterpret_cast<GlProcAddressFunction>(glfwGetProcAddress));
  } catch (...) {
    glfwDestroyWindow(impl_->window);
    glfwTerminate();
    throw;
  }
}

GlWindow::~GlWindow() {
  if (impl_->window) glfwDestroyWindow(impl_->window);
  glfwTerminate();
}

bool GlWindow::should_close() const { return glfwWindowShouldClose(impl_->window); }

void GlWindow::present() {
  glfwSwapBuffers(impl_->window);
  glfwPollEvents();
  if (glfwGetKey(impl_->window, GLFW_KEY_ESCAPE) == GLFW_PRESS) glfwSetWindowShouldClose(impl_->window, GLFW_TRUE);
}

int GlWindow::framebuffer_width_px() const {
  int width = 0, height = 0;
  glfwGetFramebufferSize(impl_->window, &width, &height);
  return width;
}

int GlWindow::framebuffer_height_px() const {
  int width = 0, height = 0;
  glfwGetFramebufferSize(impl_->window, &width, &height);
  return height;
}

GLFWwindow* GlWindow::glfw_window() const { return impl_->window; }

Image GlWindow::read_back_buffer() const {
  const int width = framebuffer_width_px(), height = framebuffer_height_px();
  std::vector<unsigned char> rgb(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  Image image(width, height);
  for (int y = 0; y < height; ++y)  // GL row 0 is the bottom; Image row 0 the top
    for (int x = 0; x < width; ++x) {
      const unsigned char* pixel = &rgb[(static_cast<std::size_t>(height - 1 - y) * width + x) * 3];
      image.set(x, y, {pixel[0] / 255.f, pixel[1] / 255.f, pixel[2] / 255.f});
    }
  return image;
}

std::string GlWindow::gl_description() const {
  return std::string(reinterpret_cast<const char*>(glGetString(GL_VERSION))) + ", " +
         reinterpret_cast<const char*>(glGetString(GL_RENDERER));
}

}  // namespace nearshore::playback
