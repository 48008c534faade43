// Weakly nonlinear checks of the DISCRETE scheme against its own continuous equations and against
// Stokes (issue 19): the bound second harmonic of a regular wave in constant depth over k d = 0.2-3
// and the amplitude dispersion (nonlinear phase speed) of a steady wave. No laboratory data: the
// references are model_nonlinear.hpp (Stokes 2nd/3rd order; the equations' own second-order
// transfer function and their exact steady waves). docs/validation.md "Nonlinear checks".
//
// Method: a long flat flume (32 cells per wavelength, Courant 0.5, sponges at both ends) starts from
// the continuous equations' steady wave (eta and P = c eta on the whole flume). A gauge in the middle
// records eta(t) until the disturbances from the flume's ends reach it. If the scheme carries the
// wave as the equations do, the record is the steady wave: a first harmonic at the nonlinear
// frequency and a bound second harmonic at twice it. Where the scheme's bound harmonic differs from
// the equations', a free second harmonic (wavenumber 2k, the scheme's own frequency w(2k), measured
// by a linear run) makes up the difference; a least-squares fit on {w, 2w, w(2k), 3w} separates the
// two over a window of at least one beat period 2 pi / |w(2k) - 2w|.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <numbers>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "boussinesq_test_support.hpp"
#include "nearshore/boussinesq/model_nonlinear.hpp"
#include "nearshore/ocean/linear_waves.hpp"
#include "nearshore/plot/plot.hpp"

namespace nearshore::boussinesq {
namespace {

constexpr double kDepth_m = 1.0;
// 32 cells per wavelength, and at most d/2: where dx approaches d the staggered differences add a
// numerical dispersion (k dx)^2/24 comparable to the physical (k d)^2/6 of long waves (their ratio
// (dx/d)^2/4) and the bound harmonic, inversely proportional to the dispersion, follows it.
int cells_per_wavelength(double k) { return std::max(32, static_cast<int>(std::ceil(2.0 * 2.0 * std::numbers::pi / k / kDepth_m))); }

struct Fit {
  std::vector<double> amplitude_m;  // per frequency
  double residual = 0.0;            // sum of squares
};

// Least squares of eta(t) on 1 and {cos, sin}(w_i t): the amplitude of each frequency.
Fit fit_frequencies(const std::vector<double>& t, const std::vector<double>& eta, const std::vector<double>& w) {
  const int columns = 1 + 2 * static_cast<int>(w.size());
  Eigen::MatrixXd A(t.size(), columns);
  Eigen::VectorXd b(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    A(i, 0) = 1.0;
    for (std::size_t f = 0; f < w.size(); ++f) {
      A(i, 1 + 2 * f) = std::cos(w[f] * t[i]);
      A(i, 2 + 2 * f) = std::sin(w[f] * t[i]);
    }
    b[i] = eta[i];
  }
  const Eigen::VectorXd x = A.colPivHouseholderQr().solve(b);
  Fit fit;
  for (std::size_t f = 0; f < w.size(); ++f) fit.amplitude_m.push_back(std::hypot(x[1 + 2 * f], x[2 + 2 * f]));
  fit.residual = (A * x - b).squaredNorm();
  return fit;
}

struct Record {
  std::vector<double> t, eta;
};

// Runs the flume from the steady wave `harmonics_m` (cos(n k (x - x_gauge))) with P = c eta and
// records the gauge from `start_s` to `start_s + window_s`. The flume is long enough that nothing
// from its ends (travelling at most at sqrt(g d)) reaches the gauge before the window closes.
Record run_flume(double k, double k_grid, const std::vector<double>& harmonics_m, double phase_speed_m_s, double start_s,
                 double window_s, const SolverParameters& parameters) {
  const double wavelength_m = 2.0 * std::numbers::pi / k, dx = wavelength_m / cells_per_wavelength(k_grid);
  const double sponge_m = 2.0 * wavelength_m;
  const double half_m = std::sqrt(ocean::kGravity_m_s2 * kDepth_m) * (start_s + window_s) + sponge_m + wavelength_m;
  const int columns = 2 * static_cast<int>(std::ceil(half_m / dx));
  const HarbourGrid harbour = testing::flume(columns, 1, dx, kDepth_m);
  SolverParameters p = parameters;
  p.sponges = {{Side::kWest, sponge_m}, {Side::kEast, sponge_m}};
  BoussinesqSolver solver(harbour, p, WaveMaker{});
  const double x_gauge = (columns / 2 + 0.5) * dx;
  auto eta = [&](double x) {
    double sum = 0.0;
    for (std::size_t n = 0; n < harmonics_m.size(); ++n) sum += harmonics_m[n] * std::cos((n + 1.0) * k * (x - x_gauge));
    return sum;
  };
  solver.set_initial_condition([&](double x, double) { return eta(x); },
                               [&](double x, double) { return phase_speed_m_s * eta(x); },
                               [](double, double) { return 0.0; });
  Record record;
  while (solver.time_s() < start_s + window_s) {
    solver.step();
    if (solver.time_s() >= start_s) {
      record.t.push_back(solver.time_s());
      record.eta.push_back(solver.surface_elevation_at(x_gauge, 0.5 * dx));
    }
  }
  return record;
}

// The frequency of the dominant harmonic near `guess` (golden section on the fit's residual, with
// `others` = functions of w giving the other frequencies of the basis).
double fit_frequency(const Record& r, double guess, const std::function<std::vector<double>(double)>& basis) {
  double lo = guess * 0.98, hi = guess * 1.02;
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  auto cost = [&](double w) { return fit_frequencies(r.t, r.eta, basis(w)).residual; };
  double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo), f1 = cost(x1), f2 = cost(x2);
  while (hi - lo > 1e-10 * guess) {
    if (f1 < f2) { hi = x2; x2 = x1; f2 = f1; x1 = hi - phi * (hi - lo); f1 = cost(x1); }
    else { lo = x1; x1 = x2; f1 = f2; x2 = lo + phi * (hi - lo); f2 = cost(x2); }
  }
  return 0.5 * (lo + hi);
}

struct NonlinearPoint {
  double kd = 0, amplitude_m = 0;
  double stokes_a2 = 0, equations_a2 = 0, equations_total_a2 = 0, fully_nonlinear_a2 = 0;  // second-order theory, m
  double steady_a2 = 0, scheme_a2 = 0, scheme_free_a2 = 0;         // exact steady wave; measured
  // The steady wave's a2 corrected for the scheme's linear dispersion: a2 is inversely proportional
  // to the mismatch w(2k)^2 - (2w)^2 of the forced and the free second harmonic (model_nonlinear.cpp),
  // so the scheme's bound harmonic is expected at a2 (w_f^2 - 4 w^2)_equations / (w_f^2 - 4 w^2)_scheme.
  double expected_scheme_a2 = 0;
  double stokes_dw = 0, equations_dw = 0, scheme_dw = 0;           // w/w0 - 1
};

// Amplitude for the check at k d: the equations' bound harmonic 5 % of the first (a clear signal,
// third-order terms small), at most k a = 0.1.
double check_amplitude_m(double k) {
  const double B = 1.0 / 15.0;
  const double transfer = boussinesq_second_harmonic_m(1.0, k, kDepth_m, B, DispersionDepth::kStillWater);  // a2 / a^2
  return std::min(0.05 / transfer, 0.1 / k);
}

NonlinearPoint measure(double kd, DispersionDepth depth_kind, SolverParameters::FaceDepth face_depth,
                       Equations equations = Equations::kWeaklyNonlinear) {
  const double B = 1.0 / 15.0, k = kd / kDepth_m, a = check_amplitude_m(k);
  SolverParameters parameters = testing::inviscid_parameters(0.5);
  parameters.dispersion_depth = depth_kind;
  parameters.face_depth = face_depth;
  parameters.equations = equations;
  const SteadyWave wave = boussinesq_steady_wave(a, k, kDepth_m, B, depth_kind, 8, equations);
  const SteadyWave linear = boussinesq_steady_wave(1e-7 * a, k, kDepth_m, B, depth_kind, 8, equations);
  const double w0 = linear.phase_speed_m_s * k,
               w_free_continuous = boussinesq_steady_wave(1e-7 * a, 2 * k, kDepth_m, B, depth_kind, 8, equations).phase_speed_m_s * 2 * k;
  const double period_s = 2 * std::numbers::pi / w0;
  const double beat_s = 2 * std::numbers::pi / std::abs(w_free_continuous - 2 * w0);
  const double window_s = std::max(10 * period_s, 1.2 * beat_s), start_s = 2 * period_s;
  // The scheme's own linear frequencies at k and 2k (tiny waves): the baseline of the amplitude
  // dispersion and the frequency of a free second harmonic.
  auto linear_frequency = [&](double wavenumber, double w_guess) {
    const std::vector<double> tiny = {1e-6 * kDepth_m};
    const double c = w_guess / wavenumber;
    const Record r = run_flume(wavenumber, k, tiny, c, start_s, std::max(10 * 2 * std::numbers::pi / w_guess, 4 * period_s), parameters);
    return fit_frequency(r, w_guess, [](double w) { return std::vector<double>{w}; });
  };
  const double w_scheme = linear_frequency(k, w0), w_free = linear_frequency(2 * k, w_free_continuous);
  // The nonlinear run, P = c eta with c scaled to the scheme's linear speed (so the initial wave
  // does not shed a backward-travelling part from the O(0.5 %) linear difference).
  const double c_start = wave.phase_speed_m_s * w_scheme / w0;
  const Record r = run_flume(k, k, wave.harmonics_m, c_start, start_s, window_s, parameters);
  auto basis = [&](double w) { return std::vector<double>{w, 2 * w, w_free, 3 * w}; };
  const double w = fit_frequency(r, w_scheme * wave.phase_speed_m_s / linear.phase_speed_m_s, basis);
  const Fit fit = fit_frequencies(r.t, r.eta, basis(w));
  NonlinearPoint p;
  p.kd = kd;
  p.amplitude_m = a;
  p.stokes_a2 = stokes_second_harmonic_m(a, k, kDepth_m);
  p.equations_a2 = boussinesq_second_harmonic_m(a, k, kDepth_m, B, DispersionDepth::kStillWater);
  p.equations_total_a2 = boussinesq_second_harmonic_m(a, k, kDepth_m, B, DispersionDepth::kTotal);
  p.fully_nonlinear_a2 = fully_nonlinear_second_harmonic_m(a, k, kDepth_m, B);
  p.steady_a2 = wave.harmonics_m[1];
  p.scheme_a2 = fit.amplitude_m[1];
  p.scheme_free_a2 = fit.amplitude_m[2];
  p.expected_scheme_a2 = p.steady_a2 * (w_free_continuous * w_free_continuous - 4 * w0 * w0) /
                         (w_free * w_free - 4 * w_scheme * w_scheme);
  p.stokes_dw = stokes_frequency_increase(a, k, kDepth_m);
  p.equations_dw = wave.phase_speed_m_s / linear.phase_speed_m_s - 1.0;
  p.scheme_dw = w / w_scheme - 1.0;
  return p;
}

// The derivation of the equations' second-order transfer function (model_nonlinear.cpp) against
// their exact steady waves, and its long-wave limit against Stokes.
TEST(BoussinesqNonlinear, SecondOrderTransferFunctionOfTheEquations) {
  const double B = 1.0 / 15.0;
  for (DispersionDepth depth_kind : {DispersionDepth::kStillWater, DispersionDepth::kTotal})
    for (double kd : {0.2, 0.5, 1.0, 2.0, 3.0}) {
      const double k = kd / kDepth_m, a = 0.2 * check_amplitude_m(k);  // a2/a = 1 %: third order 1e-4
      const double second_order = boussinesq_second_harmonic_m(a, k, kDepth_m, B, depth_kind);
      const double exact = boussinesq_steady_wave(a, k, kDepth_m, B, depth_kind).harmonics_m[1];
      // The steady wave differs from the second-order term at relative order (a2/a)^2 ~ 1e-4 and
      // (k a)^2 <= 4e-4: 0.3 % holds both with margin.
      EXPECT_NEAR(exact / second_order, 1.0, 3e-3) << "k d = " << kd;
    }
  // k d -> 0: Stokes' 3 a^2 / (4 k^2 d^3); the next term is O((kd)^2) relative (2.6 % at k d = 0.1).
  const double k = 0.1, a = 1e-5;
  EXPECT_NEAR(boussinesq_second_harmonic_m(a, k, kDepth_m, B, DispersionDepth::kStillWater) /
                  stokes_second_harmonic_m(a, k, kDepth_m), 1.0, 0.03);
}

// The fully nonlinear equations' transfer function (model_nonlinear.hpp, derived symbolically) against
// their exact steady waves, and its expansion against Stokes: a2 / a2_Stokes = 1 + c (kd)^2 + O((kd)^4)
// with c = B + 1/9 - 2/3 = -0.489 for the seed's equations and c = 5 B + 1/3 - 2/3 = 0 for the fully
// nonlinear ones at B = 1/15, so at k d = 0.1 the seed's equations are 0.49 % low and these within
// the O((kd)^4) term (4 B^2 + 8 B / 9 - Stokes' 2/45... : below 1e-4).
TEST(BoussinesqNonlinear, FullyNonlinearTransferFunctionMatchesItsSteadyWavesAndStokesToSecondOrderInKd) {
  const double B = 1.0 / 15.0;
  for (double kd : {0.2, 0.5, 1.0, 2.0, 3.0}) {
    const double k = kd / kDepth_m, a = 0.2 * check_amplitude_m(k);
    const double second_order = fully_nonlinear_second_harmonic_m(a, k, kDepth_m, B);
    const double exact = boussinesq_steady_wave(a, k, kDepth_m, B, DispersionDepth::kStillWater, 8, Equations::kFullyNonlinear).harmonics_m[1];
    EXPECT_NEAR(exact / second_order, 1.0, 3e-3) << "k d = " << kd;  // as for the seed's equations above
  }
  for (double kd : {0.05, 0.1}) {
    const double k = kd / kDepth_m, a = 1e-6, stokes = stokes_second_harmonic_m(a, k, kDepth_m);
    const double seed = boussinesq_second_harmonic_m(a, k, kDepth_m, B, DispersionDepth::kStillWater) / stokes - 1.0;
    const double full = fully_nonlinear_second_harmonic_m(a, k, kDepth_m, B) / stokes - 1.0;
    EXPECT_NEAR(seed / (kd * kd), B + 1.0 / 9.0 - 2.0 / 3.0, 0.01) << "k d = " << kd;
    EXPECT_LT(std::abs(full / (kd * kd)), 0.01) << "k d = " << kd;
  }
}

// How far the fully nonlinear equations themselves (exact steady waves) are from Stokes, the figures
// of docs/validation.md: the bound second harmonic within 5 % of Stokes to k d = 1 and within 21 % to
// k d = 2 (the seed's equations: 35 % and 72 % low), the amplitude dispersion within 5 % to k d = 1
// (seed: 49 % low) and at least 55 % of Stokes' to k d = 2 (seed: of the wrong sign beyond 1.8).
// Bars a little outside the computed values (0.955, 0.874, 0.795 and 0.972, 0.731, 0.568 at k d =
// 1, 1.5, 2), so the test guards the equations in the solver, not a rounding.
TEST(BoussinesqNonlinear, FullyNonlinearEquationsFollowStokesToKdOfTwo) {
  const double B = 1.0 / 15.0;
  struct Bar {
    double kd, second_harmonic, amplitude_dispersion;  // least ratio to Stokes
  };
  for (const Bar bar : {Bar{0.5, 0.99, 0.99}, Bar{1.0, 0.95, 0.95}, Bar{1.5, 0.86, 0.70}, Bar{2.0, 0.79, 0.55}}) {
    const double k = bar.kd / kDepth_m, a = 1e-5;
    const double a2 = fully_nonlinear_second_harmonic_m(a, k, kDepth_m, B) / stokes_second_harmonic_m(a, k, kDepth_m);
    EXPECT_GT(a2, bar.second_harmonic) << "k d = " << bar.kd;
    EXPECT_LT(a2, 1.0) << "k d = " << bar.kd;
    const double ka = 0.02, amplitude = ka / k;
    const double c = boussinesq_steady_wave(amplitude, k, kDepth_m, B, DispersionDepth::kStillWater, 8, Equations::kFullyNonlinear).phase_speed_m_s;
    const double c0 = boussinesq_steady_wave(1e-7 * amplitude, k, kDepth_m, B, DispersionDepth::kStillWater, 8, Equations::kFullyNonlinear).phase_speed_m_s;
    const double dw = (c / c0 - 1.0) / stokes_frequency_increase(amplitude, k, kDepth_m);
    EXPECT_GT(dw, bar.amplitude_dispersion) << "k d = " << bar.kd;
    EXPECT_LT(dw, 1.05) << "k d = " << bar.kd;
  }
}

// Amplitude dispersion as the dimensionless coefficient (w/w0 - 1) / (k a)^2 of the equations'
// steady wave (k a = 0.02: the third-order coefficient to 1e-3).
double equations_amplitude_dispersion(double kd, DispersionDepth depth_kind) {
  const double B = 1.0 / 15.0, k = kd / kDepth_m, a = 0.02 / k;
  const double c = boussinesq_steady_wave(a, k, kDepth_m, B, depth_kind).phase_speed_m_s;
  const double c0 = boussinesq_steady_wave(1e-7 * a, k, kDepth_m, B, depth_kind).phase_speed_m_s;
  return (c / c0 - 1.0) / (0.02 * 0.02);
}

// Amplitude dispersion of the fully nonlinear equations, likewise.
double fully_nonlinear_amplitude_dispersion(double kd) {
  const double B = 1.0 / 15.0, k = kd / kDepth_m, a = 0.02 / k;
  const double c = boussinesq_steady_wave(a, k, kDepth_m, B, DispersionDepth::kStillWater, 8, Equations::kFullyNonlinear).phase_speed_m_s;
  const double c0 =
      boussinesq_steady_wave(1e-7 * a, k, kDepth_m, B, DispersionDepth::kStillWater, 8, Equations::kFullyNonlinear).phase_speed_m_s;
  return (c / c0 - 1.0) / (0.02 * 0.02);
}

// The curves of docs/validation.md "Nonlinear checks" (copied to docs/images by the command there):
// Stokes, the three sets of equations, and the scheme's measured points (`scheme`, with its
// `scheme_label`; `second_scheme` optional, dispersion only). `suffix` names the files.
void plot_nonlinear_checks(const std::vector<NonlinearPoint>& scheme, const std::string& scheme_label,
                           const std::vector<NonlinearPoint>& second_scheme, const std::string& second_label,
                           const std::string& suffix) {
  const double B = 1.0 / 15.0;
  const Rgb grey{0.3f, 0.3f, 0.3f}, blue{0.12f, 0.47f, 0.71f}, orange{1.0f, 0.5f, 0.05f}, red{0.84f, 0.15f, 0.16f},
      purple{0.58f, 0.40f, 0.74f}, green{0.17f, 0.63f, 0.17f};
  LinePlot transfer;
  transfer.title = "Bound second harmonic / Stokes second order, constant depth";
  transfer.x_label = "k d";
  transfer.y_label = "a2 / a2_Stokes";
  PlotSeries stokes{"Stokes (1847)", {}, {}, grey, false}, full{"fully nonlinear (default)", {}, {}, green, false},
      still{"seed's, D = d", {}, {}, blue, false}, total{"seed's, D = h", {}, {}, orange, false},
      measured{scheme_label, {}, {}, red, true};
  for (double kd = 0.1; kd <= 3.0001; kd += 0.05) {
    const double k = kd / kDepth_m, a = 1e-4, reference = stokes_second_harmonic_m(a, k, kDepth_m);
    stokes.x.push_back(kd), stokes.y.push_back(1.0);
    full.x.push_back(kd), full.y.push_back(fully_nonlinear_second_harmonic_m(a, k, kDepth_m, B) / reference);
    still.x.push_back(kd), still.y.push_back(boussinesq_second_harmonic_m(a, k, kDepth_m, B, DispersionDepth::kStillWater) / reference);
    total.x.push_back(kd), total.y.push_back(boussinesq_second_harmonic_m(a, k, kDepth_m, B, DispersionDepth::kTotal) / reference);
  }
  for (const NonlinearPoint& p : scheme) measured.x.push_back(p.kd), measured.y.push_back(p.scheme_a2 / p.stokes_a2);
  transfer.series = {stokes, full, still, total, measured};
  write_png(render_line_plot(transfer), testing::plot_folder() / ("nonlinear_second_harmonic" + suffix + ".png"));

  LinePlot dispersion;
  dispersion.title = "Amplitude dispersion / Stokes third order (w/w0 - 1, no mean mass flux)";
  dispersion.x_label = "k d";
  dispersion.y_label = "(w/w0 - 1) / Stokes";
  PlotSeries stokes_dw{"Stokes third order", {}, {}, grey, false}, full_dw{"fully nonlinear (default)", {}, {}, green, false},
      still_dw{"seed's, D = d", {}, {}, blue, false}, total_dw{"seed's, D = h", {}, {}, orange, false},
      scheme_dw{scheme_label, {}, {}, red, true}, second_dw{second_label, {}, {}, purple, true};
  for (double kd = 0.5; kd <= 3.0001; kd += 0.05) {
    const double k = kd / kDepth_m;
    const double stokes = stokes_frequency_increase(1.0 / k, k, kDepth_m);  // per (k a)^2
    stokes_dw.x.push_back(kd), stokes_dw.y.push_back(1.0);
    full_dw.x.push_back(kd), full_dw.y.push_back(fully_nonlinear_amplitude_dispersion(kd) / stokes);
    still_dw.x.push_back(kd), still_dw.y.push_back(equations_amplitude_dispersion(kd, DispersionDepth::kStillWater) / stokes);
    total_dw.x.push_back(kd), total_dw.y.push_back(equations_amplitude_dispersion(kd, DispersionDepth::kTotal) / stokes);
  }
  auto add = [](PlotSeries& series, const std::vector<NonlinearPoint>& points) {
    for (const NonlinearPoint& p : points)
      if (p.kd >= 0.5) {
        series.x.push_back(p.kd), series.y.push_back(p.scheme_dw / p.stokes_dw);
      }
  };
  add(scheme_dw, scheme);
  add(second_dw, second_scheme);
  dispersion.series = {stokes_dw, full_dw, still_dw, total_dw, scheme_dw};
  if (!second_scheme.empty()) dispersion.series.push_back(second_dw);
  write_png(render_line_plot(dispersion), testing::plot_folder() / ("nonlinear_amplitude_dispersion" + suffix + ".png"));
}

// The scheme against the continuous equations (both with the dispersive terms on d). Tolerances:
// the scheme converges to the equations at second order in dx (measured at k d = 0.5 and 1: the gap
// in a2 falls from -6.8 % / -2.6 % at 32 cells per wavelength to -1.7 % / -0.7 % at 64, and in the
// amplitude dispersion from -8.8 % / -6.4 % to -2.4 % / -1.7 %), the staggered differences and
// averages of the quadratic terms losing O((2 k dx)^2 / 8) = 1.9 % at the second harmonic's 16 cells
// per wavelength plus the numerical dispersion (dx/d)^2/4 relative to the physical one at small k d.
// So a2 within 10 %, and the nonlinear frequency shift within a tenth of Stokes' (the physical
// effect the scheme must not swamp) or 12 % of the equations' own, whichever is larger.
TEST(BoussinesqNonlinear, SchemeFollowsTheEquationsBoundHarmonicAndAmplitudeDispersion) {
  std::vector<NonlinearPoint> points, old_points;
  std::printf("  k d     a (m)   a2 Stokes  a2 eq.(d)  a2 eq.(h)  a2 steady a2 expected a2 scheme  free a2   dw Stokes  dw eq.   dw scheme\n");
  for (double kd : {0.25, 0.5, 1.0, 1.5, 2.0, 3.0}) {
    const NonlinearPoint p = measure(kd, DispersionDepth::kStillWater, SolverParameters::FaceDepth::kMeanWhereWet);
    points.push_back(p);
    std::printf("%5.2f %9.5f %10.3e %10.3e %10.3e %10.3e %10.3e %10.3e %9.2e %+9.3e %+9.3e %+9.3e\n", p.kd, p.amplitude_m,
                p.stokes_a2, p.equations_a2, p.equations_total_a2, p.steady_a2, p.expected_scheme_a2, p.scheme_a2, p.scheme_free_a2,
                p.stokes_dw, p.equations_dw, p.scheme_dw);
  }
  // The face depth of the solver before issue 19, for the record and the plot (three points).
  for (double kd : {0.5, 1.0, 2.0}) {
    old_points.push_back(measure(kd, DispersionDepth::kStillWater, SolverParameters::FaceDepth::kLargerOfMeanAndAboveBed));
    std::printf("face depth larger of mean and above bed, k d = %.2f: a2 scheme %.3e, dw scheme %+.3e\n", kd,
                old_points.back().scheme_a2, old_points.back().scheme_dw);
  }
  plot_nonlinear_checks(points, "seed's scheme, mean_where_wet", old_points, "seed's scheme, larger_of_mean..", "_seed");
  for (const NonlinearPoint& p : points) {
    EXPECT_NEAR(p.scheme_a2 / p.steady_a2, 1.0, 0.10) << "k d = " << p.kd;
    EXPECT_LT(std::abs(p.scheme_dw - p.equations_dw), std::max(0.1 * p.stokes_dw, 0.12 * std::abs(p.equations_dw)))
        << "k d = " << p.kd;
  }
}

// The scheme with the fully nonlinear terms against its continuous equations (their exact steady
// waves), with the same tolerances and for the same reasons as the seed's equations above; the face
// depth is the mean (mean_where_wet), whose scheme adds no first-order amplitude dispersion of its own.
TEST(BoussinesqNonlinear, FullyNonlinearSchemeFollowsItsEquations) {
  std::printf("  k d     a (m)   a2 Stokes  a2 FN eq.  a2 steady a2 expected a2 scheme  free a2   dw Stokes  dw eq.   dw scheme\n");
  std::vector<NonlinearPoint> points;
  for (double kd : {0.25, 0.5, 1.0, 1.5, 2.0, 3.0}) {
    const NonlinearPoint p = measure(kd, DispersionDepth::kStillWater, SolverParameters::FaceDepth::kMeanWhereWet, Equations::kFullyNonlinear);
    points.push_back(p);
    std::printf("%5.2f %9.5f %10.3e %10.3e %10.3e %10.3e %10.3e %9.2e %+9.3e %+9.3e %+9.3e\n", p.kd, p.amplitude_m, p.stokes_a2,
                p.fully_nonlinear_a2, p.steady_a2, p.expected_scheme_a2, p.scheme_a2, p.scheme_free_a2, p.stokes_dw, p.equations_dw,
                p.scheme_dw);
    EXPECT_NEAR(p.scheme_a2 / p.steady_a2, 1.0, 0.10) << "k d = " << p.kd;
    EXPECT_LT(std::abs(p.scheme_dw - p.equations_dw), std::max(0.1 * p.stokes_dw, 0.12 * std::abs(p.equations_dw)))
        << "k d = " << p.kd;
  }
  plot_nonlinear_checks(points, "scheme, 32 cells/L", {}, "", "");
}

}  // namespace
}  // namespace nearshore::boussinesq
