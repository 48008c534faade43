#include "nearshore/ocean/spectrum.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "nearshore/ocean/spectrum_quadrature.hpp"
#include "nearshore/ocean/wave_component.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::ocean {
namespace {

constexpr double kPi = std::numbers::pi;

void require_positive(const std::string& subject, const char* what, double value, const char* fix) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw Error(subject, fmt::format("{} is {}, it must be a positive finite number", what, value), fix);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// FrequencySpectrum

double FrequencySpectrum::variance_between_m2(double w0, double w1) const {
  if (!(w1 > w0)) return 0.0;
  w0 = std::max(w0, 1e-6 * peak_angular_frequency_rad_s());
  // ~40 panels per decade keeps the 8-point rule exact to ~1e-10 on PM-type shapes.
  const int panels = std::max(4, static_cast<int>(40.0 * std::log10(w1 / w0)) + 1);
  return integrate_log_panels([this](double w) { return density_m2_s_rad(w); }, w0, w1, panels);
}

double FrequencySpectrum::zeroth_moment_m2() const {
  const double wp = peak_angular_frequency_rad_s();
  return variance_between_m2(0.05 * wp, 200.0 * wp);
}

double FrequencySpectrum::significant_wave_height_m() const { return 4.0 * std::sqrt(zeroth_moment_m2()); }

// ---------------------------------------------------------------------------------------------
// Pierson-Moskowitz

double PiersonMoskowitzSpectrum::shape_m2_s_rad(double w, double alpha, double wp) {
  if (!(w > 0.0)) return 0.0;
  const double ratio = wp / w;
  const double ratio4 = ratio * ratio * ratio * ratio;
  if (ratio4 > 700.0) return 0.0;  // exp underflow; the density is 0 to double precision anyway
  return alpha * kGravity_m_s2 * kGravity_m_s2 / std::pow(w, 5) * std::exp(-1.25 * ratio4);
}

PiersonMoskowitzSpectrum::PiersonMoskowitzSpectrum(double hs_m, double tp_s) {
  require_positive("Pierson-Moskowitz spectrum", "the significant wave height (m)", hs_m,
                   "give a significant wave height above 0 m");
  require_positive("Pierson-Moskowitz spectrum", "the peak period (s)", tp_s, "give a peak period above 0 s");
  peak_frequency_rad_s_ = 2.0 * kPi / tp_s;
  // m0 = alpha g^2 / (5 wp^4) = Hs^2 / 16.
  alpha_ = 5.0 * hs_m * hs_m * std::pow(peak_frequency_rad_s_, 4) / (16.0 * kGravity_m_s2 * kGravity_m_s2);
}

PiersonMoskowitzSpectrum PiersonMoskowitzSpectrum::from_wind_speed(double u19_5_m_s) {
  require_positive("Pierson-Moskowitz spectrum", "the wind speed at 19.5 m (m/s)", u19_5_m_s,
                   "give a wind speed above 0 m/s");
  // seed 000 eq. (2.2): exp(-beta (g / (U w))^4) = exp(-5/4 (wp / w)^4) with wp^4 = 4 beta / 5 (g/U)^4.
  constexpr double beta = 0.74;
  PiersonMoskowitzSpectrum spectrum;
  spectrum.alpha_ = 8.1e-3;
  spectrum.peak_frequency_rad_s_ = std::pow(4.0 * beta / 5.0, 0.25) * kGravity_m_s2 / u19_5_m_s;
  return spectrum;
}

double PiersonMoskowitzSpectrum::density_m2_s_rad(double w) const {
  return shape_m2_s_rad(w, alpha_, peak_frequency_rad_s_);
}

// ---------------------------------------------------------------------------------------------
// JONSWAP

JonswapSpectrum::JonswapSpectrum(double hs_m, double tp_s, double gamma) {
  require_positive("JONSWAP spectrum", "the significant wave height (m)", hs_m, "give a significant wave height above 0 m");
  require_positive("JONSWAP spectrum", "the peak period (s)", tp_s, "give a peak period above 0 s");
  if (!(gamma >= 1.0 && gamma <= 20.0))
    throw Error("JONSWAP spectrum", fmt::format("peak enhancement gamma = {} is outside [1, 20]", gamma),
                "use gamma = 3.3 (mean JONSWAP), 1 (Pierson-Moskowitz) or up to 7 for young swell");
  peak_frequency_rad_s_ = 2.0 * kPi / tp_s;
  gamma_ = gamma;
  alpha_ = 1.0;
  // S is linear in alpha: scale it so that the integral gives exactly Hs^2 / 16.
  alpha_ = hs_m * hs_m / 16.0 / zeroth_moment_m2();
}

JonswapSpectrum JonswapSpectrum::from_wind_and_fetch(double u10_m_s, double fetch_m, double gamma) {
  require_positive("JONSWAP spectrum", "the wind speed at 10 m (m/s)", u10_m_s, "give a wind speed above 0 m/s");
  require_positive("JONSWAP spectrum", "the fetch (m)", fetch_m, "give a fetch above 0 m");
  JonswapSpectrum spectrum;
  const double g = kGravity_m_s2;
  // seed 000 eq. (2.3) (Hasselmann et al. 1973).
  spectrum.alpha_ = 0.076 * std::pow(g * fetch_m / (u10_m_s * u10_m_s), -0.22);
  spectrum.peak_frequency_rad_s_ = 22.0 * std::pow(g * g / (u10_m_s * fetch_m), 1.0 / 3.0);
  spectrum.gamma_ = gamma;
  return spectrum;
}

double JonswapSpectrum::density_m2_s_rad(double w) const {
  if (!(w > 0.0)) return 0.0;
  const double sigma = w <= peak_frequency_rad_s_ ? 0.07 : 0.09;
  const double offset = (w - peak_frequency_rad_s_) / (sigma * peak_frequency_rad_s_);
  const double r = std::exp(-0.5 * offset * offset);
  return PiersonMoskowitzSpectrum::shape_m2_s_rad(w, alpha_, peak_frequency_rad_s_) * std::pow(gamma_, r);
}

// ---------------------------------------------------------------------------------------------
// TMA

double tma_depth_factor(double w, double depth_m) {
  if (!(w > 0.0)) return 0.0;
  if (!(depth_m > 0.0) || std::isinf(depth_m)) return 1.0;
  const double kd = wavenumber_from_frequency(w, depth_m) * depth_m;
  if (kd > 20.0) return 1.0;  // tanh(kd)^2 = 1 and 2kd/sinh(2kd) = 0 to 1e-16
  const double t = std::tanh(kd);
  return t * t / (1.0 + 2.0 * kd / std::sinh(2.0 * kd));
}

TmaSpectrum::TmaSpectrum(std::shared_ptr<const FrequencySpectrum> deep, double depth_m)
    : deep_(std::move(deep)), depth_m_(depth_m) {
  if (!deep_) throw Error("TMA spectrum", "no deep-water spectrum was given", "pass a JONSWAP or PM spectrum");
  require_positive("TMA spectrum", "the still-water depth (m)", depth_m, "give the depth of the site in metres");
}

double TmaSpectrum::density_m2_s_rad(double w) const {
  return deep_->density_m2_s_rad(w) * tma_depth_factor(w, depth_m_);
}

double TmaSpectrum::peak_angular_frequency_rad_s() const { return deep_->peak_angular_frequency_rad_s(); }

// ---------------------------------------------------------------------------------------------
// Directional spreading

double wrap_angle_rad(double angle) {
  angle = std::remainder(angle, 2.0 * kPi);  // in [-pi, pi]
  return angle <= -kPi ? angle + 2.0 * kPi : angle;
}

double DirectionalSpreading::half_width_holding_rad(double fraction, double w) const {
  const double mean = mean_direction_rad();
  auto held = [&](double half_width) {
    return integrate_gauss_legendre([&](double th) { return density_per_rad(th, w); }, mean - half_width,
                                    mean + half_width, 64);
  };
  if (held(kPi) <= fraction) return kPi;
  double low = 0.0, high = kPi;
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double middle = 0.5 * (low + high);
    (held(middle) < fraction ? low : high) = middle;
  }
  return high;
}

CosineSquaredSpreading::CosineSquaredSpreading(double mean_direction_rad, double s)
    : mean_direction_rad_(mean_direction_rad), s_(s) {
  if (!(s > 0.0 && s <= 1000.0))
    throw Error("cos^2s spreading", fmt::format("spreading exponent s = {} is outside (0, 1000]", s),
                "use s = 10-25 for wind sea, 75 for swell");
  // C(s) = Gamma(s + 1) / (2 sqrt(pi) Gamma(s + 1/2)), through lgamma to stay finite for large s.
  normalisation_per_rad_ = std::exp(std::lgamma(s + 1.0) - std::lgamma(s + 0.5)) / (2.0 * std::sqrt(kPi));
}

double CosineSquaredSpreading::density_per_rad(double direction_rad, double) const {
  const double c = std::abs(std::cos(0.5 * wrap_angle_rad(direction_rad - mean_direction_rad_)));
  return normalisation_per_rad_ * std::pow(c, 2.0 * s_);
}

}  // namespace nearshore::ocean
