// Coherence (issue 5): the harbour's Boussinesq wave maker driven by the deep-water field's own
// components makes the same waves as the field, so the runtime can blend the two.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "nearshore/bake/boussinesq_solver.hpp"
#include "nearshore/bake/deep_water.hpp"
#include "nearshore/core/harbour_grid.hpp"

using namespace nearshore;
using namespace nearshore::bake;
constexpr double kPi = std::numbers::pi;

namespace {

double linear_elevation_m(const SeaState& sea, double depth_m, double x, double y, double t) {
  double eta = 0.0;
  for (const WaveComponent& c : sea.components) {
    const double k = wavenumber_from_frequency(c.angular_frequency_rad_s, depth_m);
    eta += c.amplitude_m * std::cos(k * (x * std::cos(c.direction_rad) + y * std::sin(c.direction_rad)) -
                                    c.angular_frequency_rad_s * t + c.phase_rad);
  }
  return eta;
}

}  // namespace

TEST(Coherence, BoussinesqWaveMakerReproducesTheDeepWaterField) {
  // A flat 10 m basin, 40 m wide (long-crested waves travelling north), 500 m long, dx = 2 m.
  // The deep-water field: JONSWAP Hs 0.3 m, Tp 7 s, narrow cos^2s (s = 1000) towards north, at the
  // basin's depth, one 240 m cascade of 64^2 (cells 0.026 rad/m wide: at the peak, the
  // kx = 0 cells span +-0.13 rad, three standard deviations of the spreading). The wave maker gets the field's components that
  // travel due north (kx = 0, which the 40 m basin with side walls can carry) and that the grid
  // resolves (>= 12 cells per wavelength). The reference is the same components summed with the
  // exact linear dispersion: that sum IS the FFT field (DeepWaterField.FftIsTheDirectSumOf...).
  const double depth_m = 10.0, spacing_m = 2.0;
  auto jonswap = std::make_shared<JonswapSpectrum>(0.3, 7.0, 3.3);
  auto spreading = std::make_shared<CosineSquaredSpreading>(kPi / 2.0, 1000.0);
  DeepWaterSpecification spec;
  spec.spectrum = std::make_shared<DirectionalWavenumberSpectrum>(jonswap, spreading, depth_m);
  spec.tile_lengths_m = {240.0};
  spec.grid_size = 64;
  spec.still_water_depth_m = depth_m;
  spec.seed = 11;
  const DeepWaterField field(spec);
  SeaState north;
  north.seed = spec.seed;
  double kept_variance = 0.0;
  for (const WaveComponent& c : field.wave_components().components) {
    const double k = wavenumber_from_frequency(c.angular_frequency_rad_s, depth_m);
    if (c.direction_rad == kPi / 2.0 && k * spacing_m <= 2.0 * kPi / 12.0) {
      north.components.push_back(c);
      kept_variance += 0.5 * c.amplitude_m * c.amplitude_m;
    }
  }
  const double field_variance = field.cascade_variance_m2(0);
  std::printf("coherence: %zu components due north carry %.1f %% of the field's variance\n", north.components.size(),
              100.0 * kept_variance / field_variance);
  ASSERT_GT(kept_variance, 0.9 * field_variance);

  GridGeometry geometry;
  geometry.columns = 20;
  geometry.rows = 250;
  geometry.spacing_m = spacing_m;
  const HarbourGrid basin = HarbourGrid::open_water(geometry, static_cast<float>(depth_m));
  SolverParameters parameters;
  parameters.courant_number = 0.5;
  parameters.chezy_coefficient = 0.0;
  parameters.breaking.enabled = false;
  parameters.sponges = {{Side::kSouth, 50.0}, {Side::kNorth, 120.0}};
  WaveMaker maker;
  maker.kind = WaveMaker::Kind::kComponents;
  maker.sea_state = north;
  maker.source_line_m = 70.0;
  maker.facing = Side::kSouth;
  maker.ramp_time_s = 15.0;
  BoussinesqSolver solver(basin, parameters, maker);

  // Gauges from 1 to 5 peak wavelengths (Lp = 60 m) beyond the source line, sampled each step
  // over 100 s once the slowest resolved waves have crossed the basin.
  const std::vector<double> gauge_y_m = {130.0, 190.0, 250.0, 310.0, 370.0};
  std::vector<double> error_sq(gauge_y_m.size(), 0.0), reference_sq(gauge_y_m.size(), 0.0);
  const double x_m = 0.5 * geometry.width_m();
  while (solver.time_s() < 200.0) {
    solver.step();
    if (solver.time_s() < 100.0) continue;
    for (std::size_t g = 0; g < gauge_y_m.size(); ++g) {
      const double reference = linear_elevation_m(north, depth_m, x_m, gauge_y_m[g], solver.time_s());
      const double error = solver.surface_elevation_at(x_m, gauge_y_m[g]) - reference;
      error_sq[g] += error * error;
      reference_sq[g] += reference * reference;
    }
  }
  ASSERT_FALSE(solver.check_stability().has_value());
  for (std::size_t g = 0; g < gauge_y_m.size(); ++g) {
    const double relative_rms = std::sqrt(error_sq[g] / reference_sq[g]);
    std::printf("coherence: %5.0f m from the source line: relative RMS %.3f\n", gauge_y_m[g] - maker.source_line_m,
                relative_rms);
    // Measured 0.084 at one peak wavelength from the line (the blending zone of
    // docs/deep-water.md), growing to 0.16 at five as the Madsen-Sorensen wavenumbers drift in
    // phase from the exact linear ones. Bounds: 0.12 at one wavelength, 0.2 everywhere.
    EXPECT_LT(relative_rms, g == 0 ? 0.12 : 0.2) << gauge_y_m[g];
  }
}
