// Shared by every nearshore shader (prepended after #version). Lighting of seed 003 eq. (12)-(16);
// playback/src/lighting.cpp is the CPU reference of these functions, tested pixel against pixel.
// Coordinates: x east, y north, z up, metres, in the harbour grid's frame.

uniform vec3 u_sun_direction;      // unit vector towards the sun
uniform vec3 u_sun_radiance;       // sun colour x intensity
uniform vec3 u_sky_zenith;         // sky colour straight up
uniform vec3 u_sky_horizon;        // sky colour at the horizon
uniform vec3 u_water_colour;       // C_water of eq. (14): deep-water body colour
uniform vec3 u_water_attenuation;  // atten of eq. (14), per metre, red absorbed most
uniform vec3 u_seabed_albedo;      // C_object of eq. (14): sand
uniform vec3 u_foam_colour;        // C_foam of eq. (15)
uniform float u_exposure;

const float kWaterIndex = 1.333;
const float kSunShininess = 900.0;  // Blinn-Phong exponent: a small sharp glitter highlight

// The sky seen along `direction`: horizon-to-zenith gradient, plus a glow round the sun.
vec3 sky_radiance(vec3 direction) {
  float up = clamp(direction.z, 0.0, 1.0);
  vec3 gradient = mix(u_sky_horizon, u_sky_zenith, sqrt(up));
  float towards_sun = max(dot(direction, u_sun_direction), 0.0);
  return gradient + u_sun_radiance * (0.04 * pow(towards_sun, 8.0));
}

// Schlick's approximation of the Fresnel reflectance of water (F0 = 0.02) at cos(theta).
float fresnel_reflectance(float cos_theta) {
  float f0 = 0.02;
  return f0 + (1.0 - f0) * pow(1.0 - clamp(cos_theta, 0.0, 1.0), 5.0);
}

// Light reaching a Lambertian surface facing `normal` (sun + sky ambient).
vec3 diffuse_irradiance(vec3 normal) {
  return u_sun_radiance * max(dot(normal, u_sun_direction), 0.0) + 0.6 * mix(u_sky_horizon, u_sky_zenith, 0.5);
}

// Seed 003 eq. (12)-(16) at one point of the sea surface.
//   normal: surface normal; to_eye: unit vector to the viewer; water_depth_m: total depth d + eta
//   under the point; foam: foam concentration in [0, 1].
vec3 shade_water(vec3 normal, vec3 to_eye, float water_depth_m, float foam) {
  float cos_view = max(dot(normal, to_eye), 1e-3);
  float reflectance = fresnel_reflectance(cos_view);
  // eq. (13): sky + sun (local reflections would add here)
  vec3 reflected_direction = reflect(-to_eye, normal);
  reflected_direction.z = abs(reflected_direction.z);
  vec3 half_vector = normalize(u_sun_direction + to_eye);
  float glitter = (kSunShininess + 8.0) / 25.1327 * pow(max(dot(normal, half_vector), 0.0), kSunShininess);
  vec3 reflected = sky_radiance(reflected_direction) + u_sun_radiance * glitter * step(0.0, u_sun_direction.z);
  // eq. (14): light from the seabed attenuated along the refracted path down and back up,
  // blended with the colour of the water body itself.
  float sin_view = sqrt(max(1.0 - cos_view * cos_view, 0.0));
  float cos_refracted = sqrt(max(1.0 - (sin_view / kWaterIndex) * (sin_view / kWaterIndex), 0.0));
  float path_m = max(water_depth_m, 0.0) * (1.0 + 1.0 / max(cos_refracted, 0.2));
  vec3 transmitted = exp(-u_water_attenuation * path_m);
  vec3 seabed = u_seabed_albedo * diffuse_irradiance(vec3(0.0, 0.0, 1.0));
  vec3 water_body = u_water_colour * diffuse_irradiance(vec3(0.0, 0.0, 1.0));
  vec3 refracted = transmitted * seabed + (vec3(1.0) - transmitted) * water_body;
  // eq. (12)
  vec3 surface = reflectance * reflected + (1.0 - reflectance) * refracted;
  // eq. (15): blend the foam in
  vec3 foam_lit = u_foam_colour * diffuse_irradiance(normal);
  return mix(surface, foam_lit, clamp(foam, 0.0, 1.0));
}

// Exposure and display gamma (the default framebuffer is not sRGB).
vec3 to_display(vec3 radiance) {
  vec3 exposed = vec3(1.0) - exp(-u_exposure * radiance);
  return pow(exposed, vec3(1.0 / 2.2));
}
