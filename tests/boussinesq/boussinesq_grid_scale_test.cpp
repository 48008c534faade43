// The fine-grid two-dimensional instability of docs/solver.md ("Grid-scale filter") and its cure,
// the Shapiro (1970) filter of the fluxes: without it a grid-scale mode of P and Q grows in a narrow
// flume at d/dx = 12 (the Mase & Kirby grid) until the run blows up (t = 198 s here); with it the
// mode stays at noise level and the resolved waves keep their height.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "boussinesq_test_support.hpp"

namespace nearshore::boussinesq {

using namespace nearshore::ocean;
namespace {

struct FlumeRun {
  double across_flux_early_m2_s = 0.0;  ///< max |Q| over 15-20 s (after the ramp)
  double across_flux_late_m2_s = 0.0;   ///< max |Q| over 115-120 s
  double wave_height_m = 0.0;           ///< mean crest-to-trough height over x = 6-14 m, 50-60 s
};

// A flat 0.47 m flume at 4 cm (d/dx = 12), five cells across, regular waves H = 3 cm, T = 1.2 s
// from a source line at 3 m, and 0.1 mm of deterministic noise in the initial surface so every
// grid mode is seeded. Breaking and friction off: the scheme alone.
FlumeRun run_narrow_flume(int shapiro_filter_order) {
  const HarbourGrid harbour = testing::flume(500, 5, 0.04, 0.47);
  SolverParameters parameters = testing::inviscid_parameters();
  parameters.shapiro_filter_order = shapiro_filter_order;
  parameters.sponges = {{Side::kWest, 2.0}, {Side::kEast, 4.0}};
  BoussinesqSolver solver(harbour, parameters, testing::regular_waves_from_west(3.0, 3.0, 0.015, 1.2));
  testing::UniformNoise noise(1e-4);
  solver.set_surface_elevation([&](double, double) { return noise(); });
  FlumeRun run;
  Raster<float> flux_x, flux_y;
  std::vector<double> low(500, 1e9), high(500, -1e9);
  while (solver.time_s() < 120.0) {
    solver.step();
    const double t = solver.time_s();
    if (const auto report = solver.check_stability())
      ADD_FAILURE() << "unstable at t = " << report->time_s << " s: " << report->what;
    if ((t > 15.0 && t <= 20.0) || t > 115.0) {
      solver.cell_centred_fluxes(flux_x, flux_y);
      double across = 0.0;
      for (float q : flux_y.values()) across = std::max(across, static_cast<double>(std::abs(q)));
      double& slot = t <= 20.0 ? run.across_flux_early_m2_s : run.across_flux_late_m2_s;
      slot = std::max(slot, across);
    }
    if (t > 50.0 && t <= 60.0)
      for (int c = 150; c < 350; ++c) {
        const double eta = solver.surface_elevation_m()(c, 2);
        low[c] = std::min(low[c], eta);
        high[c] = std::max(high[c], eta);
      }
  }
  for (int c = 150; c < 350; ++c) run.wave_height_m += (high[c] - low[c]) / 200.0;
  return run;
}

TEST(BoussinesqGridScale, ShapiroFilterStopsTheFineGridModeAndKeepsTheWaves) {
  const FlumeRun unfiltered = run_narrow_flume(0);
  const FlumeRun filtered = run_narrow_flume(8);
  std::printf(
      "narrow flume, d/dx = 12: max|Q| 15-20 s -> 115-120 s: unfiltered %.2e -> %.2e m^2/s, filtered %.2e -> "
      "%.2e m^2/s\n",
      unfiltered.across_flux_early_m2_s, unfiltered.across_flux_late_m2_s, filtered.across_flux_early_m2_s,
      filtered.across_flux_late_m2_s);
  std::printf("wave height x = 6-14 m: unfiltered %.5f m, filtered %.5f m (%+.3f %%)\n",
              unfiltered.wave_height_m, filtered.wave_height_m,
              100.0 * (filtered.wave_height_m / unfiltered.wave_height_m - 1.0));
  // The mode exists: a 1-D wave in a straight flume has no across flux, yet it grows ~30-fold in
  // 100 s without the filter (it doubles about every 10 s and ends the run at t = 198 s).
  EXPECT_GT(unfiltered.across_flux_late_m2_s, 10.0 * unfiltered.across_flux_early_m2_s);
  // With the filter it decays, and stays far below the wave's own flux (~ a c = 0.03 m^2/s).
  EXPECT_LT(filtered.across_flux_late_m2_s, filtered.across_flux_early_m2_s);
  EXPECT_LT(filtered.across_flux_late_m2_s, 1e-5);
  // At 30 points per wavelength the filter's response is 1 - sin^8(pi/30) = 1 - 1.4e-7 per step:
  // the waves keep their height (the flume's own H = 3 cm, within 0.5 %).
  EXPECT_NEAR(filtered.wave_height_m / unfiltered.wave_height_m, 1.0, 0.005);
}

}  // namespace
}  // namespace nearshore::boussinesq
