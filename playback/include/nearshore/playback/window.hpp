#pragma once
// GlWindow: a GLFW window with an OpenGL 3.3+ core context (4.5 requested first, as llvmpipe and
// real GPUs offer), its loader initialised. Hidden windows serve screenshots; on a machine without
// a display run under Xvfb (`xvfb-run -a nearshore play ...`).
#include <memory>
#include <string>

#include "nearshore/core/image.hpp"

struct GLFWwindow;

namespace nearshore::playback {

class GlWindow {
 public:
  /// Throws nearshore::Error naming what failed (no display, no GL 3.3) and the fix.
  GlWindow(int width_px, int height_px, const std::string& title, bool visible);
  ~GlWindow();
  GlWindow(const GlWindow&) = delete;
  GlWindow& operator=(const GlWindow&) = delete;

  bool should_close() const;
  /// Shows what was rendered (swap) and handles window events.
  void present();
  int framebuffer_width_px() const;
  int framebuffer_height_px() const;
  /// "4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string gl_description() const;
  /// The GLFW window, for a host's own input handling and on-screen panels (Dear ImGui).
  GLFWwindow* glfw_window() const;
  /// The window's back buffer as drawn so far (before present()), row 0 at the top: the rendered
  /// sea with anything drawn over it (the viewer's panel), for screenshots.
  Image read_back_buffer() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nearshore::playback
