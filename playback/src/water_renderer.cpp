#include "nearshore/playback/water_renderer.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "gl_framebuffer.hpp"
#include "gl_mesh.hpp"
#include "gl_program.hpp"
#include "gl_texture.hpp"
#include "keyframe_textures.hpp"
#include "pass_timer.hpp"
#include "surface_layer_gpu.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::playback {

namespace {

GLuint site_texture(GLenum internal_format, GLenum type, int columns, int rows, const void* data, GLint filter) {
  const GLuint texture = new_texture(GL_TEXTURE_2D, filter, GL_CLAMP_TO_EDGE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(internal_format), columns, rows, 0, GL_RED, type, data);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  return texture;
}

// The local reflection: land and structures mirrored in still water, drawn as linear radiance
// (RGBA16F, alpha = covered) into a texture the water shader samples at its own screen position.
struct ReflectionTarget {
  GLuint colour = 0;  // the texture the water samples
  Framebuffer framebuffer;
  void resize(int w, int h) {
    if (framebuffer && w == framebuffer.width() && h == framebuffer.height()) return;
    release();
    glActiveTexture(GLenum(GL_TEXTURE0 + kReflection));  // never disturb the units the draw has bound
    colour = new_texture(GL_TEXTURE_2D, GL_LINEAR, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, w, h, 0, GL_RGBA, GL_FLOAT, nullptr);
    framebuffer = Framebuffer::with_texture(
        colour, w, h, true, {"the reflection framebuffer is incomplete", "set RendererSettings::local_reflections = false"});
  }
  void release() {
    framebuffer.release();
    if (colour) glDeleteTextures(1, &colour);
    colour = 0;
  }
};

// The deep water's persistent foam (seed 000 eq. 3.46): f_t over the largest cascade's tile, one
// texel per deep sample, in two R32F textures updated in turn (foam_decay.frag.glsl reads one,
// writes the other), so the foam a crest leaves fades with the display time, not the frame rate.
struct DeepFoamMap {
  GLuint texture[2] = {0, 0};
  Framebuffer framebuffer[2];
  int size = 0, current = 0;  // texture[current] holds f_t
  float tile_length_m = 0.f;
  double time_s = 0.0;        // the display time f_t belongs to
  bool valid = false;
  void resize(int n, float tile_m) {
    if (n == size && tile_m == tile_length_m && framebuffer[0]) return;
    release();
    for (int k = 0; k < 2; ++k) {
      glActiveTexture(GLenum(GL_TEXTURE0 + kPreviousFoam));  // never disturb the units the draw has bound
      texture[k] = new_texture(GL_TEXTURE_2D, GL_LINEAR, GL_REPEAT);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, n, n, 0, GL_RED, GL_FLOAT, nullptr);
      framebuffer[k] = Framebuffer::with_texture(
          texture[k], n, n, false, {"the deep-water foam framebuffer is incomplete", "set Lighting::foam_decay_time_s = 0"});
    }
    size = n;
    tile_length_m = tile_m;
    valid = false;
  }
  void release() {
    for (Framebuffer& f : framebuffer) f.release();
    for (GLuint& t : texture)
      if (t) glDeleteTextures(1, &t), t = 0;
    *this = DeepFoamMap{};
  }
};

bool same(const RadialGridSettings& a, const RadialGridSettings& b) {
  return a.segment_count == b.segment_count && a.inner_spacing_m == b.inner_spacing_m && a.outer_radius_m == b.outer_radius_m;
}

}  // namespace

struct WaterRenderer::Impl {
  RendererSettings settings;
  KeyframeTextures keyframes;
  FrameStatistics statistics;
  GpuTextures textures;  // of the last render or upload
  GLuint radial_program = 0, quadtree_program = 0, projected_program = 0, height_program = 0;
  GLuint terrain_program = 0, sky_program = 0, mesh_program = 0, decal_program = 0, foam_program = 0;
  GLuint empty_vertex_array = 0;
  SurfaceLayerGpu layer_gpu;  // the SurfaceLayers' patches, foam map and meshes
  bool patches_active = false;  // this draw adds the patches uploaded last
  RenderTarget target, height_target;
  ReflectionTarget reflection;
  DeepFoamMap deep_foam;
  PassTimer timer;
  int max_samples = 0;  // GL_MAX_SAMPLES, asked on the first frame
  bool software_rasteriser = false;  // GL_RENDERER names Mesa's llvmpipe, softpipe or swrast

  // The site (static for a sequence): uploaded when the snapshot's site changes.
  std::shared_ptr<const runtime::HarbourSite> site;
  GLuint depth_texture = 0, porosity_texture = 0, land_texture = 0, coast_texture = 0, relative_wave_height_texture = 0;
  Mesh terrain;
  // Slope variance (per axis) of each cascade's tiles: measured once on the first deep keyframe
  // (the spectrum is stationary: the next keyframes hold the same variance to sampling noise).
  std::vector<float> cascade_slope_variance;
  float open_sea_depth_m = 20.f;

  Mesh radial, quadtree_patch, projected, height_lattice;
  RadialGridSettings radial_built;
  int projected_columns = 0, projected_rows = 0, height_columns = 0, height_rows = 0;


  explicit Impl(const RendererSettings& s) : settings(s), keyframes(s.harbour_texture_slots, s.deep_texture_slots) {
    const std::initializer_list<const char*> water_vertex = {"common.glsl", "surface.glsl", "water_vertex.glsl"};
    const std::initializer_list<const char*> surface = {"common.glsl", "surface.glsl"};
    radial_program = link_program(water_vertex, "water_radial.vert.glsl", surface, "water.frag.glsl");
    quadtree_program = link_program(water_vertex, "water_quadtree.vert.glsl", surface, "water.frag.glsl");
    projected_program = link_program(water_vertex, "water_projected.vert.glsl", surface, "water.frag.glsl");
    height_program = link_program(water_vertex, "height.vert.glsl", surface, "height.frag.glsl");
    terrain_program = link_program(surface, "terrain.vert.glsl", {"common.glsl"}, "terrain.frag.glsl");
    sky_program = link_program({"common.glsl"}, "sky.vert.glsl", {"common.glsl"}, "sky.frag.glsl");
    mesh_program = link_program(surface, "mesh.vert.glsl", surface, "mesh.frag.glsl");
    decal_program = link_program({}, "decal.vert.glsl", {}, "decal.frag.glsl");
    foam_program = link_program({"common.glsl"}, "sky.vert.glsl", surface, "foam_decay.frag.glsl");
    glGenVertexArrays(1, &empty_vertex_array);
  }

  ~Impl() {
    for (GLuint program : {radial_program, quadtree_program, projected_program, height_program, terrain_program, sky_program,
                           mesh_program, decal_program, foam_program})
      glDeleteProgram(program);
    release_site();
    for (Mesh* mesh : {&radial, &quadtree_patch, &projected, &height_lattice}) mesh->release();
    glDeleteVertexArrays(1, &empty_vertex_array);
    target.release();
    height_target.release();
    reflection.release();
    deep_foam.release();
    timer.release();
  }

  // RendererSettings::msaa_samples within what the driver offers (GL_MAX_SAMPLES is at least 4
  // in OpenGL 3.3 core; Mesa's llvmpipe offers 4).
  int sample_count() {
    if (max_samples == 0) {
      glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
      max_samples = std::max(max_samples, 1);
      const char* renderer_name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
      const std::string name = renderer_name ? renderer_name : "";
      software_rasteriser = name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos ||
                            name.find("swrast") != std::string::npos;
    }
    const int asked = settings.msaa_samples > 0 ? settings.msaa_samples : software_rasteriser ? 1 : 4;
    return asked <= 1 ? 1 : std::min(asked, max_samples);
  }

  void release_site() {
    for (GLuint* texture : {&depth_texture, &porosity_texture, &land_texture, &coast_texture, &relative_wave_height_texture})
      if (*texture) glDeleteTextures(1, texture), *texture = 0;
    terrain.release();
    site.reset();
  }

  // 1. The site's static textures, once per site.
  void bind_site(const std::shared_ptr<const runtime::HarbourSite>& snapshot_site) {
    if (snapshot_site == site) return;
    release_site();
    site = snapshot_site;
    if (!site) return;
    const HarbourGrid& h = site->harbour;
    const int columns = h.geometry.columns, rows = h.geometry.rows;
    if (columns < 2 || rows < 2 || h.still_water_depth_m.columns() != columns || h.land.columns() != columns ||
        h.porosity.columns() != columns || h.still_water_depth_m.rows() != rows || h.land.rows() != rows ||
        h.porosity.rows() != rows)
      throw Error("harbour site", "its grid is " + std::to_string(columns) + " x " + std::to_string(rows) +
                                      " cells but its depth, land or porosity raster has another size",
                  "build the HarbourSite from one HarbourGrid of at least 2 x 2 cells");
    depth_texture = site_texture(GL_R32F, GL_FLOAT, columns, rows, h.still_water_depth_m.data(), GL_LINEAR);
    porosity_texture = site_texture(GL_R32F, GL_FLOAT, columns, rows, h.porosity.data(), GL_LINEAR);
    land_texture = site_texture(GL_R8, GL_UNSIGNED_BYTE, columns, rows, h.land.data(), GL_NEAREST);
    // The coastline's distance field for the shoreline waves; infinite (no coast) becomes far.
    std::vector<float> coast(std::size_t(columns) * rows, 1e4f);
    if (h.coast_distance_m.columns() == columns && h.coast_distance_m.rows() == rows)
      for (std::size_t k = 0; k < coast.size(); ++k)
        coast[k] = std::isfinite(h.coast_distance_m.data()[k]) ? std::clamp(h.coast_distance_m.data()[k], -1e4f, 1e4f) : 1e4f;
    coast_texture = site_texture(GL_R32F, GL_FLOAT, columns, rows, coast.data(), GL_LINEAR);
    statistics.upload_bytes += std::size_t(columns) * rows * 9;
    // K of the site: land and structure cells (NaN) take their water neighbours' mean, so the
    // bilinear filter brings no NaN to the water beside a quay (and no unsheltered halo).
    const Raster<float>& k = site->relative_wave_height;
    if (k.columns() == columns && k.rows() == rows) {
      std::vector<float> filled(k.values());
      for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
          if (std::isfinite(k(i, j))) continue;
          double sum = 0.0;
          int count = 0;
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              const int ii = i + di, jj = j + dj;
              if (ii < 0 || jj < 0 || ii >= columns || jj >= rows || !std::isfinite(k(ii, jj))) continue;
              sum += k(ii, jj);
              ++count;
            }
          filled[std::size_t(j) * columns + i] = count > 0 ? float(sum / count) : 1.f;
        }
      glActiveTexture(GLenum(GL_TEXTURE0 + kRelativeWaveHeight));
      relative_wave_height_texture = site_texture(GL_R32F, GL_FLOAT, columns, rows, filled.data(), GL_LINEAR);
      glActiveTexture(GL_TEXTURE0);
      statistics.upload_bytes += std::size_t(columns) * rows * 4;
    }
    // The sea beyond the grid takes the deepest depth found on its edges (lighting only).
    float edge_depth = 0.f;
    for (int i = 0; i < columns; ++i)
      edge_depth = std::max({edge_depth, h.still_water_depth_m(i, 0), h.still_water_depth_m(i, rows - 1)});
    for (int j = 0; j < rows; ++j)
      edge_depth = std::max({edge_depth, h.still_water_depth_m(0, j), h.still_water_depth_m(columns - 1, j)});
    open_sea_depth_m = std::max(edge_depth, 5.f);
    const int tc = std::min(columns, 768), tr = std::min(rows, 768);
    terrain = lattice_mesh(tc, tr, 1.f / float(tc - 1), 1.f / float(tr - 1));
  }

  // The snapshot's formula: the uniforms of surface.glsl, and its textures on their units.
  void set_surface_uniforms(GLuint program, const runtime::SurfaceSnapshot& snapshot, const KeyframeTextures::Bound& bound,
                            const Vector3& eye, double earth_radius_m) {
    set_uniform(program, "u_eye_m", eye);
    set_uniform(program, "u_earth_radius_m", float(earth_radius_m));
    set_uniform(program, "u_has_site", site ? 1 : 0);
    set_uniform(program, "u_has_keyframes", bound.harbour_eta[0] ? 1 : 0);
    set_uniform(program, "u_harbour_fraction", float(snapshot.harbour_fraction));
    // The Hermite in time (surface_snapshot.hpp) when both keyframes carry d eta / dt.
    const double frame_interval_s = site ? site->frame_interval_s : 0.0;
    set_uniform(program, "u_harbour_hermite", runtime::harbour_joined_by_hermite(snapshot) ? 1 : 0);
    set_uniform(program, "u_frame_interval_s", float(frame_interval_s));
    set_uniform(program, "u_open_sea_depth_m", open_sea_depth_m);
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
    } else {
      set_uniform(program, "u_choppiness", 1.f);
    }
    set_uniform(program, "u_has_relative_wave_height", relative_wave_height_texture ? 1 : 0);
    set_uniform(program, "u_cascade_count", bound.cascade_count);
    // The split (issue 14 item 1): what water_vertex.glsl draws inside the harbour rectangle.
    set_uniform(program, "u_inside_cascade_mask", static_cast<int>(bound.inside_cascade_mask));
    set_uniform(program, "u_inside_layer_count", bound.inside_layer_count);
    set_uniform(program, "u_deep_size", std::max(bound.deep_size, 1));
    set_uniform(program, "u_deep_fraction", float(snapshot.deep_fraction));
    if (!bound.tile_lengths_m.empty())
      glUniform1fv(at(program, "u_tile_length_m"), GLsizei(bound.tile_lengths_m.size()), bound.tile_lengths_m.data());
    const PatchUniforms& patches = layer_gpu.patch_uniforms();
    const int patch_count = patches_active ? patches.count : 0;
    set_uniform(program, "u_patch_count", patch_count);
    if (patch_count > 0) {
      glUniform2fv(at(program, "u_patch_origin_m"), patch_count, patches.origin_m.data());
      glUniform1fv(at(program, "u_patch_spacing_m"), patch_count, patches.spacing_m.data());
      glUniform2iv(at(program, "u_patch_cells"), patch_count, patches.cells.data());
      glUniform1iv(at(program, "u_patch_row0"), patch_count, patches.row0.data());
    }
  }

  // The layers' height patches onto their unit (before any surface uniforms are set).
  void prepare_patches(const SurfaceLayers* layers) {
    patches_active = layers && !layers->height_patches.empty();
    if (patches_active) statistics.layer_upload_bytes += layer_gpu.upload_patches(layers->height_patches, kPatches);
    statistics.height_patches = patches_active ? int(layers->height_patches.size()) : 0;
    glActiveTexture(GLenum(GL_TEXTURE0 + kPatches));
    glBindTexture(GL_TEXTURE_2D, patches_active ? layer_gpu.patch_atlas() : 0);
    glActiveTexture(GL_TEXTURE0);
  }

  // The layers' meshes, lit as the land, depth-tested against everything drawn. `mirrored`: the
  // reflection pass (z -> -z through `mirror`, the eye mirrored too so each face turns towards the
  // eye that sees its image; only what stands above still water, as linear radiance).
  void draw_meshes(const SurfaceLayers& layers, const CameraView& view, const runtime::SurfaceSnapshot& snapshot,
                   const KeyframeTextures::Bound& bound, const LightingFrame& light, double earth_radius_m,
                   const Matrix4* mirror = nullptr) {
    if (layers.meshes.empty()) return;
    glUseProgram(mesh_program);
    set_lighting_uniforms(mesh_program, light);
    set_uniform(mesh_program, "u_view_projection", mirror ? multiply(view.view_projection, *mirror) : view.view_projection);
    const Vector3 eye = mirror ? Vector3{view.eye_m[0], view.eye_m[1], -view.eye_m[2]} : view.eye_m;
    set_surface_uniforms(mesh_program, snapshot, bound, eye, earth_radius_m);
    set_uniform(mesh_program, "u_mirror", mirror ? 1 : 0);
    for (const SolidMesh& solid : layers.meshes) {
      const SurfaceLayerGpu::GpuMesh& gpu = layer_gpu.mesh(solid, statistics.layer_upload_bytes);
      float rotation[9];
      for (int k = 0; k < 9; ++k) rotation[k] = float(solid.rotation[std::size_t(k)]);
      glUniformMatrix3fv(at(mesh_program, "u_rotation"), 1, GL_TRUE, rotation);  // row-major
      set_uniform(mesh_program, "u_position_m", solid.position_m);
      set_uniform(mesh_program, "u_albedo_above", solid.albedo_above);
      set_uniform(mesh_program, "u_albedo_below", solid.albedo_below);
      set_uniform(mesh_program, "u_boot_top_z_m", float(solid.boot_top_z_m));
      glBindVertexArray(gpu.vertex_array);
      glDrawElements(GL_TRIANGLES, gpu.index_count, GL_UNSIGNED_INT, nullptr);
    }
    glBindVertexArray(0);
    if (!mirror) statistics.meshes = int(layers.meshes.size());
  }

  void bind_textures(const KeyframeTextures::Bound& bound) const {
    auto bind = [](int unit, GLenum target_kind, GLuint texture) {
      glActiveTexture(GLenum(GL_TEXTURE0 + unit));
      glBindTexture(target_kind, texture);
    };
    for (int k = 0; k < 2; ++k) {
      bind(kHarbourEta + k, GL_TEXTURE_2D, bound.harbour_eta[k]);
      bind(kHarbourBreaking + k, GL_TEXTURE_2D, bound.harbour_breaking[k]);
      bind(kHarbourEtaRate + k, GL_TEXTURE_2D, bound.harbour_eta_rate[k]);
    }
    bind(kDepth, GL_TEXTURE_2D, depth_texture);
    bind(kPorosity, GL_TEXTURE_2D, porosity_texture);
    bind(kLand, GL_TEXTURE_2D, land_texture);
    bind(kCoast, GL_TEXTURE_2D, coast_texture);
    bind(kRelativeWaveHeight, GL_TEXTURE_2D, relative_wave_height_texture);
    for (int field = 0; field < kDeepFieldCount; ++field)
      for (int k = 0; k < 2; ++k) bind(kDeepFirst + 2 * field + k, GL_TEXTURE_2D_ARRAY, bound.deep[field][k]);
    glActiveTexture(GL_TEXTURE0);
  }

  void check_snapshot(const runtime::SurfaceSnapshot& snapshot) const {
    for (const auto* keyframe : {snapshot.harbour_from.get(), snapshot.harbour_to.get()}) {
      if (!keyframe) continue;
      if (!site)
        throw Error("surface snapshot", "holds harbour keyframes but no site", "give the snapshot its HarbourSite");
      const GridGeometry& g = site->harbour.geometry;
      if (keyframe->surface_elevation_m.columns() != g.columns || keyframe->surface_elevation_m.rows() != g.rows)
        throw Error("harbour keyframe " + std::to_string(keyframe->serial),
                    "is " + std::to_string(keyframe->surface_elevation_m.columns()) + " x " +
                        std::to_string(keyframe->surface_elevation_m.rows()) + " cells but the site's grid is " +
                        std::to_string(g.columns) + " x " + std::to_string(g.rows),
                    "play a sequence baked on this harbour grid");
    }
  }

  // 2. The water on the chosen grid (`count`: the fill pass, whose vertices the statistics count).
  void draw_water(GLuint program, GridKind kind, const CameraView& view, double earth_radius_m,
                  const runtime::SurfaceSnapshot& snapshot, const KeyframeTextures::Bound& bound, const DrawOptions& options,
                  const QuadtreeSelection* selection, const ProjectedGridLayout* layout, bool count) {
    glUseProgram(program);
    set_uniform(program, "u_view_projection", view.view_projection);
    set_surface_uniforms(program, snapshot, bound, view.eye_m, earth_radius_m);
    const int colouring = options.wireframe && !count ? 3 : int(options.colouring);
    set_uniform(program, "u_colouring", colouring);
    set_uniform(program, "u_flat_colour", options.flat_colour);
    if (kind == GridKind::radial) {
      set_uniform(program, "u_lod_unit_m", float(settings.radial.inner_spacing_m));
      glBindVertexArray(radial.vertex_array);
      glDrawElements(GL_TRIANGLES, radial.index_count, GL_UNSIGNED_INT, nullptr);
      if (count) {
        statistics.vertices_drawn = radial.vertex_count;
        statistics.triangles_drawn = radial.index_count / 3;
      }
    } else if (kind == GridKind::quadtree) {
      std::vector<float> morph;
      for (const QuadtreeLevel& level : selection->levels)
        morph.insert(morph.end(), {float(level.morph_start_m), float(level.morph_end_m)});
      glUniform2fv(at(program, "u_morph_m"), GLsizei(selection->levels.size()), morph.data());
      glBindVertexArray(quadtree_patch.vertex_array);
      glDrawElementsInstanced(GL_TRIANGLES, quadtree_patch.index_count, GL_UNSIGNED_INT, nullptr,
                              GLsizei(selection->patches.size()));
      if (count) {
        statistics.vertices_drawn = selection->vertex_count();
        statistics.triangles_drawn = static_cast<long long>(selection->patches.size()) * quadtree_patch.index_count / 3;
      }
    } else {
      if (layout->vertex_count() == 0) return;
      glUniform4f(at(program, "u_ndc_rect"), float(layout->ndc_x0), float(layout->ndc_y0), float(layout->ndc_x1),
                  float(layout->ndc_y1));
      set_uniform(program, "u_inverse_rotation_projection", inverse(view.rotation_projection));
      glBindVertexArray(projected.vertex_array);
      glDrawElements(GL_TRIANGLES, projected.index_count, GL_UNSIGNED_INT, nullptr);
      if (count) {
        statistics.vertices_drawn = projected.vertex_count;
        statistics.triangles_drawn = projected.index_count / 3;
      }
    }
    glBindVertexArray(0);
  }

  // Meshes the grid needs this frame (rebuilt only when their settings change).
  void prepare_grid(GridKind kind, const CameraView& view, QuadtreeSelection& selection, ProjectedGridLayout& layout) {
    if (kind == GridKind::radial && (!radial.vertex_array || !same(radial_built, settings.radial))) {
      radial.release();
      const RadialGrid grid = build_radial_grid(settings.radial);
      radial = upload_mesh(grid.polar, grid.triangles);
      radial_built = settings.radial;
    } else if (kind == GridKind::quadtree) {
      selection = select_quadtree(settings.quadtree, view);
      const int k = selection.patch_quads;
      if (quadtree_patch.vertex_count != static_cast<long long>(k + 1) * (k + 1)) {
        quadtree_patch.release();
        quadtree_patch = lattice_mesh(k + 1, k + 1, 1.f, 1.f);
        glBindVertexArray(quadtree_patch.vertex_array);
        glGenBuffers(1, &quadtree_patch.instance_buffer);
        glBindBuffer(GL_ARRAY_BUFFER, quadtree_patch.instance_buffer);
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
      glBindBuffer(GL_ARRAY_BUFFER, quadtree_patch.instance_buffer);
      glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(instances.size() * sizeof(float)), instances.data(), GL_STREAM_DRAW);
      statistics.geometry_upload_bytes += instances.size() * sizeof(float);
      statistics.quadtree_patches = int(selection.patches.size());
      statistics.quadtree_levels = int(selection.levels.size());
    } else if (kind == GridKind::projected) {
      layout = layout_projected_grid(settings.projected, view);
      if (layout.vertex_count() > 0 && (layout.columns != projected_columns || layout.rows != projected_rows)) {
        projected.release();
        projected = lattice_mesh(layout.columns, layout.rows, 1.f / float(layout.columns - 1), 1.f / float(layout.rows - 1));
        projected_columns = layout.columns;
        projected_rows = layout.rows;
      }
    }
  }

  void remember_textures(const runtime::SurfaceSnapshot& snapshot, const KeyframeTextures::Bound& bound) {
    textures = GpuTextures{};
    for (int k = 0; k < 2; ++k) {
      textures.harbour_elevation[k] = bound.harbour_eta[k];
      textures.harbour_breaking[k] = bound.harbour_breaking[k];
      textures.harbour_elevation_rate[k] = bound.harbour_eta_rate[k];
      textures.deep_elevation[k] = bound.deep[kDeepEta][k];
      textures.deep_displacement_x[k] = bound.deep[kDeepDx][k];
      textures.deep_displacement_y[k] = bound.deep[kDeepDy][k];
      textures.deep_slope_x[k] = bound.deep[kDeepSlopeX][k];
      textures.deep_slope_y[k] = bound.deep[kDeepSlopeY][k];
    }
    textures.cascade_count = bound.cascade_count;
    textures.deep_grid_size = bound.deep_size;
    textures.tile_lengths_m = bound.tile_lengths_m;
    textures.harbour_fraction = snapshot.harbour_fraction;
    textures.harbour_has_rates = runtime::harbour_joined_by_hermite(snapshot);
    textures.frame_interval_s = snapshot.site ? snapshot.site->frame_interval_s : 0.0;
    textures.deep_fraction = snapshot.deep_fraction;
  }

  // Makes the snapshot's keyframes resident (and spends the budget on staged ones): what a frame
  // does before it draws, and all that a host drawing itself needs.
  KeyframeTextures::Bound upload(const runtime::SurfaceSnapshot& snapshot) {
    statistics = FrameStatistics{};
    bind_site(snapshot.site);
    check_snapshot(snapshot);
    UploadCounters counters;
    KeyframeTextures::Bound bound = keyframes.prepare(snapshot, settings.upload_budget_bytes_per_frame, counters);
    statistics.upload_bytes += counters.bytes;
    statistics.forced_upload_bytes = counters.forced_bytes;
    remember_textures(snapshot, bound);
    return bound;
  }

  // What only the sea's lighting needs: the cascades' slope variances (detail fading), the
  // Jacobian's foam threshold, the shoreline waves' wind and clock.
  void set_water_lighting_uniforms(GLuint program, const runtime::SurfaceSnapshot& snapshot, const LightingFrame& light) {
    if (snapshot.deep_from && cascade_slope_variance.size() != snapshot.deep_from->cascades.size()) {
      cascade_slope_variance.clear();
      for (const ocean::DeepWaterFrame& cascade : snapshot.deep_from->cascades) {
        double sum = 0.0;
        for (std::size_t k = 0; k < cascade.slope_x.size(); ++k)
          sum += double(cascade.slope_x[k]) * cascade.slope_x[k] + double(cascade.slope_y[k]) * cascade.slope_y[k];
        cascade_slope_variance.push_back(cascade.slope_x.empty() ? 0.f : float(0.5 * sum / double(cascade.slope_x.size())));
      }
    }
    std::vector<float> variances(8, 0.f);
    std::copy_n(cascade_slope_variance.begin(), std::min<std::size_t>(cascade_slope_variance.size(), 8), variances.begin());
    glUniform1fv(at(program, "u_cascade_slope_variance"), 8, variances.data());
    set_uniform(program, "u_jacobian_foam_onset", float(light.jacobian_foam_onset));
    set_uniform(program, "u_time_s", float(std::fmod(snapshot.display_time_s, 3600.0)));
    glUniform2f(at(program, "u_wind_toward"), float(std::cos(light.wind_direction_rad)), float(std::sin(light.wind_direction_rad)));
    set_uniform(program, "u_shore_amplitude_m", float(light.shore_wave_amplitude_m));
    set_uniform(program, "u_shore_band_m", float(light.shore_band_m));
  }

  // Seed 000 eq. (3.46) one step on: f_t = exp(-dt / decay time) f_t + f_b over the largest tile,
  // dt the display time since the last step. The same display time again (a paused picture, a
  // second view) changes nothing; time running backwards, another tile or decay time 0 starts
  // afresh (f_t = f_b). Needs the deep textures bound; leaves framebuffer 0 bound.
  bool update_deep_foam(const runtime::SurfaceSnapshot& snapshot, const KeyframeTextures::Bound& bound, const LightingFrame& light) {
    if (bound.cascade_count == 0 || light.foam_decay_time_s <= 0.0) {
      deep_foam.valid = false;
      return false;
    }
    deep_foam.resize(bound.deep_size, bound.tile_lengths_m[0]);
    const double dt = snapshot.display_time_s - deep_foam.time_s;
    if (deep_foam.valid && dt == 0.0) return true;
    const float persistence = deep_foam.valid && dt > 0.0 ? float(std::exp(-dt / light.foam_decay_time_s)) : 0.f;
    const int next = 1 - deep_foam.current;
    timer.begin_pass(GpuPass::deep_foam);
    glBindFramebuffer(GL_FRAMEBUFFER, deep_foam.framebuffer[next].id());
    glViewport(0, 0, deep_foam.size, deep_foam.size);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(foam_program);
    set_surface_uniforms(foam_program, snapshot, bound, {0.0, 0.0, 0.0}, 0.0);
    set_uniform(foam_program, "u_foam_persistence", persistence);
    set_uniform(foam_program, "u_jacobian_foam_onset", float(light.jacobian_foam_onset));
    set_uniform(foam_program, "u_map_texel_m", deep_foam.tile_length_m / float(deep_foam.size));
    glActiveTexture(GLenum(GL_TEXTURE0 + kPreviousFoam));
    glBindTexture(GL_TEXTURE_2D, deep_foam.texture[deep_foam.current]);
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(empty_vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glEnable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    timer.end_pass();
    deep_foam.current = next;
    deep_foam.time_s = snapshot.display_time_s;
    deep_foam.valid = true;
    return true;
  }

  Raster<float> deep_foam_map() const {
    if (!deep_foam.valid) return Raster<float>(0, 0);
    Raster<float> map(deep_foam.size, deep_foam.size);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, deep_foam.framebuffer[deep_foam.current].id());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, deep_foam.size, deep_foam.size, GL_RED, GL_FLOAT, map.data());  // row 0 = y 0 = south
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    return map;
  }

  void render(const runtime::SurfaceSnapshot& snapshot, const Camera& camera, const Lighting& lighting, int width,
              int height, const DrawOptions& options, const SurfaceLayers* layers) {
    const KeyframeTextures::Bound bound = upload(snapshot);
    timer.begin_frame(settings.gpu_timing, statistics.gpu);  // and what an earlier frame measured
    const LightingFrame light = prepare_lighting(lighting);
    prepare_patches(layers);
    // The wakes' foam map first: it draws into its own framebuffer.
    if (layers && options.colouring == SurfaceColouring::lit && !layers->foam_decals.empty())
      timer.begin_pass(GpuPass::decal_foam);
    const bool decal_foam = layers && options.colouring == SurfaceColouring::lit &&
                            layer_gpu.draw_decals(layers->foam_decals, decal_program, settings.decal_foam_texels,
                                                  settings.decal_foam_finest_m);
    timer.end_pass();
    statistics.foam_decals = decal_foam ? int(layers->foam_decals.size()) : 0;

    // Clip distances: near from the eye's height; far where the grid ends.
    const GridKind kind = settings.grid;
    const double eye_height = std::max(std::abs(camera.eye_m[2]), 0.1);
    const double earth_radius = kind == GridKind::projected ? settings.projected.earth_radius_m : 0.0;
    double far = camera.far_m;
    if (far <= 0) {
      far = kind == GridKind::radial     ? 1.05 * settings.radial.outer_radius_m
            : kind == GridKind::quadtree ? 2.0 * settings.quadtree.reach_m
                                         : 1.05 * horizon_distance_m(eye_height, earth_radius) + 1000.0;
      if (site) far = std::max(far, 2.0 * std::hypot(site->width_m, site->height_m));
    }
    const double near = camera.near_m > 0 ? camera.near_m : std::clamp(0.02 * eye_height, 0.05, 50.0);
    const CameraView view = camera_view(camera, width, height, near, far);
    statistics.near_m = near;
    statistics.far_m = far;

    const bool lit = options.colouring == SurfaceColouring::lit;
    bind_textures(bound);
    const bool deep_foam_drawn = lit && update_deep_foam(snapshot, bound, light);
    const int samples = sample_count();
    target.resize(width, height, GL_RGBA8, samples);
    statistics.msaa_samples = samples;
    glBindFramebuffer(GL_FRAMEBUFFER, target.draw_framebuffer());
    glViewport(0, 0, width, height);
    glClearColor(options.background[0], options.background[1], options.background[2], 1.f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDisable(GL_CULL_FACE);
    bind_textures(bound);

    // 1. Sky at the far plane.
    if (options.sky) {
      timer.begin_pass(GpuPass::sky);
      glUseProgram(sky_program);
      set_lighting_uniforms(sky_program, light);
      set_uniform(sky_program, "u_inverse_view_projection", inverse(view.view_projection));
      set_uniform(sky_program, "u_eye_m", view.eye_m);
      glBindVertexArray(empty_vertex_array);
      glDepthMask(GL_FALSE);
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glDepthMask(GL_TRUE);
      timer.end_pass();
    }
    // 2. Seabed, land and structures.
    if (site) {
      timer.begin_pass(GpuPass::terrain);
      glUseProgram(terrain_program);
      set_lighting_uniforms(terrain_program, light);
      set_uniform(terrain_program, "u_view_projection", view.view_projection);
      set_surface_uniforms(terrain_program, snapshot, bound, view.eye_m, earth_radius);
      set_uniform(terrain_program, "u_structure_crest_m", settings.structure_crest_m);
      set_uniform(terrain_program, "u_mirror", 0);
      glBindVertexArray(terrain.vertex_array);
      glDrawElements(GL_TRIANGLES, terrain.index_count, GL_UNSIGNED_INT, nullptr);
      timer.end_pass();
    }
    // 2b. Land and structures mirrored in still water (z -> -z), for the sea's local reflection.
    const bool reflect = site && settings.local_reflections && options.colouring == SurfaceColouring::lit;
    if (reflect) {
      timer.begin_pass(GpuPass::reflection);
      const int downscale = std::max(settings.reflection_downscale, 1);
      reflection.resize(std::max(width / downscale, 1), std::max(height / downscale, 1));
      glBindFramebuffer(GL_FRAMEBUFFER, reflection.framebuffer.id());
      glViewport(0, 0, reflection.framebuffer.width(), reflection.framebuffer.height());
      glClearColor(0.f, 0.f, 0.f, 0.f);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      Matrix4 mirror{};
      mirror[0] = mirror[5] = mirror[15] = 1.0;
      mirror[10] = -1.0;
      set_uniform(terrain_program, "u_view_projection", multiply(view.view_projection, mirror));
      set_uniform(terrain_program, "u_mirror", 1);
      glDrawElements(GL_TRIANGLES, terrain.index_count, GL_UNSIGNED_INT, nullptr);
      set_uniform(terrain_program, "u_mirror", 0);
      if (layers) draw_meshes(*layers, view, snapshot, bound, light, earth_radius, &mirror);  // the hulls mirrored too
      glBindFramebuffer(GL_FRAMEBUFFER, target.draw_framebuffer());
      glViewport(0, 0, width, height);
    }
    timer.end_pass();
    glActiveTexture(GLenum(GL_TEXTURE0 + kReflection));
    glBindTexture(GL_TEXTURE_2D, reflect ? reflection.colour : 0);
    glActiveTexture(GLenum(GL_TEXTURE0 + kDecalFoam));
    glBindTexture(GL_TEXTURE_2D, decal_foam ? layer_gpu.decal_foam() : 0);
    glActiveTexture(GLenum(GL_TEXTURE0 + kDeepFoam));
    glBindTexture(GL_TEXTURE_2D, deep_foam_drawn ? deep_foam.texture[deep_foam.current] : 0);
    glActiveTexture(GL_TEXTURE0);
    // 2c. Hulls and other solids, before the sea: the sea's depth test then hides what is under water.
    if (layers && !layers->meshes.empty()) {
      timer.begin_pass(GpuPass::meshes);
      draw_meshes(*layers, view, snapshot, bound, light, earth_radius);
      timer.end_pass();
    }
    // 3. The sea surface, and its grid's edges over it when asked.
    QuadtreeSelection selection;
    ProjectedGridLayout layout;
    prepare_grid(kind, view, selection, layout);
    const GLuint program = kind == GridKind::radial ? radial_program : kind == GridKind::quadtree ? quadtree_program : projected_program;
    glUseProgram(program);
    set_lighting_uniforms(program, light);
    set_water_lighting_uniforms(program, snapshot, light);
    set_uniform(program, "u_has_reflection", reflect ? 1 : 0);
    set_uniform(program, "u_has_decal_foam", decal_foam ? 1 : 0);
    set_uniform(program, "u_has_deep_foam", deep_foam_drawn ? 1 : 0);
    set_uniform(program, "u_detail_parallax", float(light.detail_parallax));
    if (decal_foam) {
      const std::array<float, 4>& rect = layer_gpu.decal_rect_m();
      glUniform4f(at(program, "u_decal_foam_rect_m"), rect[0], rect[1], rect[2], rect[3]);
    }
    glUniform2f(at(program, "u_viewport_px"), float(width), float(height));
    timer.begin_pass(GpuPass::water);
    draw_water(program, kind, view, earth_radius, snapshot, bound, options, &selection, &layout, true);
    if (options.wireframe) {
      glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
      glEnable(GL_POLYGON_OFFSET_LINE);
      glPolygonOffset(-1.f, -1.f);
      draw_water(program, kind, view, earth_radius, snapshot, bound, options, &selection, &layout, false);
      glDisable(GL_POLYGON_OFFSET_LINE);
      glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    }
    // 4. One sample per pixel for read_pixels() and blit_to_window().
    if (samples > 1) {
      timer.begin_pass(GpuPass::resolve);
      target.resolve();
    }
    timer.end_pass();
    if (GLenum error = glGetError(); error != GL_NO_ERROR)
      throw Error("water renderer", "OpenGL error " + std::to_string(error) + " while drawing", "report this bug");
  }

  Raster<float> render_height_map(const runtime::SurfaceSnapshot& snapshot, const SiteRectangle& r, int columns, int rows,
                                  const SurfaceLayers* layers) {
    if (columns < 1 || rows < 1 || columns > 8192 || rows > 8192 || !(r.x1_m > r.x0_m) || !(r.y1_m > r.y0_m))
      throw Error("height map", std::to_string(columns) + " x " + std::to_string(rows) + " cells over x " +
                                    std::to_string(r.x0_m) + ".." + std::to_string(r.x1_m) + ", y " +
                                    std::to_string(r.y0_m) + ".." + std::to_string(r.y1_m) + " m",
                  "ask for 1..8192 cells each way over a rectangle with x1 > x0 and y1 > y0");
    bind_site(snapshot.site);
    check_snapshot(snapshot);
    UploadCounters counters;
    const KeyframeTextures::Bound bound = keyframes.prepare(snapshot, 0, counters);
    prepare_patches(layers);
    // One lattice vertex per cell centre, plus a margin of cells so the choppy shift never
    // uncovers the rectangle's edge.
    const double dx = (r.x1_m - r.x0_m) / columns, dy = (r.y1_m - r.y0_m) / rows;
    const int margin = std::clamp(int(std::ceil(settings.quadtree.displacement_bound_m / std::min(dx, dy))) + 1, 1, 64);
    const int lattice_columns = columns + 2 * margin, lattice_rows = rows + 2 * margin;
    if (lattice_columns != height_columns || lattice_rows != height_rows) {
      height_lattice.release();
      height_lattice = lattice_mesh(lattice_columns, lattice_rows, 1.f, 1.f);
      height_columns = lattice_columns;
      height_rows = lattice_rows;
    }
    height_target.resize(columns, rows, GL_R32F);
    glBindFramebuffer(GL_FRAMEBUFFER, height_target.draw_framebuffer());
    glViewport(0, 0, columns, rows);
    const float no_water[4] = {std::numeric_limits<float>::quiet_NaN(), 0.f, 0.f, 0.f};
    glClearBufferfv(GL_COLOR, 0, no_water);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);  // the highest surface where folds overlap
    glDisable(GL_CULL_FACE);
    bind_textures(bound);
    glUseProgram(height_program);
    set_uniform(height_program, "u_view_projection", orthographic_top_down(r.x0_m, r.y0_m, r.x1_m, r.y1_m, -1000.0, 1000.0));
    const Vector3 eye = {0.5 * (r.x0_m + r.x1_m), 0.5 * (r.y0_m + r.y1_m), 1000.0};
    set_surface_uniforms(height_program, snapshot, bound, eye, 0.0);
    glUniform4f(at(height_program, "u_lattice_m"), float(r.x0_m + (0.5 - margin) * dx), float(r.y0_m + (0.5 - margin) * dy),
                float(dx), float(dy));
    glBindVertexArray(height_lattice.vertex_array);
    glDrawElements(GL_TRIANGLES, height_lattice.index_count, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    Raster<float> heights(columns, rows);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, columns, rows, GL_RED, GL_FLOAT, heights.data());  // GL row 0 = south = raster row 0
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (GLenum error = glGetError(); error != GL_NO_ERROR)
      throw Error("water renderer", "OpenGL error " + std::to_string(error) + " in the height pass", "report this bug");
    return heights;
  }
};

WaterRenderer::WaterRenderer(RendererSettings settings) : impl_(new Impl(settings)) {}
WaterRenderer::~WaterRenderer() = default;

RendererSettings& WaterRenderer::settings() { return impl_->settings; }
bool WaterRenderer::stage(std::shared_ptr<const runtime::HarbourKeyframe> k) { return impl_->keyframes.stage(std::move(k)); }
bool WaterRenderer::stage(std::shared_ptr<const runtime::DeepWaterKeyframe> k) { return impl_->keyframes.stage(std::move(k)); }

void WaterRenderer::render(const runtime::SurfaceSnapshot& snapshot, const Camera& camera, const Lighting& lighting,
                           int width_px, int height_px, const DrawOptions& options, const SurfaceLayers* layers) {
  impl_->render(snapshot, camera, lighting, width_px, height_px, options, layers);
}

void WaterRenderer::stage_upcoming(const runtime::StreamingEngine& engine) {
  for (auto& keyframe : engine.upcoming_harbour_keyframes(2)) stage(std::move(keyframe));
  for (auto& keyframe : engine.upcoming_deep_keyframes(1)) stage(std::move(keyframe));
}

const GpuTextures& WaterRenderer::upload(const runtime::SurfaceSnapshot& snapshot) {
  impl_->upload(snapshot);
  return impl_->textures;
}

const GpuTextures& WaterRenderer::textures() const { return impl_->textures; }

const FrameStatistics& WaterRenderer::last_frame() const { return impl_->statistics; }

Raster<float> WaterRenderer::deep_foam_map() const { return impl_->deep_foam_map(); }

Raster<float> WaterRenderer::render_height_map(const runtime::SurfaceSnapshot& snapshot, const SiteRectangle& rectangle,
                                               int columns, int rows, const SurfaceLayers* layers) {
  return impl_->render_height_map(snapshot, rectangle, columns, rows, layers);
}

const char* gpu_pass_name(GpuPass pass) {
  static constexpr const char* kNames[kGpuPassCount] = {"decal_foam", "deep_foam", "sky",   "terrain",
                                                        "reflection", "meshes",    "water", "resolve"};
  const int k = static_cast<int>(pass);
  return k >= 0 && k < kGpuPassCount ? kNames[k] : "unknown";
}

void WaterRenderer::blit_to_window(int window_width_px, int window_height_px) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, impl_->target.read_framebuffer());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(0, 0, impl_->target.width(), impl_->target.height(), 0, 0, window_width_px, window_height_px,
                    GL_COLOR_BUFFER_BIT, GL_LINEAR);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Image WaterRenderer::read_pixels() const {
  const RenderTarget& t = impl_->target;
  const int width = t.width(), height = t.height();
  std::vector<unsigned char> bytes(std::size_t(width) * height * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, t.read_framebuffer());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
  Image image(width, height);
  for (int y = 0; y < height; ++y)  // GL row 0 is the bottom
    for (int x = 0; x < width; ++x) {
      const unsigned char* p = &bytes[(std::size_t(height - 1 - y) * width + x) * 4];
      image.set(x, y, {p[0] / 255.f, p[1] / 255.f, p[2] / 255.f});
    }
  return image;
}

}  // namespace nearshore::playback
