#pragma once
// The sky behind everything (private to the water renderer): one triangle over the screen at the
// far plane, each pixel shaded by the Perez sky of common.glsl along its view ray.
#include <glad/gl.h>

#include "nearshore/playback/camera.hpp"
#include "nearshore/playback/lighting.hpp"

namespace nearshore::playback {

class SkyPass {
 public:
  SkyPass();  ///< links sky.vert/frag; needs the renderer's current GL context
  ~SkyPass();
  SkyPass(const SkyPass&) = delete;
  SkyPass& operator=(const SkyPass&) = delete;

  /// Draws into the bound framebuffer without writing depth, so everything drawn after covers it.
  void draw(const LightingFrame& light, const CameraView& view) const;

 private:
  GLuint program_ = 0;
  GLuint empty_vertex_array_ = 0;  // the vertex shader makes the triangle from gl_VertexID
};

}  // namespace nearshore::playback
