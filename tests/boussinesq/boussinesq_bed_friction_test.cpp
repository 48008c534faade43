// Bed friction (issue 19): the bed stress is the larger of the Chezy stress and the laminar film's
// Poiseuille stress tau_b = 3 rho nu u / h (docs/solver.md, "Bed friction"). A uniform current on
// a flat bed has no gradients, so the momentum equation of the flux form reduces to
// dP/dt = -r P with r = 3 nu / h^2 (laminar) or g |P| / (C^2 h^2) (Chezy): its decay is the
// analytic check.
#include <gtest/gtest.h>

#include <cmath>

#include "boussinesq_test_support.hpp"
#include "nearshore/ocean/wave_component.hpp"

namespace nearshore::boussinesq {
namespace {

constexpr double kViscosity_m2_s = 1.0e-6;  // fresh water at 20 C

struct CurrentRun {
  double flux_m2_s = 0.0;  // P in the middle of the flume after `duration_s`
  double duration_s = 0.0;
};

// A closed flat flume of 800 x 3 cells of 1 cm, `depth_m` deep, starting from a uniform current of
// speed `speed_m_s` along x; the middle is read after `duration_s`. The walls stop the current at
// the ends, and what they send travels at most at u + sqrt(g h): 0.8 m/s at 2.5 cm and 0.3 m/s,
// 0.18 m/s at 3 mm, so for the durations below it stays more than 0.8 m from the middle.
CurrentRun run_uniform_current(double depth_m, double speed_m_s, double duration_s, double chezy, double viscosity_m2_s) {
  const HarbourGrid flume = testing::flume(800, 3, 0.01, depth_m);
  SolverParameters parameters = testing::inviscid_parameters();
  parameters.chezy_coefficient = chezy;
  parameters.kinematic_viscosity_m2_s = viscosity_m2_s;
  parameters.dry_depth_m = 0.001;
  BoussinesqSolver solver(flume, parameters, WaveMaker{});
  const double flux = speed_m_s * depth_m;
  solver.set_initial_condition([](double, double) { return 0.0; }, [&](double, double) { return flux; },
                               [](double, double) { return 0.0; });
  while (solver.time_s() < duration_s - 1e-9) solver.step();
  Raster<float> flux_x, flux_y;
  solver.cell_centred_fluxes(flux_x, flux_y);
  return {flux_x(400, 1), solver.time_s()};
}

// A 3 mm film moving at 1 cm/s (film Reynolds number u h / nu = 30: laminar) loses its momentum
// at r = 3 nu / h^2 = 0.33 /s. Tolerance 1 %: the implicit (backward Euler) resistance decays by
// 1/(1 + r dt) per step instead of exp(-r dt), a relative error of r^2 dt t / 2 = 0.2 % here
// (dt = 0.03 s, t = 1.5 s), and the float output rounds at 1e-7.
TEST(BedFriction, LaminarFilmDecaysAtThePoiseuilleRate) {
  const double depth = 0.003, speed = 0.01;
  // Chezy 60 is on as in every bake: its rate g u / (C^2 h) = 0.009 /s is the smaller one here.
  const CurrentRun run = run_uniform_current(depth, speed, 1.5, 60.0, kViscosity_m2_s);
  const double rate = 3.0 * kViscosity_m2_s / (depth * depth);
  const double expected = speed * depth * std::exp(-rate * run.duration_s);
  EXPECT_NEAR(run.flux_m2_s / expected, 1.0, 0.01) << "P " << run.flux_m2_s << " m^2/s after " << run.duration_s
                                                   << " s, Poiseuille decay " << expected;
  // Without the viscosity the same film keeps nearly all of it (the Chezy rate alone).
  const CurrentRun turbulent_only = run_uniform_current(depth, speed, 1.5, 60.0, 0.0);
  EXPECT_GT(turbulent_only.flux_m2_s, 0.98 * speed * depth);
}

// A current 2.5 cm deep at 0.3 m/s (u h / nu = 7500, turbulent) is the Chezy stress's alone: the
// laminar stress (rate 0.005 /s against Chezy's 0.033 /s) is the smaller, so the viscosity changes
// no bit. Its decay follows dP/dt = -g P^2 / (C^2 h^2), i.e. P = P0 / (1 + g P0 t / (C^2 h^2)),
// 12 % over 4 s; tolerance 1 % as above (r^2 dt t / 2 = 2e-5).
TEST(BedFriction, ATurbulentCurrentFeelsTheChezyStressAlone) {
  const double depth = 0.025, speed = 0.3, chezy = 60.0;
  const CurrentRun with_viscosity = run_uniform_current(depth, speed, 4.0, chezy, kViscosity_m2_s);
  const CurrentRun without = run_uniform_current(depth, speed, 4.0, chezy, 0.0);
  EXPECT_EQ(with_viscosity.flux_m2_s, without.flux_m2_s);
  const double initial = speed * depth;
  const double expected = initial / (1.0 + ocean::kGravity_m_s2 * initial * with_viscosity.duration_s / (chezy * chezy * depth * depth));
  EXPECT_NEAR(with_viscosity.flux_m2_s / expected, 1.0, 0.01) << "P " << with_viscosity.flux_m2_s << " m^2/s, Chezy decay " << expected;
}

}  // namespace
}  // namespace nearshore::boussinesq
