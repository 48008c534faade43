#pragma once
// Lighting of the sea surface: seed 003 eq. (12)-(16) (Fresnel blend of reflected sky and sun with
// refracted seabed and water colour; foam). The GLSL in shaders/common.glsl computes it per pixel;
// the functions here are its CPU reference, with the same formulas, so the shading logic is tested
// without a GPU and the rendered pixels are checked against it.
#include <array>

namespace nearshore::playback {

using Vector3 = std::array<double, 3>;
using Radiance = std::array<double, 3>;  ///< linear RGB

struct Lighting {
  double sun_azimuth_deg = 200.0;   ///< compass bearing of the sun (0 north, 90 east)
  double sun_elevation_deg = 35.0;  ///< above the horizon
  Radiance sun_radiance = {1.6, 1.5, 1.35};
  Radiance sky_zenith = {0.18, 0.35, 0.70};
  Radiance sky_horizon = {0.62, 0.72, 0.82};
  Radiance water_colour = {0.02, 0.11, 0.14};       ///< C_water, eq. (14)
  Radiance water_attenuation_per_m = {0.45, 0.10, 0.07};  ///< atten, eq. (14); clear coastal water
  Radiance seabed_albedo = {0.62, 0.56, 0.42};      ///< C_object, eq. (14): sand
  Radiance foam_colour = {0.9, 0.92, 0.94};         ///< C_foam, eq. (15)
  double foam_onset_m = 0.6;  ///< h0 of eq. (16): crests below this carry no foam
  double foam_full_m = 1.6;   ///< h_max of eq. (16)
  double exposure = 1.4;

  /// Unit vector towards the sun in the harbour frame (x east, y north, z up).
  Vector3 sun_direction() const;
};

/// Sky radiance seen along a unit direction (shaders/common.glsl sky_radiance).
Radiance sky_radiance(const Lighting& lighting, const Vector3& direction);
/// Schlick's Fresnel reflectance of water, F0 = 0.02 (shaders/common.glsl fresnel_reflectance).
double fresnel_reflectance(double cos_theta);
/// eq. (12)-(15) at one surface point (shaders/common.glsl shade_water).
Radiance shade_water(const Lighting& lighting, const Vector3& normal, const Vector3& to_eye, double water_depth_m,
                     double foam);
/// Exposure and display gamma, 0..1 (shaders/common.glsl to_display).
Radiance to_display(const Lighting& lighting, const Radiance& radiance);

}  // namespace nearshore::playback
