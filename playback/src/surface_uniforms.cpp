#include "surface_uniforms.hpp"

#include <algorithm>

#include "gl_program.hpp"

namespace nearshore::playback {

void set_surface_uniforms(GLuint program, const SurfaceFormula& formula, const Vector3& eye,
                          double earth_radius_m) {
  const runtime::SurfaceSnapshot& snapshot = formula.snapshot;
  const KeyframeTextures::Bound& bound = formula.bound;
  const runtime::HarbourSite* site = formula.site;
  set_uniform(program, "u_eye_m", eye);
  set_uniform(program, "u_earth_radius_m", float(earth_radius_m));
  set_uniform(program, "u_has_site", site ? 1 : 0);
  set_uniform(program, "u_has_keyframes", bound.harbour_eta[0] ? 1 : 0);
  set_uniform(program, "u_harbour_fraction", float(snapshot.harbour_fraction));
  // The Hermite in time (surface_snapshot.hpp) when both keyframes carry d eta / dt.
  const double frame_interval_s = site ? site->frame_interval_s : 0.0;
  set_uniform(program, "u_harbour_hermite", runtime::harbour_joined_by_hermite(snapshot) ? 1 : 0);
  set_uniform(program, "u_frame_interval_s", float(frame_interval_s));
  set_uniform(program, "u_open_sea_depth_m", formula.open_sea_depth_m);
  if (site) {
    const GridGeometry& g = site->harbour.geometry;
    glUniform2i(at(program, "u_cells"), g.columns, g.rows);
    glUniform2f(at(program, "u_spacing_m"), float(g.spacing_x_m()), float(g.spacing_y_m()));  // dx, dy
    glUniform2f(at(program, "u_site_size_m"), float(site->width_m), float(site->height_m));
    set_uniform(program, "u_source_axis", site->source_axis);
    set_uniform(program, "u_inward_sign", float(site->inward_sign));
    set_uniform(program, "u_source_line_m", float(site->source_line_m));
    set_uniform(program, "u_blend_start_m", float(site->blend_start_m));
    set_uniform(program, "u_blend_width_m", float(site->blend_width_m));
    set_uniform(program, "u_edge_fade_m", float(site->edge_fade_m));
    set_uniform(program, "u_choppiness", float(site->choppiness));
    set_uniform(program, "u_dry_depth_m", float(site->dry_depth_m));
    // The highest ground on each edge (surface.glsl on_skirt_land): the edge's cells (the bilinear
    // ground along an edge lies between their values).
    const Raster<float>& d = site->harbour.still_water_depth_m;
    float edge_max[4] = {-1e30f, -1e30f, -1e30f, -1e30f};  // south, east, north, west
    for (int i = 0; i < g.columns; ++i) {
      edge_max[0] = std::max(edge_max[0], -d(i, 0));
      edge_max[2] = std::max(edge_max[2], -d(i, g.rows - 1));
    }
    for (int j = 0; j < g.rows; ++j) {
      edge_max[1] = std::max(edge_max[1], -d(g.columns - 1, j));
      edge_max[3] = std::max(edge_max[3], -d(0, j));
    }
    glUniform1fv(at(program, "u_edge_max_ground_m"), 4, edge_max);
    // The surroundings (site_terrain.hpp SurroundingGround), their texture on kSurroundings.
    set_uniform(program, "u_has_surroundings", formula.surroundings ? 1 : 0);
    if (formula.surroundings) {
      const GridGeometry& s = *formula.surroundings;
      glUniform2f(at(program, "u_surroundings_origin_m"), float(s.origin_x_m), float(s.origin_y_m));
      glUniform2f(at(program, "u_surroundings_size_m"), float(s.width_m()), float(s.height_m()));
      set_uniform(program, "u_surroundings_blend_m", formula.surroundings_edge_blend_m);
    }
  } else {
    set_uniform(program, "u_has_surroundings", 0);
    set_uniform(program, "u_choppiness", 1.f);
  }
  set_uniform(program, "u_has_relative_wave_height", formula.has_relative_wave_height ? 1 : 0);
  set_uniform(program, "u_cascade_count", bound.cascade_count);
  // The split (issue 14 item 1): what water_vertex.glsl draws inside the harbour rectangle.
  set_uniform(program, "u_inside_cascade_mask", static_cast<int>(bound.inside_cascade_mask));
  set_uniform(program, "u_inside_layer_count", bound.inside_layer_count);
  set_uniform(program, "u_deep_size", std::max(bound.deep_size, 1));
  set_uniform(program, "u_deep_fraction", float(snapshot.deep_fraction));
  if (!bound.tile_lengths_m.empty())
    glUniform1fv(at(program, "u_tile_length_m"), GLsizei(bound.tile_lengths_m.size()),
                 bound.tile_lengths_m.data());
  const PatchUniforms& patches = formula.patches;
  const int patch_count = formula.patch_count;
  set_uniform(program, "u_patch_count", patch_count);
  if (patch_count > 0) {
    glUniform2fv(at(program, "u_patch_origin_m"), patch_count, patches.origin_m.data());
    glUniform1fv(at(program, "u_patch_spacing_m"), patch_count, patches.spacing_m.data());
    glUniform2iv(at(program, "u_patch_cells"), patch_count, patches.cells.data());
    glUniform1iv(at(program, "u_patch_row0"), patch_count, patches.row0.data());
  }
}

}  // namespace nearshore::playback
