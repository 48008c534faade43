#include "nearshore/ocean/spectrum_wavenumber.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "nearshore/ocean/spectrum_quadrature.hpp"
#include "nearshore/ocean/wave_component.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::ocean {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double g = kGravity_m_s2;

void require_positive(const char* subject, const char* what, double value, const char* fix) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw Error(subject, fmt::format("{} is {}, it must be a positive finite number", what, value), fix);
}

/// cos of the angle between the wavevector and the wind: k^ . w^.
double cosine_to(double kx, double ky, double k, double direction_rad) {
  return (kx * std::cos(direction_rad) + ky * std::sin(direction_rad)) / k;
}

/// The factor WindHalfPlane applies at a wavevector: 1 both ways; 2 down-wind and 0 up-wind
/// when folding (on the cross-wind line, the half with a positive cross product keeps it, so
/// exactly one of k and -k does).
double half_plane_factor(WindHalfPlane half_plane, double kx, double ky, double direction_rad) {
  if (half_plane == WindHalfPlane::kBothWays) return 1.0;
  const double along = kx * std::cos(direction_rad) + ky * std::sin(direction_rad);
  const double across = -kx * std::sin(direction_rad) + ky * std::cos(direction_rad);
  const double scale = std::hypot(kx, ky);
  if (std::abs(along) <= 1e-12 * scale) return across > 0.0 ? 2.0 : 0.0;
  return along > 0.0 ? 2.0 : 0.0;
}

const char* half_plane_name(WindHalfPlane half_plane) {
  return half_plane == WindHalfPlane::kDownwind ? "downwind" : "both_ways";
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// WavenumberSpectrum

double WavenumberSpectrum::omnidirectional_density_m3(double k) const {
  if (!(k > 0.0)) return 0.0;
  // 32 panels of 8 points around the circle: exact to ~1e-12 for the cos^2 and cos 2theta shapes here.
  return integrate_gauss_legendre(
      [&](double theta) { return density_m4(k * std::cos(theta), k * std::sin(theta)) * k; }, -kPi, kPi, 32);
}

double WavenumberSpectrum::moment_between(double k0, double k1, int power) const {
  k0 = std::max(k0, 1e-3 * peak_wavenumber_rad_m());
  k1 = std::min(k1, highest_wavenumber_rad_m());
  if (!(k1 > k0)) return 0.0;
  const int panels = std::max(4, static_cast<int>(30.0 * std::log10(k1 / k0)) + 1);
  return integrate_log_panels([&](double k) { return omnidirectional_density_m3(k) * std::pow(k, power); }, k0, k1,
                              panels);
}

double WavenumberSpectrum::zeroth_moment_m2() const {
  return moment_between(1e-3 * peak_wavenumber_rad_m(), highest_wavenumber_rad_m(), 0);
}

double WavenumberSpectrum::significant_wave_height_m() const { return 4.0 * std::sqrt(zeroth_moment_m2()); }

// ---------------------------------------------------------------------------------------------
// Phillips

PhillipsSpectrum::PhillipsSpectrum(double amplitude, double wind_speed_m_s, double wind_direction_rad,
                                   double small_wave_fraction, WindHalfPlane half_plane)
    : amplitude_(amplitude), wind_speed_m_s_(wind_speed_m_s), wind_direction_rad_(wind_direction_rad),
      small_wave_fraction_(small_wave_fraction), half_plane_(half_plane) {
  if (!(amplitude >= 0.0) || !std::isfinite(amplitude))
    throw Error("Phillips spectrum", fmt::format("amplitude A = {} is negative or not finite", amplitude),
                "give A >= 0, or build it from a wave height with amplitude_for_significant_wave_height");
  require_positive("Phillips spectrum", "the wind speed (m/s)", wind_speed_m_s, "give a wind speed above 0 m/s");
  if (!(small_wave_fraction >= 0.0 && small_wave_fraction < 1.0))
    throw Error("Phillips spectrum", fmt::format("small-wave fraction l/L = {} is outside [0, 1)", small_wave_fraction),
                "use 1e-3 (seed 000)");
}

double PhillipsSpectrum::amplitude_for_significant_wave_height(double hs_m, double wind_speed_m_s) {
  require_positive("Phillips spectrum", "the wind speed (m/s)", wind_speed_m_s, "give a wind speed above 0 m/s");
  // m0 = A pi Lw^2 / 2 (integral of exp(-1/(k Lw)^2) k^-3 dk = Lw^2 / 2, of cos^2 over the circle = pi).
  const double largest_wave_m = wind_speed_m_s * wind_speed_m_s / g;
  return hs_m * hs_m / 16.0 * 2.0 / (kPi * largest_wave_m * largest_wave_m);
}

double PhillipsSpectrum::density_m4(double kx, double ky) const {
  const double k2 = kx * kx + ky * ky;
  if (!(k2 > 0.0)) return 0.0;
  const double k = std::sqrt(k2);
  const double largest_wave_m = wind_speed_m_s_ * wind_speed_m_s_ / g;  // Lw
  const double smallest_wave_m = small_wave_fraction_ * largest_wave_m;  // l
  const double alignment = cosine_to(kx, ky, k, wind_direction_rad_);
  // seed 000 eq. (2.4)
  return amplitude_ * std::exp(-1.0 / (k2 * largest_wave_m * largest_wave_m) - k2 * smallest_wave_m * smallest_wave_m) /
         (k2 * k2) * alignment * alignment * half_plane_factor(half_plane_, kx, ky, wind_direction_rad_);
}

double PhillipsSpectrum::omnidirectional_density_m3(double k) const {
  if (!(k > 0.0)) return 0.0;
  const double largest_wave_m = wind_speed_m_s_ * wind_speed_m_s_ / g;
  const double smallest_wave_m = small_wave_fraction_ * largest_wave_m;
  return amplitude_ * kPi * std::exp(-1.0 / (k * k * largest_wave_m * largest_wave_m) - k * k * smallest_wave_m * smallest_wave_m) /
         (k * k * k);
}

double PhillipsSpectrum::peak_wavenumber_rad_m() const {
  // S(k) ~ k^-3 exp(-1/(k Lw)^2) peaks at k = sqrt(2/3) / Lw.
  return std::sqrt(2.0 / 3.0) * g / (wind_speed_m_s_ * wind_speed_m_s_);
}

nlohmann::json PhillipsSpectrum::to_json() const {
  return {{"name", name()},
          {"amplitude", amplitude_},
          {"wind_speed_m_s", wind_speed_m_s_},
          {"wind_direction_rad", wind_direction_rad_},
          {"small_wave_fraction", small_wave_fraction_},
          {"half_plane", half_plane_name(half_plane_)}};
}

// ---------------------------------------------------------------------------------------------
// Unified (Elfouhaily et al. 1997)

namespace {
constexpr double kCapillaryPeak_rad_m = 370.0;   // km
constexpr double kCapillaryPhaseSpeed_m_s = 0.23;  // cm
constexpr double kFetchScale = 2.2e4;             // X0 of eq. (2.8)
}  // namespace

UnifiedSpectrum::UnifiedSpectrum(double u10, double omega_c, double wind_direction_rad, WindHalfPlane half_plane)
    : wind_speed_m_s_(u10), inverse_wave_age_(omega_c), wind_direction_rad_(wind_direction_rad), half_plane_(half_plane) {
  require_positive("unified spectrum", "the wind speed at 10 m (m/s)", u10, "give a wind speed above 0 m/s");
  if (!(omega_c >= 0.83 && omega_c <= 5.0))
    throw Error("unified spectrum", fmt::format("inverse wave age Omega_c = {} is outside Elfouhaily's [0.83, 5]", omega_c),
                "use 0.84 for a fully developed sea, up to 5 for a young sea (or give a fetch)");
  // eq. (2.10): kp = g Omega^2 / U10^2.
  peak_wavenumber_rad_m_ = g * omega_c * omega_c / (u10 * u10);
  peak_phase_speed_m_s_ = phase_speed(peak_wavenumber_rad_m_);
  alpha_p_ = 6e-3 * std::sqrt(omega_c);  // eq. (2.7)
  // eq. (2.15), (2.14): roughness length and friction velocity.
  const double roughness_m = 3.7e-5 * u10 * u10 / g * std::pow(u10 / peak_phase_speed_m_s_, 0.9);
  friction_velocity_m_s_ = 0.41 * u10 / std::log(10.0 / roughness_m);
  // eq. (2.13), kept >= 0 (for u* < cm / e the log form would go negative: no capillary waves).
  const double ratio = std::log(friction_velocity_m_s_ / kCapillaryPhaseSpeed_m_s);
  alpha_m_ = std::max(0.0, 1e-2 * (friction_velocity_m_s_ < kCapillaryPhaseSpeed_m_s ? 1.0 + ratio : 1.0 + 3.0 * ratio));
  // Elfouhaily eq. (3): peak enhancement and width of the JONSWAP factor J_p.
  gamma_ = omega_c < 1.0 ? 1.7 : 1.7 + 6.0 * std::log10(omega_c);
  sigma_ = 0.08 * (1.0 + 4.0 / (omega_c * omega_c * omega_c));
}

double UnifiedSpectrum::inverse_wave_age_from_fetch(double u10, double fetch_m) {
  require_positive("unified spectrum", "the wind speed at 10 m (m/s)", u10, "give a wind speed above 0 m/s");
  require_positive("unified spectrum", "the fetch (m)", fetch_m, "give a fetch above 0 m");
  const double x = g * fetch_m / (u10 * u10);
  return 0.84 * std::pow(std::tanh(std::pow(x / kFetchScale, 0.4)), -0.75);  // eq. (2.8)
}

double UnifiedSpectrum::fetch_from_inverse_wave_age(double u10, double omega_c) {
  if (!(omega_c > 0.84)) return std::numeric_limits<double>::infinity();
  // eq. (2.8) inverted: tanh(y) = (Omega/0.84)^(-4/3), X = X0 y^(1/0.4).
  const double y = std::atanh(std::pow(omega_c / 0.84, -4.0 / 3.0));
  return kFetchScale * std::pow(y, 2.5) * u10 * u10 / g;
}

double UnifiedSpectrum::phase_speed(double k) const {
  // Gravity-capillary phase speed (Elfouhaily eq. 33): c = sqrt(g/k (1 + (k/km)^2)).
  const double ratio = k / kCapillaryPeak_rad_m;
  return std::sqrt(g / k * (1.0 + ratio * ratio));
}

double UnifiedSpectrum::omnidirectional_density_m3(double k) const {
  if (!(k > 0.0)) return 0.0;
  const double kp = peak_wavenumber_rad_m_;
  const double c = phase_speed(k);
  const double root_ratio = std::sqrt(k / kp);
  const double long_pm = std::exp(-1.25 * (kp / k) * (kp / k));  // eq. (2.10)
  const double big_gamma = std::exp(-(root_ratio - 1.0) * (root_ratio - 1.0) / (2.0 * sigma_ * sigma_));
  const double jonswap = std::pow(gamma_, big_gamma);             // J_p
  const double f_p = long_pm * jonswap * std::exp(-inverse_wave_age_ / std::sqrt(10.0) * (root_ratio - 1.0));  // eq. (2.9)
  const double b_l = 0.5 * alpha_p_ * peak_phase_speed_m_s_ / c * f_p;                                        // eq. (2.7)
  const double capillary = k / kCapillaryPeak_rad_m - 1.0;
  const double f_m = long_pm * jonswap * std::exp(-0.25 * capillary * capillary);  // eq. (2.12)
  const double b_h = 0.5 * alpha_m_ * kCapillaryPhaseSpeed_m_s / c * f_m;          // eq. (2.11)
  return (b_l + b_h) / (k * k * k);                                                 // eq. (2.6)
}

double UnifiedSpectrum::density_m4(double kx, double ky) const {
  const double k = std::hypot(kx, ky);
  if (!(k > 0.0)) return 0.0;
  // Spreading (Elfouhaily eq. 57, seed 000 eq. 2.5): Delta(k) = tanh(a0 + ap (c/cp)^2.5 + am (cm/c)^2.5).
  const double c = phase_speed(k);
  const double a0 = std::log(2.0) / 4.0, ap = 4.0, am = 0.13 * friction_velocity_m_s_ / kCapillaryPhaseSpeed_m_s;
  const double delta = std::tanh(a0 + ap * std::pow(c / peak_phase_speed_m_s_, 2.5) +
                                 am * std::pow(kCapillaryPhaseSpeed_m_s / c, 2.5));
  const double cos_angle = cosine_to(kx, ky, k, wind_direction_rad_);
  const double cos_twice = 2.0 * cos_angle * cos_angle - 1.0;
  return omnidirectional_density_m3(k) / k * (1.0 + delta * cos_twice) / (2.0 * kPi) *
         half_plane_factor(half_plane_, kx, ky, wind_direction_rad_);
}

double UnifiedSpectrum::highest_wavenumber_rad_m() const {
  return std::max(1e4 * peak_wavenumber_rad_m_, 10.0 * kCapillaryPeak_rad_m);
}

nlohmann::json UnifiedSpectrum::to_json() const {
  return {{"name", name()},
          {"wind_speed_10_m_s", wind_speed_m_s_},
          {"inverse_wave_age", inverse_wave_age_},
          {"wind_direction_rad", wind_direction_rad_},
          {"half_plane", half_plane_name(half_plane_)}};
}

// ---------------------------------------------------------------------------------------------
// PM-ITTC

PmIttcSpectrum::PmIttcSpectrum(double u10, double wind_direction_rad)
    : wind_speed_m_s_(u10), wind_direction_rad_(wind_direction_rad) {
  require_positive("PM-ITTC spectrum", "the wind speed at 10 m (m/s)", u10, "give a wind speed above 0 m/s");
}

double PmIttcSpectrum::density_m4(double kx, double ky) const {
  const double k2 = kx * kx + ky * ky;
  if (!(k2 > 0.0)) return 0.0;
  const double k = std::sqrt(k2);
  const double along_wind = cosine_to(kx, ky, k, wind_direction_rad_);
  if (along_wind < 0.0) return 0.0;  // k . U >= 0
  const double u2 = wind_speed_m_s_ * wind_speed_m_s_;
  // seed 001 eq. (19) with |k . U|^2 = k^2 U^2 cos^2.
  return 8.1e-3 / (kPi * k2 * k2) * std::exp(-0.688 * g * g / (k2 * u2 * u2)) * along_wind * along_wind;
}

double PmIttcSpectrum::omnidirectional_density_m3(double k) const {
  if (!(k > 0.0)) return 0.0;
  const double u2 = wind_speed_m_s_ * wind_speed_m_s_;
  return 8.1e-3 / (2.0 * k * k * k) * std::exp(-0.688 * g * g / (k * k * u2 * u2));
}

double PmIttcSpectrum::peak_wavenumber_rad_m() const {
  // S(k) ~ k^-3 exp(-B/k^2) peaks at k = sqrt(2B/3), B = 0.688 g^2 / U^4.
  return std::sqrt(2.0 * 0.688 / 3.0) * g / (wind_speed_m_s_ * wind_speed_m_s_);
}

nlohmann::json PmIttcSpectrum::to_json() const {
  return {{"name", name()}, {"wind_speed_10_m_s", wind_speed_m_s_}, {"wind_direction_rad", wind_direction_rad_}};
}

// ---------------------------------------------------------------------------------------------
// Frequency spectrum x spreading

DirectionalWavenumberSpectrum::DirectionalWavenumberSpectrum(std::shared_ptr<const FrequencySpectrum> spectrum,
                                                             std::shared_ptr<const DirectionalSpreading> spreading,
                                                             double depth_m)
    : spectrum_(std::move(spectrum)), spreading_(std::move(spreading)), depth_m_(depth_m) {
  if (!spectrum_ || !spreading_)
    throw Error("directional wavenumber spectrum", "needs both a frequency spectrum and a spreading",
                "pass e.g. a JonswapSpectrum and a CosineSquaredSpreading");
}

double DirectionalWavenumberSpectrum::density_m4(double kx, double ky) const {
  const double k = std::hypot(kx, ky);
  if (!(k > 0.0)) return 0.0;
  const double w = frequency_from_wavenumber(k, depth_m_);
  // seed 001 eq. (17): E_k = E(w, theta) (dw/dk) / k, dw/dk = c_g (= sqrt(g/k)/2 in deep water).
  return spectrum_->density_m2_s_rad(w) * spreading_->density_per_rad(std::atan2(ky, kx), w) *
         group_speed_m_s(k, depth_m_) / k;
}

double DirectionalWavenumberSpectrum::peak_wavenumber_rad_m() const {
  return wavenumber_from_frequency(spectrum_->peak_angular_frequency_rad_s(), depth_m_);
}

nlohmann::json DirectionalWavenumberSpectrum::to_json() const {
  return {{"name", name()},
          {"significant_wave_height_m", spectrum_->significant_wave_height_m()},
          {"peak_period_s", 2.0 * kPi / spectrum_->peak_angular_frequency_rad_s()},
          {"mean_direction_rad", spreading_->mean_direction_rad()},
          {"still_water_depth_m", depth_m_}};
}

// ---------------------------------------------------------------------------------------------
// Sum of independent seas

SpectrumSum::SpectrumSum(std::vector<std::shared_ptr<const WavenumberSpectrum>> parts) : parts_(std::move(parts)) {
  if (parts_.empty())
    throw Error("spectrum sum", "has no part", "give at least one spectrum (a swell, a local wind sea)");
  double largest_variance_m2 = -1.0;
  for (const std::shared_ptr<const WavenumberSpectrum>& part : parts_) {
    if (!part) throw Error("spectrum sum", "has a null part", "pass built spectra");
    const double variance_m2 = part->zeroth_moment_m2();
    if (variance_m2 > largest_variance_m2) {
      largest_variance_m2 = variance_m2;
      mean_direction_rad_ = part->mean_direction_rad();
    }
  }
}

double SpectrumSum::density_m4(double kx, double ky) const {
  double density = 0.0;
  for (const std::shared_ptr<const WavenumberSpectrum>& part : parts_) density += part->density_m4(kx, ky);
  return density;
}

double SpectrumSum::omnidirectional_density_m3(double k) const {
  double density = 0.0;
  for (const std::shared_ptr<const WavenumberSpectrum>& part : parts_) density += part->omnidirectional_density_m3(k);
  return density;
}

double SpectrumSum::peak_wavenumber_rad_m() const {
  double lowest = std::numeric_limits<double>::infinity();
  for (const std::shared_ptr<const WavenumberSpectrum>& part : parts_) lowest = std::min(lowest, part->peak_wavenumber_rad_m());
  return lowest;
}

double SpectrumSum::highest_wavenumber_rad_m() const {
  double highest = 0.0;
  for (const std::shared_ptr<const WavenumberSpectrum>& part : parts_) highest = std::max(highest, part->highest_wavenumber_rad_m());
  return highest;
}

nlohmann::json SpectrumSum::to_json() const {
  nlohmann::json parts = nlohmann::json::array();
  for (const std::shared_ptr<const WavenumberSpectrum>& part : parts_) parts.push_back(part->to_json());
  return {{"name", name()}, {"significant_wave_height_m", significant_wave_height_m()}, {"parts", parts}};
}

}  // namespace nearshore::ocean
