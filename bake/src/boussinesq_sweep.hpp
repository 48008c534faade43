#pragma once
// The one line sweep of the ADI scheme (docs/solver.md, "Discretisation"). The x sweep runs it on
// the harbour in its natural orientation (lines = rows, normal flux = P, tangential flux = Q); the
// y sweep runs the SAME code on transposed copies (lines = columns, normal flux = Q, tangential
// flux = P), so both directions share every line of the discretisation.
//
// Layout of a frame (cols cells along the sweep, rows lines):
//   cells         cols x rows,        index row * cols + col
//   normal faces  (cols + 1) x rows,  index row * (cols + 1) + face; face f lies between cells f-1, f
//   tangential    cols x (rows + 1),  index face_row * cols + col; face_row r lies between rows r-1, r
#include <cstdint>
#include <vector>

namespace nearshore::bake::detail {

/// Everything about one orientation that does not change during a run.
struct StaticFrame {
  int cols = 0, rows = 0;
  double spacing_m = 1.0;
  std::vector<double> depth_m;             ///< d per cell (land negative)
  std::vector<double> inverse_porosity;    ///< 1/n per cell, 0 for solid walls (n below kWallPorosity)
  std::vector<double> face_depth_m;        ///< d at normal faces (mean of the two cells)
  std::vector<double> face_porosity;       ///< n at normal faces (mean of the two cells)
  std::vector<std::uint8_t> face_open;     ///< 0: grid edge or next to a wall, flux is always 0
  std::vector<double> face_dispersion_weight;  ///< taper of docs/solver.md, 0..1
  std::vector<double> face_slope_along;    ///< d_x at the face (clamped, see kMaxDispersiveSlope)
  std::vector<double> face_slope_across;   ///< d_y at the face (clamped)
  std::vector<double> face_porous_laminar_s;   ///< alpha (1/s) of seed 003 eq. (2), 0 in open water
  std::vector<double> face_porous_turbulent_m; ///< beta (1/m), 0 in open water
};

/// Porosity below which a cell is a solid wall (no flux through its faces).
inline constexpr double kWallPorosity = 0.05;
/// The bed-slope terms of Madsen & Sorensen (1992) assume mild slopes; steeper slopes are clamped
/// to this value inside the dispersive terms only, so charts with quays and dredged channels stay stable.
inline constexpr double kMaxDispersiveSlope = 0.5;

/// The time-dependent input of one sweep, all in the frame's orientation.
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
  const std::uint8_t* dispersive; ///< 1 where the cell and its 4 neighbours are wet
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

/// Per-thread scratch of one line (allocated once per thread, reused every step).
struct SweepScratch {
  std::vector<double> lower, diagonal, upper, right, increment, eta_half, flux_half, cell_term, fixed_term,
      tangential_squared, active;
  void resize(int faces);
};

/// Solves line `row` of the frame: the tridiagonal system of docs/solver.md for the normal flux
/// increment, iterated `iterations` times for the time-centred non-linear and dispersive terms,
/// then eta from the mass equation. Reads only `input`, writes only line `row` of `output`.
void sweep_line(const StaticFrame& frame, const SweepConstants& constants, const SweepInput& input,
                const SweepOutput& output, int row, SweepScratch& scratch);

/// out[c * rows + r] = in[r * cols + c]: in is cols x rows (row-major), out is rows x cols.
void transpose(const double* in, double* out, int cols, int rows);
void transpose(const std::uint8_t* in, std::uint8_t* out, int cols, int rows);

}  // namespace nearshore::bake::detail
