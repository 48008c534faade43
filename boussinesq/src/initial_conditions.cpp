#include "nearshore/boussinesq/initial_conditions.hpp"

#include <algorithm>
#include <cmath>

#include "nearshore/core/error.hpp"
#include "nearshore/ocean/linear_waves.hpp"

namespace nearshore::boussinesq {

void start_solitary_wave(BoussinesqSolver& solver, const HarbourGrid& harbour, const SolitaryWave& wave) {
  const GridGeometry& geometry = harbour.geometry;
  const bool along_x = wave.facing == Side::kWest || wave.facing == Side::kEast;
  const double sign = (wave.facing == Side::kWest || wave.facing == Side::kSouth) ? 1.0 : -1.0;
  const double H = wave.height_m, s0 = wave.crest_position_m;
  const double dx = along_x ? geometry.spacing_x_m() : geometry.spacing_y_m();  // along the travel
  const int nx = geometry.columns, ny = geometry.rows;
  const double origin = along_x ? geometry.origin_x_m : geometry.origin_y_m;
  const int crest = std::clamp(static_cast<int>(std::floor((s0 - origin) / dx)), 0, (along_x ? nx : ny) - 1);
  double d_sum = 0.0;
  int d_count = 0;
  for (int t = 0; t < (along_x ? ny : nx); ++t) {
    const double d = along_x ? harbour.still_water_depth_m(crest, t) : harbour.still_water_depth_m(t, crest);
    if (d > 0.0) {
      d_sum += d;
      ++d_count;
    }
  }
  if (!(H > 0.0) || d_count == 0)
    throw Error("solitary wave", "needs height_m > 0 and water under crest_position_m",
                "set the height and put the crest over water");
  const double d0 = d_sum / d_count;
  const double K = std::sqrt(3.0 * H / (4.0 * d0 * d0 * d0)), c = std::sqrt(ocean::kGravity_m_s2 * (d0 + H));
  const auto profile = [&](double position) {
    const double sech = 1.0 / std::cosh(K * (position - s0));
    return H * sech * sech;
  };
  const auto at_rest = [](double, double) { return 0.0; };
  const auto travelling = [&](double x_m, double y_m) { return sign * c * profile(along_x ? x_m : y_m); };
  solver.set_initial_condition([&](double x_m, double y_m) { return profile(along_x ? x_m : y_m); },
                               along_x ? std::function<double(double, double)>(travelling) : at_rest,
                               along_x ? std::function<double(double, double)>(at_rest) : travelling);
}

}  // namespace nearshore::boussinesq
