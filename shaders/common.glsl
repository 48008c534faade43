// Shared by every nearshore shader (prepended after #version): the lighting of docs/lighting.md.
// Each function is the twin of the C++ function of the same name in playback/src/ (sky_model.cpp,
// ocean_brdf.cpp, water_optics.cpp, lighting.cpp); tests/playback/lighting_render_test.cpp
// renders through them on Mesa and compares the pixels with the twins.
// Coordinates: x east, y north, z up, metres, in the harbour grid's frame. Radiance in kcd/m2
// (luminance-weighted linear sRGB), illuminance in klx.

const float kPi = 3.14159265358979;
const float kWaterIndex = 1.333;

// The sky (sky_model.hpp): Preetham's Perez coefficients and zenith values, the sun.
uniform vec3 u_sun_direction;      // unit vector towards the sun
uniform vec3 u_sun_illuminance;    // klx per band on a plane facing the sun (0 once it set)
uniform vec3 u_sky_illuminance;    // klx per band of the sky dome on a horizontal plane
uniform float u_perez_Y[5], u_perez_x[5], u_perez_y[5];
uniform vec3 u_zenith_Yxy;         // Y_zenith (kcd/m2, twilight-dimmed), x_zenith, y_zenith
uniform vec3 u_perez_zenith;       // F(0, theta_s) of Y, x, y
uniform float u_night_luminance;   // kcd/m2 floor
uniform float u_cloud_cover;       // c: the CIE overcast sky's share (sky_model.hpp)
uniform float u_overcast_zenith_luminance;  // its L_z, kcd/m2
// The air (lighting.hpp): Koschmieder's extinction in a fog layer up to u_fog_top_m, the viewer.
uniform float u_fog_extinction_per_m;  // 0: clear air
uniform float u_fog_top_m;
uniform vec3 u_eye_m;              // the viewer (site frame)
// The water (water_optics.hpp) and the surfaces.
uniform vec3 u_water_attenuation;  // K = a + b_b per band, 1/m
uniform vec3 u_deep_reflectance;   // R_inf per band
uniform vec3 u_seabed_albedo;      // I_g of eq. (3.25): sand
uniform vec3 u_foam_albedo;        // C_foam, seed 003 eq. (15)
uniform float u_slope_variance;    // sigma^2 per axis the drawn normals cannot show (the mean of:)
uniform float u_slope_variance_upwind, u_slope_variance_crosswind;  // ... along and across the wind
uniform vec2 u_wind_toward;        // unit vector the wind blows towards
uniform float u_translucency;      // mu scale of eq. (3.38)
uniform float u_exposure;          // displayed luminance = 1 - exp(-exposure Y)

// ---- sky: Preetham (1999), seed 001 eq. (3)-(12) -------------------------------------------
float perez(float c[5], float cos_theta, float gamma) {
  float cos_gamma = cos(gamma);
  return (1.0 + c[0] * exp(c[1] / cos_theta)) * (1.0 + c[2] * exp(c[3] * gamma) + c[4] * cos_gamma * cos_gamma);
}

vec3 xyY_to_linear_srgb(float x, float y, float Y) {
  y = max(y, 1e-4);
  float X = x * Y / y, Z = (1.0 - x - y) * Y / y;
  return max(vec3(3.240479 * X - 1.537150 * Y - 0.498535 * Z, -0.969256 * X + 1.875991 * Y + 0.041556 * Z,
                  0.055648 * X - 0.204043 * Y + 1.057311 * Z), vec3(0.0));
}

vec3 sky_radiance(vec3 direction) {
  float cos_theta = max(direction.z, 0.01);
  float gamma = acos(clamp(dot(direction, u_sun_direction), -1.0, 1.0));
  float Y = max(u_zenith_Yxy.x * perez(u_perez_Y, cos_theta, gamma) / u_perez_zenith.x, u_night_luminance);
  float x = u_zenith_Yxy.y * perez(u_perez_x, cos_theta, gamma) / u_perez_zenith.y;
  float y = u_zenith_Yxy.z * perez(u_perez_y, cos_theta, gamma) / u_perez_zenith.z;
  vec3 clear = xyY_to_linear_srgb(x, y, Y);
  if (u_cloud_cover <= 0.0) return clear;
  // CIE standard overcast sky L_z (1 + 2 cos theta) / 3, grey (sky_model.cpp)
  float overcast = max(u_overcast_zenith_luminance * (1.0 + 2.0 * max(direction.z, 0.0)) / 3.0, u_night_luminance);
  return mix(clear, vec3(overcast), u_cloud_cover);
}

// ---- the air: Koschmieder (1924) in a fog layer (lighting.cpp, the same names) --------------
float fog_transmittance(vec3 eye, vec3 point) {
  if (u_fog_extinction_per_m <= 0.0) return 1.0;
  float low = min(eye.z, point.z), high = max(eye.z, point.z);
  float inside = low >= u_fog_top_m ? 0.0 : high > u_fog_top_m ? (u_fog_top_m - low) / (high - low) : 1.0;
  return exp(-u_fog_extinction_per_m * length(point - eye) * inside);
}
vec3 fog_radiance(vec3 direction) {
  vec2 horizontal = direction.xy;
  return sky_radiance(dot(horizontal, horizontal) > 1e-18 ? vec3(normalize(horizontal), 0.0) : vec3(1.0, 0.0, 0.0));
}
vec3 through_air(vec3 radiance, vec3 eye, vec3 point) {
  float t = fog_transmittance(eye, point);
  if (t >= 1.0) return radiance;
  return mix(fog_radiance(point - eye), radiance, t);
}
vec3 sky_seen(vec3 from_m, vec3 direction) {
  vec3 sky = sky_radiance(direction);
  if (u_fog_extinction_per_m <= 0.0) return sky;
  float t = exp(-u_fog_extinction_per_m * max(u_fog_top_m - from_m.z, 0.0) / max(direction.z, 0.01));
  return mix(fog_radiance(direction), sky, t);
}

// ---- Fresnel and the Bruneton (2010) BRDF, seed 000 eq. (3.13)-(3.24) -----------------------
float fresnel_reflectance(float cos_incidence) {
  const float r = 0.020373;  // ((n - 1) / (n + 1))^2, n = 1.333
  return r + (1.0 - r) * pow(1.0 - clamp(cos_incidence, 0.0, 1.0), 5.0);
}

float erfc_approximation(float x) { return 2.0 * exp(-x * x) / (2.319 * x + sqrt(4.0 + 1.52 * x * x)); }

float smith_lambda(float cos_theta, float slope_variance) {
  float c = clamp(cos_theta, 1e-4, 1.0);
  float a = c / sqrt(2.0 * slope_variance * max(1.0 - c * c, 1e-12));
  return max(0.0, (exp(-a * a) - a * sqrt(kPi) * erfc_approximation(a)) / (2.0 * a * sqrt(kPi)));
}

float mean_fresnel_reflectance(float cos_view, float slope_variance) {
  const float r = 0.020373;
  float sigma = sqrt(slope_variance);
  return r + (1.0 - r) * pow(1.0 - clamp(cos_view, 0.0, 1.0), 5.0 * exp(-2.69 * sigma)) / (1.0 + 22.7 * pow(sigma, 1.5));
}

// ---- textures: value noise and the seabed (lighting.cpp, the same names) ------------------------
// A smooth value noise in [0, 1] on a unit lattice (an integer hash per lattice point, smoothstep
// between them): the "foam map" of seed 000 eq. (3.48) and section 4.1, which the paper lays over
// the foam "to lower its continuity", made procedurally (no texture asset to ship or to tile), and
// the seabed's patches.
float lattice_hash(vec2 cell) {
  uvec2 q = uvec2(ivec2(cell)) * uvec2(1597334677u, 3812015801u);
  uint n = (q.x ^ q.y) * 1597334677u;
  return float(n >> 8) * (1.0 / 16777215.0);
}
float value_noise(vec2 x) {
  vec2 i = floor(x), f = fract(x), u = f * f * (3.0 - 2.0 * f);
  return mix(mix(lattice_hash(i), lattice_hash(i + vec2(1.0, 0.0)), u.x),
             mix(lattice_hash(i + vec2(0.0, 1.0)), lattice_hash(i + vec2(1.0, 1.0)), u.x), u.y);
}
// The seabed's texture, a factor of mean 1 on its albedo: patches 14 m and 5 m across between 0.7
// and 1.3 (sand with darker mud or weed and cleaner, lighter sand).
float seabed_texture(vec2 p) { return 0.7 + 0.6 * (0.65 * value_noise(p / 14.0) + 0.35 * value_noise(p / 5.0 + 7.1)); }
// Where the view from the eye, refracted into the water at a surface point with normal n (Snell,
// n = 1.333: seed 003 eq. 14), meets a flat seabed depth_m below: the seabed seen through the waves.
vec2 refracted_seabed_point(vec2 p, vec3 n, vec3 to_eye, float depth_m) {
  vec3 r = refract(-to_eye, n, 1.0 / kWaterIndex);
  return p + r.xy * (max(depth_m, 0.0) / max(-r.z, 0.1));
}
// Screen-space refraction's step (lighting.cpp refraction_probe_m): where the refracted view from
// the surface point reaches depth_m below it.
vec3 refraction_probe_m(vec3 surface_m, vec3 n, vec3 to_eye, float depth_m) {
  vec3 r = refract(-to_eye, n, 1.0 / kWaterIndex);
  return surface_m + r * (max(depth_m, 0.0) / max(-r.z, 0.1));
}

// Foam where the sea runs along a structure's face (lighting.cpp structure_foam, the same name).
uniform float u_structure_foam_onset_m_s;  // Lighting::structure_foam_onset_m_s
const float kRubbleMoundFaceSine = 0.5547002;  // a 1:1.5 armour slope
const float kVerticalFacePorosity = 0.88;
float structure_foam(float rise_rate_m_s, float face_sine, float distance_m, float band_m) {
  float onset = u_structure_foam_onset_m_s;
  if (!(onset > 0.0) || !(band_m > 0.0) || !(face_sine > 0.0)) return 0.0;
  float along_face = (face_sine >= 1.0 ? max(rise_rate_m_s, 0.0) : abs(rise_rate_m_s)) / face_sine;
  return clamp((along_face - onset) / onset, 0.0, 1.0) * clamp(1.0 - distance_m / band_m, 0.0, 1.0);
}

// ---- surfaces -----------------------------------------------------------------------------
vec3 shade_lambertian(vec3 normal, vec3 albedo) {
  return albedo * (u_sun_illuminance * max(dot(normal, u_sun_direction), 0.0) + u_sky_illuminance * 0.5 * (1.0 + normal.z)) / kPi;
}

// The sea surface (lighting.cpp shade_water, step for step).
//   normal, to_eye: unit; water_depth_m: d + eta under the point; foam in [0, 1];
//   extra_slope_variance: what the drawn normals filtered out here; crest_thinness: mu of eq. (3.38).
//   local_reflection: radiance of land or structures seen in the mirror direction, alpha = covered.
float slope_variance_along(vec3 direction, float extra) {
  float horizontal = length(direction.xy);
  float along = u_slope_variance;
  if (horizontal > 1e-9) {
    float cos_phi = dot(direction.xy, u_wind_toward) / horizontal;
    along = u_slope_variance_upwind * cos_phi * cos_phi + u_slope_variance_crosswind * (1.0 - cos_phi * cos_phi);
  }
  return along + max(extra, 0.0);
}
float facet_slope_density(float a, float c, float extra) {
  float s_u = u_slope_variance_upwind + max(extra, 0.0), s_c = u_slope_variance_crosswind + max(extra, 0.0);
  return exp(-0.5 * (a * a / s_u + c * c / s_c)) / (2.0 * kPi * sqrt(s_u * s_c));
}

// What a submerged object keeps of its light (lighting.cpp submerged_transmittance): down depth / 0.8
// and back up the path through the water, per band.
vec3 submerged_transmittance(float depth_m, float path_m) {
  return exp(-u_water_attenuation * (max(depth_m, 0.0) / 0.8 + max(path_m, 0.0)));
}
//   refracted_scene: the opaque scene under the surface (radiance drawn in air, alpha = coverage),
//   refracted_depth_path: its vertical depth below the surface point and its path along the view.
vec3 shade_water(vec3 n, vec3 v, float water_depth_m, float foam, float extra_slope_variance, float crest_thinness,
                 vec4 local_reflection, float seabed_scale, vec4 refracted_scene, vec2 refracted_depth_path) {
  vec3 l = u_sun_direction;
  float cos_v = max(dot(n, v), 1e-3);
  float extra = max(extra_slope_variance, 0.0);
  float sigma2 = slope_variance_along(v, extra), sigma2_light = slope_variance_along(l, extra);
  // 1. sky reflected, eq. (3.23)-(3.24)
  vec3 mirror = reflect(-v, n);
  mirror.z = abs(mirror.z);
  float sky_fresnel = mean_fresnel_reflectance(cos_v, sigma2);
  vec3 sky = mix(sky_seen(vec3(0.0), mirror), local_reflection.rgb, clamp(local_reflection.a, 0.0, 1.0));
  // 2. sun glitter, eq. (3.22)
  float glitter = 0.0;
  float cos_l = dot(n, l);
  if (cos_l > 0.0) {
    vec3 h = normalize(v + l);
    float h_z = max(dot(n, h), 1e-4);
    vec2 zeta = (h.xy - h_z * n.xy) / h_z;  // the mirroring facet's slope relative to n
    float p = facet_slope_density(dot(zeta, u_wind_toward), dot(zeta, vec2(-u_wind_toward.y, u_wind_toward.x)), extra);
    glitter = p * fresnel_reflectance(dot(v, h)) /
              (4.0 * pow(h_z, 4.0) * cos_v * (1.0 + smith_lambda(cos_v, sigma2) + smith_lambda(cos_l, sigma2_light)));
  }
  // 3. water body and seabed, eq. (3.25) with the shallow-water reflectance (water_optics.hpp)
  float mu_s = max(l.z, 0.0);
  float n2 = kWaterIndex * kWaterIndex;
  float cos_v_water = sqrt(max(1.0 - (1.0 - cos_v * cos_v) / n2, 0.0));
  float path_factor = 1.0 / 0.8 + 1.0 / max(cos_v_water, 0.1);
  vec3 seen = exp(-u_water_attenuation * path_factor * max(water_depth_m, 0.0));
  vec3 reflectance = u_deep_reflectance * (1.0 - seen) + seabed_scale * u_seabed_albedo * seen;
  // 4. thin crests lit from behind, eq. (3.38)
  float lobe = pow(clamp(0.5 * (cos_l - dot(v, l)), 0.0, 1.0), 5.0);
  float crest = u_translucency * clamp(crest_thinness, 0.0, 1.0) * lobe * 0.15;
  float sun_in = 1.0 - fresnel_reflectance(mu_s);
  vec3 e_down = u_sun_illuminance * mu_s * sun_in + u_sky_illuminance * (1.0 - 0.066);
  // 3b. the opaque scene the refraction found (lit in air by E_air, under water by e_down)
  vec3 seen_object = submerged_transmittance(refracted_depth_path.x, refracted_depth_path.y);
  vec3 e_air = u_sun_illuminance * mu_s + u_sky_illuminance;
  vec3 object = refracted_scene.rgb * e_down / max(e_air, vec3(1e-12));
  vec3 refracted = e_down * u_deep_reflectance * (1.0 - seen_object) / kPi + object * seen_object;
  float scene = clamp(refracted_scene.a, 0.0, 1.0);
  vec3 water_leaving = (1.0 - sky_fresnel) / n2 * ((1.0 - scene) * e_down * reflectance / kPi + scene * refracted);
  vec3 through_crest = crest * u_sun_illuminance * sun_in / kPi * exp(-u_water_attenuation * 4.0);
  vec3 surface = sky_fresnel * sky + u_sun_illuminance * glitter + water_leaving + through_crest;
  // 5. foam, seed 003 eq. (15)
  vec3 foam_lit = u_foam_albedo * (u_sun_illuminance * max(cos_l, 0.0) + u_sky_illuminance * 0.5 * (1.0 + n.z)) / kPi;
  return mix(surface, foam_lit, clamp(foam, 0.0, 1.0));
}

// ---- detail normals (lighting.hpp, the same names) -----------------------------------------
const float kMeshVertexSpacingPx = 4.0;      // the grids' vertex spacing on screen (surface_grids.hpp)
const float kParallaxMinViewCosine = 0.12;   // eye rays of eq. (5) no flatter than ~7 degrees

// How much of a cascade's normal map a pixel of footprint_m keeps: all while it covers one texel,
// none from four on (its slopes move into the BRDF's variance instead: Bruneton 2010 section 4).
float detail_normal_weight(float texel_m, float footprint_m) { return 1.0 - smoothstep(texel_m, 4.0 * texel_m, footprint_m); }
// How much of a cascade's height the grid (a vertex every kMeshVertexSpacingPx pixels) cannot draw.
float unresolved_relief_weight(float texel_m, float footprint_m) {
  return smoothstep(texel_m, 4.0 * texel_m, kMeshVertexSpacingPx * footprint_m);
}
// Seed 004 section 1.3, eq. (5): the eye ray through the drawn point meets a relief relief_m above
// it at to_eye.xy / to_eye.z * relief_m further towards the eye; the normal map is read there.
vec2 parallax_offset_m(vec3 to_eye, float relief_m) { return to_eye.xy / max(to_eye.z, kParallaxMinViewCosine) * relief_m; }

// ---- the baked field's slopes at distance (slope_moments.hpp, the same names) --------------
// The keyframes' slope moments (g_x, g_y, g_x^2, g_y^2: rise per cell and its square) are a mip
// pyramid; a pixel reads the level of its footprint (LEADR, Dupuy et al. 2013): the mean slope
// there, and Var = E[g^2] - E[g]^2 for the BRDF's roughness.
float baked_slope_lod(float footprint_m, float cell_m) {
  return footprint_m > cell_m && cell_m > 0.0 ? log2(footprint_m / cell_m) : 0.0;
}
// xy: the mean slope; z: the slope variance per axis, 0.5 (Var s_x + Var s_y), each keyframe's own
// interpolated in time.
vec3 filtered_baked_slope(vec4 from, vec4 to, float fraction, vec2 spacing_m) {
  vec2 mean = mix(from.xy, to.xy, fraction) / spacing_m;
  vec2 variance = mix(from.zw - from.xy * from.xy, to.zw - to.xy * to.xy, fraction) / (spacing_m * spacing_m);
  return vec3(mean, max(0.5 * (variance.x + variance.y), 0.0));
}

// Exposure and display gamma (the default framebuffer is not sRGB). The exposure curve
// 1 - exp(-k Y) acts on the luminance Y alone and the colour keeps its chromaticity: applied per
// channel it squeezed the brightest channel most and turned a bright blue sky grey-violet. A
// colour whose brightest channel would pass 1 is moved towards the grey of the same luminance
// just far enough to fit (Y stays, so the picture's brightness is unchanged; Y_display < 1, so
// that grey always fits).
const vec3 kLuminanceWeights = vec3(0.2126, 0.7152, 0.0722);  // linear sRGB (ITU-R BT.709)
vec3 to_display(vec3 radiance) {
  vec3 c = max(radiance, vec3(0.0));
  float Y = dot(c, kLuminanceWeights);
  if (!(Y > 0.0)) return vec3(0.0);
  float Y_display = 1.0 - exp(-u_exposure * Y);
  vec3 exposed = c * (Y_display / Y);
  float brightest = max(exposed.r, max(exposed.g, exposed.b));
  if (brightest > 1.0) exposed = vec3(Y_display) + (exposed - vec3(Y_display)) * ((1.0 - Y_display) / (brightest - Y_display));
  return pow(clamp(exposed, 0.0, 1.0), vec3(1.0 / 2.2));
}
// The inverse of to_display (lighting.cpp from_display): the opaque scene's displayed colour back
// to radiance for the refraction (luminance exact; a colour desaturated to fit keeps that hue).
vec3 from_display(vec3 displayed) {
  vec3 exposed = pow(clamp(displayed, 0.0, 1.0), vec3(2.2));
  float Y_display = min(dot(exposed, kLuminanceWeights), 0.999);
  if (!(Y_display > 0.0)) return vec3(0.0);
  return exposed * (-log(1.0 - Y_display) / u_exposure / Y_display);
}
