#pragma once
// The deep water's persistent foam (private to the water renderer; seed 000 eq. 3.46): f_t over
// the largest cascade's tile, one texel per deep sample, in two R32F textures updated in turn
// (foam_decay.frag.glsl reads one, writes the other), so the foam a crest leaves fades with the
// display time, not the frame rate. Needs the renderer's current GL context.
#include <glad/gl.h>

#include "gl_framebuffer.hpp"
#include "nearshore/core/raster.hpp"
#include "nearshore/playback/lighting.hpp"
#include "pass_timer.hpp"
#include "surface_uniforms.hpp"

namespace nearshore::playback {

class DeepFoamPass {
 public:
  DeepFoamPass();  ///< links sky.vert + foam_decay.frag (one triangle over the map)
  ~DeepFoamPass();
  DeepFoamPass(const DeepFoamPass&) = delete;
  DeepFoamPass& operator=(const DeepFoamPass&) = delete;

  /// Seed 000 eq. (3.46) one step on: f_t = exp(-dt / decay time) f_t + f_b over the largest tile,
  /// dt the display time since the last step. The same display time again (a paused picture, a
  /// second view) changes nothing; time running backwards, another tile or decay time 0 starts
  /// afresh (f_t = f_b). Returns whether there is a map to sample (false without deep water or
  /// with decay time 0). Needs the deep textures bound; leaves framebuffer 0 bound.
  bool update(const SurfaceFormula& formula, const LightingFrame& light, PassTimer& timer);
  /// The texture holding f_t (unit kDeepFoam when drawing the sea).
  GLuint foam() const { return texture_[current_]; }
  /// f_t read back (row 0 = y 0 = south); 0 x 0 before the first update.
  Raster<float> read_map() const;

 private:
  void resize(int texels, float tile_length_m);
  void release();
  GLuint program_ = 0;
  GLuint empty_vertex_array_ = 0;  // the vertex shader makes the triangle from gl_VertexID
  GLuint texture_[2] = {0, 0};
  Framebuffer framebuffer_[2];
  int size_ = 0, current_ = 0;  // texture_[current_] holds f_t
  float tile_length_m_ = 0.f;
  double time_s_ = 0.0;  // the display time f_t belongs to
  bool valid_ = false;
};

}  // namespace nearshore::playback
