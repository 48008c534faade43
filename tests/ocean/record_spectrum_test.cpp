// Welch's spectrum of an elevation record and the sea-state parameters read from it
// (record_spectrum.hpp) against records whose answers are known: a regular wave, a JONSWAP sea
// synthesised from its components, white noise.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "nearshore/core/error.hpp"
#include "nearshore/ocean/linear_waves.hpp"
#include "nearshore/ocean/record_spectrum.hpp"
#include "nearshore/ocean/spectrum.hpp"

using namespace nearshore::ocean;

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// The smallest difference of two directions, degrees.
double angle_between_deg(double a_deg, double b_deg) { return std::abs(std::remainder(a_deg - b_deg, 360.0)); }

// Linear theory's depth-integrated flux under eta = a cos(psi) of a wave of angular frequency omega
// in depth d: the integral of u = a omega cosh(k (z + d)) / sinh(k d) cos(psi) over the depth is
// (omega / k) eta, along the direction of travel.
double flux_per_elevation_m_s(double omega_rad_s, double depth_m) {
  return omega_rad_s / wavenumber_from_frequency(omega_rad_s, depth_m);
}

}  // namespace

TEST(RecordSpectrum, ARegularWaveGivesItsHeightAndPeriodEveryWay) {
  // eta = a cos(2 pi t / T): variance a^2 / 2, so Hm0 = 2 sqrt(2) a; every period is T. T = 10 s on
  // 1024-sample segments of 0.25 s falls between bins (25.6 bins), so the window's leakage is in it.
  const double a = 0.5, T = 10.0, dt = 0.25;
  std::vector<double> eta(4800);
  for (std::size_t j = 0; j < eta.size(); ++j) eta[j] = 0.2 + a * std::cos(kTwoPi * j * dt / T + 0.3);  // 0.2 m set-up
  const RecordSpectrum s = record_spectrum(eta, dt);
  EXPECT_EQ(s.segment_samples, 1024);
  EXPECT_EQ(s.segment_count, 9);
  // The Hann-weighted mean of cos^2 over a segment of 102.4 periods differs from 1/2 by under 1e-3.
  EXPECT_NEAR(s.significant_height_hm0_m, 2.0 * std::sqrt(2.0) * a, 1e-3 * 2.0 * std::sqrt(2.0) * a);
  // The main lobe is symmetric about 1/T: the first moment lands on it; its width (2 bins each
  // side) adds about (0.7 df)^2 to m2 / m0, 0.04 % of 1/T^2 here.
  EXPECT_NEAR(s.mean_period_tm01_s, T, 1e-3 * T);
  EXPECT_NEAR(s.zero_crossing_period_tm02_s, T, 2e-3 * T);
  // The vertex of the parabola through log S at 25.6 bins: a Hann lobe is nearly Gaussian, so a few
  // hundredths of a bin (measured 0.012); the bar is 0.05 of a bin.
  const double bin_in_period_s = T * s.frequency_resolution_hz * T;  // dT = T^2 df
  EXPECT_NEAR(s.peak_period_s, T, 0.05 * bin_in_period_s);
}

TEST(RecordSpectrum, AJonswapSeaGivesTheMomentsItsComponentsHold) {
  // A 3-hour record of a JONSWAP sea (Hs 1.5 m, Tp 12 s, gamma 3.3) made of 960 components of
  // random phase, amplitudes a_i = sqrt(2 S(f_i) df_i), frequencies jittered inside their 0.5 mHz
  // cells so the record never repeats. The record holds m_n = sum a_i^2 / 2 f_i^n exactly (over a
  // long record the cross terms average out); Welch's estimate must return them.
  const JonswapSpectrum jonswap(1.5, 12.0, 3.3);
  const double dt = 0.5, cell_hz = 0.0005;
  std::mt19937 random(20261130);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> frequency_hz, amplitude_m, phase_rad;
  double m0 = 0.0, m1 = 0.0, m2 = 0.0;
  for (double low = 0.02; low < 0.5 - 1e-12; low += cell_hz) {
    const double f = low + cell_hz * unit(random);
    const double density_m2_hz = kTwoPi * jonswap.density_m2_s_rad(kTwoPi * f);
    const double a = std::sqrt(2.0 * density_m2_hz * cell_hz);
    frequency_hz.push_back(f);
    amplitude_m.push_back(a);
    phase_rad.push_back(kTwoPi * unit(random));
    m0 += a * a / 2.0;
    m1 += a * a / 2.0 * f;
    m2 += a * a / 2.0 * f * f;
  }
  std::vector<double> eta(21600);
  for (std::size_t j = 0; j < eta.size(); ++j)
    for (std::size_t i = 0; i < frequency_hz.size(); ++i)
      eta[j] += amplitude_m[i] * std::cos(kTwoPi * frequency_hz[i] * j * dt + phase_rad[i]);
  // 512-sample segments: df = 3.9 mHz, 83 segments (166 degrees of freedom a bin, so a bin scatters
  // by about 11 %) against a peak whose width (sigma fp = 0.07 x 83 mHz) spans 1.5 bins.
  RecordSpectrumOptions options;
  options.segment_samples = 512;
  const RecordSpectrum s = record_spectrum(eta, dt, options);
  EXPECT_EQ(s.segment_count, 84);
  // Hm0 of the record, not of the spectrum's infinite band (m0 of 0.02-0.5 Hz is 99.8 % of it); a
  // 3-hour record of a fixed-amplitude sea varies by well under the 2 % allowed (the wave groups).
  EXPECT_NEAR(s.significant_height_hm0_m, 4.0 * std::sqrt(m0), 0.02 * 4.0 * std::sqrt(m0));
  EXPECT_NEAR(4.0 * std::sqrt(m0), 1.5, 0.01);
  EXPECT_NEAR(s.mean_period_tm01_s, m0 / m1, 0.02 * m0 / m1);
  EXPECT_NEAR(s.zero_crossing_period_tm02_s, std::sqrt(m0 / m2), 0.02 * std::sqrt(m0 / m2));
  // The peak within one bin of 12 s (one bin is 0.56 s of period there).
  EXPECT_NEAR(s.peak_period_s, 12.0, 12.0 * 12.0 * s.frequency_resolution_hz);
}

TEST(RecordSpectrum, WhiteNoiseSpreadsItsVarianceOverTheBand) {
  // Parseval with the window's power divided out: the density of unit-variance white noise is 2 dt
  // (one-sided) at every frequency, and its integral the variance.
  std::mt19937 random(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> eta(65536);
  for (double& v : eta) v = normal(random);
  const double dt = 0.1;
  const RecordSpectrum s = record_spectrum(eta, dt);
  // 2^16 samples: m0 scatters by about sqrt(2 / 65536) = 0.6 %; Hm0 by half that.
  EXPECT_NEAR(s.significant_height_hm0_m, 4.0, 4.0 * 0.01);
  double mean_density = 0.0;
  for (std::size_t k = 1; k + 1 < s.variance_density_m2_hz.size(); ++k) mean_density += s.variance_density_m2_hz[k];
  mean_density /= static_cast<double>(s.variance_density_m2_hz.size() - 2);
  EXPECT_NEAR(mean_density, 2.0 * dt, 0.02 * 2.0 * dt);
  // A band: [1, 2] Hz of a 5 Hz Nyquist holds a fifth of the variance.
  RecordSpectrumOptions band;
  band.min_frequency_hz = 1.0;
  band.max_frequency_hz = 2.0;
  const RecordSpectrum part = record_spectrum(eta, dt, band);
  EXPECT_NEAR(part.significant_height_hm0_m, 4.0 * std::sqrt(0.2), 0.02 * 4.0 * std::sqrt(0.2));
}

TEST(RecordSpectrum, BadRecordsAreRefusedNamingWhatIsWrong) {
  const std::vector<double> short_record(10, 0.0);
  try {
    record_spectrum(short_record, 0.5);
    FAIL() << "a 10-sample record was accepted";
  } catch (const nearshore::Error& e) {
    EXPECT_NE(std::string(e.what()).find("elevation_m holds 10 samples"), std::string::npos) << e.what();
  }
  std::vector<double> record(100, 0.1);
  record[42] = std::nan("");
  try {
    record_spectrum(record, 0.5);
    FAIL() << "a NaN sample was accepted";
  } catch (const nearshore::Error& e) {
    EXPECT_NE(std::string(e.what()).find("elevation_m[42]"), std::string::npos) << e.what();
  }
  record[42] = 0.0;
  EXPECT_THROW(record_spectrum(record, 0.0), nearshore::Error);
  EXPECT_THROW(record_spectrum(record, std::numeric_limits<double>::infinity()), nearshore::Error);
  RecordSpectrumOptions options;
  options.segment_samples = 200;  // longer than the record
  EXPECT_THROW(record_spectrum(record, 0.5, options), nearshore::Error);
  options.segment_samples = 0;
  options.min_frequency_hz = 1.5;  // above the Nyquist frequency of 0.5 s samples (1 Hz)
  EXPECT_THROW(record_spectrum(record, 0.5, options), nearshore::Error);
}

TEST(DirectionalRecordSpectrum, ARegularWaveGivesItsDirection) {
  // eta, P, Q of one linear wave of 8 s in 15 m travelling towards theta (counter-clockwise from
  // east), over a set-up and a steady current (the segments' means are removed). Every bin's P and Q
  // are eta's times cos theta and sin theta, so a1 = cos theta, b1 = sin theta to rounding (the
  // float FFT), and the spread is 0.
  const double a = 0.4, T = 8.0, dt = 0.2, depth = 15.0;
  const double omega = kTwoPi / T, transfer = flux_per_elevation_m_s(omega, depth);
  for (const double theta_deg : {35.0, 160.0, -100.0, 0.0}) {
    const double theta = theta_deg * std::numbers::pi / 180.0;
    std::vector<double> eta(3000), flux_x(3000), flux_y(3000);
    for (std::size_t j = 0; j < eta.size(); ++j) {
      const double wave = a * std::cos(omega * j * dt + 1.1);
      eta[j] = 0.1 + wave;
      flux_x[j] = 0.8 + transfer * wave * std::cos(theta);
      flux_y[j] = -0.3 + transfer * wave * std::sin(theta);
    }
    const DirectionalRecordSpectrum s = directional_record_spectrum(eta, flux_x, flux_y, dt);
    EXPECT_NEAR(angle_between_deg(s.peak_direction_deg, theta_deg), 0.0, 0.05) << theta_deg;
    EXPECT_NEAR(angle_between_deg(s.mean_direction_deg, theta_deg), 0.0, 0.05) << theta_deg;
    EXPECT_LT(s.directional_spread_deg, 0.5) << theta_deg;
    // The elevation's parameters are record_spectrum's, bit for bit.
    const RecordSpectrum alone = record_spectrum(eta, dt);
    EXPECT_EQ(s.elevation.significant_height_hm0_m, alone.significant_height_hm0_m);
    EXPECT_EQ(s.elevation.peak_period_s, alone.peak_period_s);
    EXPECT_EQ(s.elevation.variance_density_m2_hz, alone.variance_density_m2_hz);
  }
}

TEST(DirectionalRecordSpectrum, AJonswapSeaGivesItsMeanDirectionAndSpread) {
  // A 3-hour JONSWAP record (Hs 1.5 m, Tp 10 s) in 20 m whose 960 components travel in directions
  // drawn from cos^2s((theta - theta0) / 2), theta0 = 60 degrees, s = 10 (single summation: one
  // direction per component). Its first-order moments are those its components hold,
  // a1 = sum a_i^2 cos theta_i / sum a_i^2 and b1 alike, so its mean direction is atan2(b1, a1)
  // (close to theta0) and its spread sqrt(2 (1 - |(a1, b1)|)) (close to the distribution's
  // sqrt(2 / (s + 1)) = 24.4 degrees; Kuik et al. 1988).
  const JonswapSpectrum jonswap(1.5, 10.0, 3.3);
  const double dt = 0.5, cell_hz = 0.0005, depth = 20.0, theta0 = 60.0 * std::numbers::pi / 180.0, spreading_s = 10.0;
  std::mt19937 random(45);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  struct Component {
    double omega, amplitude, phase, theta, transfer;
  };
  std::vector<Component> components;
  double a1_sum = 0.0, b1_sum = 0.0, weight = 0.0;
  for (double low = 0.02; low < 0.5 - 1e-12; low += cell_hz) {
    const double f = low + cell_hz * unit(random);
    const double amplitude = std::sqrt(2.0 * kTwoPi * jonswap.density_m2_s_rad(kTwoPi * f) * cell_hz);
    double offset = 0.0;  // rejection sampling of cos^2s(offset / 2)
    do offset = std::numbers::pi * (2.0 * unit(random) - 1.0);
    while (unit(random) > std::pow(std::cos(offset / 2.0), 2.0 * spreading_s));
    const double theta = theta0 + offset;
    components.push_back({kTwoPi * f, amplitude, kTwoPi * unit(random), theta, flux_per_elevation_m_s(kTwoPi * f, depth)});
    a1_sum += amplitude * amplitude * std::cos(theta);
    b1_sum += amplitude * amplitude * std::sin(theta);
    weight += amplitude * amplitude;
  }
  std::vector<double> eta(21600), flux_x(21600), flux_y(21600);
  for (std::size_t j = 0; j < eta.size(); ++j)
    for (const Component& c : components) {
      const double wave = c.amplitude * std::cos(c.omega * j * dt + c.phase);
      eta[j] += wave;
      flux_x[j] += c.transfer * wave * std::cos(c.theta);
      flux_y[j] += c.transfer * wave * std::sin(c.theta);
    }
  RecordSpectrumOptions options;
  options.segment_samples = 512;
  const DirectionalRecordSpectrum s = directional_record_spectrum(eta, flux_x, flux_y, dt, options);
  const double held_direction_deg = std::atan2(b1_sum, a1_sum) * 180.0 / std::numbers::pi;
  const double held_spread_deg =
      std::sqrt(2.0 * (1.0 - std::hypot(a1_sum, b1_sum) / weight)) * 180.0 / std::numbers::pi;
  // The draw itself (seed 45: 57.2 and 26.1 degrees): the energy-weighted mean of directions
  // scattered by 24 degrees, where the few dozen components near the peak carry most of the weight,
  // is theta0 to a few degrees (bars 5 and 3).
  EXPECT_NEAR(held_direction_deg, 60.0, 5.0);
  EXPECT_NEAR(held_spread_deg, 24.4, 3.0);
  // Welch's estimate of what the record holds: each bin's a1, b1 is normalised by its own spectra,
  // and the band weights bins by S_ee; within 1 degree of the components' moments (measured 0.43
  // and 0.12 degrees).
  EXPECT_NEAR(angle_between_deg(s.mean_direction_deg, held_direction_deg), 0.0, 1.0);
  EXPECT_NEAR(s.directional_spread_deg, held_spread_deg, 1.0);
  // At the peak (10 s) a bin holds about 8 components of scattered directions: within a spread.
  EXPECT_NEAR(angle_between_deg(s.peak_direction_deg, 60.0), 0.0, 24.4);
  RecordProperty("mean_direction_deg", std::to_string(s.mean_direction_deg));
  RecordProperty("held_direction_deg", std::to_string(held_direction_deg));
  RecordProperty("spread_deg", std::to_string(s.directional_spread_deg));
  RecordProperty("held_spread_deg", std::to_string(held_spread_deg));
  RecordProperty("peak_direction_deg", std::to_string(s.peak_direction_deg));
}

TEST(DirectionalRecordSpectrum, FluxesThatDoNotMatchTheElevationAreRefused) {
  const std::vector<double> eta(100, 0.0), short_flux(99, 0.0);
  std::vector<double> flux(100, 0.0);
  try {
    directional_record_spectrum(eta, short_flux, flux, 0.5);
    FAIL() << "a flux_x of 99 samples was accepted";
  } catch (const nearshore::Error& e) {
    EXPECT_NE(std::string(e.what()).find("flux_x holds 99 samples"), std::string::npos) << e.what();
  }
  flux[7] = std::nan("");
  try {
    directional_record_spectrum(eta, eta, flux, 0.5);
    FAIL() << "a NaN flux was accepted";
  } catch (const nearshore::Error& e) {
    EXPECT_NE(std::string(e.what()).find("flux_y[7]"), std::string::npos) << e.what();
  }
  // Still water: no direction, said as NaN rather than a made-up 0.
  const DirectionalRecordSpectrum still = directional_record_spectrum(eta, eta, eta, 0.5);
  EXPECT_TRUE(std::isnan(still.mean_direction_deg));
  EXPECT_TRUE(std::isnan(still.peak_direction_deg));
}
