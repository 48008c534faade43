// The effective-depth limit (issue 14 item 1, docs/solver.md "Effective depth"): an 8 s swell over
// a 74 m deep channel (Airy k d = 4.6, beyond the k d = 3 the B = 1/15 equations hold) and over a
// 74 m -> 8 m slope, against linear (Airy) theory over the TRUE depth.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "boussinesq_test_support.hpp"
#include "nearshore/boussinesq/model_dispersion.hpp"
#include "nearshore/ocean/linear_waves.hpp"

namespace nearshore::boussinesq {

using namespace nearshore::ocean;
namespace {

constexpr double kPeriod_s = 8.0, kAngularFrequency = 2 * std::numbers::pi / kPeriod_s, kChannel_m = 74.0, kHeight_m = 0.1;

// The complex amplitude of eta at angular frequency w in every cell, over the last `window_s` of a
// run of `duration_s` (a whole number of periods): A = (2/N) sum eta(t) exp(i w t), so that
// eta = |A| cos(w t - arg A) and arg A = k x - phi0 for a progressive wave.
std::vector<std::complex<double>> harmonic_amplitude(BoussinesqSolver& solver, double duration_s, double window_s) {
  const Raster<float>& eta = solver.surface_elevation_m();
  std::vector<std::complex<double>> sum(eta.size());
  long samples = 0;
  while (solver.time_s() < duration_s - 1e-9) {
    solver.step();
    if (solver.time_s() <= duration_s - window_s + 1e-9) continue;
    const std::complex<double> rotation = std::polar(1.0, kAngularFrequency * solver.time_s());
    for (std::size_t i = 0; i < eta.size(); ++i) sum[i] += static_cast<double>(eta.values()[i]) * rotation;
    ++samples;
  }
  for (auto& value : sum) value *= 2.0 / static_cast<double>(samples);
  return sum;
}

// Wavenumber from the slope of the unwrapped phase over cells [first, last) (least squares): the
// residual reflection of the sponges modulates the phase within a wavelength, the fit over several
// wavelengths averages it out.
double fitted_wavenumber(const std::vector<std::complex<double>>& amplitude, const GridGeometry& g, int first, int last) {
  std::vector<double> x, phase;
  double unwrapped = std::arg(amplitude[static_cast<std::size_t>(first)]);
  for (int c = first; c < last; ++c) {
    if (c > first) {
      double step = std::arg(amplitude[static_cast<std::size_t>(c)]) - std::arg(amplitude[static_cast<std::size_t>(c - 1)]);
      step -= 2 * std::numbers::pi * std::round(step / (2 * std::numbers::pi));
      unwrapped += step;
    }
    x.push_back(g.cell_centre_x_m(c));
    phase.push_back(unwrapped);
  }
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sx += x[i], sy += phase[i], sxx += x[i] * x[i], sxy += x[i] * phase[i];
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

double mean_height_m(const std::vector<std::complex<double>>& amplitude, int first, int last) {
  double sum = 0.0;
  for (int c = first; c < last; ++c) sum += 2.0 * std::abs(amplitude[static_cast<std::size_t>(c)]);
  return sum / (last - first);
}

WaveMaker eight_second_maker(double source_line_m) {
  WaveMaker maker;
  maker.kind = WaveMaker::Kind::kComponents;
  maker.sea_state.components = {{0.5 * kHeight_m, kAngularFrequency, 0.0, 0.0}};  // H / L = 0.001: linear
  maker.source_line_m = source_line_m;
  maker.facing = Side::kWest;
  maker.ramp_time_s = 2 * kPeriod_s;
  return maker;
}

}  // namespace

// The figures docs/solver.md states, from the seed's own dispersion relation (seed 003 eq. 1-5,
// w^2 = g d k^2 (1 + B (kd)^2) / (1 + (B + 1/3)(kd)^2) with B = 1/15).
TEST(BoussinesqEffectiveDepth, ToleranceIsTheErrorOfTheEquationsAtKdThree) {
  const double B = 1.0 / 15.0;
  // At a given wavenumber, k d = 3: c^2 / (g d) = 1.6 / 4.6 against tanh(3) / 3.
  const double at_wavenumber = std::sqrt((1.6 / 4.6) / (std::tanh(3.0) / 3.0)) - 1.0;
  EXPECT_NEAR(at_wavenumber, 0.0240, 5e-4);
  // At a given frequency (what a wave maker fixes) the error is larger: 4.11 %.
  EXPECT_NEAR(carried_phase_speed_tolerance(B), 0.0411, 5e-4);
  // The 8 s swell over 74 m: k d = 4.6 and 12.8 % too fast without the limit.
  EXPECT_NEAR(wavenumber_from_frequency(kAngularFrequency, kChannel_m) * kChannel_m, 4.65, 0.01);
  EXPECT_NEAR(phase_speed_error(kAngularFrequency, kChannel_m, kChannel_m, B), 0.128, 0.002);
  // The limit for that wave: 47.5 m (k d = 3 there); within tolerance over 74 m.
  const double limit_m = effective_depth_limit_m(kAngularFrequency);
  EXPECT_NEAR(wavenumber_from_frequency(kAngularFrequency, limit_m) * limit_m, kLargestCarriedKd, 1e-9);
  EXPECT_LT(std::abs(phase_speed_error(kAngularFrequency, limit_m, kChannel_m, B)), carried_phase_speed_tolerance(B));
  std::printf("tolerance %.4f, limit %.2f m, error over 74 m %+.4f (no limit %+.4f)\n", carried_phase_speed_tolerance(B), limit_m,
              phase_speed_error(kAngularFrequency, limit_m, kChannel_m, B), phase_speed_error(kAngularFrequency, kChannel_m, kChannel_m, B));
}

// The band rule: without a limit a 74 m channel carries waves only up to k d = 3 there (10 s);
// with one, a band starting at 10 s reaches further, and its longest wave stays within tolerance.
TEST(BoussinesqEffectiveDepth, BandOverADeepChannelReachesShorterWaves) {
  const double B = 1.0 / 15.0, lowest = 2 * std::numbers::pi / 10.0;
  const double without = frequency_from_wavenumber(kLargestCarriedKd / kChannel_m, kChannel_m);
  const double highest = highest_frequency_over_effective_depth_rad_s(lowest, kChannel_m, B);
  EXPECT_GT(highest, without * 1.1);
  const double limit_m = effective_depth_limit_m(highest);
  const double tolerance = carried_phase_speed_tolerance(B);
  EXPECT_NEAR(phase_speed_error(lowest, limit_m, kChannel_m, B), -tolerance, 1e-4);  // the longest wave sets it
  EXPECT_LE(phase_speed_error(highest, limit_m, limit_m, B), tolerance + 1e-9);
  // Never less than without a limit, also where the longest wave feels the bottom (10 m).
  EXPECT_GE(highest_frequency_over_effective_depth_rad_s(lowest, 10.0, B), frequency_from_wavenumber(0.3, 10.0));
  std::printf("band from 10 s over 74 m: up to %.2f s (%.2f s without the limit), limit %.1f m\n", 2 * std::numbers::pi / highest,
              2 * std::numbers::pi / without, limit_m);
}

// An 8 s wave over a flat 74 m channel, 5 m cells (20 per wavelength), sponges at both ends: phase
// speed and height against Airy over 74 m, with and without the limit.
TEST(BoussinesqEffectiveDepth, EightSecondSwellOverA74mChannel) {
  const double spacing_m = 5.0, B = 1.0 / 15.0;
  const HarbourGrid harbour = testing::flume(240, 1, spacing_m, kChannel_m);
  const double airy_m_s = kAngularFrequency / wavenumber_from_frequency(kAngularFrequency, kChannel_m);
  auto run = [&](double limit_m) {
    SolverParameters parameters = testing::inviscid_parameters();
    parameters.time_step_s = kPeriod_s / 64;  // Courant 0.44 (no limit) .. 0.35 (limit)
    parameters.effective_depth_limit_m = limit_m;
    parameters.sponges = {{Side::kWest, 120.0}, {Side::kEast, 250.0}};
    BoussinesqSolver solver(harbour, parameters, eight_second_maker(160.0));
    const auto amplitude = harmonic_amplitude(solver, 240.0, 10 * kPeriod_s);
    // Measured from 300 m to 850 m: five wavelengths, clear of the source strip and the sponges.
    const double k = fitted_wavenumber(amplitude, harbour.geometry, 60, 170);
    return std::pair{kAngularFrequency / k / airy_m_s - 1.0, mean_height_m(amplitude, 60, 170) / kHeight_m - 1.0};
  };
  const double limit_m = effective_depth_limit_m(kAngularFrequency);
  const auto [speed_error, height_error] = run(limit_m);
  const auto [uncapped_speed_error, uncapped_height_error] = run(0.0);
  std::printf("limit %.2f m: c/c_Airy - 1 = %+.4f (continuous equations %+.4f), H/H0 - 1 = %+.4f\n", limit_m, speed_error,
              phase_speed_error(kAngularFrequency, limit_m, kChannel_m, B), height_error);
  std::printf("no limit:    c/c_Airy - 1 = %+.4f (continuous equations %+.4f), H/H0 - 1 = %+.4f\n", uncapped_speed_error,
              phase_speed_error(kAngularFrequency, kChannel_m, kChannel_m, B), uncapped_height_error);
  // Phase speed within the limit's tolerance, 4.11 % (the error the equations themselves have at
  // k d = 3, their accepted range) plus 1 % for the scheme at 20 cells per wavelength (it is
  // 0.3 % slower than the continuous equations at k d = 3, boussinesq_dispersion_test.cpp).
  EXPECT_LT(std::abs(speed_error), carried_phase_speed_tolerance(B) + 0.01);
  // The limit is what brings it there: without it the wave is 12 % fast.
  EXPECT_GT(uncapped_speed_error, 0.08);
  // Height within 3 %: the wave maker's accuracy (boussinesq_wave_maker_test.cpp) and the sponges'
  // residual reflection; over a flat bed linear theory keeps H = H0.
  EXPECT_LT(std::abs(height_error), 0.03);
}

// The same wave from 74 m over a 1:20 slope to 8 m: height against linear shoaling over the TRUE
// depth, H/H0 = sqrt(cg(74 m) / cg(d)), and the phase speed on the 8 m shelf against Airy.
TEST(BoussinesqEffectiveDepth, EightSecondSwellOverA74To8mSlope) {
  const double spacing_m = 4.0, deep_m = kChannel_m, shallow_m = 8.0, slope_start_m = 500.0, slope = 1.0 / 20.0;
  const int columns = 700;
  HarbourGrid harbour = testing::flume(columns, 1, spacing_m, deep_m);
  auto depth_at = [&](double x) { return std::clamp(deep_m - (x - slope_start_m) * slope, shallow_m, deep_m); };
  for (int c = 0; c < columns; ++c)
    harbour.still_water_depth_m(c, 0) = static_cast<float>(depth_at(harbour.geometry.cell_centre_x_m(c)));
  SolverParameters parameters = testing::inviscid_parameters();
  parameters.time_step_s = kPeriod_s / 80;  // Courant 0.54 over the 47.5 m limit
  parameters.effective_depth_limit_m = effective_depth_limit_m(kAngularFrequency);
  parameters.sponges = {{Side::kWest, 120.0}, {Side::kEast, 250.0}};
  BoussinesqSolver solver(harbour, parameters, eight_second_maker(160.0));
  const auto amplitude = harmonic_amplitude(solver, 560.0, 10 * kPeriod_s);

  const GridGeometry& g = harbour.geometry;
  auto cg = [&](double d) { return group_speed_m_s(wavenumber_from_frequency(kAngularFrequency, d), d); };
  // H0 measured over the deep flat (it is the generated height, checked in the test above).
  const double generated_m = mean_height_m(amplitude, 65, 115);
  double worst = 0.0;
  std::printf("  x (m)  d (m)   H/H0 model  linear\n");
  for (int c = 130; c < 620; c += 10) {
    const double x = g.cell_centre_x_m(c), d = depth_at(x);
    // Mean over one local wavelength of cells, so partial reflection does not alias in.
    const int half = static_cast<int>(0.5 * 2 * std::numbers::pi / wavenumber_from_frequency(kAngularFrequency, d) / spacing_m);
    const double ratio = mean_height_m(amplitude, c - half, c + half + 1) / generated_m;
    const double expected = std::sqrt(cg(deep_m) / cg(d));
    std::printf("%7.1f  %5.1f   %6.3f     %6.3f\n", x, d, ratio, expected);
    worst = std::max(worst, std::abs(ratio / expected - 1.0));
  }
  // 5 %: the 3 % of the mild-slope test (boussinesq_wave_maker_test.cpp: Madsen & Sorensen shoaling
  // within 1-2 % of linear theory, reflections) plus the group speed of the wave over the limited
  // depth, which enters H0: Airy cg at k d = 3 is 2.8 % above deep water, so H0 is up to 1.4 % low.
  EXPECT_LT(worst, 0.05);
  // The 8 m shelf (x from 1900 m to 2300 m, 6 wavelengths of 66 m): k d = 0.76, no limit active.
  const double k = fitted_wavenumber(amplitude, g, 475, 575);
  const double speed_error = wavenumber_from_frequency(kAngularFrequency, shallow_m) / k - 1.0;
  std::printf("8 m shelf: c/c_Airy - 1 = %+.4f\n", speed_error);
  // 2 %: the scheme's bound at 16 cells per wavelength and k d < 1 (boussinesq_dispersion_test.cpp).
  EXPECT_LT(std::abs(speed_error), 0.02);
}

}  // namespace nearshore::boussinesq
