#pragma once
// Frequency spectra of wind seas and their directional spreading (issue 5).
//
// A FrequencySpectrum is the one-sided variance density S(w) of the surface elevation in
// m^2 s/rad, w the angular frequency in rad/s: the variance of eta is m0 = integral S(w) dw and
// the significant wave height Hs = 4 sqrt(m0). A DirectionalSpreading D(theta; w) (1/rad)
// integrates to 1 over the circle, so S(w) D(theta; w) is the directional spectrum the
// sea-state builder (sea_state_builder.hpp) discretises into wave components.
//
// Sources: seed 000 section 2.1 (Pierson-Moskowitz eq. 2.2, JONSWAP eq. 2.3); Hasselmann et al.
// (1973); Bouws et al. (1985) and Kitaigorodskii et al. (1975) for the TMA depth factor;
// Longuet-Higgins et al. (1963) / Mitsuyasu et al. (1975) for cos^2s spreading.
#include <memory>
#include <string>

namespace nearshore::ocean {

/// One-sided frequency spectrum S(w) (m^2 s/rad).
class FrequencySpectrum {
 public:
  virtual ~FrequencySpectrum() = default;
  /// S(w) in m^2 s/rad; 0 for w <= 0.
  virtual double density_m2_s_rad(double angular_frequency_rad_s) const = 0;
  /// The frequency of the spectral peak (rad/s); sets the integration ranges.
  virtual double peak_angular_frequency_rad_s() const = 0;
  /// A short name for logs and manifests ("jonswap", "pierson-moskowitz", "tma").
  virtual std::string name() const = 0;

  /// integral of S over [w0, w1] (m^2), by Gauss-Legendre quadrature on log-spaced panels.
  double variance_between_m2(double w0_rad_s, double w1_rad_s) const;
  /// m0 = integral of S over (0, inf) (m^2), taken over [0.05 wp, 200 wp]: outside, a PM-type
  /// spectrum holds less than 1e-8 of its variance (tail ~ w^-5, and w^-3 for TMA at k d << 1).
  double zeroth_moment_m2() const;
  /// Hs = 4 sqrt(m0) (metres).
  double significant_wave_height_m() const;
};

/// Pierson-Moskowitz (1964), fully developed sea; seed 000 eq. (2.2) written with its peak:
///   S(w) = alpha g^2 / w^5 exp(-5/4 (wp / w)^4),  m0 = alpha g^2 / (5 wp^4).
class PiersonMoskowitzSpectrum : public FrequencySpectrum {
 public:
  /// From the significant wave height Hs (m) and the peak period Tp (s): alpha = 5 Hs^2 wp^4 / (16 g^2)
  /// (the ITTC two-parameter / Bretschneider form).
  PiersonMoskowitzSpectrum(double significant_wave_height_m, double peak_period_s);
  /// From the wind speed 19.5 m above the sea (m/s), seed 000 eq. (2.2): alpha = 8.1e-3 and
  /// beta = 0.74, i.e. wp = (4 beta / 5)^(1/4) g / U19.5 = 0.877 g / U19.5.
  static PiersonMoskowitzSpectrum from_wind_speed(double wind_speed_19_5_m_s);

  double density_m2_s_rad(double w) const override;
  double peak_angular_frequency_rad_s() const override { return peak_frequency_rad_s_; }
  std::string name() const override { return "pierson-moskowitz"; }
  double phillips_constant() const { return alpha_; }  ///< alpha (dimensionless)

  /// The PM shape alpha g^2 / w^5 exp(-5/4 (wp/w)^4) (m^2 s/rad), shared with JONSWAP.
  static double shape_m2_s_rad(double w, double alpha, double peak_frequency_rad_s);

 private:
  PiersonMoskowitzSpectrum() = default;
  double alpha_ = 0.0, peak_frequency_rad_s_ = 0.0;
};

/// JONSWAP, Hasselmann et al. (1973); seed 000 eq. (2.3): the PM shape times the peak
/// enhancement gamma^r, r = exp(-(w - wp)^2 / (2 sigma^2 wp^2)), sigma = 0.07 for w <= wp and
/// 0.09 above.
class JonswapSpectrum : public FrequencySpectrum {
 public:
  /// From Hs (m), Tp (s) and gamma (1 = Pierson-Moskowitz, 3.3 = mean JONSWAP; seed 000: 1-7).
  /// alpha is set so that 4 sqrt(m0) = Hs exactly (numerical integration, not Goda's fit).
  JonswapSpectrum(double significant_wave_height_m, double peak_period_s, double peak_enhancement = 3.3);
  /// From the wind speed at 10 m (m/s) and the fetch (m), seed 000 eq. (2.3):
  /// alpha = 0.076 (g F / U10^2)^-0.22 and wp = 22 (g^2 / (U10 F))^(1/3).
  static JonswapSpectrum from_wind_and_fetch(double wind_speed_10_m_s, double fetch_m,
                                             double peak_enhancement = 3.3);

  double density_m2_s_rad(double w) const override;
  double peak_angular_frequency_rad_s() const override { return peak_frequency_rad_s_; }
  std::string name() const override { return "jonswap"; }
  double phillips_constant() const { return alpha_; }      ///< alpha (dimensionless)
  double peak_enhancement() const { return gamma_; }        ///< gamma (dimensionless)

 private:
  JonswapSpectrum() = default;
  double alpha_ = 0.0, peak_frequency_rad_s_ = 0.0, gamma_ = 1.0;
};

/// The TMA transformation factor (Kitaigorodskii et al. 1975; Bouws et al. 1985): the ratio of
/// the finite-depth to the deep-water saturation range, in terms of k(w, d) from w^2 = g k tanh(k d):
///   phi(w, d) = tanh^2(k d) / (1 + 2 k d / sinh(2 k d)),  -> 1 in deep water, -> w^2 d / (2 g) when shallow.
double tma_depth_factor(double angular_frequency_rad_s, double still_water_depth_m);

/// TMA spectrum: a deep-water spectrum times tma_depth_factor at the still-water depth d (m).
/// Note that this lowers Hs below the deep-water spectrum's: the depth takes energy out.
class TmaSpectrum : public FrequencySpectrum {
 public:
  TmaSpectrum(std::shared_ptr<const FrequencySpectrum> deep_water_spectrum, double still_water_depth_m);
  double density_m2_s_rad(double w) const override;
  double peak_angular_frequency_rad_s() const override;
  std::string name() const override { return "tma(" + deep_->name() + ")"; }
  double still_water_depth_m() const { return depth_m_; }

 private:
  std::shared_ptr<const FrequencySpectrum> deep_;
  double depth_m_;
};

/// Directional spreading D(theta; w) (1/rad), integral over any 2 pi of theta = 1.
/// theta is the direction of travel, counter-clockwise from +x (east), as in WaveComponent.
class DirectionalSpreading {
 public:
  virtual ~DirectionalSpreading() = default;
  virtual double density_per_rad(double direction_rad, double angular_frequency_rad_s) const = 0;
  /// The mean direction of travel (rad).
  virtual double mean_direction_rad() const = 0;
  virtual std::string name() const = 0;
  /// The smallest half-width h (rad, <= pi) such that [mean - h, mean + h] holds `fraction` of
  /// D at frequency w (bisection on the numerical integral).
  double half_width_holding_rad(double fraction, double angular_frequency_rad_s) const;
};

/// cos^2s spreading (Longuet-Higgins et al. 1963):
///   D(theta) = C(s) cos^(2s)((theta - theta_m) / 2),  C(s) = Gamma(s + 1) / (2 sqrt(pi) Gamma(s + 1/2)).
/// s ~ 10-25 for wind sea, 75 for swell (Goda 2000). Independent of frequency.
class CosineSquaredSpreading : public DirectionalSpreading {
 public:
  CosineSquaredSpreading(double mean_direction_rad, double spreading_exponent_s);
  double density_per_rad(double direction_rad, double angular_frequency_rad_s) const override;
  double mean_direction_rad() const override { return mean_direction_rad_; }
  std::string name() const override { return "cos2s"; }
  double spreading_exponent() const { return s_; }

 private:
  double mean_direction_rad_, s_, normalisation_per_rad_;
};

/// Wraps an angle to (-pi, pi].
double wrap_angle_rad(double angle_rad);

}  // namespace nearshore::ocean
