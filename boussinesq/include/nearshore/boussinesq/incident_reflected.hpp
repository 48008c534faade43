#pragma once
// Separation of a regular wave record into its incident and reflected parts, from gauges along the
// direction of travel: the least-squares method of Mansard & Funke (1980), which for two gauges is
// the exact solution of Goda & Suzuki (1976). The porous-layer flume (porous_layer_flume.hpp)
// measures reflection and transmission with it; tests use it wherever they must know the height a
// wave maker really sends, with whatever the far end reflects superposed on it.
//
// Model: at gauge p (position x_p, metres) the component of frequency w is
//   eta_p(t) = Re[ B_p exp(-i w t) ],   B_p = Z_I exp(i k x_p) + Z_R exp(-i k x_p) + noise,
// Z_I the incident (travelling towards +x) and Z_R the reflected complex amplitude. Mansard & Funke
// minimise sum_p |B_p - Z_I e_p - Z_R / e_p|^2 (e_p = exp(i k x_p)); the 2 x 2 normal equations
//   [ N        S* ] [Z_I]   [ sum B_p e_p* ]
//   [ S        N  ] [Z_R] = [ sum B_p e_p  ],   S = sum e_p^2,
// are singular only when every pair of gauges is a whole number of half wavelengths apart
// (|S| = N): choose spacings away from L/2 multiples (Mansard & Funke: x12 ~ L/10, L/6 < x13 < L/3).
#include <complex>
#include <vector>

namespace nearshore::boussinesq {

/// The complex amplitude B of exp(-i w t) in a record sampled every `sample_interval_s` from time
/// `start_time_s`, over the longest span of whole periods 2 pi / w that fits: B = (2/N) sum eta_n
/// exp(i w t_n). Over whole periods of a uniformly sampled record the harmonics and the mean are
/// orthogonal to it, so it is the least-squares amplitude of that frequency. Throws nearshore::Error
/// for a record shorter than one period.
std::complex<double> harmonic_amplitude(const std::vector<double>& elevation_m, double start_time_s,
                                        double sample_interval_s, double angular_frequency_rad_s);

struct IncidentReflected {
  std::complex<double> incident;   ///< Z_I: incident amplitude (metres) and phase at x = 0
  std::complex<double> reflected;  ///< Z_R
  double incident_height_m() const { return 2.0 * std::abs(incident); }
  double reflected_height_m() const { return 2.0 * std::abs(reflected); }
  double reflection_coefficient() const { return std::abs(reflected) / std::abs(incident); }
};

/// Mansard & Funke (1980) least squares over any number (>= 2) of gauges at `position_m` with the
/// complex amplitudes `amplitude` (harmonic_amplitude of each record) of a wave of wavenumber
/// `wavenumber_rad_m` travelling towards +x. Throws nearshore::Error when the gauges cannot tell
/// the two waves apart (spacings at multiples of half a wavelength) or are fewer than two.
IncidentReflected separate_incident_reflected(const std::vector<double>& position_m,
                                              const std::vector<std::complex<double>>& amplitude, double wavenumber_rad_m);

}  // namespace nearshore::boussinesq
