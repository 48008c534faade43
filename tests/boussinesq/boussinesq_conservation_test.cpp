// Conservation and balance of the scheme (issue 4): a lake at rest over rough bathymetry stays
// at rest; a closed basin keeps its water to round-off while waves run up a beach; results do
// not depend on the number of threads.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "boussinesq_test_support.hpp"

namespace nearshore::boussinesq {

using namespace nearshore::ocean;
namespace {

TEST(BoussinesqBalance, LakeAtRestOverRoughBathymetryStaysAtRest) {
  const HarbourGrid harbour = testing::rough_basin();
  SolverParameters parameters;  // everything on: friction, breaking, porous resistance
  parameters.sponges = {{Side::kWest, 6.0}};
  BoussinesqSolver solver(harbour, parameters, WaveMaker{});
  for (int i = 0; i < 200; ++i) solver.step();
  Raster<float> flux_x, flux_y;
  solver.cell_centred_fluxes(flux_x, flux_y);
  double largest_elevation = 0.0, largest_flux = 0.0;
  for (int r = 0; r < 40; ++r)
    for (int c = 0; c < 60; ++c) {
      if (harbour.still_water_depth_m(c, r) > 0.0)
        largest_elevation = std::max(largest_elevation, std::abs(double(solver.surface_elevation_m()(c, r))));
      largest_flux = std::max({largest_flux, std::abs(double(flux_x(c, r))), std::abs(double(flux_y(c, r)))});
    }
  // Well-balanced by construction (no gradient of a flat surface, faces to dry land inactive):
  // the state must stay exactly at rest, not merely small.
  EXPECT_EQ(largest_elevation, 0.0);
  EXPECT_EQ(largest_flux, 0.0);
}

// A 0.8 m hump in the closed rough basin: waves cross the breakwater, hit the quay and run up and
// down the island's beach (wetting and drying).
std::unique_ptr<BoussinesqSolver> hump_in_rough_basin(const HarbourGrid& harbour, int adi_passes = 1,
                                                      bool alternate_sweep_order = false) {
  SolverParameters parameters;
  parameters.dispersion_cutoff_depth_m = 0.3;
  parameters.adi_passes = adi_passes;
  parameters.alternate_sweep_order = alternate_sweep_order;
  auto solver = std::make_unique<BoussinesqSolver>(harbour, parameters, WaveMaker{});
  solver->set_surface_elevation(
      [](double x, double y) { return 0.8 * std::exp(-((x - 30) * (x - 30) + (y - 20) * (y - 20)) / 20.0); });
  return solver;
}

// Also with two ADI passes per step (the second re-solves both sweeps with this step's across
// terms) and with the sweep order alternating (y first on odd steps): the mass equation stays
// exactly Crank-Nicolson in flux form. Parameters: (ADI passes, alternate sweep order).
class BoussinesqConservation : public ::testing::TestWithParam<std::pair<int, bool>> {};
INSTANTIATE_TEST_SUITE_P(AdiPasses, BoussinesqConservation,
                         ::testing::Values(std::pair{1, false}, std::pair{2, false}, std::pair{1, true},
                                           std::pair{2, true}));

TEST_P(BoussinesqConservation, ClosedBasinKeepsItsWaterToRoundOff) {
  const HarbourGrid harbour = testing::rough_basin();
  const std::unique_ptr<BoussinesqSolver> basin =
      hump_in_rough_basin(harbour, GetParam().first, GetParam().second);
  BoussinesqSolver& solver = *basin;
  const double initial_m3 = solver.water_volume_m3();
  double worst_relative = 0.0, wetted = 0.0;
  for (int i = 0; i < 400; ++i) {
    solver.step();
    worst_relative = std::max(worst_relative, std::abs(solver.water_volume_m3() / initial_m3 - 1.0));
    for (int r = 0; r < 40; ++r)  // deepest water seen on initially dry land (the beach wets)
      for (int c = 0; c < 60; ++c)
        if (harbour.still_water_depth_m(c, r) < 0.0)
          wetted = std::max(wetted,
                            harbour.still_water_depth_m(c, r) + double(solver.surface_elevation_m()(c, r)));
  }
  ASSERT_FALSE(solver.check_stability().has_value()) << solver.check_stability()->what;
  // Flux form: every face flux leaves one cell and enters the next, and the shoreline repair
  // moves water between neighbours; what is left is round-off of ~1e-16 per step and cell.
  EXPECT_LT(worst_relative, 1e-12);
  // The waves must actually have run up the beach for this to test wetting and drying.
  std::printf("worst relative volume change %.3g, highest water depth on initially dry land %.3f m\n",
              worst_relative, wetted);
  EXPECT_GT(wetted, 0.02);
}

TEST(BoussinesqDeterminism, OneAndTwoThreadsGiveBitIdenticalResults) {
  const HarbourGrid harbour = testing::rough_basin();
  for (const bool alternate : {false, true}) {
    auto run = [&](int threads) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      SolverParameters parameters;
      parameters.alternate_sweep_order = alternate;
      parameters.dispersion_cutoff_depth_m = 0.3;
      parameters.sponges = {{Side::kWest, 6.0}, {Side::kEast, 6.0}};
      WaveMaker maker;
      maker.kind = WaveMaker::Kind::kComponents;
      maker.sea_state.components = {{0.2, 2.0 * 3.14159 / 4.0, 0.3, 0.0},
                                    {0.1, 2.0 * 3.14159 / 3.0, -0.2, 1.0}};
      maker.source_line_m = 12.0;
      maker.facing = Side::kWest;
      BoussinesqSolver solver(harbour, parameters, maker);
      for (int i = 0; i < 150; ++i) solver.step();
      Raster<float> flux_x, flux_y;
      solver.cell_centred_fluxes(flux_x, flux_y);
      std::vector<float> all = solver.surface_elevation_m().values();
      all.insert(all.end(), flux_x.values().begin(), flux_x.values().end());
      all.insert(all.end(), flux_y.values().begin(), flux_y.values().end());
      all.insert(all.end(), solver.breaking_indicator().values().begin(),
                 solver.breaking_indicator().values().end());
      return all;
    };
    const std::vector<float> one = run(1), two = run(2);
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(float)), 0);
    double largest = 0.0;
    for (float v : one) largest = std::max(largest, std::abs(double(v)));
    EXPECT_GT(largest, 0.01);  // something happened
  }
}

// A symmetric hump in a square flat basin stays symmetric about the diagonal in the exact
// equations; the splitting error of the sweeps breaks that symmetry. Measured, as a guard: with the
// fixed x-then-y order and one ADI pass the asymmetry stays near 0.06 % of the surface elevation;
// alternating the order trades the fixed order's steady bias (which under-focuses the Berkhoff
// peaks) for a fluctuating error, ~10 times larger here but still within 1 % (docs/solver.md,
// "Sweep order"). With the default two passes (since 2026-11-28) the fixed order's asymmetry is
// 1.4e-4 and alternation's 4.8e-4; the bounds below are the one-pass guards, kept.
TEST(BoussinesqSweepOrder, DiagonalSymmetryOfAHumpHoldsToTheSplittingError) {
  auto asymmetry = [](bool alternate, Equations equations) {
    const HarbourGrid harbour = testing::flume(48, 48, 0.5, 2.0);
    SolverParameters parameters = testing::inviscid_parameters(1.0);
    parameters.alternate_sweep_order = alternate;
    parameters.equations = equations;
    BoussinesqSolver solver(harbour, parameters, WaveMaker{});
    // Off the centre along the diagonal, so waves reach the walls at different times.
    solver.set_surface_elevation([](double x, double y) {
      return 0.3 * std::exp(-((x - 9.0) * (x - 9.0) + (y - 9.0) * (y - 9.0)) / 4.0);
    });
    double worst = 0.0, largest = 0.0;
    for (int i = 0; i < 300; ++i) {
      solver.step();
      const Raster<float>& eta = solver.surface_elevation_m();
      for (int r = 0; r < 48; ++r)
        for (int c = 0; c < 48; ++c) {
          worst = std::max(worst, std::abs(double(eta(c, r)) - double(eta(r, c))));
          largest = std::max(largest, std::abs(double(eta(c, r))));
        }
    }
    return worst / largest;
  };
  // The seed's equations: the splitting error of their across terms.
  const double fixed = asymmetry(false, Equations::kWeaklyNonlinear), alternating = asymmetry(true, Equations::kWeaklyNonlinear);
  std::printf(
      "seed's equations: largest |eta(x, y) - eta(y, x)| / max |eta| over 300 steps: fixed order %.3e, alternating %.3e\n",
      fixed, alternating);
  EXPECT_LT(fixed, 1e-3);
  EXPECT_LT(alternating, 1e-2);
  // The fully nonlinear terms add across terms of the same kind, O(eta/d) of the seed's (the hump
  // is 0.15 d high), which the first sweep also takes with its lagged estimate of the other flux's
  // rate: measured 4.4e-3 and 1.6e-2 at Courant 1 with one pass (2026-11-27; two passes: 1.3e-3 and
  // 2.7e-3). The guard: 6e-3 and 2.5e-2.
  const double fixed_full = asymmetry(false, Equations::kFullyNonlinear), alternating_full = asymmetry(true, Equations::kFullyNonlinear);
  std::printf("fully nonlinear equations: fixed order %.3e, alternating %.3e\n", fixed_full, alternating_full);
  EXPECT_LT(fixed_full, 6e-3);
  EXPECT_LT(alternating_full, 2.5e-2);
}

// Crossing waves and the number of ADI passes (docs/solver.md, "ADI passes"). The standing mode
// cos(k_x x) cos(k_y y) at 45 degrees in a closed flat basin is two wave trains crossing at right
// angles; Crank-Nicolson keeps a linear mode's energy, so any loss is the splitting. The first sweep
// of a step takes the across terms (the other flux's rate in -(B + 1/3) d^2 Q_xyt) from last step's
// increment, and each further pass is one block Gauss-Seidel step of the two momentum equations:
// in Fourier space (1 + a^2) P_t + a b Q_t = R_x and a b P_t + (1 + b^2) Q_t = R_y, with
// a = k_x c, b = k_y c, c^2 = (B + 1/3) d^2, whose iteration shrinks the lag by the factor
// (a b)^2 / ((1 + a^2)(1 + b^2)) per pass. So the loss per period of p passes is the one-pass loss
// times that factor to the power p - 1 (at 45 degrees: 0.028 at k d = 1, 0.20 at k d = 2).
// Measured 2026-11-28 (Courant 0.5, 20 cells per wavelength along each axis): one pass loses 4.1 %
// and 7.0 % of the amplitude per period at k d = 1 and 2; two passes 0.116 % and 1.19 % (predicted
// 0.115 % and 1.39 %); three 0.005 % and 0.23 % (predicted 0.003 % and 0.27 %). The test holds one
// pass to a loss of at least 2 % (the lag it measures is there), each further pass to 1.5 times the
// prediction plus 2e-4 (the amplitude's reading from sampled peaks), and the default to two passes.

// Loss of amplitude per period of the 45-degree standing mode at k d, with `passes` sweep pairs.
double oblique_mode_loss_per_period(double kd, int passes) {
  constexpr int kCells = 40;
  constexpr double kDx = 0.5;
  const double k_axis = 2.0 * std::numbers::pi / (20 * kDx), k = std::hypot(k_axis, k_axis), depth_m = kd / k;
  const HarbourGrid harbour = testing::flume(kCells, kCells, kDx, depth_m);
  SolverParameters parameters = testing::inviscid_parameters(0.5);
  parameters.adi_passes = passes;
  BoussinesqSolver solver(harbour, parameters, WaveMaker{});
  const double amplitude_m = 1e-5 * depth_m;  // linear
  solver.set_surface_elevation([&](double x, double y) { return amplitude_m * std::cos(k_axis * x) * std::cos(k_axis * y); });
  // The mode's shape at the cell centres, and its norm, once.
  std::vector<double> shape(kCells * kCells);
  double norm = 0.0;
  for (int row = 0; row < kCells; ++row)
    for (int column = 0; column < kCells; ++column) {
      const double value = std::cos(k_axis * (column + 0.5) * kDx) * std::cos(k_axis * (row + 0.5) * kDx);
      shape[row * kCells + column] = value;
      norm += value * value;
    }
  // The mode's amplitude: the projection of eta on its shape, every step; its extremes located by
  // a parabola through the three samples around each, so the reading does not depend on where the
  // steps fall in the period.
  auto projection = [&] {
    const Raster<float>& eta = solver.surface_elevation_m();
    double along = 0.0;
    for (int row = 0; row < kCells; ++row)
      for (int column = 0; column < kCells; ++column) along += eta(column, row) * shape[row * kCells + column];
    return along / norm;
  };
  std::vector<double> samples{projection()}, extremes;
  const double omega = k * std::sqrt(kGravity_m_s2 * depth_m * std::tanh(kd) / kd);
  const int steps = static_cast<int>(10 * 2 * std::numbers::pi / omega / solver.time_step_s());
  for (int i = 0; i < steps; ++i) {
    solver.step();
    samples.push_back(projection());
    const std::size_t n = samples.size();
    if (n < 3) continue;
    const double before = std::abs(samples[n - 3]), at = std::abs(samples[n - 2]), after = std::abs(samples[n - 1]);
    if (at > before && at >= after) extremes.push_back(at + 0.125 * (after - before) * (after - before) / (2 * at - before - after));
  }
  // Two extremes per period; the first period is left out (the start from rest in the fluxes).
  const double half_periods = static_cast<double>(extremes.size() - 3);
  return 1.0 - std::pow(extremes.back() / extremes[2], 2.0 / half_periods);
}

TEST(BoussinesqAdiPasses, CrossingWavesLoseOnlyTheSplittingLagOfTheLastPass) {
  EXPECT_EQ(SolverParameters{}.adi_passes, 2);
  const double dispersion_coefficient = SolverParameters{}.dispersion_coefficient;  // B, the one the runs use
  for (double kd : {1.0, 2.0}) {
    const double a2 = (dispersion_coefficient + 1.0 / 3.0) * 0.5 * kd * kd;  // (k_x c)^2 = (k_y c)^2 at 45 degrees
    const double factor = a2 * a2 / ((1.0 + a2) * (1.0 + a2));
    const double one_pass = oblique_mode_loss_per_period(kd, 1);
    std::printf("k d = %.1f: amplitude lost per period: 1 pass %.4f %%", kd, 100 * one_pass);
    EXPECT_GT(one_pass, 0.02) << "k d = " << kd;
    for (int passes : {2, 3}) {
      const double loss = oblique_mode_loss_per_period(kd, passes);
      const double predicted = one_pass * std::pow(factor, passes - 1);
      std::printf(", %d passes %.4f %% (predicted %.4f %%)", passes, 100 * loss, 100 * predicted);
      EXPECT_LT(std::abs(loss), 1.5 * predicted + 2e-4) << "k d = " << kd << ", " << passes << " passes";
    }
    std::printf("\n");
  }
}

}  // namespace
}  // namespace nearshore::boussinesq
