// Rectangular cells, dx != dy (issue 15). Every difference operator of the scheme divides by its
// own axis' cell size; these tests check it against linear theory and guard the square scheme.
//
// Phase speed. A standing wave cos(k x) (or cos(k y)) in a closed basin is an exact eigenmode of
// the staggered scheme (boussinesq_dispersion_test.cpp), so its period is the scheme's own
// dispersion relation. Its prediction, derived here: on the staggered grid every second difference
// of cos(k x) with spacing D gives -k_D^2 cos(k x), k_D = (2/D) sin(k D/2), for the gravity term
// (eta_x of the flux divergence), the dispersive flux term P_xxt and the third differences of eta,
// so the semi-discrete model is Madsen & Sorensen (1992) eq. 12 with k replaced by k_D:
//   w_D^2 = g d k_D^2 (1 + B (k_D d)^2) / (1 + (B + 1/3) (k_D d)^2),
// and the time-centred (Crank-Nicolson) step keeps the period of an oscillator w_D up to the lag
// tan(w dt/2) = w_D dt/2, i.e. w = (2/dt) atan(w_D dt/2). The measured phase speed must match this
// prediction made with THE AXIS' OWN spacing; a solver that differentiated along y with dx (or
// the reverse) would miss it by the difference of sin(k dx/2)/(k dx/2) and sin(k dy/2)/(k dy/2),
// 1.2 % at 10 and 20 cells per wavelength, while the prediction must hold to 0.05 % (a margin for
// the iterated dispersive terms and the zero-crossing interpolation; measured 2e-6 along an axis).
// Against the continuous M&S speed the grid's truncation error bounds the difference:
// 1 - k_D/k = 1 - sinc(k D/2) <= (k D)^2/24 in c, plus the Crank-Nicolson lag (w dt)^2/12.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "boussinesq_test_support.hpp"
#include "nearshore/core/error.hpp"
#include "square_regression_scenario.hpp"

namespace nearshore::boussinesq {

using namespace nearshore::ocean;
namespace {

// Madsen & Sorensen (1992) angular frequency of the continuous equations for wavenumber k, with the
// B the solver runs with.
double model_frequency(double k, double depth_m) {
  const double b = SolverParameters{}.dispersion_coefficient;
  const double kd2 = k * k * depth_m * depth_m;
  return k * std::sqrt(kGravity_m_s2 * depth_m * (1.0 + b * kd2) / (1.0 + (b + 1.0 / 3.0) * kd2));
}
// The staggered grid's wavenumber for k on spacing D (header comment).
double grid_wavenumber(double k, double spacing_m) { return 2.0 / spacing_m * std::sin(0.5 * k * spacing_m); }

struct Mode {
  double kx = 0.0, ky = 0.0;  // rad/m, along x and y (a standing wave cos(kx x) cos(ky y))
};

double measured_period_s(BoussinesqSolver& solver) { return testing::standing_mode_period_s(solver); }

struct PhaseSpeed {
  double measured = 0.0, predicted = 0.0, continuous = 0.0, truncation_bound = 0.0, time_step_s = 0.0;
};

// A closed basin of columns x rows cells of dx x dy and depth d holding the mode; its phase speed
// measured, predicted on the grid (header) and in the continuous model.
PhaseSpeed phase_speed(int columns, int rows, double dx, double dy, double depth_m, Mode mode) {
  HarbourGrid harbour = testing::flume(columns, rows, dx, depth_m);
  harbour.geometry.set_spacing(dx, dy);
  BoussinesqSolver solver(harbour, testing::inviscid_parameters(0.5), WaveMaker{});
  const double amplitude_m = 1e-5 * depth_m;  // linear
  solver.set_surface_elevation([&](double x, double y) { return amplitude_m * std::cos(mode.kx * x) * std::cos(mode.ky * y); });
  const double period_s = measured_period_s(solver);
  const double k = std::hypot(mode.kx, mode.ky), dt = solver.time_step_s();
  const double k_grid = std::hypot(grid_wavenumber(mode.kx, dx), grid_wavenumber(mode.ky, dy));
  PhaseSpeed c;
  c.time_step_s = dt;
  c.measured = 2.0 * std::numbers::pi / period_s / k;
  c.predicted = 2.0 / dt * std::atan(0.5 * dt * model_frequency(k_grid, depth_m)) / k;
  c.continuous = model_frequency(k, depth_m) / k;
  const double w = model_frequency(k, depth_m);
  const double kd = std::max(mode.kx * dx, mode.ky * dy);
  c.truncation_bound = kd * kd / 24.0 + w * w * dt * dt / 12.0;
  return c;
}

// FUNWAVE's Berkhoff grid has dy = 2 dx; so do these basins (dx = 0.5 m, dy = 1 m). A wave of
// 10 m at k d = 1 has 20 cells per wavelength along x and 10 along y.
constexpr double kDx = 0.5, kDy = 1.0, kWavelength_m = 10.0;

TEST(BoussinesqRectangularCells, PlaneWaveAlongXHasThePhaseSpeedOfItsSpacing) {
  const double k = 2.0 * std::numbers::pi / kWavelength_m, depth_m = 1.0 / k;
  const PhaseSpeed c = phase_speed(40, 3, kDx, kDy, depth_m, {k, 0.0});
  std::printf("along x (dx = %.2f m): c/c_grid - 1 = %+.4f %%, c/c_MS - 1 = %+.3f %% (bound %.3f %%)\n", kDx,
              100 * (c.measured / c.predicted - 1), 100 * (c.measured / c.continuous - 1), 100 * c.truncation_bound);
  EXPECT_NEAR(c.measured / c.predicted, 1.0, 5e-4);
  EXPECT_LT(std::abs(c.measured / c.continuous - 1.0), c.truncation_bound);
}

TEST(BoussinesqRectangularCells, PlaneWaveAlongYHasThePhaseSpeedOfItsSpacing) {
  const double k = 2.0 * std::numbers::pi / kWavelength_m, depth_m = 1.0 / k;
  const PhaseSpeed c = phase_speed(3, 20, kDx, kDy, depth_m, {0.0, k});
  std::printf("along y (dy = %.2f m): c/c_grid - 1 = %+.4f %%, c/c_MS - 1 = %+.3f %% (bound %.3f %%)\n", kDy,
              100 * (c.measured / c.predicted - 1), 100 * (c.measured / c.continuous - 1), 100 * c.truncation_bound);
  EXPECT_NEAR(c.measured / c.predicted, 1.0, 5e-4);
  EXPECT_LT(std::abs(c.measured / c.continuous - 1.0), c.truncation_bound);
  // The prediction on the wrong axis' spacing is 1.2 % off: the check above tells the two apart.
  const double wrong = grid_wavenumber(k, kDx) / grid_wavenumber(k, kDy) - 1.0;
  EXPECT_GT(std::abs(wrong), 20 * 5e-4);
}

// The oblique mode cos(kx x) cos(ky y) on the rectangular grid: the cross-derivative dispersive
// terms (Q_xyt, eta_xyy of eq. 4) and the cross convection differentiate along x with dx and along
// y with dy; with kx dx = ky dy each axis has 20 cells per wavelength of its own. Two checks:
// 1. Against the prediction, within the ADI splitting error: the x sweep takes the across terms
//    lagged (docs/solver.md "Discretisation"), which shifts the frequency of a 2-D mode by
//    C (w dt)^2 sin^2(2 theta) (theta the direction; 0 along an axis, where the 1-D tests above hold
//    to 1e-6). On square cells at 45 deg C is 0.6/16 at k d = 0.5 and 1.16/16 at k d = 1.5
//    (measured), so the bound is (w dt)^2 sin^2(2 theta) / 8, twice the largest C, plus 5e-4.
// 2. The mirror image: the grid of dy = dx/2 holding the mode with ky doubled is the first grid
//    with the axes exchanged and all lengths halved (same k d, Courant number and cells per
//    wavelength); the scheme is symmetric in x and y, so both give the same c / c_grid (measured:
//    equal to 1e-6; 2e-5 allows the different round-off of the two sweeps' orders).
TEST(BoussinesqRectangularCells, ObliqueStandingWaveUsesBothSpacings) {
  for (double kd : {0.5, 1.5}) {
    double ratio[2] = {0.0, 0.0};
    for (int mirror = 0; mirror < 2; ++mirror) {
      const double dy = mirror ? 0.5 * kDx : kDy;  // dy = 2 dx, then its mirror image dy = dx / 2
      const double kx = 2.0 * std::numbers::pi / (20 * kDx), ky = 2.0 * std::numbers::pi / (20 * dy), k = std::hypot(kx, ky), depth_m = kd / k;
      const PhaseSpeed c = phase_speed(40, 40, kDx, dy, depth_m, {kx, ky});
      const double w_dt = model_frequency(k, depth_m) * c.time_step_s, sin_2theta = 2.0 * kx * ky / (k * k);
      const double splitting_bound = w_dt * w_dt * sin_2theta * sin_2theta / 8.0;
      ratio[mirror] = c.measured / c.predicted;
      std::printf("oblique, dy = %.2f m, k d = %.1f: c/c_grid - 1 = %+.4f %% (ADI bound %.3f %%), c/c_MS - 1 = %+.3f %% (bound %.3f %%)\n",
                  dy, kd, 100 * (ratio[mirror] - 1), 100 * splitting_bound, 100 * (c.measured / c.continuous - 1),
                  100 * (c.truncation_bound + splitting_bound));
      EXPECT_NEAR(ratio[mirror], 1.0, 5e-4 + splitting_bound) << "k d = " << kd << ", dy = " << dy;
      EXPECT_LT(std::abs(c.measured / c.continuous - 1.0), c.truncation_bound + splitting_bound) << "k d = " << kd;
    }
    EXPECT_NEAR(ratio[0], ratio[1], 2e-5) << "k d = " << kd << ": the mirror-image grids differ";
  }
}

// The time step follows the smaller spacing: a Courant number sqrt(g d) dt / min(dx, dy).
TEST(BoussinesqRectangularCells, TimeStepFollowsTheSmallerSpacing) {
  HarbourGrid harbour = testing::flume(20, 10, 0.2, 1.0);
  harbour.geometry.set_spacing(0.2, 0.05);
  const BoussinesqSolver solver(harbour, testing::inviscid_parameters(0.5), WaveMaker{});
  EXPECT_DOUBLE_EQ(solver.time_step_s(), 0.5 * 0.05 / std::sqrt(kGravity_m_s2 * 1.0));
  SolverParameters too_long = testing::inviscid_parameters();
  too_long.time_step_s = 3.0 * 0.05 / std::sqrt(kGravity_m_s2 * 1.0);  // Courant 3 on dy
  EXPECT_THROW(BoussinesqSolver(harbour, too_long, WaveMaker{}), nearshore::Error);
}

// Mass on rectangular cells: the hump of the conservation test in the rough basin with dy = 2 dx
// (waves through the breakwater, against the quay and up the island's beach): the closed basin
// keeps n h dx dy summed to round-off.
TEST(BoussinesqRectangularCells, ClosedBasinKeepsItsWaterToRoundOff) {
  HarbourGrid harbour = testing::rough_basin();
  harbour.geometry.set_spacing(1.0, 2.0);
  SolverParameters parameters;
  parameters.dispersion_cutoff_depth_m = 0.3;
  BoussinesqSolver solver(harbour, parameters, WaveMaker{});
  solver.set_surface_elevation(
      [](double x, double y) { return 0.8 * std::exp(-((x - 30) * (x - 30) + (y - 40) * (y - 40) / 4.0) / 20.0); });
  const double start_m3 = solver.water_volume_m3();
  for (int i = 0; i < 300; ++i) solver.step();
  ASSERT_FALSE(solver.check_stability().has_value());
  // 300 steps of sums over 2400 cells of ~10 m^3: round-off ~1e-13 relative per step.
  EXPECT_NEAR(solver.water_volume_m3() / start_m3, 1.0, 1e-11);
}

// Square cells are bit for bit the scheme before rectangular cells: the XXH64 of the saved state
// of the regression scenario (square_regression_scenario.hpp), recorded with the solver of commit
// 0821369 (before issue 15's rectangular cells) built by this repository's CMake (the sweep and the
// filter with -ffp-contract=off, so every instruction-set clone gives these bits). Re-recorded once
// since, for issue 19's discrete source transfer (boussinesq_source.cpp): the scenario's wave maker
// sends a slightly different strength, so every bit moves; with the source of before that change the
// solver of that day still gave 0xea7615439be2747b (checked 2026-11-24). Re-recorded again for
// Kennedy et al.'s breaking thresholds on the still-water depth (issue 19): the hump breaks on the
// island within the 120 steps; with the thresholds on the total depth the solver of 2026-11-27 gives
// the hash before, 0x10f8ad8cc6d9365e. And again for the laminar film's bed stress (issue 19,
// docs/solver.md "Bed friction"): the bed stress is now the larger of the Chezy and the Poiseuille
// stress, and the Poiseuille one wins wherever |(P, Q)| < 3 nu C^2 / g = 1.1e-3 m^2/s, the calm
// cells of the basin, so every bit moves; before it the hash was 0xc03b0e721e2203a1.
// The hash is recorded at a physics revision (docs/solver.md, "Physics revision"): a change that
// moves it on purpose re-records it AND raises kSolverPhysicsRevision, so that no bake resumes a
// checkpoint of the other physics. Revision 2 (the fully nonlinear terms fade where cells break)
// left this scenario's bits as they were: it runs the seed's equations, which have no such terms;
// the hash was checked unchanged at revision 2. Revision 3 (on an imposed current, the Courant
// number counts it and the wave maker checks its second-harmonic correction) changes nothing without
// a current, and this scenario has none: the hash was checked unchanged at revision 3. Revision 4
// re-records it (2026-12-01): the scenario's island is land under the grid-scale filter, so the
// dispersive terms beside it now rise over the filter's half-stencil (taper_dispersion_at_walls);
// with the taper off the solver of revision 4 still gives revision 3's hash, 0x45355de31ccf514b
// (its wave maker makes one wave, whose source width did not change).
TEST(BoussinesqRectangularCells, SquareCellsAreBitIdenticalToTheSquareScheme) {
  constexpr std::uint64_t kStateHashBeforeRectangularCells = 0x7ddc8cc9457bd5faull;
  constexpr int kRecordedAtPhysicsRevision = 4;
  EXPECT_EQ(testing::square_regression_state_hash(), kStateHashBeforeRectangularCells)
      << std::hex << "state hash 0x" << testing::square_regression_state_hash()
      << ": if the physics changed on purpose, re-record the hash and raise kSolverPhysicsRevision with it";
  EXPECT_EQ(kSolverPhysicsRevision, kRecordedAtPhysicsRevision)
      << "the revision moved: re-record the hash above at the new revision (and say why in the comment)";
}

}  // namespace
}  // namespace nearshore::boussinesq
