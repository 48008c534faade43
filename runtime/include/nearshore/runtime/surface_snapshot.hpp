#pragma once
// What the sea looks like at one displayed instant: the contract between the streaming engine
// (streaming_engine.hpp, which fills it), the GPU renderer (playback/, which uploads and draws it)
// and the CPU surface queries (surface_sampler.hpp, which evaluate it). All three read the SAME
// snapshot with the SAME formulas (the GLSL in shaders/ is the twin of surface_sampler.cpp), so a
// ship's buoyancy computed on the CPU sees the water the viewer draws, without a GPU read-back.
//
// Frame: the SITE frame, metres east (x) and north (y) of the harbour grid's south-west corner
// (GridGeometry origin_x_m, origin_y_m), z up from the still-water level. Projected coordinates
// (UTM, ~4e6 m) lose half a metre in a float; the site frame keeps millimetres over 100 km. The
// deep-water field's x = 0, y = 0 is the same corner (sequence/deep_water_section.hpp coupling).
//
// The surface shown at a site point p and display time t:
//   harbour(p)  = h00 H_from(p) + h10 T R_from(p) + h01 H_to(p) + h11 T R_to(p)   cubic Hermite in
//                 time (below), bilinear in the cell-centred rasters; R = d eta / dt of each keyframe
//   deep(p)     = (1 - f_d) sum_c D_from,c(p) + f_d sum_c D_to,c(p) bilinear in each periodic cascade tile
//   inside(p)   = the deep water's components above the bake's band (the split, issue 14):
//                 (1 - f_d) sum_c I_from,c(p) + f_d sum_c I_to,c(p)  over the whole cascades of
//                 DeepWaterKeyframe::inside_cascade_mask and its inside_cascades (0 without a split)
//   shown(p)    = w(p) (harbour(p) + inside(p)) + (1 - w(p)) deep(p)  w = harbour_weight(site, p)
// Where w = 1 the bake's frames carry the band they resolve and the deep-water layer the rest;
// where w = 0 the whole field is shown; deep = (what the bake holds) + inside, so the blend only
// crossfades the bake's band and the split-off waves run through the rectangle unchanged.
// Time between the harbour keyframes (T = HarbourSite::frame_interval_s, the bake's output
// interval) is a cubic Hermite in f = f_h, so heights are C1 in time and a ship's heave feels no
// corner at each keyframe:
//   h00 = 2f^3 - 3f^2 + 1, h10 = f^3 - 2f^2 + f, h01 = -2f^3 + 3f^2, h11 = f^3 - f^2
// with each keyframe's rate R from the bake's own mass equation (surface_elevation_rate below),
// d eta/dt = -(dP/dx + dQ/dy) / n (seed 003 eq. 1), so the slopes are the physics', not a guess
// from neighbouring frames. Where a keyframe has no rate (R empty, T <= 0) the rate is the
// secant (H_to - H_from) / T at both ends, which makes the cubic the straight line. Fluxes and
// breaking stay linear in time: they feed currents and foam, not heave.
// Keyframes are immutable once published and shared (std::shared_ptr<const ...>), so a snapshot
// stays valid on any thread for as long as it is held, whatever the engine does next.
#include <cstdint>
#include <memory>
#include <vector>

#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/raster.hpp"
#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/sequence/loop_playback.hpp"

namespace nearshore::runtime {

/// One step of the playback plan, decoded (and crossfade-blended as planned): cell-centred
/// rasters of the harbour grid's size, row 0 south.
struct HarbourKeyframe {
  std::uint64_t serial = 0;      ///< unique for the engine's life: a renderer uploads each serial once
  long long plan_step = 0;       ///< index of the step in the endless plan
  sequence::BlendSource shown;   ///< the frame(s) and crossfade weight this step shows
  bool held = false;             ///< a bad frame was replaced by the previous good keyframe
  Raster<float> surface_elevation_m, flux_x_m2_s, flux_y_m2_s, breaking;
  /// d eta / dt (m/s) at this keyframe: surface_elevation_rate of its fluxes (plus, inside a
  /// crossfade, the blend weight's own rate times target - source). Empty: linear in time.
  Raster<float> surface_elevation_rate_m_s;
};

/// One cascade tile in the layout of the CPU's displaced-point queries (surface_sampler.hpp formula
/// 4, whose Newton solve samples D_x, D_y and then eta at 2-4 points per query): node (i, j) as
/// four int16 {D_x, D_y, eta, 0} side by side, value = scale[channel] x integer with scale =
/// max |value| / 32767 of the channel over the tile. 8 bytes a node where the three float channels
/// are 12 bytes in three places: a tap reads 2 cache lines instead of 6 and one float4 bilinear
/// gives all three. Rounding moves a value by at most scale / 2 (15 micrometres on a 1 m wave;
/// the bound surface_sampler.hpp adds to its tolerance). Each row holds N + 1 nodes, the last a copy
/// of the row's first (the tile is periodic), so a tap's two nodes along x are one 16-byte read.
struct QueryTile {
  int grid_size = 0;
  double tile_length_m = 0.0;
  float scale[4] = {0.0f, 0.0f, 0.0f, 0.0f};  ///< metres per unit of {D_x, D_y, eta, 0}
  std::vector<std::int16_t> nodes;            ///< 4 per node, N rows of N + 1 nodes (south row first)
};

/// `tile` := the query layout of one cascade (above; its allocation reused). A frame without
/// displacement gets D = 0.
void pack_query_tile(const ocean::DeepWaterFrame& frame, QueryTile& tile);

/// The deep-water field at one keyframe time: every cascade's tile (ocean::DeepWaterFrame:
/// eta, choppy displacement, slopes and displacement derivatives).
struct DeepWaterKeyframe {
  std::uint64_t serial = 0;
  double display_time_s = 0.0;   ///< the display time it was synthesised for
  std::vector<ocean::DeepWaterFrame> cascades;
  /// The field's still-water depth (m; <= 0: deep). With a finite depth the cascades carry the
  /// fluxes (flux_x_m2_s, flux_y_m2_s) and the deep water's velocity is flux / (depth + eta); in
  /// deep water the depth-averaged current of linear waves is zero (surface_sampler.hpp).
  double still_water_depth_m = 0.0;
  /// The split (issue 14 item 1; runtime/deep_water_source.hpp DeepWaterInsideLayer): the field's
  /// components above the bake's band, drawn inside the harbour rectangle on top of the frames.
  /// Bit c: cascades[c] lies wholly above the split and is drawn inside as it is.
  std::uint32_t inside_cascade_mask = 0;
  /// The cascades that straddle the split, with only their components above it (the same tiles:
  /// inside_cascades[i] has its tile length and grid size). Empty without a split.
  std::vector<ocean::DeepWaterFrame> inside_cascades;
  /// The cascades with an elevation in the query layout, in their order (pack_query_tiles, which
  /// the streaming engine runs on its worker after each synthesis, so hosts never pay for it).
  /// Empty or stale (sizes that do not match): a sampler packs its own copy for its lifetime.
  std::vector<QueryTile> query_tiles;
};

/// Fills keyframe.query_tiles from keyframe.cascades (call after every change to them).
void pack_query_tiles(DeepWaterKeyframe& keyframe);

/// Where the harbour is shown and how it fades into the deep water. Static for a sequence.
struct HarbourSite {
  HarbourGrid harbour;           ///< depth, land, porosity (geometry: spacing, size; origin = site (0, 0))
  double width_m = 0.0, height_m = 0.0;  ///< columns * spacing, rows * spacing
  /// The bake's blending record (sequence DeepWaterBlendingRecord): on the wave maker's side the
  /// baked weight rises as sin^2 from start_m to start_m + width_m inland of the source line.
  /// axis 0 = x, 1 = y; inward_sign +1 when waves come from the west/south (s grows with x or y).
  int source_axis = 1;
  double inward_sign = 1.0;
  double source_line_m = 0.0, blend_start_m = 0.0, blend_width_m = 0.0;
  /// The other open edges of the rectangle fade to the deep water over this width (sin^2), so the
  /// rectangle has no visible edge where the bake's absorbing layers damp its waves.
  double edge_fade_m = 0.0;
  double choppiness = 1.0;       ///< lambda of the deep water's horizontal displacement
  /// Total depth d + eta (m) at or below which a harbour point is dry (the bake's solver
  /// dry_depth_m, 0.01 m by default): the CPU queries give zero velocity and dry = true there.
  double dry_depth_m = 0.01;
  /// Display seconds between consecutive harbour keyframes (the sequence's frame interval; T of
  /// the Hermite above). 0: unknown, the harbour is linear in time.
  double frame_interval_s = 0.0;
  /// How much of the incident sea reaches each cell: Hs(cell) / Hs(incident) of the baked
  /// surface elevation (port engineers' disturbance coefficient), row 0 south, the grid's size;
  /// NaN on land and structures; empty when unknown. The renderer shelters the short waves the
  /// bake does not carry by it (docs/lighting.md); the CPU queries do not use it.
  Raster<float> relative_wave_height;
};

/// The cubic Hermite basis at fraction f in [0, 1] (above) and its derivatives d/df.
struct HermiteWeights {
  double from = 1.0, from_rate = 0.0, to = 0.0, to_rate = 0.0;      ///< h00, h10, h01, h11
  double d_from = 0.0, d_from_rate = 1.0, d_to = 0.0, d_to_rate = 0.0;  ///< their derivatives in f
};
HermiteWeights hermite_weights(double fraction);

/// d eta / dt (m/s) of a keyframe's fields from the mass equation n eta_t + P_x + Q_y = 0 (seed 003
/// eq. 1): `flux_x`, `flux_y` are the cell-centred averages of the bake's face fluxes
/// (BoussinesqSolver::flux_x_m2_s: A_i = (P_{i-1/2} + P_{i+1/2}) / 2). Their centred difference
/// G_i = (A_{i+1} - A_{i-1}) / (2 dx) is the solver's own divergence D_i = (P_{i+1/2} - P_{i-1/2}) / dx
/// smoothed by [1 2 1] / 4 (G = (D_{i-1} + 2 D_i + D_{i+1}) / 4, a response cos^2(k dx / 2));
/// D = G - (G_{i-1} - 2 G_i + G_{i+1}) / 4 undoes it to 1 - sin^4(k dx / 2) (0.4 % at 8 cells per
/// 50 m wave) where both neighbours are water, else G. Land and wall cells (porosity 0) get 0;
/// porous cells divide by n. Row 0 south; rasters of the grid's size.
Raster<float> surface_elevation_rate(const HarbourGrid& grid, const Raster<float>& flux_x_m2_s, const Raster<float>& flux_y_m2_s);

/// w(p) in [0, 1]: the harbour's weight at site point (x, y) (0 outside the rectangle).
double harbour_weight(const HarbourSite& site, double x_m, double y_m);

/// w and its gradient (1/m) at (x, y) in one pass: the analytic derivative of the product of the
/// sin^2 ramps (d/ds sin^2(pi/2 s/W) = pi/(2W) sin(pi s/W) inside a ramp, 0 outside), 0 outside
/// the rectangle. The slope of what is shown is w grad(harbour) + (1 - w) grad(deep) +
/// (harbour - deep) grad(w) (surface_sampler.hpp).
struct HarbourWeight {
  double weight = 0.0, d_dx_per_m = 0.0, d_dy_per_m = 0.0;
};
HarbourWeight harbour_weight_and_gradient(const HarbourSite& site, double x_m, double y_m);

/// Everything drawn at one displayed instant.
struct SurfaceSnapshot {
  double display_time_s = 0.0;
  std::shared_ptr<const HarbourSite> site;                 ///< null: no harbour (open sea only)
  std::shared_ptr<const HarbourKeyframe> harbour_from, harbour_to;
  double harbour_fraction = 0.0;                           ///< f_h
  std::shared_ptr<const DeepWaterKeyframe> deep_from, deep_to;  ///< null: flat sea beyond the harbour
  double deep_fraction = 0.0;                              ///< f_d
};

/// Whether the snapshot's harbour keyframes are joined by the Hermite: the site has a frame
/// interval and both keyframes (`to` may be null: `from` alone) carry rates of their elevation's size.
bool harbour_joined_by_hermite(const SurfaceSnapshot& snapshot);

/// The harbour's surface elevation at every cell centre as shown at the snapshot's time (m; row 0
/// south; `elevation_m` holds columns x rows floats): the Hermite above, else linear in time, 0
/// without harbour keyframes.
void shown_harbour_elevation(const SurfaceSnapshot& snapshot, float* elevation_m);

}  // namespace nearshore::runtime
