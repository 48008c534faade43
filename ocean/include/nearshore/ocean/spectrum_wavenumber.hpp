#pragma once
// Directional wavenumber spectra Psi(kx, ky) for the deep-water FFT field (issue 5).
//
// Psi is the variance density of the surface elevation per unit wavevector area, in m^4
// (m^2 per (rad/m)^2): the variance is m0 = integral Psi dkx dky, Hs = 4 sqrt(m0). The wavevector
// points in the direction of travel, angle counter-clockwise from +x (east). The FFT field takes
// the amplitude of each lattice wavevector from the integral of Psi over its cell (seed 001
// eq. 16), so Hs does not depend on the grid size N or the tile length L.
//
// Sources: Phillips, seed 000 eq. (2.4) (Tessendorf 1999); unified spectrum, seed 000 eq.
// (2.5)-(2.15) (Elfouhaily et al. 1997, with their eq. 57 spreading and eq. 3 for gamma and
// sigma); PM-ITTC, seed 001 eq. (19); frequency -> wavenumber, seed 001 eq. (17).
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nearshore/ocean/spectrum.hpp"

namespace nearshore::ocean {

class WavenumberSpectrum {
 public:
  virtual ~WavenumberSpectrum() = default;
  /// Psi(kx, ky) in m^4; 0 at k = 0.
  virtual double density_m4(double kx_rad_m, double ky_rad_m) const = 0;
  /// The wavenumber of the spectral peak (rad/m); sets the integration ranges.
  virtual double peak_wavenumber_rad_m() const = 0;
  /// The wind (or mean wave) direction of travel (rad).
  virtual double mean_direction_rad() const = 0;
  virtual std::string name() const = 0;
  /// Name and parameters with units, for the manifest's deep_water entry.
  virtual nlohmann::json to_json() const = 0;

  /// The omnidirectional spectrum S(k) = integral over theta of Psi k dtheta (m^3/rad); by
  /// quadrature unless a spectrum knows its closed form.
  virtual double omnidirectional_density_m3(double k_rad_m) const;
  /// integral of S(k) k^power over [k0, k1] (m^(2-power)): power 0 = variance, 2 = slope variance.
  double moment_between(double k0_rad_m, double k1_rad_m, int power = 0) const;
  /// The largest wavenumber the spectrum holds variance at (rad/m): 1e4 kp by default, above
  /// which a k^-3 tail holds less than 1e-8 of the variance.
  virtual double highest_wavenumber_rad_m() const { return 1e4 * peak_wavenumber_rad_m(); }
  /// m0 over [1e-3 kp, highest] (m^2): below 1e-3 kp every spectrum here is exp(-1e6)-small.
  double zeroth_moment_m2() const;
  double significant_wave_height_m() const;  ///< 4 sqrt(m0), metres
};

/// Which directions a spectrum with a centrosymmetric spreading (Phillips' |k^ . w^|^2,
/// Elfouhaily's cos 2 theta) keeps. kBothWays is the formula as published: as much variance
/// travelling up-wind as down-wind, i.e. partly standing waves. kDownwind (the default) folds the
/// up-wind half onto the down-wind half (Psi doubled for k . w > 0, zero behind): the same S(k),
/// m0 and Hs, but every wave travels with the wind, as the harbour's wave maker needs them to
/// (a wave maker on the offshore edge cannot make waves that leave the harbour).
enum class WindHalfPlane { kDownwind, kBothWays };

/// Phillips spectrum, seed 000 eq. (2.4) (Tessendorf 1999):
///   Psi(k) = A exp(-1/(k Lw)^2) / k^4 |k^ . w^|^2 exp(-(k l)^2),  Lw = U^2 / g,  l = small_wave_fraction Lw.
/// Its variance is m0 = A pi Lw^2 / 2 (for l -> 0), so the amplitude constant A is set from a
/// significant wave height: A = Hs^2 / (8 pi Lw^2).
class PhillipsSpectrum : public WavenumberSpectrum {
 public:
  /// amplitude: A (dimensionless); wind speed U (m/s); wind direction (rad, the waves' direction
  /// of travel); small_wave_fraction: l / Lw (seed 000 uses 1e-3).
  PhillipsSpectrum(double amplitude, double wind_speed_m_s, double wind_direction_rad,
                   double small_wave_fraction = 1e-3, WindHalfPlane half_plane = WindHalfPlane::kDownwind);
  /// The A that gives this significant wave height (m) at this wind (the l cut-off ignored: it
  /// removes less than 1e-5 of the variance for l = 1e-3 Lw).
  static double amplitude_for_significant_wave_height(double significant_wave_height_m, double wind_speed_m_s);

  double density_m4(double kx, double ky) const override;
  double peak_wavenumber_rad_m() const override;
  double mean_direction_rad() const override { return wind_direction_rad_; }
  std::string name() const override { return "phillips"; }
  nlohmann::json to_json() const override;
  /// S(k) = A pi exp(-1/(k Lw)^2 - (k l)^2) / k^3 (the cos^2 integrates to pi).
  double omnidirectional_density_m3(double k_rad_m) const override;

 private:
  double amplitude_, wind_speed_m_s_, wind_direction_rad_, small_wave_fraction_;
  WindHalfPlane half_plane_;
};

/// Unified spectrum of Elfouhaily et al. (1997), seed 000 eq. (2.5)-(2.15): long waves B_l (a
/// JONSWAP-like peak at kp = g Omega^2 / U10^2) and short gravity-capillary waves B_h (peak at
/// km = 370 rad/m, cm = 0.23 m/s), Psi = S(k)/k Phi(k, theta), S(k) = k^-3 (B_l + B_h), with the
/// spreading Phi = (1 + Delta(k) cos 2(theta - theta_w)) / (2 pi) (Elfouhaily eq. 49, 57).
class UnifiedSpectrum : public WavenumberSpectrum {
 public:
  /// wind_speed_10_m_s: U10 (m/s); inverse_wave_age: Omega_c = U10 / c_p, 0.84 fully developed
  /// ... 5 young sea (Elfouhaily's range); wind direction of travel (rad).
  UnifiedSpectrum(double wind_speed_10_m_s, double inverse_wave_age, double wind_direction_rad,
                  WindHalfPlane half_plane = WindHalfPlane::kDownwind);
  /// Omega_c from the dimensionless fetch, seed 000 eq. (2.8): 0.84 tanh((X / 2.2e4)^0.4)^-0.75,
  /// X = g fetch / U10^2.
  static double inverse_wave_age_from_fetch(double wind_speed_10_m_s, double fetch_m);
  /// The inverse: the fetch (m) at which the sea has this Omega_c (> 0.84).
  static double fetch_from_inverse_wave_age(double wind_speed_10_m_s, double inverse_wave_age);

  double density_m4(double kx, double ky) const override;
  double peak_wavenumber_rad_m() const override { return peak_wavenumber_rad_m_; }
  double mean_direction_rad() const override { return wind_direction_rad_; }
  std::string name() const override { return "unified"; }
  nlohmann::json to_json() const override;
  /// S(k) in m^3/rad (closed form, eq. 2.6; the spreading integrates to 1).
  double omnidirectional_density_m3(double k_rad_m) const override;
  /// max(1e4 kp, 10 km): the capillary peak's tail exp(-(k/km - 1)^2/4) is e^-20 there.
  double highest_wavenumber_rad_m() const override;
  double inverse_wave_age() const { return inverse_wave_age_; }

 private:
  double phase_speed(double k) const;  // gravity-capillary c(k), Elfouhaily eq. 33
  double wind_speed_m_s_, inverse_wave_age_, wind_direction_rad_;
  WindHalfPlane half_plane_;
  double peak_wavenumber_rad_m_, peak_phase_speed_m_s_, friction_velocity_m_s_, alpha_p_, alpha_m_, gamma_, sigma_;
};

/// PM-ITTC wavenumber spectrum, seed 001 eq. (19): the PM frequency spectrum with the ITTC
/// spreading (2/pi) cos^2 over the forward half-plane, converted by eq. (17):
///   Psi(k) = alpha / (pi k^6 U^2) exp(-0.688 g^2 / (k^2 U^4)) |k . U|^2  for k . U >= 0,
/// alpha = 8.1e-3, U the wind at 10 m. m0 = alpha U^4 / (4 * 0.688 g^2), Hs = 0.217 U^2 / g.
class PmIttcSpectrum : public WavenumberSpectrum {
 public:
  PmIttcSpectrum(double wind_speed_10_m_s, double wind_direction_rad);
  double density_m4(double kx, double ky) const override;
  double peak_wavenumber_rad_m() const override;
  double mean_direction_rad() const override { return wind_direction_rad_; }
  std::string name() const override { return "pm-ittc"; }
  nlohmann::json to_json() const override;
  /// S(k) = alpha / (2 k^3) exp(-0.688 g^2 / (k^2 U^4)) (the cos^2 over the half-plane gives pi/2).
  double omnidirectional_density_m3(double k_rad_m) const override;

 private:
  double wind_speed_m_s_, wind_direction_rad_;
};

/// Any frequency spectrum with a spreading as a wavenumber spectrum, seed 001 eq. (17)
/// generalised to depth d: Psi(k, theta) = S(w) D(theta; w) (dw/dk) / k with w^2 = g k tanh(k d)
/// (dw/dk the group speed). The same S and D as the sea-state builder: the harbour wave maker and
/// the FFT field share one spectrum.
class DirectionalWavenumberSpectrum : public WavenumberSpectrum {
 public:
  /// still_water_depth_m <= 0: deep water.
  DirectionalWavenumberSpectrum(std::shared_ptr<const FrequencySpectrum> spectrum,
                                std::shared_ptr<const DirectionalSpreading> spreading, double still_water_depth_m = 0.0);
  double density_m4(double kx, double ky) const override;
  double peak_wavenumber_rad_m() const override;
  double mean_direction_rad() const override { return spreading_->mean_direction_rad(); }
  std::string name() const override { return spectrum_->name() + "+" + spreading_->name(); }
  nlohmann::json to_json() const override;

 private:
  std::shared_ptr<const FrequencySpectrum> spectrum_;
  std::shared_ptr<const DirectionalSpreading> spreading_;
  double depth_m_;
};

/// The sum of independent seas, Psi = sum of the parts' Psi (variances add: Hs^2 = sum Hs_i^2): a
/// swell from offshore and the local wind sea over it, as one FFT field (issue 14: a harbour's sea
/// is rarely one spectrum). The peak wavenumber is the lowest of the parts' (the longest waves set
/// the integration ranges and the largest tile); the mean direction is the most energetic part's.
class SpectrumSum : public WavenumberSpectrum {
 public:
  /// At least one part; none null.
  explicit SpectrumSum(std::vector<std::shared_ptr<const WavenumberSpectrum>> parts);
  double density_m4(double kx, double ky) const override;
  double omnidirectional_density_m3(double k_rad_m) const override;
  double peak_wavenumber_rad_m() const override;
  double highest_wavenumber_rad_m() const override;
  double mean_direction_rad() const override { return mean_direction_rad_; }
  std::string name() const override { return "sum"; }
  /// {"name": "sum", "significant_wave_height_m": ..., "parts": [each part's to_json()]}.
  nlohmann::json to_json() const override;
  const std::vector<std::shared_ptr<const WavenumberSpectrum>>& parts() const { return parts_; }

 private:
  std::vector<std::shared_ptr<const WavenumberSpectrum>> parts_;
  double mean_direction_rad_ = 0.0;
};

}  // namespace nearshore::ocean
