// A 1-D experiment in a 2-D solver (docs/solver.md, "Modes across a narrow flume"): a flume one
// cell across carries the waves of a wider one, and a mode across a flume a few cells wide, which
// grows under steep waves on cells of a tenth of the depth, has no room in it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "boussinesq_test_support.hpp"

namespace nearshore::boussinesq {

using namespace nearshore::ocean;
namespace {

struct FlumeWaves {
  std::vector<double> centre_line_m;  ///< eta along the flume's middle row at the end
  double across_spread_early_m = 0.0; ///< max over the flume of the spread of eta across it, 4-5 s
  double across_spread_late_m = 0.0;  ///< the same over the run's last second (before a blow-up)
  std::vector<double> across_spread_each_second_m;  ///< the spread at t = 1, 2, ... s
};

// Steep regular waves (3 cm amplitude requested in 0.2 m of water, T = 1.2 s, k d = 0.82) from a
// source line at 1.5 m down a flat flume with sponges at both ends; breaking and friction off, the
// scheme alone.
// The initial surface carries 1 um of deterministic noise, so every mode across is seeded.
FlumeWaves run_flume(int rows, double spacing_m, double length_m, double duration_s) {
  const int columns = static_cast<int>(std::lround(length_m / spacing_m));
  const HarbourGrid harbour = testing::flume(columns, rows, spacing_m, 0.2);
  SolverParameters parameters = testing::inviscid_parameters();
  parameters.sponges = {{Side::kWest, 1.0}, {Side::kEast, 2.0}};
  BoussinesqSolver solver(harbour, parameters, testing::regular_waves_from_west(1.5, 2.4, 0.03, 1.2));
  testing::UniformNoise noise(1e-6);
  solver.set_surface_elevation([&](double, double) { return noise(); });
  FlumeWaves run;
  auto across_spread = [&] {
    double spread = 0.0;
    for (int c = 0; c < columns; ++c) {
      double low = 1e9, high = -1e9;
      for (int r = 0; r < rows; ++r) {
        low = std::min(low, static_cast<double>(solver.surface_elevation_m()(c, r)));
        high = std::max(high, static_cast<double>(solver.surface_elevation_m()(c, r)));
      }
      spread = std::max(spread, high - low);
    }
    return spread;
  };
  while (solver.time_s() < duration_s - 1e-9) {
    solver.step();
    const double t = solver.time_s();
    if (const auto report = solver.check_stability()) {
      ADD_FAILURE() << "unstable at t = " << report->time_s << " s: " << report->what;
      break;
    }
    const double spread = across_spread();
    if (t > 4.0 && t <= 5.0) run.across_spread_early_m = std::max(run.across_spread_early_m, spread);
    if (t > duration_s - 1.0) run.across_spread_late_m = std::max(run.across_spread_late_m, spread);
    if (std::floor(t) > std::floor(t - solver.time_step_s())) run.across_spread_each_second_m.push_back(spread);
  }
  // A run stopped by a blow-up reports the spread it had reached.
  if (!run.across_spread_each_second_m.empty() && solver.time_s() < duration_s - 1.0)
    run.across_spread_late_m = run.across_spread_each_second_m.back();
  for (int c = 0; c < columns; ++c) run.centre_line_m.push_back(solver.surface_elevation_m()(c, rows / 2));
  return run;
}

TEST(BoussinesqFlume, OneCellAcrossCarriesTheWavesOfThreeCells) {
  // 0.025 m cells (d/dx = 8), 6 m, 10 s: the waves cross the flume and reach the east sponge.
  const FlumeWaves one = run_flume(1, 0.025, 6.0, 10.0);
  const FlumeWaves three = run_flume(3, 0.025, 6.0, 10.0);
  double largest = 0.0, apart = 0.0;
  for (std::size_t c = 0; c < one.centre_line_m.size(); ++c) {
    largest = std::max(largest, std::abs(three.centre_line_m[c]));
    apart = std::max(apart, std::abs(one.centre_line_m[c] - three.centre_line_m[c]));
  }
  std::printf("flume one cell vs three cells across at 10 s: largest |eta| %.4f m, apart by at most %.2e m\n", largest,
              apart);
  EXPECT_GT(largest, 0.02);  // the waves are there
  // Nothing varies across a straight flume, so its middle row is the one-cell flume's row; what
  // differs is the noise seeded across (1 um) and float round-off, far below a micrometre.
  EXPECT_LT(apart, 1e-6);
}

// The known limit (docs/solver.md, "Modes across a narrow flume"): six cells across at d/dx = 16,
// the mixed dispersive term's lag between the two sweeps lets a nearly divergence-free mode grow out
// of the noise. Disabled until the scheme has a remedy; run it with --gtest_also_run_disabled_tests.
TEST(BoussinesqFlume, DISABLED_NoModeGrowsAcrossASixCellFlumeUnderSteepWaves) {
  // Today (2026-11-28): the seeded spread falls to 1.4e-7 m by 9 s, grows from 12 s ten-fold every
  // 1.7 s to 4e-2 m at 21 s, and the run stops at t = 27 s; one row on the same cells runs the 30 s.
  const FlumeWaves six = run_flume(6, 0.0125, 6.0, 30.0);
  std::printf("six cells across, d/dx = 16: spread of eta across %.2e m at 4-5 s, %.2e m at the end; each second:",
              six.across_spread_early_m, six.across_spread_late_m);
  for (double spread : six.across_spread_each_second_m) std::printf(" %.1e", spread);
  std::printf("\n");
  EXPECT_LT(six.across_spread_late_m, std::max(six.across_spread_early_m, 1e-6));
}

}  // namespace
}  // namespace nearshore::boussinesq
