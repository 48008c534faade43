// A porous layer (seed 003 eq. (2)-(3)) against the analytic long-wave solution, and the flume that
// fits a layer's porosity to a requested reflection or transmission (porous_layer_flume.hpp).
// Numbers and the figure: docs/validation.md, "Porous layers: reflection and transmission".
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "boussinesq_test_support.hpp"
#include "nearshore/boussinesq/model_dispersion.hpp"
#include "nearshore/boussinesq/porous_layer_flume.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/ocean/linear_waves.hpp"
#include "nearshore/plot/plot.hpp"

namespace nearshore::boussinesq {
namespace {

using Complex = std::complex<double>;
using ocean::kGravity_m_s2;
constexpr double kPi = std::numbers::pi;

// The linear long-wave equations in a layer of porosity n with a linear resistance r (1/s), as the
// solver writes them (seed 003 eq. (1)-(2): n eta_t + P_x = 0, P_t + n g h eta_x + r P = 0), for
// exp(-i w t): eta_xx + k'^2 eta = 0 with k'^2 = k^2 (1 + i r / w), k = w / sqrt(g h), and the flux
// of a wave travelling towards +x is P = Z' eta with Z' / Z = n / sqrt(1 + i r / w) (Z = g h k / w
// outside). Across the layer (0 < x < W) eta and P carry by
//   eta(W) = eta0 cos(k'W) + i P0 sin(k'W) / Z',   P(W) = P0 cos(k'W) + i Z' eta0 sin(k'W);
// with a wall at W (P(W) = 0): R / A = (cos + i q sin) / (cos - i q sin), q = Z'/Z;
// with open water behind (P(W) = Z eta(W)): R / A = i sin (q - 1/q) / (2 cos - i sin (q + 1/q)),
// T / A = (1 + R/A) cos + i (1 - R/A) sin / q. The form of Madsen (1974) and Sollitt & Cross (1972)
// for a homogeneous porous breakwater (their inertia coefficient s = 1, as in seed 003's equations).
struct AnalyticLayer {
  double reflection = 0, transmission = 0;
};
AnalyticLayer analytic_layer(double n, double r_per_s, double w, double depth_m, double width_m, bool wall_behind) {
  const double k = w / std::sqrt(kGravity_m_s2 * depth_m);
  const Complex stretch = std::sqrt(Complex(1.0, r_per_s / w));
  const Complex k_layer = k * stretch, q = n / stretch;
  const Complex c = std::cos(k_layer * width_m), s = std::sin(k_layer * width_m), i(0.0, 1.0);
  if (wall_behind) return {std::abs((c + i * q * s) / (c - i * q * s)), 0.0};
  const Complex reflected = i * s * (q - 1.0 / q) / (2.0 * c - i * s * (q + 1.0 / q));
  const Complex transmitted = (1.0 + reflected) * c + i * (1.0 - reflected) * s / q;
  return {std::abs(reflected), std::abs(transmitted)};
}

// The resistance rate r = n alpha of the solver's laminar (linear) term, alpha = alpha_l nu (1-n)^2
// / (n^3 D^2) (PorousResistance), for a stone size D that gives the requested r.
double stone_diameter_for(double n, double r_per_s, const SolverParameters& p) {
  return std::sqrt(n * p.porous.laminar_alpha * p.kinematic_viscosity_m2_s * (1 - n) * (1 - n) / (n * n * n * r_per_s));
}

// Long waves (k h = 0.1: the dispersive terms change k by B (kh)^2 ~ 0.07 %) in 1 m of water, 40
// cells per wavelength, a linear resistance only (turbulent beta 0, no bed friction).
struct LongWaveCase {
  double n, r_over_w, width_wavelengths;
  bool wall_behind;
};

TEST(PorousLayer, ReflectsAndTransmitsLongWavesAsTheAnalyticLayer) {
  const double depth_m = 1.0, kh = 0.1;
  const double k = kh / depth_m, w = k * std::sqrt(kGravity_m_s2 * depth_m), L = 2 * kPi / k;
  const LongWaveCase cases[] = {{0.45, 0.5, 0.25, true},  {0.45, 1.5, 0.25, true},  {0.45, 4.0, 0.25, true},  {0.6, 0.3, 0.5, true},
                                {0.45, 0.5, 0.25, false}, {0.45, 1.5, 0.25, false}, {0.45, 4.0, 0.25, false}, {0.8, 0.2, 0.5, false}};
  // The figure: the n = 0.45, W = L/4 layer over r / w, analytic curves and the model's points.
  const Rgb red{0.84f, 0.15f, 0.16f}, blue{0.12f, 0.47f, 0.71f}, green{0.17f, 0.63f, 0.17f};
  PlotSeries wall_theory{"Kr, wall behind: analytic", {}, {}, red, false}, wall_model{"Kr, wall behind: nearshore", {}, {}, red, true};
  PlotSeries open_r_theory{"Kr, open behind: analytic", {}, {}, blue, false}, open_r_model{"Kr, open behind: nearshore", {}, {}, blue, true};
  PlotSeries open_t_theory{"Kt, open behind: analytic", {}, {}, green, false}, open_t_model{"Kt, open behind: nearshore", {}, {}, green, true};
  for (double r_over_w = 0.0; r_over_w <= 5.0001; r_over_w += 0.05) {
    const AnalyticLayer wall = analytic_layer(0.45, r_over_w * w, w, depth_m, 0.25 * L, true);
    const AnalyticLayer open = analytic_layer(0.45, r_over_w * w, w, depth_m, 0.25 * L, false);
    wall_theory.x.push_back(r_over_w), wall_theory.y.push_back(wall.reflection);
    open_r_theory.x.push_back(r_over_w), open_r_theory.y.push_back(open.reflection);
    open_t_theory.x.push_back(r_over_w), open_t_theory.y.push_back(open.transmission);
  }
  for (const LongWaveCase& c : cases) {
    PorousLayerFlume flume;
    flume.still_water_depth_m = depth_m;
    flume.waves = {{2 * kPi / w, 0.002}};  // a / h = 0.001: linear
    flume.spacing_m = L / 40.0;
    flume.layer_width_m = c.width_wavelengths * L;
    flume.wall_behind = c.wall_behind;
    flume.solver = testing::inviscid_parameters();
    flume.solver.kinematic_viscosity_m2_s = 1.0e-6;  // the laminar resistance takes it (its film stress is 3e-6 /s here)
    flume.solver.porous.turbulent_beta = 0.0;
    flume.solver.porous.stone_diameter_m = stone_diameter_for(c.n, c.r_over_w * w, flume.solver);
    const LayerResponse model = measure_porous_layer(flume, c.n);
    const AnalyticLayer exact = analytic_layer(c.n, c.r_over_w * w, w, depth_m, c.width_wavelengths * L, c.wall_behind);
    std::printf("n %.2f, r/w %.1f, W/L %.2f, %s: Kr %.3f (analytic %.3f), Kt %.3f (analytic %.3f)\n", c.n, c.r_over_w,
                c.width_wavelengths, c.wall_behind ? "wall behind" : "open behind", model.reflection_coefficient, exact.reflection,
                model.transmission_coefficient, exact.transmission);
    // Bar 0.03: the layer's edges are smeared over one face (face porosity is the mean of the two
    // cells, boussinesq_sweep.hpp), a phase error of k dx / 2 = 0.08 rad at 40 cells per wavelength
    // in the interface's reflection; the scheme's own phase error is (k dx)^2 / 24 < 1 %.
    EXPECT_NEAR(model.reflection_coefficient, exact.reflection, 0.03);
    if (!c.wall_behind) {
      EXPECT_NEAR(model.transmission_coefficient, exact.transmission, 0.03);
    }
    if (c.n == 0.45 && c.width_wavelengths == 0.25) {
      (c.wall_behind ? wall_model : open_r_model).x.push_back(c.r_over_w);
      (c.wall_behind ? wall_model : open_r_model).y.push_back(model.reflection_coefficient);
      if (!c.wall_behind) open_t_model.x.push_back(c.r_over_w), open_t_model.y.push_back(model.transmission_coefficient);
    }
  }
  LinePlot figure{"A porous layer, n = 0.45, a quarter wavelength wide, k h = 0.1: linear resistance r",
                  "r / w (resistance rate over wave frequency)", "reflected or transmitted height / incident height",
                  {wall_theory, wall_model, open_r_theory, open_r_model, open_t_theory, open_t_model}, 900, 480};
  write_png(render_line_plot(figure), testing::plot_folder() / "porous_layer.png");
}

// A harbour grid's own stone diameters (HarbourGrid::porous_stone_diameter_m, what the bake lays
// where a structure's fit needed finer stones) act as the solver's one diameter would: in the rough
// basin's breakwater (its faces cross both sweeps), with waves through it for 300 steps. The same
// diameter as the solver's everywhere gives the same bits as no channel; 5 cm stones in the layer's
// cells and 1 m (the solver's) in the open water give what 5 cm solver stones give, to the float
// rounding of the ratio 0.05 / 1 (so a face on the layer's edge takes its porous cell's stones, not
// the open cell's); and the stones matter there (1 m everywhere is far off).
TEST(PorousLayer, TheGridsOwnStoneDiametersActAsTheSolversWould) {
  auto run = [](const HarbourGrid& grid, double solver_stone_diameter_m) {
    SolverParameters parameters;
    parameters.courant_number = 0.5;
    parameters.porous.stone_diameter_m = solver_stone_diameter_m;
    BoussinesqSolver solver(grid, parameters, testing::regular_waves_from_west(6.0, 8.0, 0.15, 5.0));
    for (int step = 0; step < 300; ++step) solver.step();
    return testing::solver_snapshot(solver);
  };
  auto largest_difference = [](const std::vector<float>& a, const std::vector<float>& b) {
    double largest = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) largest = std::max(largest, std::abs(static_cast<double>(a[i]) - b[i]));
    return largest;
  };
  const HarbourGrid plain = testing::rough_basin();
  HarbourGrid solvers_stones = plain;
  solvers_stones.porous_stone_diameter_m = Raster<float>(plain.geometry.columns, plain.geometry.rows, 1.0f);
  EXPECT_EQ(run(solvers_stones, 1.0), run(plain, 1.0));

  HarbourGrid fine_in_the_layer = solvers_stones;
  for (std::size_t i = 0; i < plain.porosity.size(); ++i)
    if (plain.porosity.values()[i] > 0.0f && plain.porosity.values()[i] < 1.0f) fine_in_the_layer.porous_stone_diameter_m.values()[i] = 0.05f;
  const std::vector<float> reference = run(plain, 0.05);
  double largest_value = 0.0;
  for (float v : reference) largest_value = std::max(largest_value, std::abs(static_cast<double>(v)));
  EXPECT_LT(largest_difference(run(fine_in_the_layer, 1.0), reference), 1e-5 * largest_value);
  EXPECT_GT(largest_difference(run(plain, 1.0), reference), 1e-2 * largest_value);

  // A stone diameter that is no positive number is refused, naming the cell.
  HarbourGrid broken = solvers_stones;
  broken.porous_stone_diameter_m(20, 12) = 0.0f;
  try {
    run(broken, 1.0);
    ADD_FAILURE() << "a zero stone diameter was accepted";
  } catch (const Error& error) {
    EXPECT_NE(error.problem().find("(20, 12)"), std::string::npos) << error.problem();
  }
}

TEST(PorousLayer, FitsThePorosityThatGivesARequestedReflectionOrTransmission) {
  // The demo harbour's breakwater faces: 8 m of water, the 12 s peak, H_rms 1.06 m of its 1.5 m
  // sea, 8 m cells, 21.5 m of faces in front of the core; the turbulent resistance as the bake runs it.
  PorousLayerFlume flume;
  flume.still_water_depth_m = 8.0;
  flume.waves = {{12.0, 1.5 / std::sqrt(2.0)}};
  flume.spacing_m = 8.0;
  flume.layer_width_m = 24.0;
  flume.wall_behind = true;
  flume.solver.shapiro_filter_order = 0;  // as the bake on 8 m cells (above)
  for (double requested : {0.5, 0.7, 0.9}) {
    const PorosityFit fit = fit_porosity_to_reflection(flume, requested, 0.02);
    std::printf("Kr %.2f requested: porosity %.3f gives %.3f (k h %.2f, W/L %.2f, %d flume runs)\n", requested, fit.response.porosity,
                fit.response.reflection_coefficient, fit.response.relative_depth_kh, fit.response.layer_width_wavelengths, fit.flume_runs);
    ASSERT_TRUE(fit.reached) << requested;
    EXPECT_NEAR(fit.response.reflection_coefficient, requested, 0.02);
    // Measured again at the fitted porosity, relative to the wall alone as the fit reads it: the
    // same (the flume is deterministic).
    EXPECT_NEAR(measure_porous_layer(flume, fit.response.porosity).reflection_coefficient / measure_porous_layer(flume, 1.0).reflection_coefficient,
                fit.response.reflection_coefficient, 1e-12);
  }
  // A free-standing layer (a pier on piles): the transmission.
  flume.wall_behind = false;
  flume.layer_width_m = 8.0;
  const PorosityFit pier = fit_porosity_to_transmission(flume, 0.9, 0.02);
  std::printf("Kt 0.90 requested: porosity %.3f gives %.3f, Kr %.3f\n", pier.response.porosity, pier.response.transmission_coefficient,
              pier.response.reflection_coefficient);
  ASSERT_TRUE(pier.reached);
  EXPECT_NEAR(pier.response.transmission_coefficient, 0.9, 0.02);
  // Energy: what is neither reflected nor transmitted is dissipated, never created.
  EXPECT_LE(pier.response.reflection_coefficient * pier.response.reflection_coefficient +
                pier.response.transmission_coefficient * pier.response.transmission_coefficient,
            1.0 + 0.02);
}

TEST(PorousLayer, RefusesALayerItCannotMeasure) {
  PorousLayerFlume flume;
  EXPECT_THROW(measure_porous_layer(flume, 0.01), Error);  // below kWallPorosity: a wall
  flume.waves = {{10.0, 20.0}};  // above 0.6 d: it would break
  EXPECT_THROW(measure_porous_layer(flume, 0.5), Error);
  flume.waves.clear();
  EXPECT_THROW(measure_porous_layer(flume, 0.5), Error);
}

TEST(PorousLayer, ASeaOfFiveWavesIsSeparatedWaveByWave) {
  // Five waves of a 1.5 m, 12 s JONSWAP swell's equal-energy shares (8.5-16 s) run together in the
  // demo harbour's 8 m of water against 24 m of faces in front of a wall. Each wave's reflection is
  // separated from the others (harmonic analysis over a common record) and the sea's is the root
  // of their energies' ratio. Check: in the linear limit (heights / 50) each wave's reflection in
  // the five together is the one it has alone, within 0.03. Measured: together 0.015-0.02 below
  // alone at every period (0.97-0.99 against 0.99-1.0, where the layer dissipates almost nothing);
  // not the scheme's wavenumber in the separation (used) nor the grid-scale filter (off); open.
  PorousLayerFlume flume;
  flume.still_water_depth_m = 8.0;
  flume.spacing_m = 8.0;
  flume.layer_width_m = 24.0;
  flume.wall_behind = true;
  // 8 m cells in at most 8 m... 15 m of water: the bake leaves the grid-scale filter off on cells
  // this coarse (bake_case.cpp, default_shapiro_filter_order), and so does the flume here.
  flume.solver.shapiro_filter_order = 0;
  for (double period_s : {16.0, 13.4, 12.0, 10.6, 8.5}) flume.waves.push_back({period_s, 2.0 * std::sqrt(2.0 * 0.140625 / 5.0) / 50.0});
  flume.waves.erase(flume.waves.begin());  // the default wave
  const LayerResponse together = measure_porous_layer(flume, 0.8);
  ASSERT_EQ(together.per_wave.size(), 5u);
  double incident = 0, reflected = 0;
  for (std::size_t i = 0; i < 5; ++i) {
    PorousLayerFlume alone = flume;
    alone.waves = {{together.per_wave[i].period_s, flume.waves[i].height_m}};
    const LayerResponse single = measure_porous_layer(alone, 0.8);
    std::printf("%.2f s (k h %.2f): Kr %.3f together, %.3f alone\n", together.per_wave[i].period_s, together.per_wave[i].relative_depth_kh,
                together.per_wave[i].reflection_coefficient, single.reflection_coefficient);
    EXPECT_NEAR(together.per_wave[i].reflection_coefficient, single.reflection_coefficient, 0.03);
    incident += 1.0, reflected += std::pow(together.per_wave[i].reflection_coefficient, 2);
  }
  // Equal incident energies: the sea's Kr is the root mean square of the waves' (to the separation's
  // own share of error in the incident amplitudes).
  EXPECT_NEAR(together.reflection_coefficient, std::sqrt(reflected / incident), 0.01);
}

}  // namespace
}  // namespace nearshore::boussinesq
