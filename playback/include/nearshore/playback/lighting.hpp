#pragma once
// Lighting of the harbour: what a host sets (Lighting: the sun, or the place and UTC time it
// stands at; the atmosphere; what is in the water; the wind) and what every shader and its CPU
// twin compute from it (LightingFrame, prepared once a frame). The models, each a GL-free core
// with analytic tests (docs/lighting.md):
//   sun_position.hpp  NOAA/Meeus sun position from latitude, longitude and UTC
//   sky_model.hpp     Preetham clear sky with seed 001's zenith luminance and chromaticity; sunlight
//   ocean_brdf.hpp    Fresnel (n = 1.333), Bruneton (2010) BRDF with slope variance, seed 000 eq. 3.12-3.24
//   water_optics.hpp  water colour from inherent optical properties, seed 000 eq. 3.25-3.37
// and here the sea surface put together (seed 000 eq. 3.22-3.25, 3.38; seed 003 eq. 12-16).
// shaders/common.glsl computes the same per pixel; tests/playback compares pixel against twin.
//
// Units: radiance in kcd/m2 (luminance-weighted linear sRGB), illuminance in klx.
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "nearshore/playback/ocean_brdf.hpp"
#include "nearshore/playback/sky_model.hpp"
#include "nearshore/playback/sun_position.hpp"
#include "nearshore/playback/water_optics.hpp"

namespace nearshore::playback {

/// Everything a host controls about the light and the look of the water.
struct Lighting {
  double sun_azimuth_deg = 200.0;   ///< compass bearing of the sun (0 north, 90 east)
  double sun_elevation_deg = 35.0;  ///< apparent height above the horizon (negative: set)
  /// Preetham's atmospheric turbidity T (1.7 .. 10): 2 very clear, 3 clear, 6 hazy, 10 thin fog.
  double atmospheric_turbidity = 2.5;
  /// Cloud cover in [0, 1]: 1 is the CIE standard overcast sky with the sun hidden (sky_model.hpp).
  double cloud_cover = 0.0;
  /// Meteorological optical range (m): the distance at which a black object's contrast against
  /// the horizon falls to 5 % (WMO); fog below 1000 m, mist 1-5 km. 0: no fog or haze layer.
  double visibility_m = 0.0;
  /// Top of the fog or haze layer above the sea (m): a bridge inside it sees the sky dimmed by the
  /// layer above it only, an aircraft above it sees it from the top down.
  double fog_top_m = 150.0;
  WaterConstituents water;                          ///< chlorophyll, CDOM, turbidity of the water
  Radiance seabed_albedo = {0.55, 0.50, 0.38};      ///< C_object / I_g of eq. (3.25): sand
  Radiance foam_albedo = {0.85, 0.87, 0.88};        ///< C_foam, seed 003 eq. (15)
  double wind_speed_m_s = 5.0;      ///< at 10 m; the fallback slope variance and the shoreline waves
  double wind_direction_rad = 0.0;  ///< where the wind blows TOWARDS, counter-clockwise from east
  /// Mean square slope (both axes summed) of the waves the drawn surface cannot show: the
  /// spectrum's tail beyond the finest cascade (ocean::DeepWaterField::unresolved_slope_variance).
  /// Negative: Cox & Munk's for wind_speed_m_s.
  double sub_grid_slope_variance = -1.0;
  double foam_onset_m = 0.6;        ///< h0 of seed 003 eq. (16): crests below this carry no foam
  double foam_full_m = 1.6;         ///< h_max of eq. (16)
  double translucency = 1.0;        ///< mu scale of eq. (3.38): light through thin crests, 0 off
  /// J_b of seed 000 eq. (3.45): deep water foams where its Jacobian falls below this (the Stokes
  /// limit of a single wave, ocean::kStokesBreakingJacobian).
  double jacobian_foam_onset = 0.557;
  /// Seed 000 section 4.1's shoreline waves: amplitude (m) on a shore the wind blows straight
  /// onto at 10 m/s or more (less in lighter wind, none on a lee shore; 0 turns them off), and how
  /// far from the coastline (m) they reach.
  double shore_wave_amplitude_m = 0.25;
  double shore_band_m = 80.0;
  double exposure_compensation = 1.0;  ///< multiplies the automatic exposure (2: one stop brighter)
  /// Parallax of the detail normals (seed 004 section 1.3, eq. 5): 1 looks each cascade's normal
  /// map up where the eye ray meets the relief the grid does not draw; 0 turns it off.
  double detail_parallax = 1.0;
  /// The baked field's slopes filtered over each pixel's footprint (slope_moments.hpp): the mean
  /// slope from the moments' mip level of the footprint and the variance it holds added to the
  /// BRDF's (a far swell keeps its mean brightness instead of aliasing). false: one point sample
  /// of the finest level, no variance (what the renderer did before; for comparisons).
  bool filter_baked_slopes = true;
  /// Seed 000 eq. (3.46): the deep water's foam fades by 1/e over this time (s) after its crest
  /// stops breaking (whitecap foam lives a few seconds: Callaghan et al. 2012, 1-5 s).
  double foam_decay_time_s = 3.0;
  /// Foam where the baked sea runs up and down a structure's face (structure_foam): the speed of
  /// the water along the face (m/s) at which it starts to entrain air and turn white (about 1 m/s
  /// for a plunging or impinging flow: Ervine, McKeogh & Elsawy 1980; Chanson 1997). Infinite: none.
  double structure_foam_onset_m_s = 1.0;

  /// Unit vector towards the sun in the harbour frame (x east, y north, z up).
  Vector3 sun_direction() const;
  /// Puts the sun where it stands seen from (latitude, longitude) at `time` (sun_position.hpp).
  void set_sun_for(double latitude_deg, double longitude_deg, const UtcTime& time);
};

/// What the shaders receive, derived once a frame from a Lighting.
struct LightingFrame {
  SkyModel sky;                 ///< sun direction and illuminance, Perez coefficients, zenith values
  Radiance sky_illuminance_klx{};  ///< of the sky dome on a horizontal plane
  WaterOptics water;
  Radiance seabed_albedo{}, foam_albedo{};
  double slope_variance_per_axis = 0.0;  ///< sigma^2 of eq. (3.13): the mean of the two axes below
  /// The sub-grid slope variance along and across the wind (cox_munk_upwind_share of the total):
  /// the glitter's ellipse of facet slopes, long along the wind.
  double slope_variance_upwind = 0.0, slope_variance_crosswind = 0.0;
  double foam_onset_m = 0.6, foam_full_m = 1.6, translucency = 1.0, jacobian_foam_onset = 0.557;
  double wind_direction_rad = 0.0, shore_wave_amplitude_m = 0.0, shore_band_m = 80.0;
  double exposure = 1.0;        ///< 1 / (kcd/m2): displayed luminance = 1 - exp(-exposure Y)
  double detail_parallax = 1.0, foam_decay_time_s = 3.0;
  bool filter_baked_slopes = true;  ///< Lighting::filter_baked_slopes
  double structure_foam_onset_m_s = 1.0;
  /// Koschmieder (1924): beta = -ln(0.05) / visibility_m, 1/m (0: clear air); the layer's top, m.
  double fog_extinction_per_m = 0.0, fog_top_m = 150.0;
};
LightingFrame prepare_lighting(const Lighting& lighting);

/// Weather an instructor selects by name: the sky's cloud cover and turbidity and the fog layer.
struct WeatherPreset {
  std::string name;
  double cloud_cover = 0.0, atmospheric_turbidity = 2.5, visibility_m = 0.0, fog_top_m = 150.0;
  std::string description;
};
/// clear, hazy, overcast, mist, fog (in that order); the one road from a name to the settings.
const std::vector<WeatherPreset>& weather_presets();
/// Sets the preset's fields of `lighting` (the sun, the water and the wind stay); throws
/// nearshore::Error naming the weather and listing the presets for an unknown name.
void apply_weather(Lighting& lighting, std::string_view name);

// ---- The air between the eye and what it sees (shaders/common.glsl, the same names) ---------
/// exp(-beta s): s the part of the segment eye -> point inside the fog layer (z below fog_top_m;
/// the layer's extinction is uniform, the air above it clear).
double fog_transmittance(const LightingFrame& frame, const Vector3& eye_m, const Vector3& point_m);
/// The fog's own radiance seen along `direction`: the horizon sky in that azimuth (a layer lit by
/// the sky above it scatters the light it receives; its colour is the horizon's).
Radiance fog_radiance(const LightingFrame& frame, const Vector3& direction);
/// What reaches the eye from a surface of `radiance` at `point_m`: Koschmieder's
/// L = T L_0 + (1 - T) L_fog, T = fog_transmittance.
Radiance through_air(const LightingFrame& frame, const Radiance& radiance, const Vector3& eye_m, const Vector3& point_m);
/// The sky seen from `from_m` along the unit `direction` (z > 0): sky_radiance through the part
/// of the fog layer above `from_m` (its slant path (top - z) / direction.z). The water's mirror
/// image of the sky is the sky seen from the sea surface (z = 0).
Radiance sky_seen(const LightingFrame& frame, const Vector3& from_m, const Vector3& direction);

/// One point of the sea surface as the fragment shader sees it.
struct SurfacePoint {
  Vector3 normal = {0, 0, 1};    ///< unit, up
  Vector3 to_eye = {0, 0, 1};    ///< unit, towards the viewer
  double water_depth_m = 100.0;  ///< total depth d + eta under the point
  double foam = 0.0;             ///< foam coverage in [0, 1]
  double extra_slope_variance_per_axis = 0.0;  ///< what the drawn normals filtered out (detail fading)
  double crest_thinness = 0.0;   ///< [0, 1]: how thin the water is here (mu of eq. 3.38)
  /// Land or a structure seen in the mirror direction (the renderer's planar reflection): its
  /// radiance replaces the sky's in proportion to the coverage.
  Radiance local_reflection{};
  double local_reflection_coverage = 0.0;
  /// The seabed's texture where the refracted view meets it (seabed_texture at
  /// refracted_seabed_point): a factor on the seabed albedo.
  double seabed_albedo_scale = 1.0;
  /// What the renderer's screen-space refraction found under the surface (seed 003 eq. 14, seed 001
  /// eq. 30-32): the radiance the opaque scene (seabed, hull, quay toe) has there as drawn in air,
  /// lit by the sun and sky above the water, and where it is: `refracted_depth_m` below the surface
  /// point (vertically) and `refracted_path_m` from it along the refracted view. Where coverage is
  /// 0 (nothing drawn there: the open sea beyond the site) the flat seabed of the procedural model
  /// (seabed_albedo_scale at water_depth_m) is seen instead; in between, in proportion.
  Radiance refracted_scene{};
  double refracted_scene_coverage = 0.0;
  double refracted_depth_m = 0.0;
  double refracted_path_m = 0.0;
};

/// Value noise in [0, 1] on a unit lattice (shaders/common.glsl value_noise, the same hash).
double value_noise(double x, double y);
/// The seabed's texture at site point (x, y): 0.7 + 0.6 (0.65 n(p / 14 m) + 0.35 n(p / 5 m + 7.1)),
/// mean 1, patches 14 m and 5 m across (sand, darker mud or weed, cleaner sand).
double seabed_texture(double x_m, double y_m);
/// Where the view refracted at a surface point (x, y) with unit normal `normal` (Snell, n = 1.333;
/// `to_eye` unit, towards the eye) meets a flat seabed `depth_m` below (GLSL refract's formula).
std::array<double, 2> refracted_seabed_point(double x_m, double y_m, const Vector3& normal, const Vector3& to_eye, double depth_m);

/// Screen-space refraction's step (shaders/common.glsl, the same name): the point the view
/// refracted at `surface_m` (normal, to_eye unit; Snell with n = 1.333) reaches `depth_m` below the
/// surface: surface + r depth / max(-r_z, 0.1). The renderer marches it down (12 depths to twice
/// the depth of what the unrefracted view meets, then 4 halvings), projecting each probe and
/// comparing it with the depth the opaque scene has there: the first probe behind the scene is
/// where the refracted ray meets it. Its `refracted_path_m` is then depth / max(-r_z, 0.1).
Vector3 refraction_probe_m(const Vector3& surface_m, const Vector3& normal, const Vector3& to_eye, double depth_m);
/// The inverse of to_display where the exposure curve is one to one: the linear radiance whose
/// displayed colour is `displayed` (luminance exact; a colour to_display desaturated to fit keeps
/// its displayed hue). What the refraction reads back from the opaque scene's 8-bit colour.
Radiance from_display(const LightingFrame& frame, const Radiance& displayed);
/// How much of the light a submerged object (lit in air as `refracted_scene`) sends back through
/// `depth_m` of water below the surface and `path_m` of water along the view keeps, per band: the
/// downwelling light crosses the surface and `depth_m / 0.8` of water (the mean cosine of
/// downwelling light), the reflected light `path_m` back up: exp(-K (depth / 0.8 + path)), the
/// same attenuation as the flat seabed's e^-KmH of eq. (3.37).
Radiance submerged_transmittance(const LightingFrame& frame, double depth_m, double path_m);

/// Foam along structures (docs/lighting.md step 7): the sine of the face the sea runs up. A rubble
/// mound's armour slope is 1:1.5 (the bake's style table, bathymetry harbour_builder.cpp; CEM VI-2
/// gives 1:1.5 - 1:2): sin(atan(1 / 1.5)) = 0.555. A vertical wall (quay, mole, caisson): 1.
inline constexpr double kRubbleMoundFaceSine = 0.5547001962252291;
/// A structure face's porosity from which it is a vertical wall. The bake fits each face layer's
/// porosity to the structure's reflection coefficient: a vertical wall reflects 0.9-1.0 (Goda 2000),
/// so its layer stays nearly open water (0.966 on the demo's quay, 0.9 nominal in the style table),
/// a rock slope 0.3-0.6 (Zanuttigh & van der Meer 2008) and its layer is denser (0.711 and 0.845 on
/// the demo's arms and detached breakwater, 0.45 nominal); the core is 0 for both.
inline constexpr double kVerticalFacePorosity = 0.88;
/// How white the water is at a structure's face, 0..1: the water there rises or falls at
/// `rise_rate_m_s` (the baked d eta / dt), so it runs along a face of sine `face_sine` at
/// |rate| / sine (up a rubble slope and down through its armour: both churn it; up a vertical wall
/// only: the clapotis falls back smoothly, the rising water is what jets and splashes). Foam from
/// the air-entrainment onset speed (Lighting::structure_foam_onset_m_s) and solid white at twice
/// it, fading linearly to nothing `band_m` off the face (the pixel is `distance_m` from it).
double structure_foam(const LightingFrame& frame, double rise_rate_m_s, double face_sine, double distance_m, double band_m);

/// The slope variance (per axis) of the rough surface in the vertical plane of `direction` (its
/// horizontal part against the wind), plus `extra_slope_variance` (isotropic): what Smith's
/// shadowing and the mean Fresnel reflectance see along a view or a light.
double slope_variance_along(const LightingFrame& frame, const Vector3& direction, double extra_slope_variance);
/// The density of facet slopes (zeta_along, zeta_across the wind) of eq. (3.13) with the two axes'
/// variances: exp(-(a^2 / s_u + c^2 / s_c) / 2) / (2 pi sqrt(s_u s_c)), s_u = upwind + extra,
/// s_c = crosswind + extra.
double facet_slope_density(const LightingFrame& frame, double zeta_along_wind, double zeta_across_wind, double extra_slope_variance);

/// Sea surface radiance: sky (eq. 3.23-3.24) and sun (eq. 3.22) reflection, the water body and
/// seabed through it (eq. 3.25 with water_optics.hpp), thin-crest translucency (eq. 3.38), foam
/// (seed 003 eq. 15).
Radiance shade_water(const LightingFrame& frame, const SurfacePoint& point);
/// A Lambertian surface (land, structures, foam): albedo (E_sun max(n.s, 0) + E_sky (1 + n_z) / 2) / pi.
Radiance shade_lambertian(const LightingFrame& frame, const Vector3& normal, const Radiance& albedo);
// ---- Detail normals (docs/lighting.md step 10; shaders/common.glsl, the same names) ----------
/// The water grids put a vertex about every 4 pixels (QuadtreeSettings::screen_error_px,
/// ProjectedGridSettings::vertex_spacing_px).
inline constexpr double kMeshVertexSpacingPx = 4.0;
/// The eye rays of eq. (5) are followed no flatter than this cosine (about 7 degrees above the
/// water): flatter, a ray meets an earlier crest long before the mean plane's point (eq. 5 with a
/// vanishing view z would send the lookup to infinity).
inline constexpr double kParallaxMinViewCosine = 0.12;
/// How much of a cascade's normal map a pixel keeps: 1 while the pixel covers at most one texel
/// (`texel_m`), 0 from four on (its slopes then go into the BRDF's variance: no shimmer).
double detail_normal_weight(double texel_m, double footprint_m);
/// How much of a cascade's height the drawn grid does not carry: none while its vertices (every
/// kMeshVertexSpacingPx pixels) are at most a texel apart, all of it from four texels apart.
double unresolved_relief_weight(double texel_m, double footprint_m);
/// How much of a deep-water cascade's slopes (cascade_share) and slope variance
/// (cascade_variance_share) a point of harbour weight w (runtime::harbour_weight) shows. Beyond
/// the harbour all of it (1 - w of it in the blend). Over the harbour only the cascades finer than
/// the bake's grid resolves (`over_harbour`: tiles under 32 cells), the short waves of the
/// incident sea; they are sheltered as the baked sea is: their amplitude scales with the relative
/// wave height K = Hs / Hs_incident of the point (runtime::HarbourSite::relative_wave_height),
/// never above 1. Shorter waves diffract less far into a breakwater's shadow than the baked ones
/// (Penney & Price 1952: the diffracted field spreads over angles of order L / B), so the baked
/// K bounds theirs from above; waves of 0.5-14 m also need fetches of kilometres to grow (JONSWAP
/// fetch laws), which a basin of a few hundred metres does not give its own wind. The wind's
/// ripples below the last cascade (Lighting::sub_grid_slope_variance) are not sheltered: they
/// rise and fall with the local wind within metres (Cox & Munk 1954).
double cascade_share(bool over_harbour, double harbour_weight, double relative_wave_height);
double cascade_variance_share(bool over_harbour, double harbour_weight, double relative_wave_height);
/// Seed 004 eq. (5): where the eye ray through a point of the drawn surface meets a relief
/// `relief_m` above it, as a horizontal offset (m) of the normal-map lookup: to_eye.xy /
/// to_eye.z * relief (to_eye unit, towards the viewer; its z at least kParallaxMinViewCosine).
std::array<double, 2> parallax_offset_m(const Vector3& to_eye, double relief_m);

/// Exposure and display gamma, 0..1 (shaders/common.glsl to_display): the luminance Y maps to
/// 1 - exp(-exposure Y), the chromaticity is kept (desaturated towards grey only where a channel
/// would pass 1), then gamma 1/2.2.
Radiance to_display(const LightingFrame& frame, const Radiance& radiance);

}  // namespace nearshore::playback
