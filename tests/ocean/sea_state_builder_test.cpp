// The sea-state builder: integral-rule amplitudes, exact looping, seeded phases.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "nearshore/ocean/sea_state_builder.hpp"
#include "nearshore/core/error.hpp"

using namespace nearshore::ocean;

namespace {

DirectionalSeaSpecification jonswap_sea(int frequencies, int directions) {
  DirectionalSeaSpecification spec;
  spec.spectrum = std::make_shared<JonswapSpectrum>(2.0, 8.0, 3.3);
  spec.spreading = std::make_shared<CosineSquaredSpreading>(0.5, 15.0);
  spec.frequency_count = frequencies;
  spec.direction_count = directions;
  spec.seed = 42;
  return spec;
}

double surface_elevation_m(const SeaState& sea, double x, double y, double t) {
  double eta = 0.0;
  for (const WaveComponent& c : sea.components) {
    const double k = wavenumber_from_frequency(c.angular_frequency_rad_s, 0.0);
    eta += c.amplitude_m * std::cos(k * (x * std::cos(c.direction_rad) + y * std::sin(c.direction_rad)) -
                                    c.angular_frequency_rad_s * t + c.phase_rad);
  }
  return eta;
}

}  // namespace

TEST(SeaStateBuilder, HsIsTheSpectrumsForAnyNumberOfComponents) {
  // The cells tile the band holding 99.5 % of m0 (and 99.9 % of D), so the components carry
  // sqrt(0.995 * 0.999) = 99.7 % of Hs whatever their number: 3 % is the bound, and the
  // result does not move with the resolution (checked to 0.1 % between resolutions).
  const double spectrum_hs = 2.0;
  double previous_hs = 0.0;
  for (int frequencies : {1, 3, 10, 32, 100, 300}) {
    for (int directions : {1, 4, 24}) {
      const SeaState sea = build_sea_state(jonswap_sea(frequencies, directions));
      ASSERT_EQ(sea.components.size(), static_cast<std::size_t>(frequencies * directions));
      const double hs = significant_wave_height_m(sea);
      EXPECT_NEAR(hs, spectrum_hs, 0.03 * spectrum_hs) << frequencies << " x " << directions;
      if (previous_hs > 0.0 && directions > 1) {
        EXPECT_NEAR(hs, previous_hs, 1e-3 * spectrum_hs);
      }
      if (directions > 1) previous_hs = hs;
    }
  }
}

TEST(SeaStateBuilder, LoopingSeaHasWholeHarmonicsAndRepeats) {
  // Every w_i T / (2 pi) is a whole number (1e-9: round-off of a product of doubles), Hs stays
  // within 3 %, and eta(t + T) = eta(t) to 1e-9 m (sum of 640 cosines in double).
  DirectionalSeaSpecification spec = jonswap_sea(64, 10);
  spec.loop_period_s = 600.0;
  const SeaState sea = build_sea_state(spec);
  EXPECT_EQ(sea.loop_period_s, 600.0);
  for (const WaveComponent& c : sea.components) {
    const double cycles = c.angular_frequency_rad_s * spec.loop_period_s / (2.0 * std::numbers::pi);
    EXPECT_NEAR(cycles, std::round(cycles), 1e-9);
  }
  EXPECT_NEAR(significant_wave_height_m(sea), 2.0, 0.06);
  for (double t : {0.0, 17.3, 401.0})
    EXPECT_NEAR(surface_elevation_m(sea, 35.0, -12.0, t + 600.0), surface_elevation_m(sea, 35.0, -12.0, t), 1e-9);
}

TEST(SeaStateBuilder, LoopTooShortForTheCellsIsAnError) {
  DirectionalSeaSpecification spec = jonswap_sea(200, 1);
  spec.loop_period_s = 30.0;  // harmonics 0.21 rad/s apart, cells ~0.01 rad/s wide
  EXPECT_THROW(build_sea_state(spec), nearshore::Error);
}

TEST(SeaStateBuilder, PhasesComeFromTheSeed) {
  const SeaState a = build_sea_state(jonswap_sea(16, 4));
  const SeaState b = build_sea_state(jonswap_sea(16, 4));
  DirectionalSeaSpecification other = jonswap_sea(16, 4);
  other.seed = 43;
  const SeaState c = build_sea_state(other);
  EXPECT_EQ(a.seed, 42u);
  int differing = 0;
  for (std::size_t i = 0; i < a.components.size(); ++i) {
    EXPECT_EQ(a.components[i].phase_rad, b.components[i].phase_rad);
    EXPECT_GE(a.components[i].phase_rad, 0.0);
    EXPECT_LT(a.components[i].phase_rad, 2.0 * std::numbers::pi);
    differing += a.components[i].phase_rad != c.components[i].phase_rad;
  }
  EXPECT_EQ(differing, static_cast<int>(a.components.size()));
}

TEST(SeaStateBuilder, EnergyIsCentredOnTheMeanDirectionAndPeak) {
  // The variance-weighted mean direction of a symmetric spreading is its mean (1e-3 rad: the
  // cells are symmetric about it, so only round-off remains), and the largest component sits in
  // the cell holding the peak frequency.
  const SeaState sea = build_sea_state(jonswap_sea(40, 15));
  double sum_sin = 0.0, sum_cos = 0.0, largest = 0.0, w_of_largest = 0.0;
  for (const WaveComponent& c : sea.components) {
    const double variance = 0.5 * c.amplitude_m * c.amplitude_m;
    sum_sin += variance * std::sin(c.direction_rad);
    sum_cos += variance * std::cos(c.direction_rad);
    if (c.amplitude_m > largest) {
      largest = c.amplitude_m;
      w_of_largest = c.angular_frequency_rad_s;
    }
  }
  EXPECT_NEAR(std::atan2(sum_sin, sum_cos), 0.5, 1e-3);
  EXPECT_NEAR(w_of_largest, 2.0 * std::numbers::pi / 8.0, 0.05);
}

TEST(SeaStateBuilder, RegularWave) {
  const SeaState sea = regular_wave_sea_state(1.5, 6.0, std::numbers::pi / 2);
  ASSERT_EQ(sea.components.size(), 1u);
  EXPECT_DOUBLE_EQ(sea.components[0].amplitude_m, 0.75);
  EXPECT_DOUBLE_EQ(sea.components[0].angular_frequency_rad_s, 2.0 * std::numbers::pi / 6.0);
  EXPECT_DOUBLE_EQ(sea.loop_period_s, 6.0);
  EXPECT_THROW(regular_wave_sea_state(1.0, 0.0, 0.0), nearshore::Error);
}

TEST(SeaStateBuilder, MissingPiecesAreErrors) {
  DirectionalSeaSpecification spec = jonswap_sea(8, 2);
  spec.spectrum = nullptr;
  EXPECT_THROW(build_sea_state(spec), nearshore::Error);
  spec = jonswap_sea(0, 2);
  EXPECT_THROW(build_sea_state(spec), nearshore::Error);
  spec = jonswap_sea(8, 2);
  spec.min_frequency_rad_s = 2.0;
  spec.max_frequency_rad_s = 1.0;
  EXPECT_THROW(build_sea_state(spec), nearshore::Error);
}
