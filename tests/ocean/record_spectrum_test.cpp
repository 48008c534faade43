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
#include "nearshore/ocean/record_spectrum.hpp"
#include "nearshore/ocean/spectrum.hpp"

using namespace nearshore::ocean;

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

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
