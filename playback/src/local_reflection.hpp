#pragma once
// The local reflection's target (private to the water renderer): land, structures and hulls
// mirrored in still water, drawn as linear radiance (RGBA16F, alpha = covered) into a texture the
// water shader samples at its own screen position. Needs the renderer's current GL context.
#include <glad/gl.h>

#include "gl_framebuffer.hpp"

namespace nearshore::playback {

class LocalReflection {
 public:
  LocalReflection() = default;
  ~LocalReflection() { release(); }
  LocalReflection(const LocalReflection&) = delete;
  LocalReflection& operator=(const LocalReflection&) = delete;

  /// Makes the texture and its framebuffer anew only when the size changed. The texture is made
  /// on unit kReflection, never disturbing the units the draw has bound.
  void resize(int width, int height);
  GLuint framebuffer() const { return framebuffer_.id(); }
  GLuint colour() const { return colour_; }
  int width() const { return framebuffer_.width(); }
  int height() const { return framebuffer_.height(); }

 private:
  void release();
  GLuint colour_ = 0;
  Framebuffer framebuffer_;
};

}  // namespace nearshore::playback
