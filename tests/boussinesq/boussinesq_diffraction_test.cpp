// Diffraction and reflection of small regular waves by a vertical circular cylinder in constant
// depth against the linear theory of MacCamy & Fuchs (1954): the amplitude round the cylinder's wall,
// along its lee and in front of it, for a cylinder of land cells and for one of wall cells
// (porosity 0), the two ways a harbour grid carries a quay or a pier. Numbers and the figure:
// docs/validation.md, "Diffraction by a vertical cylinder".
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/incident_reflected.hpp"
#include "boussinesq_test_support.hpp"
#include "nearshore/boussinesq/model_dispersion.hpp"
#include "nearshore/plot/plot.hpp"

namespace nearshore::boussinesq {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;

Complex hankel(int m, double z) { return {std::cyl_bessel_j(m, z), std::cyl_neumann(m, z)}; }
double bessel_j_derivative(int m, double z) {
  return m == 0 ? -std::cyl_bessel_j(1, z) : 0.5 * (std::cyl_bessel_j(m - 1, z) - std::cyl_bessel_j(m + 1, z));
}
Complex hankel_derivative(int m, double z) { return m == 0 ? -hankel(1, z) : 0.5 * (hankel(m - 1, z) - hankel(m + 1, z)); }

// |eta| / A at (r, theta) round a cylinder of radius a at the origin in an incident wave
// A exp(i (k x - w t)), theta from the direction of travel (0 = the lee, 180 degrees = the front):
// MacCamy & Fuchs (1954), the total field
//   eta = A sum_m eps_m i^m [J_m(kr) - J_m'(ka) H_m(kr) / H_m'(ka)] cos(m theta),  eps_0 = 1, eps_m = 2,
// H_m the Hankel function of the first kind (outgoing with exp(-i w t)). The series converges once
// m exceeds k r; twenty terms beyond it leave < 1e-12.
double maccamy_fuchs_amplitude(double k, double a, double r, double theta) {
  Complex sum = 0.0, i_power = 1.0;
  const int terms = static_cast<int>(k * r) + 20;
  for (int m = 0; m < terms; ++m, i_power *= Complex(0.0, 1.0)) {
    const Complex radial = std::cyl_bessel_j(m, k * r) - bessel_j_derivative(m, k * a) * hankel(m, k * r) / hankel_derivative(m, k * a);
    sum += (m == 0 ? 1.0 : 2.0) * i_power * radial * std::cos(m * theta);
  }
  return std::abs(sum);
}

// The amplitude of the first harmonic of eta at each point over the last `window_s` seconds up to
// `end_s` (whole periods): the least-squares amplitude of that frequency,
// nearshore::testing::harmonic_amplitude (tests/support/incident_reflected.hpp).
std::vector<double> first_harmonic_amplitudes(BoussinesqSolver& solver, const std::vector<std::array<double, 2>>& points, double omega,
                                              double end_s, double window_s) {
  std::vector<std::vector<double>> records(points.size());
  double record_start_s = -1.0;
  while (solver.time_s() < end_s) {
    solver.step();
    if (solver.step_count() % 100 == 0 && solver.check_stability()) break;  // reported below
    // One step early, so the record spans the whole window.
    if (solver.time_s() < end_s - window_s - solver.time_step_s()) continue;
    if (record_start_s < 0.0) record_start_s = solver.time_s();
    for (std::size_t p = 0; p < points.size(); ++p) records[p].push_back(solver.surface_elevation_at(points[p][0], points[p][1]));
  }
  std::vector<double> amplitude(points.size(), 0.0);
  if (const auto report = solver.check_stability()) {
    ADD_FAILURE() << "unstable at t = " << report->time_s << " s, x = " << report->x_m << " m, y = " << report->y_m << " m: " << report->what;
    return amplitude;
  }
  // The record's mean comes off first: the time step is no whole fraction of the period, so a mean
  // would leak into the amplitude (the waves' second-order set-down, for one).
  for (std::size_t p = 0; p < points.size(); ++p) {
    std::vector<double>& record = records[p];
    const double mean = std::accumulate(record.begin(), record.end(), 0.0) / static_cast<double>(record.size());
    for (double& eta : record) eta -= mean;
    amplitude[p] = std::abs(nearshore::testing::harmonic_amplitude(record, record_start_s, solver.time_step_s(), omega));
  }
  return amplitude;
}

enum class Cylinder { kLand, kWall };

struct Probe {
  double r_over_a, theta_deg;
};

struct CylinderRun {
  double wavenumber = 0, radius_m = 0, incident_amplitude_m = 0;
  std::vector<Probe> probes;
  std::vector<double> model, theory;  // |eta| / A
};

// A basin 21 x 14 m, 0.5 m deep, T = 2 s (k d = 0.78), A = 4 mm (k A = 0.006: linear), k a = 1.
// The south edge (a wall) is the cylinder's plane of symmetry: its centre lies on it, so the basin
// holds half the cylinder. The north edge is a wall 14 m away: the waves the cylinder scatters come
// back from it after 2 x 14 m / c_g = 17 s, after the 8 s record that ends at t = 20 s; a sponge
// there instead would damp the incident wave along it and send its shadow into the basin
// (docs/solver.md, "Sponge layers"). Sponges behind the source line (2 m) and at the far end (4 m).
// The incident amplitude is measured at the cylinder's place in the same flume without it.
CylinderRun run_cylinder(Cylinder kind, double spacing_m, int shapiro_filter_order, double end_s = 20.0) {
  const double depth_m = 0.5, period_s = 2.0, amplitude_m = 0.004;
  const double omega = 2.0 * kPi / period_s;
  SolverParameters parameters = testing::inviscid_parameters(0.5);
  parameters.shapiro_filter_order = shapiro_filter_order;
  parameters.sponges = {{Side::kWest, 2.0}, {Side::kEast, 4.0}};
  const double k = boussinesq_wavenumber(omega, depth_m, parameters.dispersion_coefficient);
  const double radius_m = 1.0 / k, centre_x_m = 7.5, window_s = 4.0 * period_s;
  const int columns = static_cast<int>(std::lround(21.0 / spacing_m)), rows = static_cast<int>(std::lround(14.0 / spacing_m));
  WaveMaker maker;
  maker.kind = WaveMaker::Kind::kComponents;
  maker.sea_state.components = {{amplitude_m, omega, 0.0, 0.0}};
  maker.source_line_m = 3.0;
  maker.facing = Side::kWest;
  maker.ramp_time_s = 2.0 * period_s;

  CylinderRun run;
  run.wavenumber = k;
  run.radius_m = radius_m;
  {
    BoussinesqSolver flume(testing::flume(columns, 1, spacing_m, depth_m), parameters, maker);
    run.incident_amplitude_m = first_harmonic_amplitudes(flume, {{centre_x_m, 0.5 * spacing_m}}, omega, end_s, window_s)[0];
  }
  HarbourGrid harbour = testing::flume(columns, rows, spacing_m, depth_m);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      if (std::hypot((c + 0.5) * spacing_m - centre_x_m, (r + 0.5) * spacing_m) >= radius_m) continue;
      if (kind == Cylinder::kLand) {
        harbour.still_water_depth_m(c, r) = -1.0f;  // 1 m above still water: never wet
        harbour.land(c, r) = kLandCell;
      } else {
        harbour.porosity(c, r) = 0.0f;
      }
    }
  // Round the wall one cell out every 15 degrees, the lee out to 6 a and the front's standing wave
  // out to 3 a. A gauge one cell out can have a corner of its four cells in the cylinder (at 45
  // degrees); the gauge then interpolates over the three water cells (surface_elevation_at).
  const double wall = 1.0 + spacing_m / radius_m;
  for (int degrees = 0; degrees <= 180; degrees += 15) run.probes.push_back({wall, static_cast<double>(degrees)});
  for (double r : {1.5, 2.0, 3.0, 4.0, 6.0}) run.probes.push_back({r, 0.0});
  for (double r : {1.5, 2.0, 3.0}) run.probes.push_back({r, 180.0});
  std::vector<std::array<double, 2>> points;
  for (const Probe& p : run.probes) {
    const double r_m = p.r_over_a * radius_m, theta = p.theta_deg * kPi / 180.0;
    points.push_back({centre_x_m + r_m * std::cos(theta), std::max(r_m * std::sin(theta), 0.5 * spacing_m)});
  }
  BoussinesqSolver solver(harbour, parameters, maker);
  const std::vector<double> amplitudes = first_harmonic_amplitudes(solver, points, omega, end_s, window_s);
  for (std::size_t p = 0; p < points.size(); ++p) {
    run.model.push_back(amplitudes[p] / run.incident_amplitude_m);
    run.theory.push_back(maccamy_fuchs_amplitude(k, radius_m, run.probes[p].r_over_a * radius_m, run.probes[p].theta_deg * kPi / 180.0));
  }
  return run;
}

// The analytic series itself: on the wall, |eta| / A = (2 / (pi k a)) |sum eps_m i^m cos(m theta) / H_m'(ka)|
// (the Wronskian J_m H_m' - J_m' H_m = 2 i / (pi k a)), and far from a small cylinder the incident wave.
TEST(BoussinesqDiffraction, MacCamyFuchsSeriesMeetsItsClosedFormOnTheWall) {
  for (double ka : {0.3, 1.0, 2.0})
    for (double theta : {0.0, 1.0, kPi}) {
      Complex sum = 0.0, i_power = 1.0;
      for (int m = 0; m < 40; ++m, i_power *= Complex(0.0, 1.0))
        sum += (m == 0 ? 1.0 : 2.0) * i_power * std::cos(m * theta) / hankel_derivative(m, ka);
      EXPECT_NEAR(maccamy_fuchs_amplitude(1.0, ka, ka, theta), 2.0 / (kPi * ka) * std::abs(sum), 1e-9);
    }
  EXPECT_NEAR(maccamy_fuchs_amplitude(1.0, 0.01, 50.0, 0.0), 1.0, 1e-3);
}

// Grid: 0.1 m, a = 6.5 cells, 40 cells per wavelength, d / dx = 5. Every cylinder cell is a square,
// so the wall is a staircase whose faces lie up to dx/2 (0.08 a) off the circle; at 13 cells per
// radius (0.05 m, run with shapiro_filter_order = 0: the default filter is unstable there, see the
// disabled test below) the same comparison falls within 3 % everywhere (docs/validation.md), the
// staircase's first-order error halving with the cell. The record ends at 20 s, before the north
// wall's echo and well before this basin's own filter instability (t = 32 s). The bars: 10 % at any point on the wall and 5 %
// root mean square round it, 5 % along the lee and the front; land and wall cells are the same
// boundary to the solver's fluxes, so they agree within 0.5 %.
TEST(BoussinesqDiffraction, VerticalCylinderFollowsMacCamyFuchs) {
  const double spacing_m = 0.1;
  std::vector<PlotSeries> series;
  std::vector<double> land_model;
  for (Cylinder kind : {Cylinder::kLand, Cylinder::kWall}) {
    const CylinderRun run = run_cylinder(kind, spacing_m, SolverParameters{}.shapiro_filter_order);
    const std::string name = kind == Cylinder::kLand ? "land" : "wall (porosity 0)";
    std::printf("%s cylinder: k a = %.2f, a = %.3f m (%.1f cells), incident amplitude %.5f m\n", name.c_str(),
                run.wavenumber * run.radius_m, run.radius_m, run.radius_m / spacing_m, run.incident_amplitude_m);
    double wall_square_sum = 0.0;
    int wall_count = 0;
    PlotSeries model{"nearshore, land cells", {}, {}, {0.84f, 0.15f, 0.16f}, true};
    PlotSeries theory{"MacCamy & Fuchs (1954)", {}, {}, {0.12f, 0.47f, 0.71f}, false};
    for (std::size_t p = 0; p < run.probes.size(); ++p) {
      const double error = run.model[p] / run.theory[p] - 1.0;
      std::printf("  r/a %.2f theta %5.1f deg: |eta|/A model %.3f theory %.3f (%+.1f %%)\n", run.probes[p].r_over_a,
                  run.probes[p].theta_deg, run.model[p], run.theory[p], 100 * error);
      const bool on_wall = run.probes[p].r_over_a < 1.5;
      if (on_wall) {
        wall_square_sum += error * error;
        ++wall_count;
        EXPECT_LT(std::abs(error), 0.10) << name << " wall at " << run.probes[p].theta_deg << " degrees";
        model.x.push_back(run.probes[p].theta_deg);
        model.y.push_back(run.model[p]);
      } else {
        EXPECT_LT(std::abs(error), 0.05) << name << " at r/a = " << run.probes[p].r_over_a << ", " << run.probes[p].theta_deg << " degrees";
      }
    }
    const double wall_rms = std::sqrt(wall_square_sum / wall_count);
    std::printf("  round the wall: RMS error %.1f %%\n", 100 * wall_rms);
    EXPECT_LT(wall_rms, 0.05) << name;
    if (kind == Cylinder::kLand) {
      land_model = run.model;
      for (int degrees = 0; degrees <= 180; degrees += 2) {
        theory.x.push_back(degrees);
        theory.y.push_back(maccamy_fuchs_amplitude(run.wavenumber, run.radius_m, run.radius_m + spacing_m, degrees * kPi / 180.0));
      }
      series.push_back(theory);
    } else {
      for (std::size_t p = 0; p < run.model.size(); ++p) EXPECT_NEAR(run.model[p], land_model[p], 0.005 * land_model[p]);
    }
    if (kind == Cylinder::kLand) series.push_back(model);
  }
  LinePlot plot{"Small waves round a vertical cylinder: k a = 1, k d = 0.78, 6.5 cells per radius",
                "angle from the direction of travel (degrees; 0 = lee, 180 = front)", "amplitude one cell off the wall / incident amplitude",
                series, 900, 480};
  write_png(render_line_plot(plot), testing::plot_folder() / "cylinder_diffraction.png");
}

// KNOWN INSTABILITY, kept as a reproduction (run with --gtest_also_run_disabled_tests; 40 s):
// the same basin run on to t = 60 s becomes unstable at t = 32-34 s, 0.7 m off the cylinder's wall,
// with the default grid-scale filter (shapiro_filter_order = 8); without the filter it stays stable
// (and at 0.05 m cells, 13 per radius, it fails at t = 8 s with the filter and stays within 3 % of
// the theory without it). A square block aligned with the grid ran stable with these waves, but not
// from still water with noise (boussinesq_wall_test.cpp). What grows sits between the first row of cells
// beside the wall (neither dispersion nor filter) and the filtered rows behind it; docs/solver.md,
// "Grid-scale filter", lists what was tried.
TEST(BoussinesqDiffraction, DISABLED_StaircaseCylinderStaysStableWithTheGridScaleFilter) {
  const CylinderRun run = run_cylinder(Cylinder::kLand, 0.1, SolverParameters{}.shapiro_filter_order, 60.0);
  EXPECT_TRUE(std::all_of(run.model.begin(), run.model.end(), [](double amplitude) { return std::isfinite(amplitude); }));
}

}  // namespace
}  // namespace nearshore::boussinesq
