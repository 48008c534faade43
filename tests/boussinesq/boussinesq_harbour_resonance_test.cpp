// Harbour resonance: a narrow rectangular basin open to the sea through its whole width in a straight
// coast (the fully open harbour of Ippen & Goda 1963 and Lee 1971, width / length 0.2), waves normal
// to the coast; the amplification R = wave height at the basin's back wall / height of the standing
// wave the same waves make at a straight coast (twice the incident), against k l (l the length),
// compared with the linear long-wave theory of a narrow bay (below). Numbers and figure:
// docs/validation.md, "Harbour resonance". Built twice: here (label `physics`, a coarse grid) and,
// with NEARSHORE_FULL_RESOLUTION=1, as boussinesq_harbour_resonance_full_tests (label `validation`).
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "boussinesq_test_support.hpp"
#include "nearshore/boussinesq/model_dispersion.hpp"
#include "nearshore/plot/plot.hpp"

#ifndef NEARSHORE_FULL_RESOLUTION
#define NEARSHORE_FULL_RESOLUTION 0
#endif

// Helpers in a namespace of their own: the suite is built in unity batches (cmake/NearshoreWarnings.cmake).
namespace nearshore::boussinesq::harbour_resonance {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;
constexpr double kEulerGamma = 0.57721566490153286;

// The narrow bay (Miles & Munk 1961; Ippen & Goda 1963; Mei, Stiassnie & Yue 2005, ch. 5), long
// waves, k a << 1. A basin 0 < x < l, |y| < a/2, opens at x = 0 onto a sea x < 0 with a straight,
// fully reflecting coast; the incident wave A exp(i k x) makes the standing wave 2 A cos(k x) there.
// Inside, eta = B cos(k (x - l)) (no flux at the back wall x = l), so at the mouth d(eta)/dx =
// U = k B sin(k l) across its width. Outside, the mouth radiates as a line of sources on a wall: the
// half-plane's Green function gives eta_radiated(0, y) = (i/2) int_mouth U H0(k |y - y'|) dy'
// (H0 the Hankel function of the first kind; the factor from the flux through a half circle round a
// source, 2 i alpha = -1 with H0 ~ (2 i / pi) ln r). Matching the mean elevation over the mouth,
//   B cos(k l) = 2 A + (i/2) k B sin(k l) (1/a) int int H0(k |y - y'|) dy dy',
// and with H0(z) ~ 1 + (2 i / pi) (ln(z/2) + gamma) and int_0^a int_0^a ln|y - y'| = a^2 (ln a - 3/2):
//   R = |B| / (2 A) = 1 / | cos k l + (k a / pi) sin k l ln(e^gamma k a / (2 e^{3/2})) - i (k a / 2) sin k l |.
// The real part sets the resonances: cot(k l) = -(k a/pi) ln(...) > 0, so each lies below the
// quarter-wave k l = (n + 1/2) pi of a closed-open channel (the mouth's end correction, a length
// (a/pi) ln(2 e^{3/2} / (e^gamma k a)) added to l); the imaginary part is the radiation damping,
// which alone limits the peak: R_max ~ 2 / (k a).
double narrow_bay_amplification(double kl, double a_over_l) {
  const double ka = kl * a_over_l;
  const double end = (ka / kPi) * std::log(std::exp(kEulerGamma) * ka / (2.0 * std::exp(1.5)));
  return 1.0 / std::abs(Complex(std::cos(kl) + end * std::sin(kl), -0.5 * ka * std::sin(kl)));
}

// The first resonance of the narrow bay: the k l of the largest R, by golden-section search.
double narrow_bay_first_resonance(double a_over_l) {
  double low = 0.5, high = 0.5 * kPi;
  for (int i = 0; i < 100; ++i) {
    const double m1 = high - 0.618 * (high - low), m2 = low + 0.618 * (high - low);
    if (narrow_bay_amplification(m1, a_over_l) < narrow_bay_amplification(m2, a_over_l))
      low = m1;
    else
      high = m2;
  }
  return 0.5 * (low + high);
}

// The theory's own limits, checked: a closed-open channel (a -> 0) resonates at k l = pi / 2 and
// its peak grows as 2 / (k a); a wider mouth resonates lower (the end correction).
TEST(BoussinesqHarbourResonance, NarrowBayTheoryHasItsLimits) {
  EXPECT_NEAR(narrow_bay_first_resonance(1e-4), 0.5 * kPi, 1e-3);
  for (double a_over_l : {0.02, 0.05, 0.2}) {
    const double kl = narrow_bay_first_resonance(a_over_l);
    EXPECT_LT(kl, 0.5 * kPi);
    // At the peak the real part vanishes (to the search's precision), leaving the radiation damping.
    EXPECT_NEAR(narrow_bay_amplification(kl, a_over_l), 2.0 / (kl * a_over_l * std::sin(kl)), 0.02 * 2.0 / (kl * a_over_l));
  }
  EXPECT_LT(narrow_bay_first_resonance(0.2), narrow_bay_first_resonance(0.05));
  // Far from resonance the basin follows the coast's standing wave: R -> 1 as k l -> 0.
  EXPECT_NEAR(narrow_bay_amplification(1e-3, 0.2), 1.0, 1e-3);
}

// The angular frequency whose model wavenumber is k (the solver's dispersion relation, inverted by
// bisection: boussinesq_wavenumber increases with the frequency).
double angular_frequency_of(double k, double depth_m, double dispersion_coefficient) {
  double low = 1e-6, high = 10.0 * k * std::sqrt(9.81 * depth_m);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (low + high);
    (boussinesq_wavenumber(mid, depth_m, dispersion_coefficient) < k ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

// The basin, `cells` cells to the harbour's length l. Symmetric about the harbour's axis, which is
// the grid's south edge (a wall): the model holds half the harbour, a/2 = half_width_cells wide.
//   x: a sponge of 5 l (a resonant wavelength; the solver takes sponges up to half the grid), the
//      source line at 5.5 l, the coast at 10 l (land east of it but for the harbour), the harbour
//      to 11 l, one column of land;
//   y: water 9 l (about two resonant wavelengths) to a north sponge of 5 l.
// Depth = cell size (k d < 0.2 at the resonance: long waves, as the theory).
struct Harbour {
  int length_cells = 10, half_width_cells = 1;
  double record_periods = 24;  // of the resonant wave: the frequency resolution 1/24 of it
};

Harbour ci_harbour() {
#if NEARSHORE_FULL_RESOLUTION
  return Harbour{20, 2, 32};
#else
  return Harbour{};
#endif
}

struct Response {
  std::vector<double> kl, model, theory;
  double a_over_l = 0;
};

// All frequencies in one run: a sum of components of small amplitude (linear) whose frequencies are
// whole multiples of 1 / record, so that over the record each one's complex amplitude is its
// Fourier coefficient, free of the others.
Response run_harbour(const Harbour& harbour) {
  const double dx = 1.0, depth_m = 1.0, l = harbour.length_cells * dx;
  const double a_over_l = 2.0 * harbour.half_width_cells / static_cast<double>(harbour.length_cells);
  SolverParameters parameters = testing::inviscid_parameters();
  const int sponge_cells = 5 * harbour.length_cells;
  parameters.sponges = {{Side::kWest, sponge_cells * dx}, {Side::kNorth, sponge_cells * dx}};
  // The record: record_periods of the wave at k l = 1.3; dt = record / steps with a Courant number below 1.
  const double resonant_omega = angular_frequency_of(1.3 / l, depth_m, parameters.dispersion_coefficient);
  const double record_s = harbour.record_periods * 2.0 * kPi / resonant_omega;
  const int record_steps = static_cast<int>(std::ceil(record_s * std::sqrt(9.81 * depth_m) / (0.9 * dx)));
  parameters.time_step_s = record_s / record_steps;
  const int spin_up_steps = record_steps / 2;
  // k l from 0.75 to 1.9: harmonics n of the record's frequency.
  Response response;
  response.a_over_l = a_over_l;
  WaveMaker maker;
  maker.kind = WaveMaker::Kind::kComponents;
  maker.facing = Side::kWest;
  maker.source_line_m = (sponge_cells + harbour.length_cells / 2) * dx;
  maker.ramp_time_s = 2.0 * 2.0 * kPi / resonant_omega;
  maker.second_order = false;
  std::vector<double> omegas;
  const double n_resonant = harbour.record_periods;
  for (double n = std::round(0.75 / 1.3 * n_resonant); n <= std::round(1.9 / 1.3 * n_resonant); n += (n < 0.85 * n_resonant || n > 1.2 * n_resonant) ? 2 : 1) {
    const double omega = 2.0 * kPi * n / record_s;
    omegas.push_back(omega);
    // Phases spread by the golden angle, so the components do not add up to one tall crest.
    maker.sea_state.components.push_back({0.0005, omega, 0.0, 2.39996 * static_cast<double>(omegas.size())});
    response.kl.push_back(boussinesq_wavenumber(omega, depth_m, parameters.dispersion_coefficient) * l);
  }
  const int coast_column = sponge_cells + harbour.length_cells / 2 + 9 * harbour.length_cells / 2;
  const int columns = coast_column + harbour.length_cells + 1, rows = 9 * harbour.length_cells + sponge_cells;
  // Runs a grid to the end of the record and returns each component's complex amplitude at cell (column, row).
  auto record_at = [&](const HarbourGrid& grid, const SolverParameters& run_parameters, int column, int row) {
    BoussinesqSolver solver(grid, run_parameters, maker);
    std::vector<Complex> sums(omegas.size(), 0.0);
    while (solver.step_count() < spin_up_steps + record_steps) {
      solver.step();
      if (solver.step_count() % 100 == 0 && solver.check_stability()) break;
      if (solver.step_count() <= spin_up_steps) continue;
      const double eta = solver.surface_elevation_m()(column, row);
      for (std::size_t i = 0; i < omegas.size(); ++i) sums[i] += eta * std::polar(1.0, omegas[i] * solver.time_s());
    }
    if (const auto report = solver.check_stability()) ADD_FAILURE() << "unstable at t = " << report->time_s << " s: " << report->what;
    for (Complex& sum : sums) sum *= 2.0 / record_steps;
    return sums;
  };
  auto land = [](HarbourGrid& grid, int c, int r) {
    grid.still_water_depth_m(c, r) = -1.0f;  // 1 m above still water: never wet
    grid.land(c, r) = kLandCell;
  };
  // The straight coast: a flume one row wide ending at the coast; its last water cell's standing wave.
  HarbourGrid flume = testing::flume(coast_column + 1, 1, dx, depth_m);
  land(flume, coast_column, 0);
  SolverParameters flume_parameters = parameters;
  flume_parameters.sponges = {{Side::kWest, sponge_cells * dx}};
  const std::vector<Complex> coast = record_at(flume, flume_parameters, coast_column - 1, 0);
  // The harbour: its back wall's last water cell on the axis.
  HarbourGrid grid = testing::flume(columns, rows, dx, depth_m);
  for (int r = 0; r < rows; ++r)
    for (int c = coast_column; c < columns; ++c)
      if (r >= harbour.half_width_cells || c >= coast_column + harbour.length_cells) land(grid, c, r);
  const std::vector<Complex> back = record_at(grid, parameters, coast_column + harbour.length_cells - 1, 0);
  for (std::size_t i = 0; i < omegas.size(); ++i) {
    response.model.push_back(std::abs(back[i]) / std::abs(coast[i]));
    response.theory.push_back(narrow_bay_amplification(response.kl[i], a_over_l));
  }
  return response;
}

// The resonance's k l from sampled R: the vertex of the parabola through log R at the largest sample
// and its two neighbours (a resonance peak is close to a Gaussian in log near its top).
double sampled_peak(const std::vector<double>& kl, const std::vector<double>& r) {
  const std::size_t i = static_cast<std::size_t>(std::max_element(r.begin(), r.end()) - r.begin());
  if (i == 0 || i + 1 == r.size()) return kl[i];
  const double x0 = kl[i - 1], x1 = kl[i], x2 = kl[i + 1], y0 = std::log(r[i - 1]), y1 = std::log(r[i]), y2 = std::log(r[i + 1]);
  const double d1 = (y1 - y0) / (x1 - x0), d2 = (y2 - y1) / (x2 - x1), curvature = (d2 - d1) / (x2 - x0);
  return 0.5 * (x0 + x1) - d1 / (2.0 * curvature);
}

TEST(BoussinesqHarbourResonance, FullyOpenRectangularHarbourResonatesAsANarrowBay) {
  const Harbour harbour = ci_harbour();
  const Response response = run_harbour(harbour);
  const double theory_peak = narrow_bay_first_resonance(response.a_over_l);
  const double model_peak = sampled_peak(response.kl, response.model), sampled_theory_peak = sampled_peak(response.kl, response.theory);
  std::printf("fully open harbour, a / l = %.2f, l = %d cells, a/2 = %d cells:\n", response.a_over_l, harbour.length_cells, harbour.half_width_cells);
  for (std::size_t i = 0; i < response.kl.size(); ++i)
    std::printf("  k l %.3f: R model %.2f, narrow bay %.2f\n", response.kl[i], response.model[i], response.theory[i]);
  const double model_max = *std::max_element(response.model.begin(), response.model.end());
  const double theory_max = narrow_bay_amplification(theory_peak, response.a_over_l);
  std::printf("  first resonance: k l model %.3f (from the samples), narrow bay %.3f (its samples %.3f); peak R model %.2f (largest sample), narrow bay %.2f\n",
              model_peak, theory_peak, sampled_theory_peak, model_max, theory_max);
  // The bars. The resonant k l is the sharp check (dissipation lowers a peak but hardly moves it).
  // The mouth's end correction moves the first resonance from the quarter wave's k l = pi/2 down to
  // 1.315 at a / l = 0.2, 16 % of k l, and it is the uncertain part on both sides: the narrow-bay
  // theory keeps only the leading terms in k a (k a = 0.26 here) and the model's mouth, 2 or 4 cells
  // wide on a staggered grid, is uncertain by half a cell in where its faces are. A quarter of the
  // correction is 4 % of k l; with the grid's half cell over the basin's effective length (4 % of the
  // ~12 cells of the CI grid, 2 % of the ~24 of the fine one): 7 % on the CI grid, 6 % on the fine.
  // (Measured: -4.9 % and -4.0 %; that the finer grid barely moved it says the offset is not the
  // grid's: docs/validation.md, "Harbour resonance".) The peak height: the samples lie
  // 1/record_periods of the resonant frequency apart, so the largest may sit up to 10 % below the
  // curve's top (the half-power width is about k l / 6), and the model's filter and sponges take a
  // little more; the bar is 25 %.
  const double peak_bar = NEARSHORE_FULL_RESOLUTION ? 0.06 : 0.07;
  EXPECT_NEAR(model_peak / theory_peak, 1.0, peak_bar);
  EXPECT_NEAR(model_max / theory_max, 1.0, 0.25);
  // Away from the resonance the basin follows the coast: at the lowest k l swept R is 1-2 (both).
  EXPECT_LT(response.model.front(), 2.0);
  std::vector<PlotSeries> series;
  PlotSeries theory{"narrow bay (long waves, radiation damping only)", {}, {}, {0.12f, 0.47f, 0.71f}, false};
  for (double kl = 0.7; kl <= 1.95; kl += 0.005) {
    theory.x.push_back(kl);
    theory.y.push_back(narrow_bay_amplification(kl, response.a_over_l));
  }
  PlotSeries model{"nearshore", response.kl, response.model, {0.84f, 0.15f, 0.16f}, true};
  series = {theory, model};
  char title[160];
  std::snprintf(title, sizeof title, "Fully open rectangular harbour, a / l = %.1f: amplification at the back wall (l = %d cells)", response.a_over_l,
                harbour.length_cells);
  LinePlot plot{title, "k l (l the harbour's length)", "R = H at the back wall / 2 H incident", series, 900, 480};
  write_png(render_line_plot(plot), testing::plot_folder() / (NEARSHORE_FULL_RESOLUTION ? "harbour_resonance.png" : "harbour_resonance_ci.png"));
}

}  // namespace
}  // namespace nearshore::boussinesq::harbour_resonance
