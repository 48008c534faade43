#include "deep_foam_pass.hpp"

#include <cmath>

#include "gl_program.hpp"
#include "gl_texture.hpp"

namespace nearshore::playback {

DeepFoamPass::DeepFoamPass() {
  program_ =
      link_program({"common.glsl"}, "sky.vert.glsl", {"common.glsl", "surface.glsl"}, "foam_decay.frag.glsl");
  glGenVertexArrays(1, &empty_vertex_array_);
}

DeepFoamPass::~DeepFoamPass() {
  release();
  glDeleteProgram(program_);
  glDeleteVertexArrays(1, &empty_vertex_array_);
}

void DeepFoamPass::resize(int texels, float tile_length_m) {
  if (texels == size_ && tile_length_m == tile_length_m_ && framebuffer_[0]) return;
  release();
  for (int k = 0; k < 2; ++k) {
    glActiveTexture(GLenum(GL_TEXTURE0 + kPreviousFoam));  // never disturb the units the draw has bound
    texture_[k] = new_texture(GL_TEXTURE_2D, GL_LINEAR, GL_REPEAT);  // the tile repeats
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, texels, texels, 0, GL_RED, GL_FLOAT, nullptr);
    framebuffer_[k] = Framebuffer::with_texture(
        texture_[k], texels, texels, false,
        {"the deep-water foam framebuffer is incomplete", "set Lighting::foam_decay_time_s = 0"});
  }
  size_ = texels;
  tile_length_m_ = tile_length_m;
  valid_ = false;
}

void DeepFoamPass::release() {
  for (Framebuffer& framebuffer : framebuffer_) framebuffer.release();
  for (GLuint& texture : texture_)
    if (texture) glDeleteTextures(1, &texture), texture = 0;
  size_ = current_ = 0;
  tile_length_m_ = 0.f;
  time_s_ = 0.0;
  valid_ = false;
}

bool DeepFoamPass::update(const SurfaceFormula& formula, const LightingFrame& light, PassTimer& timer) {
  const KeyframeTextures::Bound& bound = formula.bound;
  if (bound.cascade_count == 0 || light.foam_decay_time_s <= 0.0) {
    valid_ = false;
    return false;
  }
  resize(bound.deep_size, bound.tile_lengths_m[0]);
  const double dt = formula.snapshot.display_time_s - time_s_;
  if (valid_ && dt == 0.0) return true;
  const float persistence = valid_ && dt > 0.0 ? float(std::exp(-dt / light.foam_decay_time_s)) : 0.f;
  const int next = 1 - current_;
  timer.begin_pass(GpuPass::deep_foam);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_[next].id());
  glViewport(0, 0, size_, size_);
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program_);
  set_surface_uniforms(program_, formula, {0.0, 0.0, 0.0}, 0.0);
  set_uniform(program_, "u_foam_persistence", persistence);
  set_uniform(program_, "u_jacobian_foam_onset", float(light.jacobian_foam_onset));
  set_uniform(program_, "u_map_texel_m", tile_length_m_ / float(size_));
  glActiveTexture(GLenum(GL_TEXTURE0 + kPreviousFoam));
  glBindTexture(GL_TEXTURE_2D, texture_[current_]);
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(empty_vertex_array_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glEnable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  timer.end_pass();
  current_ = next;
  time_s_ = formula.snapshot.display_time_s;
  valid_ = true;
  return true;
}

Raster<float> DeepFoamPass::read_map() const {
  if (!valid_) return Raster<float>(0, 0);
  Raster<float> map(size_, size_);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_[current_].id());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, size_, size_, GL_RED, GL_FLOAT, map.data());  // row 0 = y 0 = south
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return map;
}

}  // namespace nearshore::playback
