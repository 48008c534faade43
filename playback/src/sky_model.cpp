#include "nearshore/playback/sky_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace nearshore::playback {
namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;
// Solar illuminance constant outside the atmosphere (IES Lighting Handbook: 128 klx).
constexpr double kExtraterrestrialSunKlx = 128.0;
// Twilight: a decade of sky luminance per 2.4 degrees the sun is below the horizon (~3 cd/m2 at
// the zenith at civil dusk, 6 degrees down, from ~1 kcd/m2 at sunset).
constexpr double kTwilightDegreesPerDecade = 2.4;

double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// [T^2 T 1] M [theta^3 theta^2 theta 1]^T of seed 001 eq. (4)-(5).
double zenith_chromaticity(const double (&m)[3][4], double turbidity, double theta) {
  const double t[3] = {turbidity * turbidity, turbidity, 1.0};
  const double th[4] = {theta * theta * theta, theta * theta, theta, 1.0};
  double sum = 0.0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) sum += t[r] * m[r][c] * th[c];
  return sum;
}
}  // namespace

double preetham_zenith_luminance_kcd_m2(double turbidity, double sun_zenith_rad) {
  const double chi = (4.0 / 9.0 - turbidity / 120.0) * (kPi - 2.0 * sun_zenith_rad);
  return (4.0453 * turbidity - 4.9710) * std::tan(chi) - 0.2155 * turbidity + 2.4192;
}

double preetham_zenith_x(double turbidity, double sun_zenith_rad) {
  static constexpr double m[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                                     {-0.02903, 0.06377, -0.03202, 0.00394},
                                     {0.11693, -0.21196, 0.06052, 0.25886}};
  return zenith_chromaticity(m, turbidity, sun_zenith_rad);
}

double preetham_zenith_y(double turbidity, double sun_zenith_rad) {
  static constexpr double m[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                                     {-0.04214, 0.08970, -0.04153, 0.00516},
                                     {0.15346, -0.26756, 0.06670, 0.26688}};
  return zenith_chromaticity(m, turbidity, sun_zenith_rad);
}

PerezCoefficients preetham_perez_Y(double T) {
  return {0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251, 0.1206 * T - 2.5771, -0.0670 * T + 0.3703};
}
PerezCoefficients preetham_perez_x(double T) {
  return {-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125, -0.0641 * T - 0.8989, -0.0033 * T + 0.0452};
}
PerezCoefficients preetham_perez_y(double T) {
  return {-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102, -0.0441 * T - 1.6537, -0.0109 * T + 0.0529};
}

double perez(const PerezCoefficients& c, double cos_theta, double gamma_rad) {
  const double cos_gamma = std::cos(gamma_rad);
  return (1.0 + c[0] * std::exp(c[1] / cos_theta)) * (1.0 + c[2] * std::exp(c[3] * gamma_rad) + c[4] * cos_gamma * cos_gamma);
}

double relative_air_mass(double zenith_rad) {
  const double zenith_deg = std::min(zenith_rad / kDegree, 90.0);
  return 1.0 / (std::cos(zenith_deg * kDegree) + 0.15 * std::pow(93.885 - zenith_deg, -1.253));
}

Radiance sun_transmittance(double turbidity, double zenith_rad) {
  const double m = relative_air_mass(zenith_rad);
  const double beta = std::max(0.04608365 * turbidity - 0.04586025, 0.0);  // Angstrom turbidity
  Radiance t{};
  for (int c = 0; c < 3; ++c) {
    const double lambda_um = kBandWavelengthsNm[std::size_t(c)] / 1000.0;
    const double tau = 0.008735 * std::pow(lambda_um, -4.08) + beta * std::pow(lambda_um, -1.3);
    t[std::size_t(c)] = std::exp(-m * tau);
  }
  return t;
}

double overcast_horizontal_illuminance_klx(double sun_elevation_deg) {
  if (sun_elevation_deg >= 0.0) return 0.3 + 21.0 * std::sin(sun_elevation_deg * kDegree);
  return 0.3 * std::pow(10.0, sun_elevation_deg / kTwilightDegreesPerDecade);
}

SkyModel make_sky(double sun_azimuth_deg, double sun_elevation_deg, double turbidity, double cloud_cover) {
  SkyModel sky;
  sky.cloud_cover = std::isfinite(cloud_cover) ? std::clamp(cloud_cover, 0.0, 1.0) : 0.0;
  // E_h = integral of L_z (1 + 2 cos t) / 3 cos t sin t dt dphi = 7 pi L_z / 9.
  sky.overcast_zenith_luminance_kcd_m2 = 9.0 * overcast_horizontal_illuminance_klx(sun_elevation_deg) / (7.0 * kPi);
  const double azimuth = sun_azimuth_deg * kDegree, elevation = sun_elevation_deg * kDegree;
  sky.sun_direction = {std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth), std::sin(elevation)};
  sky.turbidity = std::clamp(turbidity, 1.7, 10.0);
  // 1. The model's sun: never below the horizon (Preetham's fit ends there).
  sky.sun_zenith_rad = std::clamp(kPi / 2 - elevation, 0.0, kPi / 2);
  const double T = sky.turbidity, theta_s = sky.sun_zenith_rad;
  sky.perez_Y = preetham_perez_Y(T);
  sky.perez_x = preetham_perez_x(T);
  sky.perez_y = preetham_perez_y(T);
  // 2. Zenith values, seed 001 eq. (3)-(5), dimmed through twilight.
  const double twilight = sun_elevation_deg >= 0.0 ? 1.0 : std::pow(10.0, sun_elevation_deg / kTwilightDegreesPerDecade);
  sky.zenith_luminance_kcd_m2 = std::max(preetham_zenith_luminance_kcd_m2(T, theta_s), 0.0) * twilight;
  sky.zenith_x = preetham_zenith_x(T, theta_s);
  sky.zenith_y = preetham_zenith_y(T, theta_s);
  // 3. The Perez denominators F(0, theta_s): the zenith (theta = 0) seen at gamma = theta_s.
  sky.perez_zenith_Y = perez(sky.perez_Y, 1.0, theta_s);
  sky.perez_zenith_x = perez(sky.perez_x, 1.0, theta_s);
  sky.perez_zenith_y = perez(sky.perez_y, 1.0, theta_s);
  // 4. The sun's beam, fading out while its disc (0.53 degree) sinks under the horizon.
  const Radiance transmittance = sun_transmittance(T, theta_s);
  const double above = smoothstep(-0.27, 0.27, sun_elevation_deg);
  for (int c = 0; c < 3; ++c)
    sky.sun_illuminance_klx[std::size_t(c)] = kExtraterrestrialSunKlx * transmittance[std::size_t(c)] * above * (1.0 - sky.cloud_cover);
  return sky;
}

Radiance xyY_to_linear_srgb(double x, double y, double Y) {
  // seed 001 eq. (11)-(12)
  y = std::max(y, 1e-4);
  const double X = x * Y / y, Z = (1.0 - x - y) * Y / y;
  return {std::max(3.240479 * X - 1.537150 * Y - 0.498535 * Z, 0.0),
          std::max(-0.969256 * X + 1.875991 * Y + 0.041556 * Z, 0.0),
          std::max(0.055648 * X - 0.204043 * Y + 1.057311 * Z, 0.0)};
}

Radiance sky_radiance(const SkyModel& sky, const Vector3& direction) {
  // theta: the direction's zenith angle (clamped just above the horizon: 1 / cos theta stays
  // finite, and B < 0 makes e^(B / cos theta) vanish there); gamma: its angle from the sun.
  const double cos_theta = std::max(direction[2], 0.01);
  const double cos_gamma = std::clamp(direction[0] * sky.sun_direction[0] + direction[1] * sky.sun_direction[1] +
                                          direction[2] * sky.sun_direction[2],
                                      -1.0, 1.0);
  const double gamma = std::acos(cos_gamma);
  const double Y = std::max(sky.zenith_luminance_kcd_m2 * perez(sky.perez_Y, cos_theta, gamma) / sky.perez_zenith_Y,
                            sky.night_luminance_kcd_m2);
  const double x = sky.zenith_x * perez(sky.perez_x, cos_theta, gamma) / sky.perez_zenith_x;
  const double y = sky.zenith_y * perez(sky.perez_y, cos_theta, gamma) / sky.perez_zenith_y;
  Radiance clear = xyY_to_linear_srgb(x, y, Y);
  if (sky.cloud_cover <= 0.0) return clear;
  // CIE overcast: grey (linear sRGB white is D65 with Y = 1), below the horizon its horizon value.
  const double overcast = std::max(sky.overcast_zenith_luminance_kcd_m2 * (1.0 + 2.0 * std::max(direction[2], 0.0)) / 3.0,
                                   sky.night_luminance_kcd_m2);
  for (double& channel : clear) channel = (1.0 - sky.cloud_cover) * channel + sky.cloud_cover * overcast;
  return clear;
}

Radiance sky_illuminance_klx(const SkyModel& sky) {
  // Midpoint rule over zenith angle and azimuth: E = integral of L cos(theta) sin(theta).
  constexpr int kZenithSteps = 24, kAzimuthSteps = 48;
  const double d_theta = 0.5 * kPi / kZenithSteps, d_phi = 2.0 * kPi / kAzimuthSteps;
  Radiance e{};
  for (int i = 0; i < kZenithSteps; ++i) {
    const double theta = (i + 0.5) * d_theta;
    const double weight = std::cos(theta) * std::sin(theta) * d_theta * d_phi;
    for (int j = 0; j < kAzimuthSteps; ++j) {
      const double phi = (j + 0.5) * d_phi;
      const Radiance l = sky_radiance(sky, {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
      for (int c = 0; c < 3; ++c) e[std::size_t(c)] += l[std::size_t(c)] * weight;
    }
  }
  return e;
}

}  // namespace nearshore::playback
