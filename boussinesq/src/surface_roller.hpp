#pragma once
// The surface roller of Schaffer, Madsen & Deigaard (1993), as Madsen, Sorensen & Schaffer (1997,
// Part I) use it with the Madsen-Sorensen equations: where a wave front is steeper than tan(phi),
// the water above the line of slope tan(phi) tangent to the front at its toe is a roller riding on
// the wave at its celerity c. With a velocity c in the roller (thickness delta) and u0 below it,
// the depth-integrated momentum flux exceeds the depth-uniform P^2/h by
//   R = delta (c - P/h)^2 / (1 - delta/h)                    Schaffer et al. (1993) eq. (9)
// (tensor form R_ij = delta (c_i - u_i)(c_j - u_j) / (1 - delta/h), Madsen et al. 1997 eq. 5-6),
// which enters the momentum equations as -dR_xx/dx - dR_xy/dy (and likewise for Q).
// docs/solver.md, "Breaking", gives the geometry and the constants. Private to boussinesq/.
#include <cstddef>
#include <utility>
#include <vector>

namespace nearshore::boussinesq::detail {

struct RollerConstants {
  double onset_slope = 0.0;     ///< tan(phi_B)
  double final_slope = 0.0;     ///< tan(phi_0)
  double half_time_s = 0.0;     ///< t_1/2 of phi(t) = phi_0 + (phi_B - phi_0) 2^(-t / t_1/2), seconds
  double onset_angle_rad = 0.0, final_angle_rad = 0.0;
  double celerity_factor = 1.3; ///< c = celerity_factor sqrt(g h)
  double shape_factor = 1.5;    ///< f_delta
  double dry_depth_m = 0.01;
};

/// The grid the roller sees: the natural layout of the solver (cells r * nx + c, x faces
/// f * ny + r, y faces k * nx + c), as boussinesq_solver.cpp holds it.
struct RollerGrid {
  int nx = 0, ny = 0;
  double dx = 1.0, dy = 1.0;
  const float* depth_m = nullptr;           ///< d per cell (land negative)
  const float* porosity = nullptr;          ///< n per cell: the roller lives only in open water (n = 1)
};

/// The roller's work arrays (cells and faces) and its per-step update.
class SurfaceRoller {
 public:
  SurfaceRoller() = default;
  SurfaceRoller(const RollerGrid& grid, const RollerConstants& constants);

  /// From the state at t^n (eta per cell and eta^{n-1}, P on x faces, Q on y faces) and the roller start times of
  /// the last step (per cell, seconds; -1 = no roller): finds the rollers, writes their start times
  /// back (a roller keeps the start time of the roller it grew from), writes 1 to
  /// `breaking_indicator` in roller cells and 0 elsewhere, and computes the roller force per face,
  /// force_x() and force_y() in m^2/s^2 (d(P)/dt, d(Q)/dt). Returns whether any cell holds a roller.
  bool update(double now_s, const double* eta, const double* eta_previous, const double* flux_x, const double* flux_y, double* start_time_s,
              float* breaking_indicator);

  const std::vector<double>& force_x() const { return force_x_; }  ///< x faces, f * ny + r
  const std::vector<double>& force_y() const { return force_y_; }  ///< y faces, k * nx + c
  std::size_t memory_bytes() const;

 private:
  // One roller scan along a line of cells (x rows or y columns) in one direction of travel.
  // `flux_along`: the flux along the line at the cell centres; `cells`: scratch for one roller.
  void scan_line(double now_s, const double* eta, const double* eta_previous, const double* flux_along, const double* start_time_s, std::size_t first,
                 std::ptrdiff_t step, int count, double spacing_m, bool along_x, int direction,
                 std::vector<std::pair<std::size_t, double>>& cells);
  double slope_of(double age_s) const;
  void smooth_stresses(const double* eta);

  RollerGrid grid_;
  RollerConstants k_;
  // Per cell: thickness delta (m), the start time of its roller (s), the unit direction of travel.
  std::vector<double> thickness_, start_, direction_x_, direction_y_, gradient_x_, gradient_y_;
  std::vector<double> stress_xx_, stress_xy_, stress_yy_;
  std::vector<double> force_x_, force_y_;
};

}  // namespace nearshore::boussinesq::detail
