#include "nearshore/playback/lighting.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace nearshore::playback {
namespace {
// Mirrors shaders/common.glsl constants.
constexpr double kWaterIndex = 1.333;
constexpr double kSunShininess = 900.0;

double dot(const Vector3& a, const Vector3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vector3 normalize(const Vector3& v) {
  const double length = std::sqrt(dot(v, v));
  return {v[0] / length, v[1] / length, v[2] / length};
}
Radiance add(const Radiance& a, const Radiance& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Radiance scale(const Radiance& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
Radiance multiply(const Radiance& a, const Radiance& b) { return {a[0] * b[0], a[1] * b[1], a[2] * b[2]}; }
Radiance mix(const Radiance& a, const Radiance& b, double t) { return add(scale(a, 1 - t), scale(b, t)); }

Radiance diffuse_irradiance(const Lighting& l, const Vector3& normal) {
  return add(scale(l.sun_radiance, std::max(dot(normal, l.sun_direction()), 0.0)),
             scale(mix(l.sky_horizon, l.sky_zenith, 0.5), 0.6));
}
}  // namespace

Vector3 Lighting::sun_direction() const {
  const double azimuth = sun_azimuth_deg * std::numbers::pi / 180.0;
  const double elevation = sun_elevation_deg * std::numbers::pi / 180.0;
  return {std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth), std::sin(elevation)};
}

Radiance sky_radiance(const Lighting& l, const Vector3& direction) {
  const double up = std::clamp(direction[2], 0.0, 1.0);
  const Radiance gradient = mix(l.sky_horizon, l.sky_zenith, std::sqrt(up));
  const double towards_sun = std::max(dot(direction, l.sun_direction()), 0.0);
  return add(gradient, scale(l.sun_radiance, 0.04 * std::pow(towards_sun, 8.0)));
}

double fresnel_reflectance(double cos_theta) {
  constexpr double f0 = 0.02;
  return f0 + (1.0 - f0) * std::pow(1.0 - std::clamp(cos_theta, 0.0, 1.0), 5.0);
}

Radiance shade_water(const Lighting& l, const Vector3& normal, const Vector3& to_eye, double water_depth_m,
                     double foam) {
  const double cos_view = std::max(dot(normal, to_eye), 1e-3);
  const double reflectance = fresnel_reflectance(cos_view);
  // eq. (13): sky + sun glitter (Blinn-Phong, normalised)
  Vector3 reflected_direction = {2 * dot(normal, to_eye) * normal[0] - to_eye[0],
                                 2 * dot(normal, to_eye) * normal[1] - to_eye[1],
                                 2 * dot(normal, to_eye) * normal[2] - to_eye[2]};
  reflected_direction[2] = std::abs(reflected_direction[2]);
  const Vector3 sun = l.sun_direction();
  const Vector3 half_vector = normalize({sun[0] + to_eye[0], sun[1] + to_eye[1], sun[2] + to_eye[2]});
  const double glitter =
      (kSunShininess + 8.0) / 25.1327 * std::pow(std::max(dot(normal, half_vector), 0.0), kSunShininess);
  const Radiance reflected =
      add(sky_radiance(l, reflected_direction), scale(l.sun_radiance, sun[2] >= 0 ? glitter : 0.0));
  // eq. (14)
  const double sin_view = std::sqrt(std::max(1.0 - cos_view * cos_view, 0.0));
  const double cos_refracted = std::sqrt(std::max(1.0 - std::pow(sin_view / kWaterIndex, 2), 0.0));
  const double path_m = std::max(water_depth_m, 0.0) * (1.0 + 1.0 / std::max(cos_refracted, 0.2));
  const Radiance transmitted = {std::exp(-l.water_attenuation_per_m[0] * path_m),
                                std::exp(-l.water_attenuation_per_m[1] * path_m),
                                std::exp(-l.water_attenuation_per_m[2] * path_m)};
  const Vector3 up = {0, 0, 1};
  const Radiance seabed = multiply(l.seabed_albedo, diffuse_irradiance(l, up));
  const Radiance water_body = multiply(l.water_colour, diffuse_irradiance(l, up));
  const Radiance refracted = add(multiply(transmitted, seabed),
                                 multiply({1 - transmitted[0], 1 - transmitted[1], 1 - transmitted[2]}, water_body));
  // eq. (12), then eq. (15)
  const Radiance surface = add(scale(reflected, reflectance), scale(refracted, 1.0 - reflectance));
  const Radiance foam_lit = multiply(l.foam_colour, diffuse_irradiance(l, normal));
  return mix(surface, foam_lit, std::clamp(foam, 0.0, 1.0));
}

Radiance to_display(const Lighting& l, const Radiance& radiance) {
  Radiance out;
  for (int c = 0; c < 3; ++c) out[c] = std::pow(1.0 - std::exp(-l.exposure * radiance[c]), 1.0 / 2.2);
  return out;
}

}  // namespace nearshore::playback
