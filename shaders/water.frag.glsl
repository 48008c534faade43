// The sea surface, lit as docs/lighting.md describes (common.glsl shade_water), or coloured flat /
// by level of detail for tests and pictures of the grids.
uniform int u_colouring;                // 0 lit, 1 flat u_flat_colour, 2 level of detail, 3 wire (darker LOD colour)
uniform vec3 u_flat_colour;
uniform float u_foam_onset_m;           // h0 of seed 003 eq. (16)
uniform float u_foam_full_m;            // h_max of eq. (16)
uniform float u_cascade_slope_variance[8];  // sigma^2 per axis each cascade's slopes carry
uniform float u_jacobian_foam_onset;    // J_b: foam where the deep water's Jacobian falls below it
uniform float u_time_s;                 // display time, for the shoreline waves
// u_wind_toward: common.glsl
uniform float u_shore_amplitude_m;      // the shoreline waves' amplitude on a windward shore (0: none)
uniform float u_shore_band_m;           // how far from the coastline they reach
uniform sampler2D u_coast_distance;     // signed distance to the coastline (m), negative on land
uniform bool u_has_reflection;          // the terrain mirrored in still water was drawn
uniform sampler2D u_reflection;         // ... as linear radiance, alpha = covered
uniform vec2 u_viewport_px;
uniform vec2 u_viewport_origin_px;      // the viewport's lower-left corner (a host's: nearshore::osg)
uniform bool u_has_decal_foam;          // playback::SurfaceLayers foam decals were drawn into ...
uniform sampler2D u_decal_foam;         // ... this foam map (R8, cover 0..1) over ...
uniform vec4 u_decal_foam_rect_m;       // ... x0, y0, width, height of the site frame
uniform float u_detail_parallax;        // seed 004 eq. (5) on (1) or off (0): Lighting::detail_parallax
uniform bool u_filter_baked_slopes;     // Lighting::filter_baked_slopes
uniform sampler2D u_harbour_slope_moments_from, u_harbour_slope_moments_to;  // slope_moments.hpp, mip-mapped
uniform bool u_has_deep_foam;           // the persistent foam f_t of seed 000 eq. (3.46) (foam_decay.frag.glsl) ...
uniform sampler2D u_deep_foam;          // ... over the largest cascade's tile, repeating
uniform bool u_has_scene;               // the opaque scene (sky, seabed, land, structures, hulls) ...
uniform sampler2D u_scene_colour;       // ... as displayed (to_display of through_air), and ...
uniform sampler2D u_scene_depth;        // ... its window depth, copied before the sea is drawn
uniform mat4 u_view_projection;         // water_vertex.glsl's, and its inverse:
uniform mat4 u_inverse_view_projection;
uniform bool u_has_relative_wave_height;     // runtime::HarbourSite::relative_wave_height (K) ...
uniform sampler2D u_relative_wave_height;    // ... over the site, cell centres at texel centres
in vec2 v_site_m;
in vec3 v_position_m;
in float v_lod;
in float v_eta_m;
in float v_weight;
out vec4 fragment_colour;

vec3 lod_colour(float lod) {
  const vec3 palette[6] = vec3[6](vec3(0.90, 0.25, 0.20), vec3(0.95, 0.75, 0.20), vec3(0.30, 0.80, 0.30),
                                  vec3(0.20, 0.70, 0.90), vec3(0.45, 0.35, 0.90), vec3(0.90, 0.40, 0.80));
  int level = int(floor(lod));
  return mix(palette[level % 6], palette[(level + 1) % 6], fract(lod));
}

// value_noise (the foam map of seed 000 eq. 3.48): common.glsl
// Foam's texture at p (m): two octaves of noise 6 m and 2.5 m across, sharpened into patches and
// streaks; where one pixel spans the texture's detail it fades to its mean (0.5) so it never shimmers.
float foam_texture(vec2 p, float footprint_m) {
  float n = 0.65 * value_noise(p / 6.0) + 0.35 * value_noise(p / 2.5 + 17.3);
  float patches = smoothstep(0.30, 0.70, n);
  return mix(patches, 0.5, smoothstep(0.6, 2.5, footprint_m));
}

// Seed 000 section 4.1: a pair of Gerstner-like waves running up the coast-distance gradient on
// shores the wind blows onto (eq. 4.1, 4.3: phase from the distance to the coast; amplitude
// falling off with that distance, eq. 4.4), and the breaking and turbulent foam bands of their
// phase (eq. 4.5, 4.6). They shade (normal and foam) but do not move the surface: the CPU queries
// a ship's physics reads must see the same water the bake made. Along the shore the crests are
// not one line: eq. (4.3)'s phase carries a term beside the distance (the wind's, cos theta_w (1 -
// s_p)), here a slowly varying phase (noise 45 m across, up to +-1.2 wavelengths) so each crest
// breaks in segments that lead and lag, sets of larger and smaller waves along the beach (noise
// 70 m across), and the foam map over the bands (eq. 3.48).
void shoreline_waves(vec2 p, float still_depth_m, float footprint_m, inout vec2 slope, inout float foam) {
  if (u_shore_amplitude_m <= 0.0 || !u_has_site || any(lessThan(p, vec2(0.0))) || any(greaterThan(p, u_site_size_m))) return;
  vec2 uv = clamp(p / u_site_size_m, vec2(0.0), vec2(1.0));
  float distance_m = texture(u_coast_distance, uv).r;
  if (distance_m <= 0.0 || distance_m >= u_shore_band_m) return;
  vec2 texel = 1.0 / vec2(u_cells);
  vec2 seaward = vec2(texture(u_coast_distance, uv + vec2(texel.x, 0.0)).r - texture(u_coast_distance, uv - vec2(texel.x, 0.0)).r,
                      texture(u_coast_distance, uv + vec2(0.0, texel.y)).r - texture(u_coast_distance, uv - vec2(0.0, texel.y)).r);
  if (dot(seaward, seaward) < 1e-8) return;
  seaward = normalize(seaward);
  float windward = clamp(dot(u_wind_toward, -seaward), 0.0, 1.0);  // wind onto the shore
  float alpha_s = distance_m / u_shore_band_m;                       // eq. 4.3's normalised distance
  // How strong the surf is here: windward, in enough wind (the amplitude reaches 0.15 m at about
  // force 4), fading out towards the band's outer edge and onto the dry beach, in sets along the shore.
  float sets = mix(0.45, 1.0, value_noise(p / 70.0 + 3.1));
  float surf = windward * sets * clamp(u_shore_amplitude_m / 0.15, 0.0, 1.0) * sqrt(1.0 - alpha_s) * smoothstep(0.0, 0.4, still_depth_m);
  float amplitude = u_shore_amplitude_m * surf;
  float texture_here = foam_texture(p, footprint_m);
  const float lengths_m[2] = float[2](14.0, 9.0);
  for (int i = 0; i < 2; ++i) {
    float k = 2.0 * kPi / lengths_m[i];
    float omega = sqrt(9.81 * k);
    float along = 2.0 * kPi * 1.2 * (2.0 * value_noise(p / 45.0 + 11.0 * float(i)) - 1.0);
    float phase = k * distance_m + omega * u_time_s + 1.7 * float(i) + along;  // crests run shorewards
    slope += amplitude * k * cos(phase) * seaward / float(i + 1);
    float f = fract(phase / (2.0 * kPi));
    float breaking = clamp(20.0 * f, 0.0, 1.0) - clamp(17.0 * f, 0.0, 1.0);  // eq. (4.6)
    float turbulent = clamp(20.0 * f, 0.0, 1.0) - clamp(2.0 * f, 0.0, 1.0);  // eq. (4.5)
    // the breaking band half solid, half torn by the foam map; the turbulent band behind it torn
    foam = max(foam, surf * (breaking * mix(texture_here, 1.0, 0.5) + 0.5 * turbulent * texture_here));
  }
}

// d eta / dt of the harbour at p (m/s): the time derivative of harbour_in_time (surface.glsl), the
// Hermite's basis derivatives over the frame interval, else the keyframes' difference over it.
float harbour_rate_in_time(vec2 p) {
  float T = u_frame_interval_s;
  if (T <= 0.0) return 0.0;
  float from = harbour_bilinear(u_harbour_eta_from, p), to = harbour_bilinear(u_harbour_eta_to, p);
  if (!u_harbour_hermite) return (to - from) / T;
  float f = u_harbour_fraction, f2 = f * f;
  return ((6.0 * f2 - 6.0 * f) * from + (-6.0 * f2 + 6.0 * f) * to) / T +
         (3.0 * f2 - 4.0 * f + 1.0) * harbour_bilinear(u_harbour_eta_rate_from, p) +
         (3.0 * f2 - 2.0 * f) * harbour_bilinear(u_harbour_eta_rate_to, p);
}

// Foam at the face of a breakwater or quay (docs/lighting.md step 7): the nearest structure cell
// (porosity < 0.99) among this cell and its eight neighbours, its kind from its porosity (a
// vertical wall's face layer is mostly open water, a rock face about half), and the baked rise
// rate here. White within one cell of the face, fading off it.
float structure_face_foam(vec2 p) {
  if (!u_has_site || !u_has_keyframes) return 0.0;
  ivec2 cell = ivec2(floor(p / u_spacing_m));
  float nearest_m = 1e9, face_porosity = 1.0;
  for (int dj = -1; dj <= 1; ++dj)
    for (int di = -1; di <= 1; ++di) {
      ivec2 c = cell + ivec2(di, dj);
      if (any(lessThan(c, ivec2(0))) || any(greaterThanEqual(c, u_cells))) continue;
      float n = texelFetch(u_porosity, c, 0).r;
      if (n >= 0.99) continue;
      vec2 low = vec2(c) * u_spacing_m, high = low + u_spacing_m;
      float d = length(max(max(low - p, p - high), vec2(0.0)));
      if (d < nearest_m) { nearest_m = d; face_porosity = n; }
    }
  float band_m = max(u_spacing_m.x, u_spacing_m.y);
  if (nearest_m >= band_m) return 0.0;
  float face_sine = face_porosity >= kVerticalFacePorosity ? 1.0 : kRubbleMoundFaceSine;
  return structure_foam(harbour_rate_in_time(p), face_sine, nearest_m, band_m);
}

// How much of cascade c a point of harbour weight w gets (cascade_share, cascade_variance_share:
// lighting.hpp): all of it beyond the harbour; over the harbour only the finest cascades (tiles
// under 32 harbour cells), which stand for the short waves a bake's grid is too coarse to carry,
// sheltered as the baked sea is there (the relative wave height K of the site).
float relative_wave_height_at(vec2 p) {
  if (!u_has_relative_wave_height || !u_has_site) return 1.0;
  return texture(u_relative_wave_height, clamp(p / u_site_size_m, vec2(0.0), vec2(1.0))).r;
}
bool over_harbour(int c) { return u_has_site && u_tile_length_m[c] < 32.0 * max(u_spacing_m.x, u_spacing_m.y); }
float cascade_share(int c, float w, float k) { return over_harbour(c) ? (1.0 - w) + w * clamp(k, 0.0, 1.0) : 1.0 - w; }
float cascade_variance_share(int c, float w, float k) {
  float kc = clamp(k, 0.0, 1.0);
  return over_harbour(c) ? (1.0 - w) + w * kc * kc : 1.0 - w;
}

// Screen-space refraction (seed 003 eq. 14, seed 001 eq. 30-32, seed 000 section 3.3.2): what the
// opaque scene drawn before the sea shows under this surface point, looked up where the view
// refracted at the surface (Snell, the pixel's normal) meets it. The drawn frame (with the Earth's
// curvature drop) throughout: the depth buffer's points and the water's are in the same one.
vec3 drawn_point(vec2 uv, float window_depth) {
  vec4 h = u_inverse_view_projection * vec4(2.0 * vec3(uv, window_depth) - 1.0, 1.0);
  return h.xyz / h.w;
}
vec3 window_point(vec3 point_m) {  // uv and window depth
  vec4 clip = u_view_projection * vec4(point_m, 1.0);
  return clip.xyz / max(clip.w, 1e-6) * 0.5 + 0.5;
}
bool on_screen(vec3 w) { return all(greaterThanEqual(w.xy, vec2(0.0))) && all(lessThanEqual(w.xy, vec2(1.0))); }
// Returns the scene's radiance as drawn in air (rgb; alpha 1 where found, 0 where nothing is
// drawn under the surface here: the procedural seabed stands in) and in depth_path its depth below
// the surface point and the path to it along the refracted view.
vec4 refracted_scene(vec3 normal, vec3 to_eye, float water_depth_m, out vec2 depth_path) {
  depth_path = vec2(0.0);
  if (!u_has_scene) return vec4(0.0);
  vec2 uv0 = gl_FragCoord.xy / u_viewport_px;
  vec3 here = drawn_point(uv0, gl_FragCoord.z);  // this pixel's surface point, as the depth buffer has it
  float depth0 = texture(u_scene_depth, uv0).r;
  if (depth0 >= 1.0) return vec4(0.0);  // nothing behind the sea here but the sky
  vec3 behind = drawn_point(uv0, depth0);  // what the unrefracted view meets
  float below_m = here.z - behind.z;
  if (below_m <= 0.0) return vec4(0.0);  // above this point (a crest before a quay's face): nothing submerged
  // March the refracted ray down (refraction_probe_m at 12 depths) until it passes behind what the
  // scene shows there, then halve the last step 4 times. As deep as the seabed under this point
  // and a quarter more (a slope falling away), or twice what the unrefracted view meets.
  const int kSteps = 12;
  float reach_m = max(2.0 * below_m, 1.25 * water_depth_m + 1.0), before_m = 0.0, after_m = -1.0;
  for (int k = 1; k <= kSteps; ++k) {
    float h = reach_m * float(k) / float(kSteps);
    vec3 w = window_point(refraction_probe_m(here, normal, to_eye, h));
    if (!on_screen(w)) break;
    float d = texture(u_scene_depth, w.xy).r;
    if (d < 1.0 && w.z >= d) { after_m = h; break; }
    before_m = h;
  }
  // The ray left the picture, or went deeper than the seabed without meeting what is drawn: the
  // procedural seabed stands in (the same sand at the same refracted point, for a flat bottom).
  if (after_m <= 0.0) return vec4(0.0);
  vec2 uv = uv0;
  vec3 found = behind;
  {
    for (int k = 0; k < 4; ++k) {
      float h = 0.5 * (before_m + after_m);
      vec3 w = window_point(refraction_probe_m(here, normal, to_eye, h));
      float d = texture(u_scene_depth, w.xy).r;
      if (d < 1.0 && w.z >= d) after_m = h; else before_m = h;
    }
    vec3 w = window_point(refraction_probe_m(here, normal, to_eye, after_m));
    float d = texture(u_scene_depth, w.xy).r;
    vec3 q = drawn_point(w.xy, d);
    // The usual fix: a refracted sample that lands on what stands in front of the water (nearer
    // than this surface point, or not under it: a hull or a quay above the surface) is not what
    // the water shows; the unrefracted sample stands in.
    if (d > gl_FragCoord.z && d < 1.0 && q.z < here.z) {
      uv = w.xy;
      found = q;
    }
  }
  // Undo the display curve and the fog the scene was drawn through (its whole path from the eye:
  // the water's own through_air adds the air part again); fog too thick to see through: not found.
  float t = fog_transmittance(u_eye_m, found);
  if (t < 0.02) return vec4(0.0);
  vec3 drawn = from_display(texture(u_scene_colour, uv).rgb);
  vec3 radiance = t >= 1.0 ? drawn : max((drawn - (1.0 - t) * fog_radiance(found - u_eye_m)) / t, vec3(0.0));
  // The path through the water along the refracted view to the depth of what is seen.
  vec3 r = refract(-to_eye, normal, 1.0 / kWaterIndex);
  float depth_m = here.z - found.z;
  depth_path = vec2(depth_m, depth_m / max(-r.z, 0.1));
  return vec4(radiance, 1.0);
}

void main() {
  vec2 p = v_site_m;
  // How many metres of sea one pixel covers: detail finer than that would alias (shimmer), so
  // it fades into the BRDF's slope variance (Bruneton 2010 section 4).
  float footprint_m = max(length(dFdx(p)), length(dFdy(p)));
  float eta = v_eta_m, weight = v_weight;  // interpolated from the vertices (water_vertex.glsl)
  if (is_dry(p, eta) || on_skirt_land(p)) discard;  // the terrain shows
  if (u_colouring == 1) { fragment_colour = vec4(u_flat_colour, 1.0); return; }
  if (u_colouring == 2) { fragment_colour = vec4(lod_colour(v_lod), 1.0); return; }
  if (u_colouring == 3) { fragment_colour = vec4(0.35 * lod_colour(v_lod), 1.0); return; }
  // The normal: the harbour's slopes filtered over the pixel's footprint (its slope moments' mip
  // level: slope_moments.hpp), the variance the footprint holds into the BRDF's; deep slopes from
  // the cascades' slope tiles, blended as the elevations are. The harbour's slope enters as w s,
  // so its variance as w^2 Var s.
  vec2 slope = vec2(0.0);
  float breaking = 0.0, baked_variance = 0.0;
  if (weight > 0.0 && u_has_keyframes) {
    vec2 size = u_spacing_m * vec2(u_cells);
    vec2 uv = p / size;
    float f = u_harbour_fraction;
    float lod = u_filter_baked_slopes ? baked_slope_lod(footprint_m, min(u_spacing_m.x, u_spacing_m.y)) : 0.0;
    vec3 filtered = filtered_baked_slope(textureLod(u_harbour_slope_moments_from, uv, lod),
                                         textureLod(u_harbour_slope_moments_to, uv, lod), f, u_spacing_m);
    slope += weight * filtered.xy;
    if (u_filter_baked_slopes) baked_variance = weight * weight * filtered.z;
    breaking = weight * mix(texture(u_harbour_breaking_from, uv).r, texture(u_harbour_breaking_to, uv).r, f);
  }
  vec3 to_eye = normalize(u_eye_m - v_position_m);
  // Deep cascades: their slopes as a normal map (the finest ones also over the harbour, where they
  // stand for the wind chop a bake's grid is too coarse to carry), each fading with distance into
  // slope variance; their displacement gradients give the Jacobian of seed 000 eq. (3.39)-(3.44).
  // Parallax (seed 004 section 1.3, eq. 5): the grid draws only what its vertices sample; the
  // finer cascades' relief stands above or below the drawn triangle, and at a grazing view the eye
  // ray meets that relief short of (or beyond) the drawn point. All the cascades' normals are read
  // where it meets it: the drawn point moved along the view by eq. (5) for the relief the grid
  // leaves out (each cascade's height weighted by how much of it the grid cannot draw and, as
  // its normals are, by how much detail the pixel keeps).
  float sheltering = relative_wave_height_at(p);
  float relief_m = 0.0;
  for (int c = 0; c < u_cascade_count && u_detail_parallax > 0.0; ++c) {
    float texel_m = u_tile_length_m[c] / float(u_deep_size);
    float share = cascade_share(c, weight, sheltering);
    float w = share * detail_normal_weight(texel_m, footprint_m) * unresolved_relief_weight(texel_m, footprint_m);
    if (w <= 0.0) continue;
    vec3 uvw = cascade_uvw(p, c);
    relief_m += w * mix(texture(u_deep_eta_from, uvw).r, texture(u_deep_eta_to, uvw).r, u_deep_fraction);
  }
  vec2 p_detail = p + u_detail_parallax * parallax_offset_m(to_eye, relief_m);
  float extra_variance = baked_variance;
  vec4 gradient = vec4(0.0);  // dDx/dx, dDy/dy, dDx/dy, dDy/dx
  for (int c = 0; c < u_cascade_count; ++c) {
    float texel_m = u_tile_length_m[c] / float(u_deep_size);
    float detail = detail_normal_weight(texel_m, footprint_m);
    float share = cascade_share(c, weight, sheltering);
    extra_variance += cascade_variance_share(c, weight, sheltering) * (1.0 - detail) * u_cascade_slope_variance[c];
    if (detail <= 0.0 || share <= 0.0) continue;
    vec3 uvw = cascade_uvw(p_detail, c);
    slope += share * detail * mix(vec2(texture(u_deep_slope_x_from, uvw).r, texture(u_deep_slope_y_from, uvw).r),
                                  vec2(texture(u_deep_slope_x_to, uvw).r, texture(u_deep_slope_y_to, uvw).r), u_deep_fraction);
    if (weight < 1.0) gradient += detail * cascade_displacement_gradient(p_detail, c);
  }
  slope += patch_slope(p);  // the height patches (bow waves) tilt the normal as they lift the surface
  // Seed 000 eq. (3.45) f_b here and now, and eq. (3.46)'s f_t: the foam that stays and fades after
  // the crest stopped breaking (kept over the largest tile by foam_decay.frag.glsl), both under
  // the foam map (eq. 3.48).
  float deep_breaking = clamp(u_jacobian_foam_onset - jacobian_of(gradient), 0.0, 1.0);
  if (u_has_deep_foam) deep_breaking = max(deep_breaking, texture(u_deep_foam, p_detail / u_tile_length_m[0]).r);
  // How white: eq. (3.45)'s f_b is J_b - J in metres' units, a few tenths at most, where the
  // seed's texture units made it reach 1. Monahan's coverage (ocean/whitecap_coverage.hpp sets
  // J_b from it) is the area of white water, so a crest 0.1 past the onset (ak 0.1 beyond the
  // Stokes limit: J = 1 - ak cos) is drawn fully broken and white, less thinly in proportion.
  const float kFoamOpaqueBeyondOnset = 0.1;
  float whiteness = clamp(deep_breaking / kFoamOpaqueBeyondOnset, 0.0, 1.0);
  float deep_foam = (1.0 - weight) * whiteness * mix(foam_texture(p_detail, footprint_m), 1.0, whiteness);
  float still_depth = still_water_depth_at(p);
  float shore_foam = 0.0;
  shoreline_waves(p, still_depth, footprint_m, slope, shore_foam);
  vec3 normal = normalize(vec3(-slope, 1.0));
  float total_depth = still_depth + eta;
  // Seed 003 eq. (16): foam grows with the surface elevation ("the higher the sea surface, the
  // denser the foam"), with the solver's breaking, the deep water's folds and the shore's surf.
  // In the harbour only: beyond it the deep water's own folds (the Jacobian) say where it breaks,
  // and a height threshold there paints every tall crest of a long swell white.
  // Crests foam only where the water is shallow enough for them to break by depth (McCowan's
  // limit H / d = 0.78, i.e. a crest eta ~ 0.39 d): a tall swell in deep water does not whitecap.
  float depth_limited = smoothstep(0.25, 0.39, eta / max(still_water_depth_at(p) + eta, 0.05));
  float crest_foam = weight * depth_limited * clamp((eta - u_foam_onset_m) / (u_foam_full_m - u_foam_onset_m), 0.0, 1.0);
  // At breakwaters and quays: where the baked sea runs up and down their faces fast enough to
  // entrain air, under the foam map (eq. 3.48) as the surf is.
  float face_foam = weight * structure_face_foam(p);
  if (face_foam > 0.0) face_foam *= mix(foam_texture(p, footprint_m), 1.0, 0.5 * face_foam);
  float foam = max(max(max(breaking, crest_foam), max(deep_foam, shore_foam)), face_foam);
  if (u_has_decal_foam) {  // the wakes' decals, shaded as the sea's own foam
    vec2 uv = (p - u_decal_foam_rect_m.xy) / u_decal_foam_rect_m.zw;
    if (all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)))) foam = max(foam, texture(u_decal_foam, uv).r);
  }
  float crest_thinness = clamp(eta / max(u_foam_onset_m, 0.1), 0.0, 1.0);
  // Land and structures seen in the water: the mirrored terrain at this pixel, displaced by the
  // surface's slope (a planar reflection's usual distortion, 3 % of the picture per unit slope).
  vec4 local = vec4(0.0);
  if (u_has_reflection) local = texture(u_reflection, (gl_FragCoord.xy - u_viewport_origin_px) / u_viewport_px + 0.03 * normal.xy);
  // The seabed seen through the water where the refracted view meets it (its texture there).
  float seabed = seabed_texture(refracted_seabed_point(p, normal, to_eye, total_depth));
  vec2 scene_depth_path;
  vec4 scene = refracted_scene(normal, to_eye, total_depth, scene_depth_path);
  vec3 radiance = shade_water(normal, to_eye, total_depth, foam, extra_variance, crest_thinness, local, seabed,
                              scene, scene_depth_path);
  fragment_colour = vec4(to_display(through_air(radiance, u_eye_m, v_position_m)), 1.0);
}
