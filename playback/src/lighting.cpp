#include "nearshore/playback/lighting.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "nearshore/core/error.hpp"
#include "nearshore/ocean/deep_water.hpp"

namespace nearshore::playback {
namespace {
constexpr double kPi = std::numbers::pi;
// Mean Fresnel reflectance of a uniform sky seen from under a flat surface... from above: the
// fraction of diffuse sky light a calm sea reflects (6.6 %, Mobley 1994 section 4.4).
constexpr double kDiffuseSkyReflectance = 0.066;
// Mean cosine of the downwelling light just under the surface (Kirk 2011: 0.8-0.9 in clear water).
constexpr double kDownwellingMeanCosine = 0.8;
// Exposure: a white Lambertian surface under the day's light maps to 1 - e^-0.9 (0.59 linear): the
// sky near the horizon, often brighter than that surface (Preetham), keeps some headroom.
constexpr double kExposureKey = 0.9;
constexpr double kAdaptationFloorKcdM2 = 0.01;  // the eye stops adapting at dusk (~10 cd/m2)
// Path through a wave crest for eq. (3.38)'s colour (m) and the fraction of light it lets through.
constexpr double kCrestPathM = 4.0;
constexpr double kCrestTransmission = 0.15;

double luminance(const Radiance& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }
double smoothstep(double edge0, double edge1, double x) {  // GLSL's
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}
}  // namespace

static_assert(Lighting{}.jacobian_foam_onset - ocean::kStokesBreakingJacobian < 1e-12 &&
                  ocean::kStokesBreakingJacobian - Lighting{}.jacobian_foam_onset < 1e-12,
              "Lighting::jacobian_foam_onset defaults to the Stokes limit of ocean/deep_water.hpp");

Vector3 Lighting::sun_direction() const {
  const double azimuth = sun_azimuth_deg * kPi / 180.0;
  const double elevation = sun_elevation_deg * kPi / 180.0;
  return {std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth), std::sin(elevation)};
}

void Lighting::set_sun_for(double latitude_deg, double longitude_deg, const UtcTime& time) {
  const SunPosition sun = sun_position(latitude_deg, longitude_deg, time);
  sun_azimuth_deg = sun.azimuth_deg;
  sun_elevation_deg = sun.elevation_deg;
}

LightingFrame prepare_lighting(const Lighting& l) {
  LightingFrame f;
  f.sky = make_sky(l.sun_azimuth_deg, l.sun_elevation_deg, l.atmospheric_turbidity, l.cloud_cover);
  f.sky_illuminance_klx = sky_illuminance_klx(f.sky);
  f.water = water_optics(l.water);
  f.seabed_albedo = l.seabed_albedo;
  f.foam_albedo = l.foam_albedo;
  const double total = l.sub_grid_slope_variance >= 0.0 ? l.sub_grid_slope_variance : cox_munk_slope_variance(l.wind_speed_m_s);
  const double upwind_share = cox_munk_upwind_share(l.wind_speed_m_s);
  f.slope_variance_upwind = std::max(total * upwind_share, 1e-4);
  f.slope_variance_crosswind = std::max(total * (1.0 - upwind_share), 1e-4);
  f.slope_variance_per_axis = 0.5 * (f.slope_variance_upwind + f.slope_variance_crosswind);
  f.foam_onset_m = l.foam_onset_m;
  f.foam_full_m = l.foam_full_m;
  f.translucency = std::max(l.translucency, 0.0);
  f.jacobian_foam_onset = l.jacobian_foam_onset;
  f.structure_foam_onset_m_s = l.structure_foam_onset_m_s;
  f.wind_direction_rad = l.wind_direction_rad;
  f.shore_wave_amplitude_m = std::max(l.shore_wave_amplitude_m, 0.0) * std::clamp(l.wind_speed_m_s / 10.0, 0.0, 1.0);
  f.shore_band_m = std::max(l.shore_band_m, 1.0);
  // The luminance of a white Lambertian surface under sun and sky sets the exposure; at a low sun
  // the sky, twice as bright as its mean (E_sky / pi) towards the horizon, fills the view instead.
  const double sky_mean = luminance(f.sky_illuminance_klx) / kPi;
  const double adaptation = std::max(
      luminance(f.sky.sun_illuminance_klx) * std::max(f.sky.sun_direction[2], 0.0) / kPi + sky_mean, 2.0 * sky_mean);
  f.exposure = std::max(l.exposure_compensation, 0.0) * kExposureKey / std::max(adaptation, kAdaptationFloorKcdM2);
  f.detail_parallax = std::max(l.detail_parallax, 0.0);
  f.filter_baked_slopes = l.filter_baked_slopes;
  f.foam_decay_time_s = std::max(l.foam_decay_time_s, 0.0);
  // Koschmieder: the contrast of a black object falls as exp(-beta s); the WMO's meteorological
  // optical range is where it reaches 5 %.
  f.fog_extinction_per_m = l.visibility_m > 0.0 && std::isfinite(l.visibility_m) ? -std::log(0.05) / l.visibility_m : 0.0;
  f.fog_top_m = std::max(l.fog_top_m, 0.0);
  return f;
}

const std::vector<WeatherPreset>& weather_presets() {
  // Visibility classes of the WMO (No. 8, 2018: fog below 1 km, mist 1-5 km) and Preetham's
  // turbidity (2 very clear, 6 hazy); fog layers of sea fog are 100-400 m deep.
  static const std::vector<WeatherPreset> presets = {
      {"clear", 0.0, 2.5, 0.0, 150.0, "clear sky, sun, unlimited visibility"},
      {"hazy", 0.0, 6.0, 8000.0, 800.0, "hazy sun, visibility 8 km in a haze layer 800 m deep"},
      {"overcast", 1.0, 4.0, 0.0, 150.0, "CIE overcast sky, no sun, good visibility"},
      {"mist", 1.0, 4.0, 2000.0, 300.0, "overcast, mist: visibility 2 km in a layer 300 m deep"},
      {"fog", 1.0, 4.0, 400.0, 150.0, "overcast, fog: visibility 400 m in a layer 150 m deep"},
  };
  return presets;
}

void apply_weather(Lighting& lighting, std::string_view name) {
  std::string names;
  for (const WeatherPreset& preset : weather_presets()) {
    if (preset.name == name) {
      lighting.cloud_cover = preset.cloud_cover;
      lighting.atmospheric_turbidity = preset.atmospheric_turbidity;
      lighting.visibility_m = preset.visibility_m;
      lighting.fog_top_m = preset.fog_top_m;
      return;
    }
    names += (names.empty() ? "" : ", ") + preset.name;
  }
  throw Error("weather \"" + std::string(name) + "\"", "is not a preset", "choose one of " + names);
}

double fog_transmittance(const LightingFrame& f, const Vector3& eye_m, const Vector3& point_m) {
  if (f.fog_extinction_per_m <= 0.0) return 1.0;
  const Vector3 d = {point_m[0] - eye_m[0], point_m[1] - eye_m[1], point_m[2] - eye_m[2]};
  const double length = std::sqrt(dot(d, d));
  const double low = std::min(eye_m[2], point_m[2]), high = std::max(eye_m[2], point_m[2]);
  double inside = 1.0;  // the fraction of the segment below the layer's top (z is linear along it)
  if (low >= f.fog_top_m) inside = 0.0;
  else if (high > f.fog_top_m) inside = (f.fog_top_m - low) / (high - low);
  return std::exp(-f.fog_extinction_per_m * length * inside);
}

Radiance fog_radiance(const LightingFrame& f, const Vector3& direction) {
  const double horizontal = std::hypot(direction[0], direction[1]);
  const Vector3 horizon = horizontal > 1e-9 ? Vector3{direction[0] / horizontal, direction[1] / horizontal, 0.0} : Vector3{1, 0, 0};
  return sky_radiance(f.sky, horizon);
}

Radiance through_air(const LightingFrame& f, const Radiance& radiance, const Vector3& eye_m, const Vector3& point_m) {
  const double t = fog_transmittance(f, eye_m, point_m);
  if (t >= 1.0) return radiance;
  const Radiance fog = fog_radiance(f, {point_m[0] - eye_m[0], point_m[1] - eye_m[1], point_m[2] - eye_m[2]});
  return {t * radiance[0] + (1 - t) * fog[0], t * radiance[1] + (1 - t) * fog[1], t * radiance[2] + (1 - t) * fog[2]};
}

Radiance sky_seen(const LightingFrame& f, const Vector3& from_m, const Vector3& direction) {
  const Radiance sky = sky_radiance(f.sky, direction);
  if (f.fog_extinction_per_m <= 0.0) return sky;
  const double path_m = std::max(f.fog_top_m - from_m[2], 0.0) / std::max(direction[2], 0.01);
  const double t = std::exp(-f.fog_extinction_per_m * path_m);
  const Radiance fog = fog_radiance(f, direction);
  return {t * sky[0] + (1 - t) * fog[0], t * sky[1] + (1 - t) * fog[1], t * sky[2] + (1 - t) * fog[2]};
}

Radiance shade_lambertian(const LightingFrame& f, const Vector3& normal, const Radiance& albedo) {
  const double sun = std::max(dot(normal, f.sky.sun_direction), 0.0);
  const double sky = 0.5 * (1.0 + normal[2]);  // the part of the sky dome the surface faces
  Radiance out{};
  for (std::size_t c = 0; c < 3; ++c)
    out[c] = albedo[c] * (f.sky.sun_illuminance_klx[c] * sun + f.sky_illuminance_klx[c] * sky) / kPi;
  return out;
}

namespace {
double lattice_hash(double cell_x, double cell_y) {  // GLSL: uvec2(ivec2(cell)) * (...), wrapping
  const std::uint32_t qx = std::uint32_t(std::int32_t(cell_x)) * 1597334677u, qy = std::uint32_t(std::int32_t(cell_y)) * 3812015801u;
  const std::uint32_t n = (qx ^ qy) * 1597334677u;
  return double(n >> 8) * (1.0 / 16777215.0);
}
}  // namespace

double value_noise(double x, double y) {
  const double ix = std::floor(x), iy = std::floor(y), fx = x - ix, fy = y - iy;
  const double ux = fx * fx * (3.0 - 2.0 * fx), uy = fy * fy * (3.0 - 2.0 * fy);
  const double south = lattice_hash(ix, iy) + (lattice_hash(ix + 1, iy) - lattice_hash(ix, iy)) * ux;
  const double north = lattice_hash(ix, iy + 1) + (lattice_hash(ix + 1, iy + 1) - lattice_hash(ix, iy + 1)) * ux;
  return south + (north - south) * uy;
}

double seabed_texture(double x_m, double y_m) {
  return 0.7 + 0.6 * (0.65 * value_noise(x_m / 14.0, y_m / 14.0) + 0.35 * value_noise(x_m / 5.0 + 7.1, y_m / 5.0 + 7.1));
}

namespace {
// GLSL refract(-to_eye, n, 1 / n_water): the view's direction in the water (0 at total reflection).
Vector3 refracted_view(const Vector3& n, const Vector3& to_eye) {
  const double eta = 1.0 / kWaterRefractiveIndex;
  const Vector3 i = {-to_eye[0], -to_eye[1], -to_eye[2]};
  const double n_dot_i = dot(n, i);
  const double k = 1.0 - eta * eta * (1.0 - n_dot_i * n_dot_i);
  Vector3 r = {0, 0, 0};
  if (k >= 0.0)
    for (std::size_t c = 0; c < 3; ++c) r[c] = eta * i[c] - (eta * n_dot_i + std::sqrt(k)) * n[c];
  return r;
}
}  // namespace

std::array<double, 2> refracted_seabed_point(double x_m, double y_m, const Vector3& n, const Vector3& to_eye, double depth_m) {
  const Vector3 r = refracted_view(n, to_eye);
  const double reach = std::max(depth_m, 0.0) / std::max(-r[2], 0.1);
  return {x_m + r[0] * reach, y_m + r[1] * reach};
}

Vector3 refraction_probe_m(const Vector3& surface_m, const Vector3& n, const Vector3& to_eye, double depth_m) {
  const Vector3 r = refracted_view(n, to_eye);
  const double reach = std::max(depth_m, 0.0) / std::max(-r[2], 0.1);
  return {surface_m[0] + r[0] * reach, surface_m[1] + r[1] * reach, surface_m[2] + r[2] * reach};
}

Radiance from_display(const LightingFrame& f, const Radiance& displayed) {
  Radiance exposed;
  for (std::size_t i = 0; i < 3; ++i) exposed[i] = std::pow(std::clamp(displayed[i], 0.0, 1.0), 2.2);
  const double y_display = std::min(luminance(exposed), 0.999);  // 1 - e^-7: the curve's top
  if (!(y_display > 0.0)) return {0.0, 0.0, 0.0};
  const double y = -std::log(1.0 - y_display) / f.exposure;
  Radiance out;
  for (std::size_t i = 0; i < 3; ++i) out[i] = exposed[i] * y / y_display;
  return out;
}

Radiance submerged_transmittance(const LightingFrame& f, double depth_m, double path_m) {
  Radiance t;
  for (std::size_t c = 0; c < 3; ++c)
    t[c] = std::exp(-f.water.diffuse_attenuation_per_m[c] *
                    (std::max(depth_m, 0.0) / kDownwellingMeanCosine + std::max(path_m, 0.0)));
  return t;
}

double structure_foam(const LightingFrame& f, double rise_rate_m_s, double face_sine, double distance_m, double band_m) {
  const double onset = f.structure_foam_onset_m_s;
  if (!(onset > 0.0) || !std::isfinite(onset) || !(band_m > 0.0) || !(face_sine > 0.0)) return 0.0;
  const bool vertical = face_sine >= 1.0;
  const double along_face = (vertical ? std::max(rise_rate_m_s, 0.0) : std::abs(rise_rate_m_s)) / face_sine;
  return std::clamp((along_face - onset) / onset, 0.0, 1.0) * std::clamp(1.0 - distance_m / band_m, 0.0, 1.0);
}

double slope_variance_along(const LightingFrame& f, const Vector3& direction, double extra) {
  const double horizontal = std::hypot(direction[0], direction[1]);
  double along = f.slope_variance_per_axis;
  if (horizontal > 1e-9) {
    const double cos_phi = (direction[0] * std::cos(f.wind_direction_rad) + direction[1] * std::sin(f.wind_direction_rad)) / horizontal;
    along = f.slope_variance_upwind * cos_phi * cos_phi + f.slope_variance_crosswind * (1.0 - cos_phi * cos_phi);
  }
  return along + std::max(extra, 0.0);
}

double facet_slope_density(const LightingFrame& f, double a, double c, double extra) {
  const double s_u = f.slope_variance_upwind + std::max(extra, 0.0), s_c = f.slope_variance_crosswind + std::max(extra, 0.0);
  return std::exp(-0.5 * (a * a / s_u + c * c / s_c)) / (2.0 * kPi * std::sqrt(s_u * s_c));
}

Radiance shade_water(const LightingFrame& f, const SurfacePoint& s) {
  const Vector3& n = s.normal;
  const Vector3& v = s.to_eye;
  const Vector3& l = f.sky.sun_direction;
  const double cos_v = std::max(dot(n, v), 1e-3);
  const double extra = std::max(s.extra_slope_variance_per_axis, 0.0);
  // The roughness each direction sees: Cox & Munk's ellipse, long along the wind.
  const double sigma2 = slope_variance_along(f, v, extra), sigma2_light = slope_variance_along(f, l, extra);
  // 1. Sky light reflected, eq. (3.23)-(3.24): the sky in the mirror direction times the mean
  //    Fresnel reflectance of the rough surface. A ray mirrored downwards sees the sky's lowest band.
  Vector3 mirror = {2 * dot(n, v) * n[0] - v[0], 2 * dot(n, v) * n[1] - v[1], 2 * dot(n, v) * n[2] - v[2]};
  mirror[2] = std::abs(mirror[2]);
  const double sky_fresnel = mean_fresnel_reflectance(cos_v, sigma2);
  const Radiance sky_seen = playback::sky_seen(f, {0.0, 0.0, 0.0}, mirror);
  const double covered = std::clamp(s.local_reflection_coverage, 0.0, 1.0);
  Radiance sky{};
  for (std::size_t c = 0; c < 3; ++c) sky[c] = (1.0 - covered) * sky_seen[c] + covered * s.local_reflection[c];
  // 2. Sun glitter, eq. (3.22): E_sun p(zeta_h) F(v.h) / (4 h_z^4 cos theta_v (1 + Lambda_v + Lambda_l)).
  double glitter = 0.0;
  const double cos_l = dot(n, l);
  if (cos_l > 0.0) {
    const Vector3 h = normalize({v[0] + l[0], v[1] + l[1], v[2] + l[2]});
    const double h_z = std::max(dot(n, h), 1e-4);
    // The facet slope that mirrors l into v, relative to n (its tangential part over h_z), in the
    // wind's frame: (along, across).
    const double zx = (h[0] - h_z * n[0]) / h_z, zy = (h[1] - h_z * n[1]) / h_z;
    const double cw = std::cos(f.wind_direction_rad), sw = std::sin(f.wind_direction_rad);
    const double p = facet_slope_density(f, zx * cw + zy * sw, -zx * sw + zy * cw, extra);
    glitter = p * fresnel_reflectance(dot(v, h)) /
              (4.0 * std::pow(h_z, 4) * cos_v * (1.0 + smith_lambda(cos_v, sigma2) + smith_lambda(cos_l, sigma2_light)));
  }
  // 3. Light from the water body and the seabed, eq. (3.25): the downwelling illuminance that
  //    crosses the surface, times the shallow-water reflectance along the refracted view, back
  //    out through the surface ((1 - F) / n^2, the radiance of a beam leaving a denser medium).
  const double mu_s = std::max(l[2], 0.0);
  const double n2 = kWaterRefractiveIndex * kWaterRefractiveIndex;
  const double cos_v_water = std::sqrt(std::max(1.0 - (1.0 - cos_v * cos_v) / n2, 0.0));
  const double path_factor = 1.0 / kDownwellingMeanCosine + 1.0 / std::max(cos_v_water, 0.1);
  const Radiance seabed = {f.seabed_albedo[0] * s.seabed_albedo_scale, f.seabed_albedo[1] * s.seabed_albedo_scale,
                           f.seabed_albedo[2] * s.seabed_albedo_scale};
  const Radiance reflectance = shallow_water_reflectance(f.water, seabed, s.water_depth_m, path_factor);
  // 3b. What the screen-space refraction found under the surface instead (a hull, a quay's toe,
  //     the drawn seabed): drawn in air, it is lit by E_air = E_sun mu_s + E_sky; under the water
  //     by the E_down that crossed the surface, attenuated on the way down and back up
  //     (submerged_transmittance), over the water body's own R_inf (1 - that). For the flat seabed
  //     (L = A E_air / pi) this is the reflectance above, term for term.
  const double scene = std::clamp(s.refracted_scene_coverage, 0.0, 1.0);
  const Radiance seen_object = submerged_transmittance(f, s.refracted_depth_m, s.refracted_path_m);
  // 4. Thin crests lit from behind, eq. (3.38): (n.l + v.l)^5 mu, v the viewing direction (from
  //    the eye); halved so the lobe peaks at 1 looking straight into the sun through the crest.
  const double lobe = std::pow(std::clamp(0.5 * (cos_l - dot(v, l)), 0.0, 1.0), 5.0);
  const double crest = f.translucency * std::clamp(s.crest_thinness, 0.0, 1.0) * lobe * kCrestTransmission;
  const double sun_in = 1.0 - fresnel_reflectance(mu_s);
  const double sun_normal = std::max(cos_l, 0.0);
  Radiance out{};
  for (std::size_t c = 0; c < 3; ++c) {
    const double e_sun = f.sky.sun_illuminance_klx[c], e_sky = f.sky_illuminance_klx[c];
    const double e_down = e_sun * mu_s * sun_in + e_sky * (1.0 - kDiffuseSkyReflectance);
    const double e_air = e_sun * mu_s + e_sky;
    const double object = e_air > 0.0 ? s.refracted_scene[c] * e_down / e_air : 0.0;
    const double refracted = e_down * f.water.deep_reflectance[c] * (1.0 - seen_object[c]) / kPi + object * seen_object[c];
    const double water_leaving =
        (1.0 - sky_fresnel) / n2 * ((1.0 - scene) * e_down * reflectance[c] / kPi + scene * refracted);
    const double through_crest = crest * e_sun * sun_in / kPi * std::exp(-f.water.diffuse_attenuation_per_m[c] * kCrestPathM);
    const double surface = sky_fresnel * sky[c] + e_sun * glitter + water_leaving + through_crest;
    // 5. Foam, seed 003 eq. (15): a Lambertian white over the water.
    const double foam_lit = f.foam_albedo[c] * (e_sun * sun_normal + e_sky * 0.5 * (1.0 + n[2])) / kPi;
    const double foam = std::clamp(s.foam, 0.0, 1.0);
    out[c] = (1.0 - foam) * surface + foam * foam_lit;
  }
  return out;
}

double cascade_share(bool over_harbour, double harbour_weight, double relative_wave_height) {
  const double k = std::clamp(relative_wave_height, 0.0, 1.0);
  return over_harbour ? (1.0 - harbour_weight) + harbour_weight * k : 1.0 - harbour_weight;
}

double cascade_variance_share(bool over_harbour, double harbour_weight, double relative_wave_height) {
  const double k = std::clamp(relative_wave_height, 0.0, 1.0);
  return over_harbour ? (1.0 - harbour_weight) + harbour_weight * k * k : 1.0 - harbour_weight;
}

double detail_normal_weight(double texel_m, double footprint_m) {
  return 1.0 - smoothstep(texel_m, 4.0 * texel_m, footprint_m);
}

double unresolved_relief_weight(double texel_m, double footprint_m) {
  return smoothstep(texel_m, 4.0 * texel_m, kMeshVertexSpacingPx * footprint_m);
}

std::array<double, 2> parallax_offset_m(const Vector3& to_eye, double relief_m) {
  // The eye ray through the drawn point B climbs to_eye.z per unit of its path; it crosses the
  // relief's height h at B + to_eye.xy / to_eye.z * h (seed 004 fig. 2: the point A seen, whose
  // texture coordinate D is B's shifted along the view).
  const double z = std::max(to_eye[2], kParallaxMinViewCosine);
  return {to_eye[0] / z * relief_m, to_eye[1] / z * relief_m};
}

Radiance to_display(const LightingFrame& f, const Radiance& radiance) {
  // The exposure acts on the luminance and keeps the chromaticity (a per-channel curve greyed the
  // blue sky); a colour too saturated for its luminance is desaturated towards the grey of the
  // same luminance until its brightest channel fits (shaders/common.glsl to_display).
  Radiance c;
  for (std::size_t i = 0; i < 3; ++i) c[i] = std::max(radiance[i], 0.0);
  const double y = luminance(c);
  if (!(y > 0.0)) return {0.0, 0.0, 0.0};
  const double y_display = 1.0 - std::exp(-f.exposure * y);
  Radiance exposed;
  for (std::size_t i = 0; i < 3; ++i) exposed[i] = c[i] * y_display / y;
  const double brightest = std::max({exposed[0], exposed[1], exposed[2]});
  if (brightest > 1.0)
    for (double& e : exposed) e = y_display + (e - y_display) * (1.0 - y_display) / (brightest - y_display);
  Radiance out;
  for (std::size_t i = 0; i < 3; ++i) out[i] = std::pow(std::clamp(exposed[i], 0.0, 1.0), 1.0 / 2.2);
  return out;
}

}  // namespace nearshore::playback
