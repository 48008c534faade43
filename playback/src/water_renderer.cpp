#include "nearshore/playback/water_renderer.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "deep_foam_pass.hpp"
#include "gl_framebuffer.hpp"
#include "gl_program.hpp"
#include "height_pass.hpp"
#include "keyframe_textures.hpp"
#include "local_reflection.hpp"
#include "nearshore/core/error.hpp"
#include "pass_timer.hpp"
#include "refraction_source.hpp"
#include "site_textures.hpp"
#include "sky_pass.hpp"
#include "solid_mesh_pass.hpp"
#include "surface_layer_gpu.hpp"
#include "surface_uniforms.hpp"
#include "terrain_pass.hpp"
#include "water_surface_pass.hpp"

namespace nearshore::playback {

namespace {
// Where a frame's picture goes: the renderer's own target (cleared first), or the framebuffer and
// viewport a host bound (drawn over, depth-tested against the host's depth buffer).
struct Destination {
  GLuint framebuffer = 0;
  int x = 0, y = 0, width = 0, height = 0;
  // The renderer's target (cleared first; the refraction copies it), or false: a host's framebuffer
  // (drawn over as the host left it, no refraction).
  bool own_target = true;
  void bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(x, y, width, height);
  }
};
}  // namespace

// The orchestration: what a frame uploads, in which order the passes draw into which target, and
// which texture units and statistics connect them. The GL objects belong to the passes.
struct WaterRenderer::Impl {
  RendererSettings settings;
  KeyframeTextures keyframes;
  FrameStatistics statistics;
  GpuTextures textures;         // of the last render or upload
  SiteTextures site_textures;   // the site (static for a sequence): uploaded when the snapshot's site changes
  SurfaceLayerGpu layer_gpu;    // the SurfaceLayers' patches, decal foam map and meshes
  GLuint decal_program = 0;     // decal.vert/frag, for layer_gpu.draw_decals
  bool patches_active = false;  // this draw adds the patches uploaded last
  DeepFoamPass deep_foam;
  SkyPass sky;
  TerrainPass terrain;
  LocalReflection reflection;
  RefractionSource refraction;
  SolidMeshPass solid_meshes;
  WaterSurfacePass water;
  HeightPass height;
  RenderTarget target;
  PassTimer timer;
  int max_samples = 0;               // GL_MAX_SAMPLES, asked on the first frame
  bool software_rasteriser = false;  // GL_RENDERER names Mesa's llvmpipe, softpipe or swrast

  explicit Impl(const RendererSettings& s)
      : settings(s), keyframes(s.harbour_texture_slots, s.deep_texture_slots) {
    decal_program = link_program({}, "decal.vert.glsl", {}, "decal.frag.glsl");
  }

  ~Impl() {
    glDeleteProgram(decal_program);
    target.release();
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
      software_rasteriser = name.find("llvmpipe") != std::string::npos ||
                            name.find("softpipe") != std::string::npos ||
                            name.find("swrast") != std::string::npos;
    }
    const int asked = settings.msaa_samples > 0 ? settings.msaa_samples : software_rasteriser ? 1 : 4;
    return asked <= 1 ? 1 : std::min(asked, max_samples);
  }

  // The snapshot's formula as every pass sets it (after prepare_patches: it counts the patches).
  SurfaceFormula formula(const runtime::SurfaceSnapshot& snapshot,
                         const KeyframeTextures::Bound& bound) const {
    const PatchUniforms& patches = layer_gpu.patch_uniforms();
    return SurfaceFormula{snapshot,
                          bound,
                          site_textures.site(),
                          site_textures.open_sea_depth_m(),
                          site_textures.has_relative_wave_height(),
                          patches,
                          patches_active ? patches.count : 0,
                          site_textures.has_surroundings() ? &site_textures.surroundings_cells() : nullptr,
                          float(site_textures.surroundings_edge_blend_m())};
  }

  // The layers' height patches onto their unit (before any surface uniforms are set).
  void prepare_patches(const SurfaceLayers* layers) {
    patches_active = layers && !layers->height_patches.empty();
    if (patches_active)
      statistics.layer_upload_bytes += layer_gpu.upload_patches(layers->height_patches, kPatches);
    statistics.height_patches = patches_active ? int(layers->height_patches.size()) : 0;
    glActiveTexture(GLenum(GL_TEXTURE0 + kPatches));
    glBindTexture(GL_TEXTURE_2D, patches_active ? layer_gpu.patch_atlas() : 0);
    glActiveTexture(GL_TEXTURE0);
  }

  // The keyframes' and the site's textures on their SamplerUnits.
  void bind_textures(const KeyframeTextures::Bound& bound) const {
    auto bind = [](int unit, GLenum target_kind, GLuint texture) {
      glActiveTexture(GLenum(GL_TEXTURE0 + unit));
      glBindTexture(target_kind, texture);
    };
    for (int k = 0; k < 2; ++k) {
      bind(kHarbourEta + k, GL_TEXTURE_2D, bound.harbour_eta[k]);
      bind(kHarbourBreaking + k, GL_TEXTURE_2D, bound.harbour_breaking[k]);
      bind(kHarbourEtaRate + k, GL_TEXTURE_2D, bound.harbour_eta_rate[k]);
      bind(kHarbourSlopeMoments + k, GL_TEXTURE_2D, bound.harbour_slope_moments[k]);
    }
    site_textures.bind_units();
    for (int field = 0; field < kDeepFieldCount; ++field)
      for (int k = 0; k < 2; ++k) bind(kDeepFirst + 2 * field + k, GL_TEXTURE_2D_ARRAY, bound.deep[field][k]);
    glActiveTexture(GL_TEXTURE0);
  }

  void check_snapshot(const runtime::SurfaceSnapshot& snapshot) const {
    const runtime::HarbourSite* site = site_textures.site();
    for (const auto* keyframe : {snapshot.harbour_from.get(), snapshot.harbour_to.get()}) {
      if (!keyframe) continue;
      if (!site)
        throw Error("surface snapshot", "holds harbour keyframes but no site",
                    "give the snapshot its HarbourSite");
      const GridGeometry& g = site->harbour.geometry;
      if (keyframe->surface_elevation_m.columns() != g.columns ||
          keyframe->surface_elevation_m.rows() != g.rows)
        throw Error("harbour keyframe " + std::to_string(keyframe->serial),
                    "is " + std::to_string(keyframe->surface_elevation_m.columns()) + " x " +
                        std::to_string(keyframe->surface_elevation_m.rows()) +
                        " cells but the site's grid is " + std::to_string(g.columns) + " x " +
                        std::to_string(g.rows),
                    "play a sequence baked on this harbour grid");
    }
  }

  void remember_textures(const runtime::SurfaceSnapshot& snapshot, const KeyframeTextures::Bound& bound) {
    textures = GpuTextures{};
    for (int k = 0; k < 2; ++k) {
      textures.harbour_elevation[k] = bound.harbour_eta[k];
      textures.harbour_breaking[k] = bound.harbour_breaking[k];
      textures.harbour_elevation_rate[k] = bound.harbour_eta_rate[k];
      textures.harbour_slope_moments[k] = bound.harbour_slope_moments[k];
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
    statistics.upload_bytes += site_textures.bind_site(snapshot.site, settings.structure_crest_m);
    check_snapshot(snapshot);
    UploadCounters counters;
    KeyframeTextures::Bound bound =
        keyframes.prepare(snapshot, settings.upload_budget_bytes_per_frame, counters);
    statistics.upload_bytes += counters.bytes;
    statistics.forced_upload_bytes = counters.forced_bytes;
    remember_textures(snapshot, bound);
    return bound;
  }

  // Clip distances: near from the eye's height; far where the grid ends (or beyond the site).
  CameraView frame_view(const Camera& camera, int width, int height, double earth_radius_m) {
    const GridKind kind = settings.grid;
    const double eye_height = std::max(std::abs(camera.eye_m[2]), 0.1);
    double far = camera.far_m;
    if (far <= 0) {
      far = kind == GridKind::radial     ? 1.05 * settings.radial.outer_radius_m
            : kind == GridKind::quadtree ? 2.0 * settings.quadtree.reach_m
                                         : 1.05 * horizon_distance_m(eye_height, earth_radius_m) + 1000.0;
      if (const runtime::HarbourSite* site = site_textures.site())
        far = std::max(far, 2.0 * std::hypot(site->width_m, site->height_m));
    }
    const double near = camera.near_m > 0 ? camera.near_m : std::clamp(0.02 * eye_height, 0.05, 50.0);
    statistics.near_m = near;
    statistics.far_m = far;
    return camera_view(camera, width, height, near, far);
  }

  // 2b. Land, structures and hulls mirrored in still water (z -> -z) into the local reflection's
  // texture, then back to the frame's target. After the terrain pass (whose uniforms it keeps).
  void draw_reflection(const SurfaceFormula& surface, const LightingFrame& light, const CameraView& view,
                       double earth_radius_m, const Destination& destination, const SurfaceLayers* layers) {
    const int width = destination.width, height = destination.height;
    const int downscale = std::max(settings.reflection_downscale, 1);
    reflection.resize(std::max(width / downscale, 1), std::max(height / downscale, 1));
    glBindFramebuffer(GL_FRAMEBUFFER, reflection.framebuffer());
    glViewport(0, 0, reflection.width(), reflection.height());
    glClearColor(0.f, 0.f, 0.f, 0.f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    Matrix4 mirror{};
    mirror[0] = mirror[5] = mirror[15] = 1.0;
    mirror[10] = -1.0;
    terrain.draw_mirrored(site_textures.terrain(), multiply(view.view_projection, mirror));
    if (layers)  // the hulls mirrored too
      solid_meshes.draw(*layers, layer_gpu, surface, light, view, earth_radius_m, statistics, &mirror);
    destination.bind();
  }

  // The maps the sea samples, on their units (0: none this frame).
  void bind_sea_maps(bool reflect, bool decal_foam, bool deep_foam_drawn, bool refract) const {
    glActiveTexture(GLenum(GL_TEXTURE0 + kSceneColour));
    glBindTexture(GL_TEXTURE_2D, refract ? refraction.colour() : 0);
    glActiveTexture(GLenum(GL_TEXTURE0 + kSceneDepth));
    glBindTexture(GL_TEXTURE_2D, refract ? refraction.depth() : 0);
    glActiveTexture(GLenum(GL_TEXTURE0 + kReflection));
    glBindTexture(GL_TEXTURE_2D, reflect ? reflection.colour() : 0);
    glActiveTexture(GLenum(GL_TEXTURE0 + kDecalFoam));
    glBindTexture(GL_TEXTURE_2D, decal_foam ? layer_gpu.decal_foam() : 0);
    glActiveTexture(GLenum(GL_TEXTURE0 + kDeepFoam));
    glBindTexture(GL_TEXTURE_2D, deep_foam_drawn ? deep_foam.foam() : 0);
    glActiveTexture(GL_TEXTURE0);
  }

  void render(const runtime::SurfaceSnapshot& snapshot, const Camera& camera, const Lighting& lighting,
              int width, int height, const DrawOptions& options, const SurfaceLayers* layers) {
    const KeyframeTextures::Bound bound = upload(snapshot);
    const double earth_radius =
        settings.grid == GridKind::projected ? settings.projected.earth_radius_m : 0.0;
    const CameraView view = frame_view(camera, width, height, earth_radius);
    const int samples = sample_count();
    target.resize(width, height, GL_RGBA8, samples);
    statistics.msaa_samples = samples;
    draw_frame(snapshot, bound, view, lighting, options, layers,
               Destination{target.draw_framebuffer(), 0, 0, width, height, true});
    // 4. One sample per pixel for read_pixels() and blit_to_window().
    if (samples > 1) {
      timer.begin_pass(GpuPass::resolve);
      target.resolve();
    }
    timer.end_pass();
    check_errors();
  }

  void render_into_bound_framebuffer(const runtime::SurfaceSnapshot& snapshot, const CameraView& view,
                                     const Lighting& lighting, const DrawOptions& options,
                                     const SurfaceLayers* layers) {
    GLint framebuffer = 0, viewport[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    glGetIntegerv(GL_VIEWPORT, viewport);
    const KeyframeTextures::Bound bound = upload(snapshot);
    statistics.near_m = view.near_m;
    statistics.far_m = view.far_m;
    statistics.msaa_samples = 1;
    draw_frame(snapshot, bound, view, lighting, options, layers,
               Destination{GLuint(framebuffer), viewport[0], viewport[1], viewport[2], viewport[3], false});
    timer.end_pass();
    check_errors();
  }

  void check_errors() const {
    if (GLenum error = glGetError(); error != GL_NO_ERROR)
      throw Error("water renderer", "OpenGL error " + std::to_string(error) + " while drawing",
                  "report this bug");
  }

  // Passes 0-3 of a frame into `destination` (the renderer's target, or the host's framebuffer).
  void draw_frame(const runtime::SurfaceSnapshot& snapshot, const KeyframeTextures::Bound& bound,
                  const CameraView& view, const Lighting& lighting, const DrawOptions& options,
                  const SurfaceLayers* layers, const Destination& destination) {
    timer.begin_frame(settings.gpu_timing, statistics.gpu);  // and what an earlier frame measured
    const LightingFrame light = prepare_lighting(lighting);
    prepare_patches(layers);
    const SurfaceFormula surface = formula(snapshot, bound);
    const bool lit = options.colouring == SurfaceColouring::lit;
    // The wakes' foam map first: it draws into its own framebuffer.
    if (layers && lit && !layers->foam_decals.empty()) timer.begin_pass(GpuPass::decal_foam);
    const bool decal_foam = layers && lit &&
                            layer_gpu.draw_decals(layers->foam_decals, decal_program,
                                                  settings.decal_foam_texels, settings.decal_foam_finest_m);
    timer.end_pass();
    statistics.foam_decals = decal_foam ? int(layers->foam_decals.size()) : 0;

    const double earth_radius =
        settings.grid == GridKind::projected ? settings.projected.earth_radius_m : 0.0;
    bind_textures(bound);
    const bool deep_foam_drawn = lit && deep_foam.update(surface, light, timer);
    destination.bind();
    if (destination.own_target) {
      glClearColor(options.background[0], options.background[1], options.background[2], 1.f);
      glClearDepth(1.0);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    bind_textures(bound);

    // 1. Sky at the far plane.
    if (options.sky) {
      timer.begin_pass(GpuPass::sky);
      sky.draw(light, view);
      timer.end_pass();
    }
    // 2. Seabed, land and structures.
    if (site_textures.site()) {
      timer.begin_pass(GpuPass::terrain);
      terrain.draw(site_textures.terrain(), surface, light, view, earth_radius);
      timer.end_pass();
    }
    // 2b. Their image in still water, for the sea's local reflection.
    const bool reflect = site_textures.site() && settings.local_reflections && lit;
    if (reflect) {
      timer.begin_pass(GpuPass::reflection);
      draw_reflection(surface, light, view, earth_radius, destination, layers);
    }
    timer.end_pass();
    // 2c. Hulls and other solids, before the sea: the sea's depth test hides what is under water,
    // and the sea shows it through the surface by refraction (2d).
    if (layers && !layers->meshes.empty() && options.draw_meshes) {
      timer.begin_pass(GpuPass::meshes);
      solid_meshes.draw(*layers, layer_gpu, surface, light, view, earth_radius, statistics);
      timer.end_pass();
    }
    // 2d. The opaque scene so far (colour and depth) copied for the sea's refraction. Only in the
    // renderer's own target: a host's framebuffer (render_into_bound_framebuffer) may hold a depth
    // format the copy cannot blit (a blit of depth needs equal formats) and multisamples of its own,
    // so a host's sea is drawn without it (docs/osg.md, "Limits").
    const bool refract = settings.refraction && lit && destination.own_target;
    if (refract) {
      timer.begin_pass(GpuPass::refraction);
      refraction.copy_from(target);
      timer.end_pass();
    }
    bind_sea_maps(reflect, decal_foam, deep_foam_drawn, refract);
    // 3. The sea surface, and its grid's edges over it when asked.
    SeaDraw sea{settings, surface, light, view, earth_radius, options, destination.width, destination.height};
    sea.viewport_x_px = destination.x;
    sea.viewport_y_px = destination.y;
    sea.reflection = reflect;
    sea.decal_foam = decal_foam;
    if (decal_foam) sea.decal_foam_rect_m = layer_gpu.decal_rect_m();
    sea.deep_foam = deep_foam_drawn;
    sea.refraction = refract;
    water.draw(sea, timer, statistics);
  }

  Raster<float> render_height_map(const runtime::SurfaceSnapshot& snapshot, const SiteRectangle& r,
                                  int columns, int rows, const SurfaceLayers* layers) {
    if (columns < 1 || rows < 1 || columns > 8192 || rows > 8192 || !(r.x1_m > r.x0_m) || !(r.y1_m > r.y0_m))
      throw Error("height map",
                  std::to_string(columns) + " x " + std::to_string(rows) + " cells over x " +
                      std::to_string(r.x0_m) + ".." + std::to_string(r.x1_m) + ", y " +
                      std::to_string(r.y0_m) + ".." + std::to_string(r.y1_m) + " m",
                  "ask for 1..8192 cells each way over a rectangle with x1 > x0 and y1 > y0");
    statistics.upload_bytes += site_textures.bind_site(snapshot.site, settings.structure_crest_m);
    check_snapshot(snapshot);
    UploadCounters counters;
    const KeyframeTextures::Bound bound = keyframes.prepare(snapshot, 0, counters);
    prepare_patches(layers);
    bind_textures(bound);
    Raster<float> heights =
        height.render(formula(snapshot, bound), r, columns, rows, settings.quadtree.displacement_bound_m);
    if (GLenum error = glGetError(); error != GL_NO_ERROR)
      throw Error("water renderer", "OpenGL error " + std::to_string(error) + " in the height pass",
                  "report this bug");
    return heights;
  }
};

WaterRenderer::WaterRenderer(RendererSettings settings) : impl_(new Impl(settings)) {}
WaterRenderer::~WaterRenderer() = default;

RendererSettings& WaterRenderer::settings() {
  return impl_->settings;
}
bool WaterRenderer::stage(std::shared_ptr<const runtime::HarbourKeyframe> k) {
  return impl_->keyframes.stage(std::move(k));
}
bool WaterRenderer::stage(std::shared_ptr<const runtime::DeepWaterKeyframe> k) {
  return impl_->keyframes.stage(std::move(k));
}

void WaterRenderer::render(const runtime::SurfaceSnapshot& snapshot, const Camera& camera,
                           const Lighting& lighting, int width_px, int height_px, const DrawOptions& options,
                           const SurfaceLayers* layers) {
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

const GpuTextures& WaterRenderer::textures() const {
  return impl_->textures;
}

void WaterRenderer::render_into_bound_framebuffer(const runtime::SurfaceSnapshot& snapshot, const CameraView& view,
                                                  const Lighting& lighting, const DrawOptions& options,
                                                  const SurfaceLayers* layers) {
  impl_->render_into_bound_framebuffer(snapshot, view, lighting, options, layers);
}

const FrameStatistics& WaterRenderer::last_frame() const {
  return impl_->statistics;
}

Raster<float> WaterRenderer::deep_foam_map() const {
  return impl_->deep_foam.read_map();
}

Raster<float> WaterRenderer::render_height_map(const runtime::SurfaceSnapshot& snapshot,
                                               const SiteRectangle& rectangle, int columns, int rows,
                                               const SurfaceLayers* layers) {
  return impl_->render_height_map(snapshot, rectangle, columns, rows, layers);
}

const char* gpu_pass_name(GpuPass pass) {
  static constexpr const char* kNames[kGpuPassCount] = {"decal_foam", "deep_foam", "sky",     "terrain",   "reflection",
                                                        "meshes",     "water",     "resolve", "refraction"};
  const int k = static_cast<int>(pass);
  return k >= 0 && k < kGpuPassCount ? kNames[k] : "unknown";
}

void WaterRenderer::blit_to_window(int window_width_px, int window_height_px) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, impl_->target.read_framebuffer());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(0, 0, impl_->target.width(), impl_->target.height(), 0, 0, window_width_px,
                    window_height_px, GL_COLOR_BUFFER_BIT, GL_LINEAR);
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
