#include "terrain_pass.hpp"

#include "gl_program.hpp"

namespace nearshore::playback {

TerrainPass::TerrainPass() {
  program_ = link_program({"common.glsl", "surface.glsl"}, "terrain.vert.glsl", {"common.glsl"},
                          "terrain.frag.glsl");
}

TerrainPass::~TerrainPass() {
  glDeleteProgram(program_);
}

void TerrainPass::draw(const Mesh& terrain, const SurfaceFormula& formula, const LightingFrame& light,
                       const CameraView& view, double earth_radius_m) const {
  glUseProgram(program_);
  set_lighting_uniforms(program_, light);
  set_uniform(program_, "u_view_projection", view.view_projection);
  set_surface_uniforms(program_, formula, view.eye_m, earth_radius_m);
  set_uniform(program_, "u_mirror", 0);
  glBindVertexArray(terrain.vertex_array);
  glDrawElements(GL_TRIANGLES, terrain.index_count, GL_UNSIGNED_INT, nullptr);
}

void TerrainPass::draw_mirrored(const Mesh& terrain, const Matrix4& mirrored_view_projection) const {
  glUseProgram(program_);
  glBindVertexArray(terrain.vertex_array);
  set_uniform(program_, "u_view_projection", mirrored_view_projection);
  set_uniform(program_, "u_mirror", 1);
  glDrawElements(GL_TRIANGLES, terrain.index_count, GL_UNSIGNED_INT, nullptr);
  set_uniform(program_, "u_mirror", 0);
}

}  // namespace nearshore::playback
