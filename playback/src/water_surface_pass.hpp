#pragma once
// The sea surface (private to the water renderer): the water programs of the three grids (radial,
// quadtree, projected; surface_grids.hpp), their meshes, rebuilt only when their settings change,
// and the sea's own lighting uniforms; drawn filled and, when asked, its grid's edges over it.
// Needs the renderer's current GL context.
#include <glad/gl.h>

#include <array>
#include <vector>

#include "gl_mesh.hpp"
#include "nearshore/playback/camera.hpp"
#include "nearshore/playback/lighting.hpp"
#include "nearshore/playback/surface_grids.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "pass_timer.hpp"
#include "surface_uniforms.hpp"

namespace nearshore::playback {

/// One frame's sea: what it is drawn on and with, and which of the other passes' maps it samples.
struct SeaDraw {
  const RendererSettings& settings;
  const SurfaceFormula& formula;
  const LightingFrame& light;
  const CameraView& view;
  double earth_radius_m = 0.0;
  const DrawOptions& options;
  int width_px = 0, height_px = 0;
  int viewport_x_px = 0, viewport_y_px = 0;  ///< the viewport's lower-left corner (a host's may not be 0, 0)
  bool reflection = false;                   ///< LocalReflection's texture on unit kReflection
  bool decal_foam = false;                   ///< the decals' foam map on unit kDecalFoam
  std::array<float, 4> decal_foam_rect_m{};  ///< x0, y0, width, height of that map
  bool deep_foam = false;                    ///< DeepFoamPass's map on unit kDeepFoam
  bool refraction = false;                   ///< RefractionSource's colour and depth on kSceneColour, kSceneDepth
};

class WaterSurfacePass {
 public:
  WaterSurfacePass();  ///< links water.frag with each grid's vertex shader
  ~WaterSurfacePass();
  WaterSurfacePass(const WaterSurfacePass&) = delete;
  WaterSurfacePass& operator=(const WaterSurfacePass&) = delete;

  /// The sea into the bound framebuffer (timed as GpuPass::water), counting the fill pass's
  /// vertices, triangles and quadtree patches into `statistics`.
  void draw(const SeaDraw& sea, PassTimer& timer, FrameStatistics& statistics);

 private:
  GLuint program(GridKind kind) const;
  // The meshes the grid needs this frame (rebuilt only when their settings change).
  void prepare_grid(const RendererSettings& settings, const CameraView& view, QuadtreeSelection& selection,
                    ProjectedGridLayout& layout, FrameStatistics& statistics);
  void set_water_lighting_uniforms(GLuint program, const runtime::SurfaceSnapshot& snapshot,
                                   const LightingFrame& light);
  // One draw of the grid (`count`: the fill pass, whose vertices the statistics count).
  void draw_grid(GLuint program, const SeaDraw& sea, const QuadtreeSelection& selection,
                 const ProjectedGridLayout& layout, bool count, FrameStatistics& statistics);

  GLuint radial_program_ = 0, quadtree_program_ = 0, projected_program_ = 0;
  Mesh radial_, quadtree_patch_, projected_;
  RadialGridSettings radial_built_;
  int projected_columns_ = 0, projected_rows_ = 0;
  // Slope variance (per axis) of each cascade's tiles: measured once on the first deep keyframe
  // (the spectrum is stationary: the next keyframes hold the same variance to sampling noise).
  std::vector<float> cascade_slope_variance_;
};

}  // namespace nearshore::playback
