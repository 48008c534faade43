#pragma once
// The one line sweep of the ADI scheme (docs/solver.md, "Discretisation"), run by both sweeps.
// Its frame puts the sweep direction on the SLOW index and the lines on the FAST index, so a
// block of neighbouring lines is solved in lock-step and every loop runs over contiguous lanes
// (vectorised, and the Thomas recurrences of different lines overlap in the pipeline).
//   y sweep: the harbour's natural layout (rows slow, columns fast), normal flux Q, tangential P
//   x sweep: the transposed layout (columns slow, rows fast), normal flux P, tangential Q
// Layout of a frame (`cols` cells along the sweep, `rows` lines):
//   cells         index c * rows + l
//   normal faces  index f * rows + l, f = 0..cols; face f lies between cells f-1 and f
//   tangential    index c * (rows + 1) + k, k = 0..rows; face k lies between lines k-1 and k
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nearshore/boussinesq/solver_parameters.hpp"

namespace nearshore::boussinesq::detail {

/// Everything about one orientation that does not change during a run. Only what cannot be
/// recomputed cheaply is stored (docs/solver.md, "Memory"): the face values of seed 003 eq. (2)-(5)
/// (depth, porosity, openness, bed slopes, porous resistance) follow from the two cells of the face
/// inside the sweep, where the cell values are read anyway; see the face_* functions below.
struct StaticFrame {
  int cols = 0, rows = 0;
  /// Cell size along the sweep (between normal faces) and across it (between lines), metres: dx and
  /// dy for the x sweep, dy and dx for the y sweep. Every difference divides by its own axis' size.
  double spacing_along_m = 1.0, spacing_across_m = 1.0;
  /// Van Gent (1995) porous resistance of the faces (build_frame): alpha = laminar_factor (1-n)^2 /
  /// (n^3 D^2), beta = turbulent_factor (1-n) / (n^3 D); porous_stone_diameter_m = D (0: none).
  double porous_laminar_factor = 0.0, porous_turbulent_factor = 0.0, porous_stone_diameter_m = 0.0;
  /// Each cell's D over porous_stone_diameter_m, for a grid with stones of its own
  /// (HarbourGrid::porous_stone_diameter_m); empty otherwise: every ratio is then 1, read without
  /// an array (StoneDiameterRatio), so such a grid holds no more memory and computes what it did
  /// bit for bit. A face's D is its two cells' weighted by their solid fraction 1 - n
  /// (face_stone_diameter_ratio).
  std::vector<float> stone_diameter_ratio;
  /// d per cell (land negative), float: the harbour grid's own precision, so the values are exact.
  std::vector<float> depth_m;
  /// n per cell clamped to [0, 1], float: the harbour grid's precision (exact).
  std::vector<float> porosity;
  /// 1/n per cell, 0 for solid walls (n below kWallPorosity). Float: 1 exactly in open water; in
  /// porous cells its rounding (6e-8 relative) is far below the uncertainty of n itself, and the
  /// mass equation and water_volume_m3 use the same value, so mass stays conserved to round-off.
  std::vector<float> inverse_porosity;
  /// The dispersion taper of docs/solver.md at the normal faces, 0..1 (float: a smooth weight,
  /// exact where it is 0 or 1, i.e. everywhere when no cut-off is set).
  std::vector<float> face_dispersion_weight;
  /// Per block of kBlockLines lines: 1 when a face of the block is porous (0 < n < 1), else 0.
  /// Blocks of open water run a sweep without the porous terms (fewer arrays streamed).
  std::vector<unsigned char> block_is_porous;
};

/// The storage type of the eddy viscosity nu (m^2/s) of eq. (6)-(7): float, because nu is a
/// turbulence-closure estimate (Kennedy et al. 2000) good to tens of per cent, not a state variable
/// (docs/solver.md, "Memory").
using EddyViscosity = float;

/// Porosity below which a cell is a solid wall (no flux through its faces): the public one.
using nearshore::boussinesq::kWallPorosity;
/// The bed-slope terms of Madsen & Sorensen (1992) assume mild slopes; steeper slopes are clamped
/// to this value inside the dispersive terms only, so charts with quays and dredged channels stay stable.
inline constexpr double kMaxDispersiveSlope = 0.5;
/// Largest Froude number |P| / (h sqrt(g h)) of a face flux (thin-film guard of the shoreline).
inline constexpr double kMaxFroude = 3.0;
/// The dispersion mask of a cell (SweepInput::dispersive, mark_dispersive): bit 0 set where the
/// dispersive terms apply (the cell wet, each of its 4 neighbours wet or a wall); the other bits say
/// which neighbours are dry walls, read as the mirror of the cell (its level and depth) by the
/// stencils that reach them, as the grid's edges are: before / after it along the frame's lines,
/// south / north of it across them (lines l - 1 and l + 1).
inline constexpr unsigned char kDispersive = 1, kMirrorBefore = 2, kMirrorAfter = 4, kMirrorSouth = 8, kMirrorNorth = 16;
/// Lines solved together in one block.
inline constexpr int kBlockLines = 16;

/// std::clamp by value: x < lo ? lo : (hi < x ? hi : x), the same result bit for bit. std::clamp,
/// std::min and std::max return a reference; on array elements that is a load from a selected
/// address, which keeps GCC from vectorising a loop over the lines (boussinesq_sweep.cpp).
inline double clamped(double x, double lo, double hi) { return x < lo ? lo : (hi < x ? hi : x); }

// The face values, from the two cells of normal face `face` (cells L = face - rows, R = face) of a
// frame; faces 0 and cols (the grid edges) are walls, or hold the imposed current's flux, and are never asked. Both cells are read
// unconditionally and the result selected by value (`&`, not `&&`): a load under a condition
// keeps the sweep's loops from vectorising.
/// 1 when the face can carry flux (neither cell is a solid wall), else 0.
inline double face_open(const float* inverse_porosity, std::size_t L, std::size_t R) {
  // Compared as double: a float mask selecting doubles does not vectorise either.
  const double left = inverse_porosity[L], right = inverse_porosity[R];
  return (left > 0.0) & (right > 0.0) ? 1.0 : 0.0;
}
/// Still-water depth d at the face: the mean of the two cells.
inline double face_depth(const float* depth, std::size_t L, std::size_t R) {
  return 0.5 * (static_cast<double>(depth[L]) + static_cast<double>(depth[R]));
}
/// Porosity n at an open face: the mean of the two cells; 1 at a closed face (no flux: no resistance).
inline double face_porosity(const float* porosity, const float* inverse_porosity, std::size_t L, std::size_t R) {
  const double mean = 0.5 * (static_cast<double>(porosity[L]) + static_cast<double>(porosity[R]));
  return face_open(inverse_porosity, L, R) != 0.0 ? mean : 1.0;
}
/// The cells' stone diameter ratios as the sweep reads them: scale x values[i] + offset, with
/// (1, 0) and StaticFrame::stone_diameter_ratio, or (0, 1) and any array of finite values (the
/// porosity) when the frame has none, which gives exactly 1 with no branch in the vectorised loop.
struct StoneDiameterRatio {
  const float* values;
  double scale, offset;
  static StoneDiameterRatio of(const StaticFrame& frame) {
    return frame.stone_diameter_ratio.empty() ? StoneDiameterRatio{frame.porosity.data(), 0.0, 1.0}
                                              : StoneDiameterRatio{frame.stone_diameter_ratio.data(), 1.0, 0.0};
  }
  double operator[](std::size_t i) const { return scale * static_cast<double>(values[i]) + offset; }
};
/// A porous face's stone diameter over the solver's: its two cells' ratios weighted by their solid
/// fractions 1 - n, so the stones of a porous cell, not an open one beside it (n = 1, no stones),
/// set a face on the layer's edge; equal ratios give that ratio exactly.
inline double face_stone_diameter_ratio(const float* porosity, const StoneDiameterRatio& ratio, std::size_t L, std::size_t R) {
  const double solid_L = 1.0 - static_cast<double>(porosity[L]), solid_R = 1.0 - static_cast<double>(porosity[R]);
  const double weight_R = solid_R / std::max(solid_L + solid_R, 1e-30);
  const double ratio_L = ratio[L];
  return ratio_L + weight_R * (ratio[R] - ratio_L);
}
/// Bed slope along the sweep at the face, clamped to kMaxDispersiveSlope (the dispersive terms only).
inline double face_slope_along(const float* depth, std::size_t L, std::size_t R, double spacing_m) {
  return clamped((static_cast<double>(depth[R]) - static_cast<double>(depth[L])) / spacing_m, -kMaxDispersiveSlope,
                 kMaxDispersiveSlope);
}

/// The time-dependent input of one sweep, all in the frame's layout.
struct SweepInput {
  const double* eta_old;          ///< eta^n, cells
  const double* eta_base;         ///< E: eta after every explicit flux of this sweep, cells
  /// eta at t^{n+1/2} for the derivatives ACROSS the lines is computed from eta_old and this partner:
  /// (eta_old + partner) / 2, or eta_old + (eta_old - partner) / 2 when `eta_across_extrapolates`
  /// (partner = eta^{n-1}); not stored (docs/solver.md, "Memory").
  const double* eta_across_partner;
  bool eta_across_extrapolates;
  const double* normal_old;       ///< normal flux at t^n, normal faces
  /// First guess of the normal flux increment over the step; the normal flux at t^{n+1/2} for the
  /// across derivatives is normal_old + normal_guess / 2 (computed, not stored).
  const double* normal_guess;
  const double* tangential_half;  ///< tangential flux at t^{n+1/2}, tangential faces
  const double* tangential_rate;  ///< its time derivative at t^{n+1/2}, (m^2/s)/s
  const EddyViscosity* eddy_viscosity;  ///< nu of eq. (6)-(7), m^2/s, cells
  const unsigned char* dispersive;  ///< the dispersion mask and its walls (kDispersive, kMirror*)
  bool viscous = true;            ///< false: eddy_viscosity is 0 everywhere (no cell breaks)
  /// The fully nonlinear dispersive terms' explicit remainder at the normal faces, m^2/s^2, on the
  /// momentum equation's left side like Psi (nonlinear_dispersion.hpp), or nullptr for none.
  const float* explicit_force = nullptr;
  /// The fully nonlinear terms' subcritical factor at the normal faces for this step (0 to 1, 0 at
  /// porous faces; NonlinearDispersion::update_subcritical), or nullptr with the seed's equations.
  const float* fully_nonlinear_subcritical = nullptr;
  /// The breaking strength B per cell (0 to 1, the sweep's layout) by which the fully nonlinear
  /// terms fade (BreakingParameters::fade_fully_nonlinear_terms): each cell's share of them is
  /// weighted by 1 - B. All zeros when they do not fade; nullptr with the seed's equations.
  const float* fully_nonlinear_breaking = nullptr;
};

struct SweepOutput {
  /// cells: eta of cell (c along, l line) goes to eta_new[c * eta_cell_stride + l * eta_line_stride],
  /// so the x sweep writes the natural layout directly (no transposed copy, no transpose pass).
  double* eta_new;
  double* normal_new;  ///< normal faces, the frame's layout
  std::size_t eta_cell_stride = 0, eta_line_stride = 1;
};

struct SweepConstants {
  double time_step_s = 0.0;
  double dispersion_coefficient = 1.0 / 15.0;
  double dry_depth_m = 0.01;
  double chezy_coefficient = 0.0;
  double kinematic_viscosity_m2_s = 0.0;
  int iterations = 2;
  /// The dispersive terms on the total depth h = d + eta at t^{n+1/2} instead of d
  /// (SolverParameters::dispersion_depth = kTotal).
  bool dispersion_on_total_depth = false;
  /// The face depth of gravity and resistance is the mean of two wet cells
  /// (SolverParameters::face_depth = kMeanWhereWet); otherwise the larger of the mean and the water
  /// above the higher bed.
  bool mean_face_depth_where_wet = false;
  /// Equations::kFullyNonlinear: the along-line flux-rate part of the fully nonlinear dispersive
  /// terms is added to the tridiagonal system (the rest is SweepInput::explicit_force;
  /// nonlinear_dispersion.hpp).
  bool fully_nonlinear = false;
  /// SolverParameters::WallDispersion::kMirrorAtWalls: the stencils read the walls the mask marks
  /// (kMirror*) as mirrors; otherwise the mask has no such bits and the reads are left as they are.
  bool mirror_walls = false;
  /// SolverParameters::current: the grid's edge faces hold the flux they have (the imposed current's
  /// P = u d through them) instead of being walls (flux 0), and their depth is the edge cell's.
  bool edges_hold_flux = false;
  /// The same as the factor of the edge flux's increment -P_old: 1 for walls, 0 when held. A value
  /// the compiler cannot fold (a select on edges_hold_flux inside the lines' loops stops GCC 12 with
  /// an internal error vectorising them); times 1 keeps every bit.
  double edge_release_factor = 1.0;
};

/// Per-thread scratch of one block (allocated once per thread, reused every step).
struct SweepScratch {
  std::vector<double> upper, right, increment, eta_half, flux_half, cell_term, fixed_term,
      tangential_squared, active, face_velocity, h_pair_north, h_pair_south, cell_eta_yy, cell_eta_y, cell_flux_yt,
      cell_slope_across, nu_pair_north, nu_pair_south, dispersion_weight, mirror_before, mirror_after, mirror_south,
      mirror_north;
  void resize(int cols);
  /// The bytes its arrays hold (the solver's memory_bytes).
  std::size_t memory_bytes() const;
};

/// Solves lines [line_begin, line_end) (at most kBlockLines) of the frame: the tridiagonal system
/// of docs/solver.md for the normal flux increment, iterated `iterations` times for the
/// time-centred non-linear and dispersive terms, then eta from the mass equation. Reads only
/// `input`, writes only those lines of `output`.
void sweep_lines(const StaticFrame& frame, const SweepConstants& constants, const SweepInput& input,
                 const SweepOutput& output, int line_begin, int line_end, SweepScratch& scratch);

/// out[c * rows + r] = in[r * cols + c]: in is cols x rows (row-major), out is rows x cols.
/// Parallel over blocks; the result does not depend on the thread count.
void transpose(const double* in, double* out, int cols, int rows);
/// The same for float arrays (the eddy viscosity, the static depths), same layout.
void transpose(const float* in, float* out, int cols, int rows);

/// How transpose_half_and_rate gets the flux's change over the step from `other`.
enum class HalfAndRate {
  kFromNewFlux,    ///< other = the flux at t^{n+1}: half = (old + new) / 2, rate = (new - old) / dt
  kFromIncrement,  ///< other = an increment estimate: half = old + increment / 2, rate = increment / dt
  kFromPass,       ///< other = the previous pass's new flux, used as an increment estimate (new - old)
};
/// The flux at t^{n+1/2} and its rate d/dt, transposed like `transpose` (in one pass): the across
/// flux a sweep needs, in its tangential layout.
void transpose_half_and_rate(HalfAndRate kind, const double* old_flux, const double* other, double time_step_s,
                             double* half, double* rate, int cols, int rows);

}  // namespace nearshore::boussinesq::detail
