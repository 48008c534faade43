#include "water_surface_pass.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "gl_program.hpp"

namespace nearshore::playback {

namespace {

bool same(const RadialGridSettings& a, const RadialGridSettings& b) {
  return a.segment_count == b.segment_count && a.inner_spacing_m == b.inner_spacing_m &&
         a.outer_radius_m == b.outer_radius_m;
}

}  // namespace

WaterSurfacePass::WaterSurfacePass() {
  const std::initializer_list<const char*> water_vertex = {"common.glsl", "surface.glsl",
                                                           "water_vertex.glsl"};
  const std::initializer_list<const char*> surface = {"common.glsl", "surface.glsl"};
  radial_program_ = link_program(water_vertex, "water_radial.vert.glsl", surface, "water.frag.glsl");
  quadtree_program_ = link_program(water_vertex, "water_quadtree.vert.glsl", surface, "water.frag.glsl");
  projected_program_ = link_program(water_vertex, "water_projected.vert.glsl", surface, "water.frag.glsl");
}

WaterSurfacePass::~WaterSurfacePass() {
  for (GLuint program : {radial_program_, quadtree_program_, projected_program_}) glDeleteProgram(program);
  for (Mesh* mesh : {&radial_, &quadtree_patch_, &projected_}) mesh->release();
}

GLuint WaterSurfacePass::program(GridKind kind) const {
  return kind == GridKind::radial     ? radial_program_
         : kind == GridKind::quadtree ? quadtree_program_
                                      : projected_program_;
}

void WaterSurfacePass::draw(const SeaDraw& sea, PassTimer& timer, FrameStatistics& statistics) {
  QuadtreeSelection selection;
  ProjectedGridLayout layout;
  prepare_grid(sea.settings, sea.view, selection, layout, statistics);
  const GLuint program = this->program(sea.settings.grid);
  glUseProgram(program);
  set_lighting_uniforms(program, sea.light);
  set_water_lighting_uniforms(program, sea.formula.snapshot, sea.light);
  set_uniform(program, "u_has_reflection", sea.reflection ? 1 : 0);
  set_uniform(program, "u_has_decal_foam", sea.decal_foam ? 1 : 0);
  set_uniform(program, "u_has_deep_foam", sea.deep_foam ? 1 : 0);
  set_uniform(program, "u_has_scene", sea.refraction ? 1 : 0);
  if (sea.refraction) set_uniform(program, "u_inverse_view_projection", inverse(sea.view.view_projection));
  set_uniform(program, "u_detail_parallax", float(sea.light.detail_parallax));
  set_uniform(program, "u_filter_baked_slopes", sea.light.filter_baked_slopes ? 1 : 0);
  if (sea.decal_foam) {
    const std::array<float, 4>& rect = sea.decal_foam_rect_m;
    glUniform4f(at(program, "u_decal_foam_rect_m"), rect[0], rect[1], rect[2], rect[3]);
  }
  glUniform2f(at(program, "u_viewport_px"), float(sea.width_px), float(sea.height_px));
  glUniform2f(at(program, "u_viewport_origin_px"), float(sea.viewport_x_px), float(sea.viewport_y_px));
  timer.begin_pass(GpuPass::water);
  draw_grid(program, sea, selection, layout, true, statistics);
  if (sea.options.wireframe) {
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glEnable(GL_POLYGON_OFFSET_LINE);
    glPolygonOffset(-1.f, -1.f);
    draw_grid(program, sea, selection, layout, false, statistics);
    glDisable(GL_POLYGON_OFFSET_LINE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
}

void WaterSurfacePass::draw_grid(GLuint program, const SeaDraw& sea, const QuadtreeSelection& selection,
                                 const ProjectedGridLayout& layout, bool count, FrameStatistics& statistics) {
  const GridKind kind = sea.settings.grid;
  glUseProgram(program);
  set_uniform(program, "u_view_projection", sea.view.view_projection);
  set_surface_uniforms(program, sea.formula, sea.view.eye_m, sea.earth_radius_m);
  const int colouring = sea.options.wireframe && !count ? 3 : int(sea.options.colouring);
  set_uniform(program, "u_colouring", colouring);
  set_uniform(program, "u_flat_colour", sea.options.flat_colour);
  if (kind == GridKind::radial) {
    set_uniform(program, "u_lod_unit_m", float(sea.settings.radial.inner_spacing_m));
    glBindVertexArray(radial_.vertex_array);
    glDrawElements(GL_TRIANGLES, radial_.index_count, GL_UNSIGNED_INT, nullptr);
    if (count) {
      statistics.vertices_drawn = radial_.vertex_count;
      statistics.triangles_drawn = radial_.index_count / 3;
    }
  } else if (kind == GridKind::quadtree) {
    std::vector<float> morph;
    for (const QuadtreeLevel& level : selection.levels)
      morph.insert(morph.end(), {float(level.morph_start_m), float(level.morph_end_m)});
    glUniform2fv(at(program, "u_morph_m"), GLsizei(selection.levels.size()), morph.data());
    glBindVertexArray(quadtree_patch_.vertex_array);
    glDrawElementsInstanced(GL_TRIANGLES, quadtree_patch_.index_count, GL_UNSIGNED_INT, nullptr,
                            GLsizei(selection.patches.size()));
    if (count) {
      statistics.vertices_drawn = selection.vertex_count();
      statistics.triangles_drawn =
          static_cast<long long>(selection.patches.size()) * quadtree_patch_.index_count / 3;
    }
  } else {
    if (layout.vertex_count() == 0) return;
    glUniform4f(at(program, "u_ndc_rect"), float(layout.ndc_x0), float(layout.ndc_y0), float(layout.ndc_x1),
                float(layout.ndc_y1));
    set_uniform(program, "u_inverse_rotation_projection", inverse(sea.view.rotation_projection));
    glBindVertexArray(projected_.vertex_array);
    glDrawElements(GL_TRIANGLES, projected_.index_count, GL_UNSIGNED_INT, nullptr);
    if (count) {
      statistics.vertices_drawn = projected_.vertex_count;
      statistics.triangles_drawn = projected_.index_count / 3;
    }
  }
  glBindVertexArray(0);
}

void WaterSurfacePass::prepare_grid(const RendererSettings& settings, const CameraView& view,
                                    QuadtreeSelection& selection, ProjectedGridLayout& layout,
                                    FrameStatistics& statistics) {
  const GridKind kind = settings.grid;
  if (kind == GridKind::radial && (!radial_.vertex_array || !same(radial_built_, settings.radial))) {
    radial_.release();
    const RadialGrid grid = build_radial_grid(settings.radial);
    radial_ = upload_mesh(grid.polar, grid.triangles);
    radial_built_ = settings.radial;
  } else if (kind == GridKind::quadtree) {
    selection = select_quadtree(settings.quadtree, view);
    const int k = selection.patch_quads;
    if (quadtree_patch_.vertex_count != static_cast<long long>(k + 1) * (k + 1)) {
      quadtree_patch_.release();
      quadtree_patch_ = lattice_mesh(k + 1, k + 1, 1.f, 1.f);
      // Per patch (attribute 1, one per instance): origin x, y, vertex spacing, level.
      glBindVertexArray(quadtree_patch_.vertex_array);
      glGenBuffers(1, &quadtree_patch_.instance_buffer);
      glBindBuffer(GL_ARRAY_BUFFER, quadtree_patch_.instance_buffer);
      glEnableVertexAttribArray(1);
      glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 4 * sizeof(float), nullptr);
      glVertexAttribDivisor(1, 1);
      glBindVertexArray(0);
    }
    std::vector<float> instances;
    instances.reserve(selection.patches.size() * 4);
    for (const QuadtreePatch& patch : selection.patches)
      instances.insert(instances.end(), {float(patch.origin_x_m), float(patch.origin_y_m),
                                         float(selection.levels[std::size_t(patch.level)].vertex_spacing_m),
                                         float(patch.level)});
    glBindBuffer(GL_ARRAY_BUFFER, quadtree_patch_.instance_buffer);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(instances.size() * sizeof(float)), instances.data(),
                 GL_STREAM_DRAW);
    statistics.geometry_upload_bytes += instances.size() * sizeof(float);
    statistics.quadtree_patches = int(selection.patches.size());
    statistics.quadtree_levels = int(selection.levels.size());
  } else if (kind == GridKind::projected) {
    layout = layout_projected_grid(settings.projected, view);
    if (layout.vertex_count() > 0 &&
        (layout.columns != projected_columns_ || layout.rows != projected_rows_)) {
      projected_.release();
      projected_ = lattice_mesh(layout.columns, layout.rows, 1.f / float(layout.columns - 1),
                                1.f / float(layout.rows - 1));
      projected_columns_ = layout.columns;
      projected_rows_ = layout.rows;
    }
  }
}

// What only the sea's lighting needs: the cascades' slope variances (detail fading), the
// Jacobian's foam threshold, the shoreline waves' wind and clock.
void WaterSurfacePass::set_water_lighting_uniforms(GLuint program, const runtime::SurfaceSnapshot& snapshot,
                                                   const LightingFrame& light) {
  if (snapshot.deep_from && cascade_slope_variance_.size() != snapshot.deep_from->cascades.size()) {
    cascade_slope_variance_.clear();
    for (const ocean::DeepWaterFrame& cascade : snapshot.deep_from->cascades) {
      double sum = 0.0;
      for (std::size_t k = 0; k < cascade.slope_x.size(); ++k)
        sum +=
            double(cascade.slope_x[k]) * cascade.slope_x[k] + double(cascade.slope_y[k]) * cascade.slope_y[k];
      cascade_slope_variance_.push_back(
          cascade.slope_x.empty() ? 0.f : float(0.5 * sum / double(cascade.slope_x.size())));
    }
  }
  std::vector<float> variances(8, 0.f);
  std::copy_n(cascade_slope_variance_.begin(), std::min<std::size_t>(cascade_slope_variance_.size(), 8),
              variances.begin());
  glUniform1fv(at(program, "u_cascade_slope_variance"), 8, variances.data());
  set_uniform(program, "u_jacobian_foam_onset", float(light.jacobian_foam_onset));
  set_uniform(program, "u_time_s", float(std::fmod(snapshot.display_time_s, 3600.0)));
  glUniform2f(at(program, "u_wind_toward"), float(std::cos(light.wind_direction_rad)),
              float(std::sin(light.wind_direction_rad)));
  set_uniform(program, "u_shore_amplitude_m", float(light.shore_wave_amplitude_m));
  set_uniform(program, "u_shore_band_m", float(light.shore_band_m));
}

}  // namespace nearshore::playback
