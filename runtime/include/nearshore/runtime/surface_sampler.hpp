#pragma once
// CPU surface queries: the water a SurfaceSnapshot shows, at site points, for a ship's physics and
// a host's buoyancy code, without a GPU read-back. The formulas below are THE definition of the
// shown surface; the GLSL in shaders/ implements the same ones (a test renders a top-down height
// pass on Mesa and compares it with this sampler in millimetres).
//
// Frame: site metres (surface_snapshot.hpp): x east, y north of the harbour grid's south-west
// corner; z up from still water. Arithmetic: double on the CPU, texel values are float.
//
// 1. Harbour raster F (columns C, rows R, spacings s_x, s_y: equal for square cells; texel (i, j)
//    is the cell centre ((i + 0.5) s_x, (j + 0.5) s_y), row 0 south), bilinear with clamping at
//    the rectangle's edge:
//      u = clamp(x / s_x - 0.5, 0, C - 1),  v = clamp(y / s_y - 0.5, 0, R - 1)
//      i0 = min(floor(u), C - 2), i1 = i0 + 1, a = u - i0   (C = 1: i0 = i1 = 0, a = 0; rows alike)
//      F(x, y) = (1 - b) ((1 - a) F[i0, j0] + a F[i1, j0]) + b ((1 - a) F[i0, j1] + a F[i1, j1])
//    i.e. GL_CLAMP_TO_EDGE with texture coordinates (x / width, y / height). Within half a cell of
//    the edge the value is the edge texel's (flat), which only matters where w > 0 there, i.e.
//    with edge_fade_m < s / 2. GLSL: do this by hand with texelFetch (hardware bilinear filtering
//    quantises a to 8 bits on many GPUs: up to 2 mm on a 1 m wave).
//    Time: H_eta(p) = h00 F_from(p) + h10 T R_from(p) + h01 F_to(p) + h11 T R_to(p), the cubic
//    Hermite of surface_snapshot.hpp with R = HarbourKeyframe::surface_elevation_rate_m_s sampled
//    like F (the secant (F_to - F_from) / T for both where a keyframe has no rate);
//    H(p) = (1 - f_h) F_from(p) + f_h F_to(p) for P, Q, breaking and the slopes.
// 2. Deep-water cascade c (tile L_c, N nodes; node (i, j) at (i L/N, j L/N), periodic):
//      u = frac(x / L) N, v = frac(y / L) N  (frac in double: x may be 100 km, L 10 m)
//      i0 = floor(u), i1 = (i0 + 1) mod N, a = u - i0; rows alike; bilinear as above
//    (ocean::DeepWaterField::sample). GLSL: fract(x / L) loses millimetres at large x in float;
//    subtract a multiple of L on the CPU (a per-cascade uniform) before the shader sees x.
//    D(p) = (1 - f_d) sum_c D_from,c(p) + f_d sum_c D_to,c(p) for every channel.
// 3. Shown at a LATTICE point p (what a vertex shader computes at its grid vertex):
//      w = harbour_weight(site, p),  eta(p) = w (H_eta(p) + I_eta(p)) + (1 - w) D_eta(p)
//    I, the split's inside layer (surface_snapshot.hpp; 0 without a split), is sampled as D is
//    (formula 2) over the keyframes' inside cascades: the deep water's components above the
//    bake's band, which the frames do not hold (issue 14 item 1).
//    and the vertex moves horizontally to p + (1 - w(p)) lambda D_disp(p) (the choppy
//    displacement of the deep water; the baked frames have none, so it fades with 1 - w). The
//    inside layer is drawn without it: it would move the harbour's own lattice points, and so
//    the frames under them, by up to lambda a of the split-off waves; its slopes still light it.
// 4. Shown at a DISPLACED point q (the default: what lies over q on screen and under a hull):
//    the lattice point p with F(p) = p + (1 - w(p)) lambda D_disp(p) - q = 0, by Newton's method
//    from p_0 = q with the exact Jacobian of the sampled field, J = I + lambda ((1 - w) grad D -
//    D grad w^T) (grad D of the bilinear interpolant, from the same four nodes), falling back to
//    the fixed-point step p - F(p) where det J < 0.2 (near a folding crest); it stops at the first
//    p whose residual |F(p)| <= kDisplacementTolerance_m (at most kDisplacementIterations steps):
//    the surface point it reports lies within 0.1 mm of q horizontally, so its height is off by
//    at most 0.1 mm x the slope. Then eta(q) := eta(p) (formula 3), with D_eta taken from the
//    sample that checked the residual. A step after the first that stays inside the cell of
//    every cascade it last sampled is checked without a new sample: there each cascade is the
//    same bilinear polynomial, so D at p + s is D + D_x s_x + D_y s_y + D_xy s_x s_y of the last
//    sample (value, gradient and cross term of the same four nodes), the same field to float
//    round-off (0.1 um on a metre). It halves the third sample most points took (3.1 -> 2.1
//    samples a point on a Beaufort 5 sea). Solvable while the Jacobian of the displacement stays
//    positive (no folded crests; ocean/deep_water.hpp). Inside the full-weight box (w = 1) p = q.
//    The solve reads the cascades in the query layout (surface_snapshot.hpp QueryTile: D_x, D_y,
//    eta as int16 of a per-channel scale), whose rounding moves each cascade's value by at most
//    scale / 2 (15 micrometres on a 1 m wave); so a displaced height is eta at its lattice point
//    to within sum_c (scale_c / 2) (+ float round-off), not bit for bit. tests/runtime
//    (SurfaceSampler.DisplacedQueriesMatchAConvergedSolve) holds it to 1 mm of a solve converged
//    to 1e-10 m on the float fields, over a Beaufort 5 sea. The solve's taps take formula 2 as
//    u = frac(q_x / L) N + (p_x - q_x) N / L (the query point's fraction once, in double): formula
//    2 at p to double round-off. The GLSL does not need the inverse: a vertex shader displaces
//    lattice points (formula 3).
// 5. Velocity (m/s): harbour u_h = (P, Q) / h with h = d + eta_H (d bilinear still-water depth of
//    depth.exr); zero, and the point DRY, where the cell holding p (floor(x/s), floor(y/s),
//    clamped) is land or h <= site.dry_depth_m. Deep water u_d = (P_d, Q_d) / (d_deep + D_eta)
//    when the field has a finite depth (DeepWaterKeyframe::still_water_depth_m > 0; the bake's
//    field, at the source line's depth), else 0 (the depth-averaged current of linear waves in
//    deep water). The inside layer's u_i = (P_i, Q_i) / (d_deep + I_eta) likewise (its fluxes
//    at the field's depth; 0 in deep water). Shown u = w (u_h + u_i) + (1 - w) u_d. Dry only
//    where w > 0 (a dry point keeps u = 0: the layer does not wet land).
// 7. Vertical velocity (m/s): d eta / dt of formula 3 at the lattice point, with w fixed:
//    w (dH_eta/dt + dI_eta/dt) + (1 - w) dD_eta/dt, dH_eta/dt the Hermite's derivative
//    (h00' F_from + h10' T R_from + h01' F_to + h11' T R_to) / T, the deep water's and the inside
//    layer's (D_to - D_from) / (t_to - t_from) of their keyframes' display times (0 when equal).
//    At a displaced point it is the lattice point's (the horizontal drift of p is left out: the
//    deep water's keyframes are 1/30 s apart, the harbour's have no displacement).
// 6. Normal: slope = w (grad H + grad I) + (1 - w) grad D + (H_eta + I_eta - D_eta) grad w, normal = normalize(
//    -slope_x, -slope_y, 1). grad H is the bilinear interpolation (weights of 1.) of per-texel
//    central differences (F[i+1, j] - F[i-1, j]) / ((i+1 - (i-1)) s) with i-1, i+1 clamped to
//    [0, C-1] (one-sided at the edge); grad D and grad I from the cascades' slope channels; grad w analytic
//    (harbour_weight_and_gradient). At a displaced point all of them are taken at its lattice p.
//
// Thread-safety: a sampler only reads its snapshot's immutable keyframes; every method is const
// and may run on any number of threads at once.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "nearshore/runtime/surface_snapshot.hpp"

namespace nearshore::runtime {

/// A site point (m east, m north of the harbour grid's south-west corner).
struct SitePoint {
  double x_m = 0.0, y_m = 0.0;
};

/// Where a query evaluates the choppy deep water (see 3. and 4. above).
enum class ChoppyPoint {
  kDisplaced,  ///< the surface over the point (default; for ship physics)
  kLattice,    ///< the undisplaced lattice point (what a vertex shader displaces)
};

inline constexpr int kDisplacementIterations = 8;
inline constexpr double kDisplacementTolerance_m = 1e-4;

/// Everything a query gives at one point.
struct SurfaceState {
  double surface_elevation_m = 0.0;
  double velocity_x_m_s = 0.0, velocity_y_m_s = 0.0;
  double slope_x = 0.0, slope_y = 0.0;        ///< d eta / dx, d eta / dy
  double normal_x = 0.0, normal_y = 0.0, normal_z = 1.0;  ///< unit, z up
  double vertical_velocity_m_s = 0.0;         ///< d eta / dt (formula 7)
  double harbour_weight = 0.0;                ///< w at the lattice point used
  bool dry = false;
};

class SurfaceSampler {
 public:
  /// Holds the snapshot (shared keyframes: cheap) and caches raw pointers to its rasters.
  explicit SurfaceSampler(SurfaceSnapshot snapshot);

  /// Elevation (m) at (x, y).
  double elevation_m(double x_m, double y_m, ChoppyPoint point = ChoppyPoint::kDisplaced) const;
  /// Batched: out[i] = elevation_m(points[i]), bit for bit; out.size() >= points.size(). A
  /// displaced batch solves blocks of kSolveBlock points side by side, so their cache misses
  /// overlap: the batch of a hull's points is cheaper than the single calls.
  void elevations_m(std::span<const SitePoint> points, std::span<double> out,
                    ChoppyPoint point = ChoppyPoint::kDisplaced) const;
  /// Elevation, velocity, slopes, normal and the dry flag at (x, y).
  SurfaceState state(double x_m, double y_m, ChoppyPoint point = ChoppyPoint::kDisplaced) const;
  void states(std::span<const SitePoint> points, std::span<SurfaceState> out,
              ChoppyPoint point = ChoppyPoint::kDisplaced) const;

  /// The parts of formula 3 at a lattice point, for tests and the GLSL twin: H_eta (0 without a
  /// harbour), D_eta (0 without deep water) and the lattice point of a displaced query.
  double harbour_elevation_m(double x_m, double y_m) const;
  double deep_elevation_m(double x_m, double y_m) const;
  /// I_eta at a lattice point: the split's inside layer (0 without a split or deep water).
  double inside_elevation_m(double x_m, double y_m) const;
  /// Whether the snapshot carries a split's inside layer.
  bool has_inside_layer() const { return has_inside_; }
  SitePoint lattice_point(double x_m, double y_m) const;

  const SurfaceSnapshot& snapshot() const { return snapshot_; }

 private:
  struct Raster2 {  // one harbour channel at both keyframes
    const float* from = nullptr;
    const float* to = nullptr;
  };
  struct Cascade {
    int n = 0;
    double tile_length_m = 0.0, inverse_tile_length = 0.0;
    const ocean::DeepWaterFrame* from = nullptr;
    const ocean::DeepWaterFrame* to = nullptr;
  };
  double weight(double x_m, double y_m) const;
  // w (with_slope: and its gradient) at a point of the site rectangle: inline in the band where
  // only the maker's ramp varies (surface_sampler.cpp), else harbour_weight(_and_gradient).
  HarbourWeight site_weight(double x_m, double y_m, bool with_slope) const;
  double harbour_eta(double x_m, double y_m) const;
  struct EtaAndRate {
    double eta = 0.0, rate = 0.0;
  };
  // H_eta and its time derivative from the keyframes' values (and rates) at one point.
  EtaAndRate harbour_in_time(double from, double to, double from_rate, double to_rate) const;
  double deep_eta(double x_m, double y_m) const;
  // eta, slopes and (with_flux) fluxes of a list of cascades at (x, y), both keyframes blended in time.
  struct CascadeSum {
    double eta = 0.0, slope_x = 0.0, slope_y = 0.0, flux_x = 0.0, flux_y = 0.0, eta_rate = 0.0;
  };
  double cascades_eta(const std::vector<Cascade>& cascades, double x_m, double y_m) const;
  CascadeSum cascades_sum(const std::vector<Cascade>& cascades, double x_m, double y_m, bool with_flux) const;
  // The lattice point of a displaced query with what the last sample there gave: D_eta at p (the
  // deep part of the height: no second pass over the cascades).
  struct Solution {
    SitePoint lattice;
    double deep_eta = 0.0;
    double harbour_weight = 0.0;  // w at the lattice point (set with has_deep_eta)
    bool has_deep_eta = false;    // false: p = q taken at once, or the iterations ran out
  };
  static constexpr int kSolveBlock = 16;
  static constexpr std::size_t kStoredTaps = 6;
  bool in_full_box(double x_m, double y_m) const {
    return has_harbour_ && x_m > full_x0_ && x_m < full_x1_ && y_m > full_y0_ && y_m < full_y1_;
  }
  bool in_site(double x_m, double y_m) const {
    return x_m >= 0.0 && y_m >= 0.0 && x_m <= site_width_m_ && y_m <= site_height_m_;
  }
  // out[i] for q[i], i < count <= kSolveBlock, the points iterated side by side.
  void solve_block(const SitePoint* q, int count, Solution* out) const;
  Solution solve(double x_m, double y_m) const;
  double elevation_at_solution(const Solution& solution) const;
  double elevation_at_lattice(SitePoint p) const;

  SurfaceSnapshot snapshot_;
  bool has_harbour_ = false, has_deep_ = false, has_deep_flux_ = false, has_inside_ = false, has_inside_flux_ = false;
  int columns_ = 0, rows_ = 0;
  double spacing_x_m_ = 1.0, spacing_y_m_ = 1.0, inverse_spacing_x_ = 1.0, inverse_spacing_y_ = 1.0;  // dx, dy
  double harbour_fraction_ = 0.0, deep_fraction_ = 0.0, choppiness_ = 0.0;
  double frame_interval_s_ = 0.0;    // T of the Hermite (0: linear, no rate)
  // harbour_eta's Hermite weights {h00, h10 T, h01, h11 T}, each twice (columns i0 and i0 + 1).
  float hermite_by_channel_[8] = {};
  // The maker's ramp (HarbourSite's blending record) and the edge fade, for site_weight.
  int ramp_axis_ = 1;
  double ramp_inward_sign_ = 1.0, ramp_line_m_ = 0.0, ramp_start_m_ = 0.0, ramp_width_m_ = 0.0, edge_fade_m_ = 0.0;
  double inverse_deep_interval_ = 0.0;  // 1 / (t_to - t_from) of the deep keyframes (0 when equal)
  HermiteWeights hermite_;
  // Where w = 1 exactly (beyond the maker's zone and every edge fade): no ramp to evaluate.
  double full_x0_ = 0.0, full_x1_ = -1.0, full_y0_ = 0.0, full_y1_ = -1.0;
  double site_width_m_ = 0.0, site_height_m_ = 0.0;  // the rectangle off which w = 0
  Raster2 eta_, flux_x_, flux_y_, eta_rate_;  // eta_rate_: both null unless both keyframes have rates
  const float* depth_ = nullptr;
  const std::uint8_t* land_ = nullptr;
  std::vector<Cascade> cascades_;
  // The cascades in the query layout (surface_snapshot.hpp QueryTile), both keyframes, with each
  // keyframe's time weight folded into its channel scales: (1 - f_d) scale_from, f_d scale_to.
  struct PackedCascade {
    int n = 0;
    double inverse_tile_length = 0.0;
    float texels_per_m = 0.0f;  // N / L
    double texels_per_m_d = 0.0;
    const std::int16_t* from = nullptr;
    const std::int16_t* to = nullptr;
    // {D_x, D_y, eta, 0} twice: the weights of a row's two nodes, read at once
    float from_weight[8] = {0, 0, 0, 0, 0, 0, 0, 0}, to_weight[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  };
  std::vector<PackedCascade> packed_;
  std::vector<QueryTile> own_tiles_;  // only for keyframes that came without (valid) query tiles
  std::vector<Cascade> inside_;  // the split's inside layer: whole cascades of the mask, then the straddling ones
};

}  // namespace nearshore::runtime
