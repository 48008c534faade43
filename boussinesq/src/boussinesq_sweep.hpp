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
#include <cstdint>
#include <vector>

namespace nearshore::boussinesq::detail {

/// Everything about one orientation that does not change during a run.
struct StaticFrame {
  int cols = 0, rows = 0;
  double spacing_m = 1.0;
  std::vector<double> depth_m;             ///< d per cell (land negative)
  std::vector<double> inverse_porosity;    ///< 1/n per cell, 0 for solid walls (n below kWallPorosity)
  std::vector<double> face_depth_m;        ///< d at normal faces (mean of the two cells)
  std::vector<double> face_porosity;       ///< n at normal faces (mean of the two cells)
  std::vector<double> face_inverse_porosity;
  std::vector<double> face_open;           ///< 0: grid edge or next to a wall, flux is always 0; else 1
  std::vector<double> face_dispersion_weight;  ///< taper of docs/solver.md, 0..1
  std::vector<double> face_slope_along;    ///< d_x at the face (clamped, see kMaxDispersiveSlope)
  std::vector<double> face_slope_across;   ///< d_y at the face (clamped)
  std::vector<double> face_porous_laminar_s;   ///< alpha (1/s) of seed 003 eq. (2), 0 in open water
  std::vector<double> face_porous_turbulent_m; ///< beta (1/m), 0 in open water
  /// Per block of kBlockLines lines: 1 when a face of the block is porous (0 < n < 1), else 0.
  /// Blocks of open water run a sweep without the porous terms (fewer arrays streamed).
  std::vector<unsigned char> block_is_porous;
};

/// Porosity below which a cell is a solid wall (no flux through its faces).
inline constexpr double kWallPorosity = 0.05;
/// The bed-slope terms of Madsen & Sorensen (1992) assume mild slopes; steeper slopes are clamped
/// to this value inside the dispersive terms only, so charts with quays and dredged channels stay stable.
inline constexpr double kMaxDispersiveSlope = 0.5;
/// Largest Froude number |P| / (h sqrt(g h)) of a face flux (thin-film guard of the shoreline).
inline constexpr double kMaxFroude = 3.0;
/// Lines solved together in one block.
inline constexpr int kBlockLines = 16;

/// The time-dependent input of one sweep, all in the frame's layout.
struct SweepInput {
  const double* eta_old;          ///< eta^n, cells
  const double* eta_base;         ///< E: eta after every explicit flux of this sweep, cells
  const double* eta_across;       ///< eta at t^{n+1/2} estimated for derivatives ACROSS the lines
  const double* normal_old;       ///< normal flux at t^n, normal faces
  const double* normal_across;    ///< normal flux at t^{n+1/2} estimated for across derivatives
  const double* normal_guess;     ///< first guess of the normal flux increment over the step
  const double* tangential_half;  ///< tangential flux at t^{n+1/2}, tangential faces
  const double* tangential_rate;  ///< its time derivative at t^{n+1/2}, (m^2/s)/s
  const double* eddy_viscosity;   ///< nu of eq. (6)-(7), m^2/s, cells
  const double* dispersive;       ///< 1 where the cell and its 4 neighbours are wet, else 0
  bool viscous = true;            ///< false: eddy_viscosity is 0 everywhere (no cell breaks)
};

struct SweepOutput {
  double* eta_new;     ///< cells
  double* normal_new;  ///< normal faces
};

struct SweepConstants {
  double time_step_s = 0.0;
  double dispersion_coefficient = 1.0 / 15.0;
  double dry_depth_m = 0.01;
  double chezy_coefficient = 0.0;
  int iterations = 2;
};

/// Per-thread scratch of one block (allocated once per thread, reused every step).
struct SweepScratch {
  std::vector<double> upper, right, increment, eta_half, flux_half, cell_term, fixed_term,
      tangential_squared, active, face_velocity, h_pair_north, h_pair_south, cell_eta_yy, cell_eta_y, cell_flux_yt,
      nu_pair_north, nu_pair_south;
  void resize(int cols);
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
