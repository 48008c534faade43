#include "nearshore/playback/ocean_brdf.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace nearshore::playback {
namespace {
constexpr double kPi = std::numbers::pi;
}  // namespace

double fresnel_reflectance_at_normal_incidence(double n) { return std::pow((n - 1.0) / (n + 1.0), 2); }

double fresnel_reflectance(double cos_incidence) {
  const double r = fresnel_reflectance_at_normal_incidence();
  return r + (1.0 - r) * std::pow(1.0 - std::clamp(cos_incidence, 0.0, 1.0), 5.0);
}

double fresnel_reflectance_exact(double cos_incidence, double n) {
  // Fresnel's equations for s and p polarisation, averaged (unpolarised light from air).
  const double ci = std::clamp(cos_incidence, 0.0, 1.0);
  const double st = std::sqrt(1.0 - ci * ci) / n;
  const double ct = std::sqrt(std::max(1.0 - st * st, 0.0));
  const double rs = (ci - n * ct) / (ci + n * ct);
  const double rp = (n * ci - ct) / (n * ci + ct);
  return 0.5 * (rs * rs + rp * rp);
}

double erfc_approximation(double x) { return 2.0 * std::exp(-x * x) / (2.319 * x + std::sqrt(4.0 + 1.52 * x * x)); }

double smith_lambda(double cos_theta, double slope_variance) {
  const double c = std::clamp(cos_theta, 1e-4, 1.0);
  const double a = c / std::sqrt(2.0 * slope_variance * std::max(1.0 - c * c, 1e-12));
  return std::max(0.0, (std::exp(-a * a) - a * std::sqrt(kPi) * erfc_approximation(a)) / (2.0 * a * std::sqrt(kPi)));
}

double cox_munk_slope_variance(double wind_speed_m_s) { return 0.003 + 0.00512 * std::max(wind_speed_m_s, 0.0); }

double cox_munk_upwind_share(double wind_speed_m_s) {
  const double u = std::max(wind_speed_m_s, 0.0);
  return (0.0015 + 0.00316 * u) / (0.003 + 0.00508 * u);
}

double ocean_brdf(const Vector3& n, const Vector3& v, const Vector3& l, double slope_variance) {
  const double cos_v = dot(n, v), cos_l = dot(n, l);
  if (cos_v <= 0.0 || cos_l <= 0.0) return 0.0;
  const Vector3 h = normalize({v[0] + l[0], v[1] + l[1], v[2] + l[2]});
  const double h_z = dot(n, h);
  // eq. (3.13): the probability density of the facet slope zeta_h that mirrors l into v.
  const double zeta_squared = (1.0 - h_z * h_z) / (h_z * h_z);
  const double p = std::exp(-0.5 * zeta_squared / slope_variance) / (2.0 * kPi * slope_variance);
  const double shadowing = 1.0 + smith_lambda(cos_v, slope_variance) + smith_lambda(cos_l, slope_variance);
  return p * fresnel_reflectance(dot(v, h)) / (4.0 * std::pow(h_z, 4) * cos_v * cos_l * shadowing);
}

double mean_fresnel_reflectance(double cos_view, double slope_variance) {
  const double r = fresnel_reflectance_at_normal_incidence();
  const double sigma = std::sqrt(slope_variance);
  const double c = std::clamp(cos_view, 0.0, 1.0);
  return r + (1.0 - r) * std::pow(1.0 - c, 5.0 * std::exp(-2.69 * sigma)) / (1.0 + 22.7 * std::pow(sigma, 1.5));
}

}  // namespace nearshore::playback
