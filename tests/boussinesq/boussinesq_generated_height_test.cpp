// Issue 19: the internal wave maker (Wei, Kirby & Sun 1999 source, amplitude derived for the
// Madsen & Sorensen equations, docs/solver.md "Wave maker") must send the requested height over the
// k h range the equations carry, 0.3-2.5, within 2 %. "Sends" is measured as the incident wave
// separated from whatever the sponge at the far end reflects (Mansard & Funke 1980 least squares,
// tests/support/incident_reflected.hpp), not as a local crest-to-trough height, which a 2 %
// reflection alone would modulate by +-2 %.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "../support/incident_reflected.hpp"
#include "boussinesq_test_support.hpp"
#include "nearshore/boussinesq/model_dispersion.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::boussinesq {
using ocean::kGravity_m_s2;
namespace {

namespace separation = nearshore::testing;  // tests/support/incident_reflected.hpp

struct GeneratedWave {
  double requested_height_m = 0, incident_height_m = 0, reflection_coefficient = 0;
};

// A flat flume of depth d = 0.5 m on a grid of `cells_per_wavelength` (model wavelength), in units
// of the wavelength L: sponge 0-1.5 L (behind the source), source line at 2.5 L (its Gaussian reaches
// +-0.67 L), gauges at 3.6-4.4 L, open water to 5.5 L, sponge 5.5-7.5 L (2 L: its reflection is
// below 1 % and is separated anyway). Regular waves of amplitude 2 mm (a/d = 0.004, k a <= 0.01:
// linear, the bound second harmonic below 4 % of a at k h = 0.3 and orthogonal to the first in the
// analysis) for 12 periods after the reflected wave from the far sponge has passed the gauges.
GeneratedWave generate_regular_wave(double kh, int cells_per_wavelength) {
  const double depth_m = 0.5, amplitude_m = 0.002;
  const double B = SolverParameters{}.dispersion_coefficient;
  const double k = kh / depth_m;
  // The frequency whose *model* wavenumber is k (model_dispersion.hpp, inverted): the wave maker
  // and the separation both use the model's k, so the test checks the amplitude, not the dispersion.
  const double w = std::sqrt(kGravity_m_s2 * depth_m * k * k * (1 + B * kh * kh) / (1 + (B + 1.0 / 3.0) * kh * kh));
  EXPECT_NEAR(boussinesq_wavenumber(w, depth_m, B), k, 1e-9 * k);
  const double L = 2 * std::numbers::pi / k, period_s = 2 * std::numbers::pi / w, dx = L / cells_per_wavelength;
  const int columns = static_cast<int>(std::lround(7.5 * cells_per_wavelength));
  const HarbourGrid harbour = testing::flume(columns, 1, dx, depth_m);
  SolverParameters parameters = testing::inviscid_parameters();
  // A whole number of steps per period (Courant <= 0.5), so the harmonic analysis is exact.
  const double courant_dt = 0.5 * dx / std::sqrt(kGravity_m_s2 * depth_m);
  const int steps_per_period = static_cast<int>(std::ceil(period_s / courant_dt));
  parameters.time_step_s = period_s / steps_per_period;
  parameters.sponges = {{Side::kWest, 1.5 * L}, {Side::kEast, 2.0 * L}};
  WaveMaker maker;
  maker.kind = WaveMaker::Kind::kComponents;
  maker.sea_state.components = {{amplitude_m, w, 0.0, 0.0}};
  maker.source_line_m = 2.5 * L;
  maker.facing = Side::kWest;
  maker.ramp_time_s = 2 * period_s;
  BoussinesqSolver solver(harbour, parameters, maker);

  // Five gauges on cell centres 3.6-4.4 L, 0.2 L apart: no spacing is a multiple of L/2, so the
  // least-squares separation is well conditioned (Mansard & Funke 1980).
  std::vector<int> gauge_cells;
  for (double position = 3.6; position <= 4.41; position += 0.2)
    gauge_cells.push_back(static_cast<int>(std::lround(position * cells_per_wavelength)));
  // Steady once the front (group speed) has gone source -> far sponge -> back past the gauges:
  // about (3 L + 4 L) / cg plus the ramp; cg >= c / 2, so 14 periods + ramp, taken as 18.
  const double cg_over_c = 0.5 * (1 + 2 * kh / std::sinh(2 * kh));
  const int spin_up_periods = static_cast<int>(std::ceil(2.0 + 8.0 / cg_over_c));
  const int record_periods = 6;
  const long first_step = static_cast<long>(spin_up_periods) * steps_per_period;
  const long last_step = first_step + static_cast<long>(record_periods) * steps_per_period;
  std::vector<std::vector<double>> records(gauge_cells.size());
  const auto& eta = solver.surface_elevation_m().values();
  for (long step = 1; step <= last_step; ++step) {
    solver.step();
    if (step <= first_step) continue;
    for (std::size_t g = 0; g < gauge_cells.size(); ++g) records[g].push_back(eta[static_cast<std::size_t>(gauge_cells[g])]);
  }
  EXPECT_FALSE(solver.check_stability().has_value());
  std::vector<double> positions;
  std::vector<std::complex<double>> amplitudes;
  for (std::size_t g = 0; g < gauge_cells.size(); ++g) {
    positions.push_back(harbour.geometry.cell_centre_x_m(gauge_cells[g]));
    amplitudes.push_back(separation::harmonic_amplitude(records[g], (first_step + 1) * parameters.time_step_s, parameters.time_step_s, w));
  }
  const separation::IncidentReflected waves = separation::separate_incident_reflected(positions, amplitudes, k);
  return {2 * amplitude_m, waves.incident_height_m(), waves.reflection_coefficient()};
}

TEST(SeparationOfIncidentAndReflectedWaves, RecoversASyntheticPartialStandingWave) {
  // The analysis alone: a known incident (1 cm) and reflected (3 mm, another phase) wave, sampled
  // at 20 per period over 5 periods at three Mansard-Funke gauges; recovered to round-off.
  const double k = 2.0, w = 3.0, dt = 2 * std::numbers::pi / w / 20;
  const std::complex<double> incident = std::polar(0.01, 0.4), reflected = std::polar(0.003, -1.1);
  std::vector<double> positions = {1.0, 1.0 + 0.1 * 2 * std::numbers::pi / k, 1.0 + 0.27 * 2 * std::numbers::pi / k};
  std::vector<std::complex<double>> amplitudes;
  for (double x : positions) {
    std::vector<double> record;
    for (int n = 0; n < 100; ++n) {
      const std::complex<double> b = incident * std::polar(1.0, k * x) + reflected * std::polar(1.0, -k * x);
      record.push_back(std::real(b * std::polar(1.0, -w * n * dt)) + 0.002);  // a mean level, rejected
    }
    amplitudes.push_back(separation::harmonic_amplitude(record, 0.0, dt, w));
  }
  const separation::IncidentReflected waves = separation::separate_incident_reflected(positions, amplitudes, k);
  EXPECT_NEAR(std::abs(waves.incident - incident), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(waves.reflected - reflected), 0.0, 1e-12);
  EXPECT_NEAR(waves.reflection_coefficient(), 0.3, 1e-10);
  // Gauges half a wavelength apart cannot separate the two waves: refused, not a silent answer.
  EXPECT_THROW(separation::separate_incident_reflected({0.0, std::numbers::pi / k}, {amplitudes[0], amplitudes[1]}, k), nearshore::Error);
}

TEST(BoussinesqWaveMaker, GeneratedHeightWithinTwoPerCentOverKhFromPointThreeToTwoPointFive) {
  // Two grids: 10 cells per wavelength (the coarsest a case should use; the Berkhoff CI grid has
  // that over the shoal), where the continuous source transfer sent 3.2-4.1 % too much, and 24.
  // Each run is a fraction of a second.
  std::printf("  cells/L  k h   requested H (m)  incident H (m)  error    reflection\n");
  for (const int cells_per_wavelength : {10, 24})
    for (const double kh : {0.3, 0.6, 1.0, 1.5, 2.0, 2.5}) {
      const GeneratedWave wave = generate_regular_wave(kh, cells_per_wavelength);
      const double error = wave.incident_height_m / wave.requested_height_m - 1;
      std::printf("  %2d       %.1f   %.5f          %.5f         %+.2f %%  %.3f\n", cells_per_wavelength, kh,
                  wave.requested_height_m, wave.incident_height_m, 100 * error, wave.reflection_coefficient);
      // Issue 19's bar: the incident height within 2 % of the request at every k h.
      EXPECT_LT(std::abs(error), 0.02) << "k h = " << kh << ", " << cells_per_wavelength << " cells per wavelength";
      // The far sponge (2 L) must reflect little, or the separation would be carrying the test.
      EXPECT_LT(wave.reflection_coefficient, 0.05) << "k h = " << kh;
    }
}

}  // namespace
}  // namespace nearshore::boussinesq
