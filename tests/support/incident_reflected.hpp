#pragma once
// Separation of a regular wave record into its incident and reflected parts, from gauges along the
// direction of travel: the least-squares method of Mansard & Funke (1980), which for two gauges is
// the exact solution of Goda & Suzuki (1976). Used wherever a test must know the height a wave
// maker really sends, with whatever the far end reflects superposed on it (issue 19).
//
// Model: at gauge p (position x_p, metres) the component of frequency w is
//   eta_p(t) = Re[ B_p exp(-i w t) ],   B_p = Z_I exp(i k x_p) + Z_R exp(-i k x_p) + noise,
// Z_I the incident (travelling towards +x) and Z_R the reflected complex amplitude. Mansard & Funke
// minimise sum_p |B_p - Z_I e_p - Z_R / e_p|^2 (e_p = exp(i k x_p)); the 2 x 2 normal equations
//   [ N        S* ] [Z_I]   [ sum B_p e_p* ]
//   [ S        N  ] [Z_R] = [ sum B_p e_p  ],   S = sum e_p^2,
// are singular only when every pair of gauges is a whole number of half wavelengths apart
// (|S| = N): choose spacings away from L/2 multiples (Mansard & Funke: x12 ~ L/10, L/6 < x13 < L/3).
// Header only: the test executables that use it share no library.
#include <cmath>
#include <complex>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace nearshore::testing {

/// The complex amplitude B of exp(-i w t) in a record sampled every `sample_interval_s` from time
/// `start_time_s`, over the longest span of whole periods 2 pi / w that fits: B = (2/N) sum eta_n
/// exp(i w t_n). Over whole periods of a uniformly sampled record the harmonics and the mean are
/// orthogonal to it, so it is the least-squares amplitude of that frequency.
inline std::complex<double> harmonic_amplitude(const std::vector<double>& elevation_m, double start_time_s,
                                               double sample_interval_s, double angular_frequency_rad_s) {
  const double period_s = 2.0 * std::numbers::pi / angular_frequency_rad_s;
  const double span_s = sample_interval_s * static_cast<double>(elevation_m.size());
  const double whole_periods = std::floor(span_s / period_s);
  if (whole_periods < 1.0) throw std::invalid_argument("harmonic_amplitude: the record is shorter than one period");
  // Samples spanning whole periods; exact only when the period is a whole number of samples, and
  // within O(dt / record) otherwise (the caller picks dt = T / integer where it can).
  const auto count = static_cast<std::size_t>(std::lround(whole_periods * period_s / sample_interval_s));
  std::complex<double> sum = 0.0;
  for (std::size_t n = 0; n < count; ++n) {
    const double t = start_time_s + sample_interval_s * static_cast<double>(n);
    sum += elevation_m[n] * std::polar(1.0, angular_frequency_rad_s * t);
  }
  return 2.0 * sum / static_cast<double>(count);
}

struct IncidentReflected {
  std::complex<double> incident;   ///< Z_I: incident amplitude (metres) and phase at x = 0
  std::complex<double> reflected;  ///< Z_R
  double incident_height_m() const { return 2.0 * std::abs(incident); }
  double reflected_height_m() const { return 2.0 * std::abs(reflected); }
  double reflection_coefficient() const { return std::abs(reflected) / std::abs(incident); }
};

/// Mansard & Funke (1980) least squares over any number (>= 2) of gauges at `position_m` with the
/// complex amplitudes `amplitude` (harmonic_amplitude of each record) of a wave of wavenumber
/// `wavenumber_rad_m` travelling towards +x.
inline IncidentReflected separate_incident_reflected(const std::vector<double>& position_m,
                                                     const std::vector<std::complex<double>>& amplitude,
                                                     double wavenumber_rad_m) {
  if (position_m.size() < 2 || position_m.size() != amplitude.size())
    throw std::invalid_argument("separate_incident_reflected: needs at least two gauges, one amplitude each");
  const double n = static_cast<double>(position_m.size());
  std::complex<double> s = 0.0, right_incident = 0.0, right_reflected = 0.0;
  for (std::size_t p = 0; p < position_m.size(); ++p) {
    const std::complex<double> e = std::polar(1.0, wavenumber_rad_m * position_m[p]);
    s += e * e;
    right_incident += amplitude[p] * std::conj(e);
    right_reflected += amplitude[p] * e;
  }
  const std::complex<double> determinant = n * n - std::norm(s);
  // |S| -> N: the gauges cannot tell the two waves apart (spacings at multiples of L/2).
  if (std::abs(determinant) < 1e-3 * n * n)
    throw std::invalid_argument("separate_incident_reflected: gauge spacings are (near) multiples of half a wavelength (k = " +
                                std::to_string(wavenumber_rad_m) + " rad/m); move a gauge");
  return {(n * right_incident - std::conj(s) * right_reflected) / determinant,
          (n * right_reflected - s * right_incident) / determinant};
}

}  // namespace nearshore::testing
