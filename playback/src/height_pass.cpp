#include "height_pass.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gl_program.hpp"

namespace nearshore::playback {

HeightPass::HeightPass() {
  program_ = link_program({"common.glsl", "surface.glsl", "water_vertex.glsl"}, "height.vert.glsl",
                          {"common.glsl", "surface.glsl"}, "height.frag.glsl");
}

HeightPass::~HeightPass() {
  glDeleteProgram(program_);
  lattice_.release();
  target_.release();
}

Raster<float> HeightPass::render(const SurfaceFormula& formula, const SiteRectangle& r, int columns, int rows,
                                 double displacement_bound_m) {
  // One lattice vertex per cell centre, plus a margin of cells so the choppy shift never
  // uncovers the rectangle's edge.
  const double dx = (r.x1_m - r.x0_m) / columns, dy = (r.y1_m - r.y0_m) / rows;
  const int margin = std::clamp(int(std::ceil(displacement_bound_m / std::min(dx, dy))) + 1, 1, 64);
  const int lattice_columns = columns + 2 * margin, lattice_rows = rows + 2 * margin;
  if (lattice_columns != lattice_columns_ || lattice_rows != lattice_rows_) {
    lattice_.release();
    lattice_ = lattice_mesh(lattice_columns, lattice_rows, 1.f, 1.f);
    lattice_columns_ = lattice_columns;
    lattice_rows_ = lattice_rows;
  }
  target_.resize(columns, rows, GL_R32F);
  glBindFramebuffer(GL_FRAMEBUFFER, target_.draw_framebuffer());
  glViewport(0, 0, columns, rows);
  const float no_water[4] = {std::numeric_limits<float>::quiet_NaN(), 0.f, 0.f, 0.f};
  glClearBufferfv(GL_COLOR, 0, no_water);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);  // the highest surface where folds overlap
  glDisable(GL_CULL_FACE);
  glUseProgram(program_);
  set_uniform(program_, "u_view_projection",
              orthographic_top_down(r.x0_m, r.y0_m, r.x1_m, r.y1_m, -1000.0, 1000.0));
  const Vector3 eye = {0.5 * (r.x0_m + r.x1_m), 0.5 * (r.y0_m + r.y1_m), 1000.0};
  set_surface_uniforms(program_, formula, eye, 0.0);
  glUniform4f(at(program_, "u_lattice_m"), float(r.x0_m + (0.5 - margin) * dx),
              float(r.y0_m + (0.5 - margin) * dy), float(dx), float(dy));
  glBindVertexArray(lattice_.vertex_array);
  glDrawElements(GL_TRIANGLES, lattice_.index_count, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  Raster<float> heights(columns, rows);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, columns, rows, GL_RED, GL_FLOAT, heights.data());  // GL row 0 = south = raster row 0
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return heights;
}

}  // namespace nearshore::playback
