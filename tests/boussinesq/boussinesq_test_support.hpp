#pragma once
// Shared set-up of the Boussinesq solver tests: quiet parameters and simple grids.
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "nearshore/boussinesq/boussinesq_solver.hpp"

namespace nearshore::boussinesq::testing {

/// A flat-bottomed flume of `columns` x `rows` cells of `spacing_m`, depth `depth_m`.
inline HarbourGrid flume(int columns, int rows, double spacing_m, double depth_m) {
  GridGeometry geometry;
  geometry.columns = columns;
  geometry.rows = rows;
  geometry.spacing_m = spacing_m;
  return HarbourGrid::open_water(geometry, static_cast<float>(depth_m));
}

/// Inviscid, non-breaking parameters: the linear and conservation tests check the scheme alone.
inline SolverParameters inviscid_parameters(double courant_number = 0.5) {
  SolverParameters parameters;
  parameters.courant_number = courant_number;
  parameters.chezy_coefficient = 0.0;
  parameters.kinematic_viscosity_m2_s = 0.0;
  parameters.breaking.enabled = false;
  return parameters;
}

/// Regular waves of one component (amplitude, period) from a source line facing west, ramped in.
inline WaveMaker regular_waves_from_west(double source_line_m, double ramp_time_s, double amplitude_m, double period_s) {
  WaveMaker maker;
  maker.kind = WaveMaker::Kind::kComponents;
  maker.facing = Side::kWest;
  maker.source_line_m = source_line_m;
  maker.ramp_time_s = ramp_time_s;
  maker.sea_state.components = {{amplitude_m, 2.0 * std::numbers::pi / period_s, 0.0, 0.0}};
  return maker;
}

/// Deterministic noise to seed every grid mode of a state: a linear congruential sequence, the same
/// on every platform, each call uniform in [-amplitude/2, +amplitude/2] in 1000 levels.
class UniformNoise {
 public:
  explicit UniformNoise(double amplitude) : amplitude_(amplitude) {}
  double operator()() {
    state_ = state_ * 1103515245u + 12345u;
    return amplitude_ * (static_cast<double>((state_ >> 16) % 1000u) / 999.0 - 0.5);
  }

 private:
  double amplitude_;
  unsigned state_ = 12345u;
};

/// Where tests write plots: <build>/validation/boussinesq/.
// Period of a standing mode (a closed basin's eigenmode set by set_surface_elevation) from the
// zero crossings of the corner cell (0, 0), each interpolated linearly within its time step:
// eight half periods.
inline double standing_mode_period_s(BoussinesqSolver& solver) {
  std::vector<double> crossings;
  double previous = solver.surface_elevation_at(0.0, 0.0);
  while (crossings.size() < 9) {
    solver.step();
    const double now = solver.surface_elevation_at(0.0, 0.0);
    if ((previous > 0.0) != (now > 0.0)) crossings.push_back(solver.time_s() - solver.time_step_s() * now / (now - previous));
    previous = now;
  }
  return 2.0 * (crossings.back() - crossings.front()) / (crossings.size() - 1.0);
}

inline std::filesystem::path plot_folder() {
  std::filesystem::path folder = std::filesystem::path(NEARSHORE_BINARY_DIR) / "validation" / "boussinesq";
  std::filesystem::create_directories(folder);
  return folder;
}

}  // namespace nearshore::boussinesq::testing

namespace nearshore::boussinesq::testing {

/// Everything a run leaves in float, for bit-for-bit comparisons of two runs: eta, the cell-centred
/// fluxes and the breaking indicator, one after the other.
inline std::vector<float> solver_snapshot(const BoussinesqSolver& solver) {
  Raster<float> flux_x, flux_y;
  solver.cell_centred_fluxes(flux_x, flux_y);
  std::vector<float> all = solver.surface_elevation_m().values();
  all.insert(all.end(), flux_x.values().begin(), flux_x.values().end());
  all.insert(all.end(), flux_y.values().begin(), flux_y.values().end());
  all.insert(all.end(), solver.breaking_indicator().values().begin(), solver.breaking_indicator().values().end());
  return all;
}

/// A closed 60 x 40 basin (1 m cells) over rough bathymetry: a smooth 2-5 m bed with 0.6 m
/// deterministic roughness, a beached island rising to 2 m above still water, a porous
/// breakwater (n = 0.45) and a solid quay wall (n = 0). Land carries minus its elevation.
inline HarbourGrid rough_basin() {
  HarbourGrid harbour = flume(60, 40, 1.0, 3.0);
  for (int r = 0; r < 40; ++r)
    for (int c = 0; c < 60; ++c) {
      const double x = c + 0.5, y = r + 0.5;
      // Roughness from a hash of the cell (no <random>: identical on every platform).
      const unsigned hash = (static_cast<unsigned>(c) * 73856093u) ^ (static_cast<unsigned>(r) * 19349663u);
      const double noise = ((hash % 1000u) / 999.0 - 0.5) * 0.6;
      double depth = 3.5 + 1.2 * std::sin(0.21 * x) * std::cos(0.17 * y) + noise;
      const double island = std::hypot(x - 42.0, y - 20.0);
      if (island < 9.0) depth = std::min(depth, -2.0 + 0.6 * island);  // beach slope 0.6 m per cell
      harbour.still_water_depth_m(c, r) = static_cast<float>(depth);
      harbour.land(c, r) = depth < 0.0;
      if (c == 20 && r >= 10 && r < 30) harbour.porosity(c, r) = 0.45f;  // rubble-mound breakwater
      if (r == 8 && c >= 5 && c < 18) harbour.porosity(c, r) = 0.0f;      // vertical quay wall
    }
  return harbour;
}

}  // namespace nearshore::boussinesq::testing
