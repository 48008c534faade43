#pragma once
// WaterRenderer: draws a runtime::SurfaceSnapshot (runtime/surface_snapshot.hpp): sky, seabed and
// land, breakwaters and quays, and the sea surface on one of three grids (surface_grids.hpp),
// displaced in the vertex shader by exactly the snapshot's formula (shaders/surface.glsl: the
// harbour keyframe pair blended by its fraction, the deep-water cascades summed and blended, the
// harbour weight w(p), the deep water's choppy shift) and lit by seed 003 eq. (12)-(16)
// (shaders/common.glsl). Everything is in the site frame. docs/rendering.md shows how to use it.
//
// Keyframes go to the GPU once each, by serial, as R32F textures (float32: the same numbers the
// CPU sampler reads, so the height pass agrees with it to a fraction of a millimetre). A keyframe
// the engine announces with stage() is uploaded in row chunks within
// RendererSettings::upload_budget_bytes_per_frame; one a snapshot needs before it is complete is
// finished at once, and last_frame() says how many bytes each frame sent, and how many were forced.
//
// Needs a current OpenGL 3.3+ context (GlWindow) on the calling thread; not thread-safe. Renders
// into its own framebuffer object, so screenshots are exact even from a hidden window.
#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/image.hpp"
#include "nearshore/playback/camera.hpp"
#include "nearshore/playback/lighting.hpp"
#include "nearshore/playback/surface_grids.hpp"
#include "nearshore/playback/surface_layers.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"

namespace nearshore::playback {

struct RendererSettings {
  GridKind grid = GridKind::quadtree;
  RadialGridSettings radial;
  QuadtreeSettings quadtree;
  ProjectedGridSettings projected;
  /// Texture bytes a frame may spend on staged keyframes (at least one row is always sent).
  /// 2 MiB: a 1024 x 1024 harbour keyframe (8 MiB) in 4 frames.
  std::size_t upload_budget_bytes_per_frame = std::size_t(2) << 20;
  int harbour_texture_slots = 6;  ///< keyframes kept on the GPU: the pair on screen + staged ones
  int deep_texture_slots = 6;
  /// The crest of breakwaters and quays a grid knows only by their porous cells (no CoastalStructure
  /// geometry: grids written before it), metres above still water (drawing only).
  float structure_crest_m = 2.5f;
  /// Land, breakwaters and quays mirrored in the sea (planar reflection in still water, one extra
  /// terrain pass into a texture of 1/reflection_downscale the picture's size; docs/lighting.md).
  bool local_reflections = true;
  int reflection_downscale = 2;
  /// What lies under the water seen through it (screen-space refraction, docs/lighting.md step 5):
  /// the opaque scene (seabed, hulls, structures) is copied before the sea is drawn and the sea
  /// samples it where its refracted view meets it, attenuated by the water's optics. false: the
  /// sea is opaque over them and shows only its procedural seabed.
  bool refraction = true;
  /// Side of the square foam map the SurfaceLayers' decals are drawn into (texels), over the
  /// decals' bounding box but never finer than decal_foam_finest_m per texel.
  int decal_foam_texels = 1024;
  double decal_foam_finest_m = 0.25;
  /// Samples per pixel of the picture (multisample anti-aliasing): edges of land, structures,
  /// hulls and the horizon are covered by this many samples and averaged when the frame is
  /// resolved. Clamped to the driver's GL_MAX_SAMPLES; 1 = off; 0 (the default) = automatic: 4 on a
  /// GPU, 1 on a software rasteriser (Mesa's llvmpipe, softpipe or swrast: GL_RENDERER), where 4
  /// samples cost 2-6 times the frame. The height pass (render_height_map) is always
  /// single-sample. docs/rendering.md ("Anti-aliasing") gives the cost.
  int msaa_samples = 0;
  /// GPU time per pass in FrameStatistics::gpu (timer queries, read back frames later without
  /// waiting); false issues no queries.
  bool gpu_timing = true;
};

/// How the sea is coloured: lit (the frame loop), or flat and by level of detail for tests and
/// pictures of the grids.
enum class SurfaceColouring { lit, flat, level_of_detail };

struct DrawOptions {
  SurfaceColouring colouring = SurfaceColouring::lit;
  Rgb flat_colour = {1.f, 0.f, 1.f};  ///< for SurfaceColouring::flat
  bool wireframe = false;             ///< the grid's edges drawn over the sea
  bool sky = true;                    ///< false: a plain background instead of the sky
  Rgb background = {0.f, 0.f, 0.f};
  /// false: the SurfaceLayers' meshes are not drawn into the picture, only mirrored into the local
  /// reflection: for a host whose scene graph draws those objects itself (nearshore::osg).
  bool draw_meshes = true;
};

/// The passes of render(), in the order drawn, for the GPU time of each (FrameStatistics::gpu).
enum class GpuPass {
  decal_foam,  ///< the SurfaceLayers' foam decals into their foam map
  deep_foam,   ///< one step of the deep water's persistent foam (seed 000 eq. 3.46)
  sky,         ///< the sky at the far plane
  terrain,     ///< seabed, land and structures
  reflection,  ///< land, structures and hulls mirrored into the reflection texture
  meshes,      ///< hulls and other solids
  water,       ///< the sea surface on its grid (and the wireframe over it when asked)
  resolve,     ///< the multisampled picture averaged into one sample per pixel
  refraction,  ///< the opaque scene's colour and depth copied for the sea to refract (before the water)
};
inline constexpr int kGpuPassCount = 9;
/// "decal_foam", "deep_foam", "sky", "terrain", "reflection", "meshes", "water", "resolve", "refraction".
const char* gpu_pass_name(GpuPass pass);

/// GPU time of each pass of one earlier frame (GL_TIME_ELAPSED). Timer queries are read back only
/// once the GPU has finished them, so these belong to the frame `frames_behind` renders back
/// (typically 1 or 2); `measured` is false (and every time 0) while no frame has finished yet, with
/// RendererSettings::gpu_timing off, or when the driver has no timer (GL_QUERY_COUNTER_BITS 0).
struct GpuPassTimes {
  bool measured = false;
  int frames_behind = 0;
  std::array<double, kGpuPassCount> ms{};  ///< per GpuPass; 0 for a pass that frame did not draw
  double total_ms = 0;                     ///< sum of the passes (uploads and the CPU are not in it)
  double ms_of(GpuPass pass) const { return ms[static_cast<std::size_t>(pass)]; }
};

/// What the last render() did.
struct FrameStatistics {
  std::size_t upload_bytes = 0;           ///< texture bytes sent (keyframes and, once, the site)
  std::size_t forced_upload_bytes = 0;    ///< of which for keyframes needed before their upload was done
  std::size_t geometry_upload_bytes = 0;  ///< per-frame vertex data (the quadtree's patch list)
  long long vertices_drawn = 0;           ///< water grid vertices submitted
  long long triangles_drawn = 0;
  int quadtree_patches = 0, quadtree_levels = 0;
  double near_m = 0, far_m = 0;           ///< the clip distances used
  std::size_t layer_upload_bytes = 0;     ///< height patches and meshes sent (SurfaceLayers)
  int height_patches = 0, foam_decals = 0, meshes = 0;  ///< the layers drawn
  int msaa_samples = 1;                   ///< samples per pixel drawn (RendererSettings::msaa_samples, clamped)
  GpuPassTimes gpu;                       ///< GPU ms per pass of an earlier frame (see GpuPassTimes)
};

/// A rectangle of the site frame, metres.
struct SiteRectangle {
  double x0_m = 0, y0_m = 0, x1_m = 0, y1_m = 0;
};

/// The GL textures of the keyframe pair a draw binds, for a host that draws the sea itself
/// (docs/c-api.md). Harbour: one R32F GL_TEXTURE_2D per keyframe and field, columns x rows texels,
/// texel (i, j) at the centre of cell (i, j), row 0 south (bilinear by hand: surface_sampler.hpp
/// formula 1). Deep water: per field one R32F GL_TEXTURE_2D_ARRAY per keyframe, N x N texels and
/// one layer per cascade, texel (i, j) of layer c at (i L_c / N, j L_c / N), repeating (formula 2).
/// Valid until the next render() or upload(); the renderer owns them.
struct GpuTextures {
  unsigned harbour_elevation[2] = {0, 0}, harbour_breaking[2] = {0, 0};  ///< [0] from, [1] to
  unsigned deep_elevation[2] = {0, 0}, deep_displacement_x[2] = {0, 0}, deep_displacement_y[2] = {0, 0};
  unsigned deep_slope_x[2] = {0, 0}, deep_slope_y[2] = {0, 0};
  int cascade_count = 0, deep_grid_size = 0;
  std::vector<float> tile_lengths_m;
  double harbour_fraction = 0.0, deep_fraction = 0.0;  ///< shown = (1 - f) from + f to
  /// d eta / dt of the harbour keyframes (R32F, m/s; zeros where a keyframe has none) and whether
  /// both have one: then the harbour is the cubic Hermite of runtime/surface_snapshot.hpp with
  /// T = frame_interval_s.
  unsigned harbour_elevation_rate[2] = {0, 0};
  /// The harbour keyframes' slope moments: RGBA32F (g_x, g_y, g_x^2, g_y^2), mip-mapped
  /// (playback/slope_moments.hpp), for a host filtering the baked slopes itself as the shader does.
  unsigned harbour_slope_moments[2] = {0, 0};
  bool harbour_has_rates = false;
  double frame_interval_s = 0.0;
};

class WaterRenderer {
 public:
  explicit WaterRenderer(RendererSettings settings = {});
  ~WaterRenderer();
  WaterRenderer(const WaterRenderer&) = delete;
  WaterRenderer& operator=(const WaterRenderer&) = delete;

  /// The settings; change them between frames (the grid kind, its parameters, the budget).
  RendererSettings& settings();

  /// Announces a keyframe a coming snapshot will show, for the budgeted upload. Returns false
  /// when it is already on the GPU or queued, or the queue is full (slots - 2 keyframes).
  bool stage(std::shared_ptr<const runtime::HarbourKeyframe> keyframe);
  bool stage(std::shared_ptr<const runtime::DeepWaterKeyframe> keyframe);
  /// Stages what `engine` has decoded beyond the pair on screen (two harbour keyframes, one deep
  /// one): call once per frame after its advance_to, on the render thread.
  void stage_upcoming(const runtime::StreamingEngine& engine);

  /// Draws `snapshot` seen by `camera` (site frame) into the renderer's framebuffer. Throws
  /// nearshore::Error for a snapshot it cannot draw (keyframes of another size than the site's
  /// grid, deep-water cascades of different sizes) and for a camera that looks nowhere.
  /// `layers` (may be null): height patches, foam decals and meshes drawn with the sea
  /// (surface_layers.hpp); throws nearshore::Error for more patches than kMaxHeightPatches or a
  /// patch or mesh without data.
  void render(const runtime::SurfaceSnapshot& snapshot, const Camera& camera, const Lighting& lighting, int width_px,
              int height_px, const DrawOptions& options = {}, const SurfaceLayers* layers = nullptr);
  /// Draws `snapshot` into the framebuffer and viewport the HOST has bound (a scene graph's
  /// window or render target), seen by the host's `view` (camera_view_from_matrices): nothing is
  /// cleared, the sky, terrain and sea are depth-tested against (and write) the host's depth
  /// buffer in the host's depth range, so the host's objects drawn before or after are sorted
  /// against the water per pixel. One sample per pixel as the host's buffer has them
  /// (RendererSettings::msaa_samples does not apply); read_pixels() and blit_to_window() do not
  /// see this draw. The GL state it leaves: framebuffer, viewport, program, vertex array and
  /// texture bindings, depth and blend settings changed (docs/osg.md lists them): a host that
  /// tracks GL state saves and restores it around the call. Throws as render().
  void render_into_bound_framebuffer(const runtime::SurfaceSnapshot& snapshot, const CameraView& view,
                                     const Lighting& lighting, const DrawOptions& options = {},
                                     const SurfaceLayers* layers = nullptr);
  const FrameStatistics& last_frame() const;
  /// Makes the snapshot's keyframes resident without drawing (and spends the upload budget on
  /// staged ones), for a host that draws them itself; returns what textures() returns after.
  const GpuTextures& upload(const runtime::SurfaceSnapshot& snapshot);
  /// The textures bound by the last render() or upload().
  const GpuTextures& textures() const;

  /// The shown surface elevation (m) over `rectangle`, seen straight down through the water's own
  /// vertex path, one value per cell of a columns x rows raster (cell (i, j) centred at x0 + (i +
  /// 0.5) (x1 - x0) / columns, row 0 south); NaN where no water is drawn (land, structures, dry).
  /// For tests and documentation (it reads the GPU back): never in the frame loop.
  /// With `layers`, their height patches are added as in render() (the CPU twin of the sum:
  /// ships::ShipFleet::shown_elevation_m).
  Raster<float> render_height_map(const runtime::SurfaceSnapshot& snapshot, const SiteRectangle& rectangle, int columns,
                                  int rows, const SurfaceLayers* layers = nullptr);

  /// The deep water's persistent foam f_t (seed 000 eq. 3.46) after the last lit render(): one
  /// value in [0, 1] per sample of the largest cascade's tile (cell (i, j) at x = (i + 0.5) L_0 / N,
  /// row 0 south; the tile repeats); empty without deep water or with Lighting::foam_decay_time_s
  /// = 0. For tests and documentation (it reads the GPU back): never in the frame loop.
  Raster<float> deep_foam_map() const;

  /// Copies the last render (resolved to one sample per pixel) to the window's back buffer, scaled
  /// to the window's size (call GlWindow::present after).
  void blit_to_window(int window_width_px, int window_height_px) const;
  /// The last render as an image (row 0 at the top).
  Image read_pixels() const;


 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nearshore::playback
