#pragma once
// The screen-space refraction's source (private to the water renderer): the opaque scene (sky,
// seabed, land, structures, hulls) as drawn before the sea, copied into a colour texture (the
// displayed 8-bit colour) and a depth texture the water shader samples where the refracted view
// meets it (docs/lighting.md step 5b). Needs the renderer's current GL context.
#include <glad/gl.h>

#include "gl_framebuffer.hpp"

namespace nearshore::playback {

class RefractionSource {
 public:
  RefractionSource() = default;
  ~RefractionSource() { release(); }
  RefractionSource(const RefractionSource&) = delete;
  RefractionSource& operator=(const RefractionSource&) = delete;

  /// Copies what `target` holds now (resized first when the size changed). The textures are made
  /// on units kSceneColour and kSceneDepth, never disturbing the units the draw has bound.
  void copy_from(const RenderTarget& target);
  GLuint colour() const { return colour_; }
  GLuint depth() const { return depth_; }

 private:
  void resize(int width, int height);
  void release();
  GLuint colour_ = 0, depth_ = 0;
  Framebuffer framebuffer_;
};

}  // namespace nearshore::playback
