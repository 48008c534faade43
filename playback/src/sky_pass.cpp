#include "sky_pass.hpp"

#include "gl_program.hpp"

namespace nearshore::playback {

SkyPass::SkyPass() {
  program_ = link_program({"common.glsl"}, "sky.vert.glsl", {"common.glsl"}, "sky.frag.glsl");
  glGenVertexArrays(1, &empty_vertex_array_);
}

SkyPass::~SkyPass() {
  glDeleteProgram(program_);
  glDeleteVertexArrays(1, &empty_vertex_array_);
}

void SkyPass::draw(const LightingFrame& light, const CameraView& view) const {
  glUseProgram(program_);
  set_lighting_uniforms(program_, light);
  set_uniform(program_, "u_inverse_view_projection", inverse(view.view_projection));
  set_uniform(program_, "u_eye_m", view.eye_m);
  glBindVertexArray(empty_vertex_array_);
  glDepthMask(GL_FALSE);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
}

}  // namespace nearshore::playback
