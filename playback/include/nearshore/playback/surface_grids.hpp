#pragma once
// The three grids the sea surface is drawn on (docs/rendering.md). Each decides, on the CPU and
// without OpenGL, WHERE the vertices are; the vertex shaders (shaders/water_*.vert.glsl) then
// displace them by the snapshot's surface (shaders/surface.glsl). The functions marked "twin"
// compute what a shader computes, so the grids' properties (no cracks, the horizon where the
// camera says) are tested here without a GPU and again in rendered pictures.
//
//   radial     rings round the point under the eye (seed 003 section 2.2 fig. 2; seed 000
//              eq. 2.20): dense near, sparse far, level of detail for free. Flat; low views.
//   quadtree   CDLOD (Strugar 2009; seed 000 section 3.2): square patches whose level follows the
//              distance to the eye against a screen-space error; vertices morph to the coarser
//              level before the level changes, so neighbouring levels meet without cracks.
//   projected  a screen-space grid cast onto the sphere of the Earth (seed 002 section 3), so the
//              sea ends at the sphere's horizon, acos(R / (R + h)) below the horizontal: high views.
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "nearshore/playback/camera.hpp"

namespace nearshore::playback {

enum class GridKind { radial, quadtree, projected };

/// "radial", "quadtree", "projected".
std::string_view grid_kind_name(GridKind kind);
/// The kind named `name`; throws nearshore::Error listing the names otherwise.
GridKind grid_kind_from_name(std::string_view name);

inline constexpr double kEarthRadiusM = 6371000.0;  ///< mean Earth radius (IUGG), metres

// ---- radial ----------------------------------------------------------------------------------
struct RadialGridSettings {
  int segment_count = 256;           ///< M of eq. 2.20: vertices per ring
  double inner_spacing_m = 0.5;      ///< radial spacing at the centre (m)
  double outer_radius_m = 100000.0;  ///< radius of the last ring (m): where the flat sea ends
};

/// Ring i at radius R_i, vertex j at angle 2 pi j / M + pi i / M (seed 000 eq. 2.20: each ring
/// turned half a step from the last, so the triangles between rings are near equilateral). The
/// radial spacing grows geometrically by (1 + 2 pi / M) per ring, R_i = s ((1 + g)^i - 1) / g,
/// which makes the cells square once the rings are wide (arc step 2 pi R / M = radial step).
struct RadialGrid {
  int ring_count = 0;             ///< rings, including ring 0 at the centre (radius 0)
  int segment_count = 0;
  std::vector<float> polar;       ///< (radius m, angle rad) per vertex, ring by ring
  std::vector<std::uint32_t> triangles;  ///< three indices per triangle
  std::size_t vertex_count() const { return polar.size() / 2; }
};
RadialGrid build_radial_grid(const RadialGridSettings& settings);

// ---- quadtree (CDLOD) ------------------------------------------------------------------------
struct QuadtreeSettings {
  double finest_spacing_m = 0.25;      ///< vertex spacing of level 0 (m); level L has 2^L times it
  int patch_quads = 8;                 ///< quads along a patch's side (even); a node is 2 x 2 patches
  double screen_error_px = 4.0;        ///< a level's quads span at most this on screen (pixels) where it ends
  double reach_m = 100000.0;           ///< the grid covers at least this distance round the eye (m)
  double displacement_bound_m = 8.0;   ///< largest |eta| and choppy shift, for culling (m): Beaufort 7-8 seas
};

/// One level of detail. A level-L node is 2 x 2 patches; it is split into level L-1 nodes where
/// it comes within range_m of level L-1 of the eye; its vertices morph toward the level-(L+1)
/// lattice between morph_start_m and morph_end_m (3-D distance from the eye to the vertex at still
/// water), fully morphed before range_m, where the coarser level may begin.
struct QuadtreeLevel {
  double vertex_spacing_m = 0.0, patch_size_m = 0.0, range_m = 0.0, morph_start_m = 0.0, morph_end_m = 0.0;
};
struct QuadtreePatch {
  double origin_x_m = 0.0, origin_y_m = 0.0;  ///< south-west corner (a multiple of the patch size)
  int level = 0;
};
struct QuadtreeSelection {
  int patch_quads = 0;
  std::vector<QuadtreeLevel> levels;  ///< level 0 finest
  std::vector<QuadtreePatch> patches;
  long long vertex_count() const { return static_cast<long long>(patches.size()) * (patch_quads + 1) * (patch_quads + 1); }
};

/// Strugar's selection: the ranges follow the screen-space error (range_L = spacing_L *
/// focal_length_px / screen_error_px), but never below 4 node sizes, which is what keeps the
/// joins conforming (docs/rendering.md derives it: a level's region then ends before the next
/// level starts to morph, and neighbouring patches differ by at most one level). Patches outside
/// the view frustum (widened by displacement_bound_m) are left out. Throws nearshore::Error for
/// settings out of range.
QuadtreeSelection select_quadtree(const QuadtreeSettings& settings, const CameraView& view);

/// Twin of shaders/water_quadtree.vert.glsl: the still-water position of vertex (gx, gy) of
/// `patch` (0 <= gx, gy <= patch_quads) after the CDLOD morph, in float as the GPU computes it.
std::array<float, 2> quadtree_vertex(const QuadtreeSelection& selection, const QuadtreePatch& patch, int gx, int gy,
                                     const Vector3& eye_m);

// ---- projected (on the sphere) ---------------------------------------------------------------
struct ProjectedGridSettings {
  double vertex_spacing_px = 4.0;       ///< grid spacing on screen (pixels)
  double earth_radius_m = kEarthRadiusM;
  double margin_ndc = 0.06;             ///< the grid overhangs the screen's edges (normalised device units)
};

/// The screen-space rectangle the grid spans (normalised device coordinates): the whole width,
/// from below the bottom edge up to just above the highest point of the horizon, so no row is
/// spent on the sky. columns x rows vertices; none when the horizon is below the screen.
struct ProjectedGridLayout {
  int columns = 0, rows = 0;
  double ndc_x0 = -1, ndc_x1 = 1, ndc_y0 = -1, ndc_y1 = 1;
  long long vertex_count() const { return static_cast<long long>(columns) * rows; }
};
ProjectedGridLayout layout_projected_grid(const ProjectedGridSettings& settings, const CameraView& view);

/// Twin of shaders/water_projected.vert.glsl: where the ray through the screen point (ndc_x,
/// ndc_y) meets the sphere of radius R that touches still water under the eye. A ray that misses
/// (above the horizon) is turned down to the horizon at the same bearing (on_horizon). x, y: the
/// site point (the tangent plane's coordinates, where the wave fields are looked up); z: the
/// sphere's drop below the tangent plane there, curvature_drop_m.
struct SpherePoint {
  double x_m = 0, y_m = 0, z_m = 0;
  bool on_horizon = false;
};
SpherePoint project_to_sphere(const CameraView& view, double ndc_x, double ndc_y, double earth_radius_m);

/// R - sqrt(R^2 - rho^2) written as rho^2 / (R + sqrt(R^2 - rho^2)): the sphere's drop below its
/// tangent plane at horizontal distance rho (m), without the cancellation of the first form.
double curvature_drop_m(double horizontal_distance_m, double earth_radius_m);

}  // namespace nearshore::playback
