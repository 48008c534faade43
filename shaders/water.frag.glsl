// The sea surface, lit as docs/lighting.md describes (common.glsl shade_water), or coloured flat /
// by level of detail for tests and pictures of the grids.
uniform int u_colouring;                // 0 lit, 1 flat u_flat_colour, 2 level of detail, 3 wire (darker LOD colour)
uniform vec3 u_flat_colour;
uniform float u_foam_onset_m;           // h0 of seed 003 eq. (16)
uniform float u_foam_full_m;            // h_max of eq. (16)
uniform float u_cascade_slope_variance[8];  // sigma^2 per axis each cascade's slopes carry
uniform float u_jacobian_foam_onset;    // J_b: foam where the deep water's Jacobian falls below it
uniform float u_time_s;                 // display time, for the shoreline waves
uniform vec2 u_wind_toward;             // unit vector the wind blows towards
uniform float u_shore_amplitude_m;      // the shoreline waves' amplitude on a windward shore (0: none)
uniform float u_shore_band_m;           // how far from the coastline they reach
uniform sampler2D u_coast_distance;     // signed distance to the coastline (m), negative on land
uniform bool u_has_reflection;          // the terrain mirrored in still water was drawn
uniform sampler2D u_reflection;         // ... as linear radiance, alpha = covered
uniform vec2 u_viewport_px;
uniform bool u_has_decal_foam;          // playback::SurfaceLayers foam decals were drawn into ...
uniform sampler2D u_decal_foam;         // ... this foam map (R8, cover 0..1) over ...
uniform vec4 u_decal_foam_rect_m;       // ... x0, y0, width, height of the site frame
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

// Seed 000 section 4.1: a pair of Gerstner-like waves running up the coast-distance gradient on
// shores the wind blows onto (eq. 4.1, 4.3: phase from the distance to the coast; amplitude
// falling off with that distance, eq. 4.4), and the breaking and turbulent foam bands of their
// phase (eq. 4.5, 4.6). They shade (normal and foam) but do not move the surface: the CPU queries
// a ship's physics reads must see the same water the bake made.
void shoreline_waves(vec2 p, float still_depth_m, inout vec2 slope, inout float foam) {
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
  // force 4), fading out towards the band's outer edge and onto the dry beach.
  float surf = windward * clamp(u_shore_amplitude_m / 0.15, 0.0, 1.0) * sqrt(1.0 - alpha_s) * smoothstep(0.0, 0.4, still_depth_m);
  float amplitude = u_shore_amplitude_m * surf;
  const float lengths_m[2] = float[2](14.0, 9.0);
  for (int i = 0; i < 2; ++i) {
    float k = 2.0 * kPi / lengths_m[i];
    float omega = sqrt(9.81 * k);
    float phase = k * distance_m + omega * u_time_s + 1.7 * float(i);  // crests run shorewards
    slope += amplitude * k * cos(phase) * seaward / float(i + 1);
    float f = fract(phase / (2.0 * kPi));
    float breaking = clamp(20.0 * f, 0.0, 1.0) - clamp(17.0 * f, 0.0, 1.0);  // eq. (4.6)
    float turbulent = clamp(20.0 * f, 0.0, 1.0) - clamp(2.0 * f, 0.0, 1.0);  // eq. (4.5)
    foam = max(foam, surf * (breaking + 0.5 * turbulent));
  }
}

void main() {
  vec2 p = v_site_m;
  // How many metres of sea one pixel covers: detail finer than that would alias (shimmer), so
  // it fades into the BRDF's slope variance (Bruneton 2010 section 4).
  float footprint_m = max(length(dFdx(p)), length(dFdy(p)));
  float eta = v_eta_m, weight = v_weight;  // interpolated from the vertices (water_vertex.glsl)
  if (is_dry(p, eta)) discard;  // the terrain shows
  if (u_colouring == 1) { fragment_colour = vec4(u_flat_colour, 1.0); return; }
  if (u_colouring == 2) { fragment_colour = vec4(lod_colour(v_lod), 1.0); return; }
  if (u_colouring == 3) { fragment_colour = vec4(0.35 * lod_colour(v_lod), 1.0); return; }
  // The normal: harbour slopes by central differences of its (hardware-filtered) keyframes, deep
  // slopes from the cascades' slope tiles, blended as the elevations are.
  vec2 slope = vec2(0.0);
  float breaking = 0.0;
  if (weight > 0.0 && u_has_keyframes) {
    vec2 size = u_spacing_m * vec2(u_cells);
    vec2 uv = p / size, du = vec2(1.0 / float(u_cells.x), 0.0), dv = vec2(0.0, 1.0 / float(u_cells.y));
    float f = u_harbour_fraction;
    float ex = mix(texture(u_harbour_eta_from, uv + du).r - texture(u_harbour_eta_from, uv - du).r,
                   texture(u_harbour_eta_to, uv + du).r - texture(u_harbour_eta_to, uv - du).r, f);
    float ey = mix(texture(u_harbour_eta_from, uv + dv).r - texture(u_harbour_eta_from, uv - dv).r,
                   texture(u_harbour_eta_to, uv + dv).r - texture(u_harbour_eta_to, uv - dv).r, f);
    slope += weight * vec2(ex, ey) / (2.0 * u_spacing_m);
    breaking = weight * mix(texture(u_harbour_breaking_from, uv).r, texture(u_harbour_breaking_to, uv).r, f);
  }
  // Deep cascades: their slopes as a normal map (the finest ones also over the harbour, where they
  // stand for the wind chop a bake's grid is too coarse to carry), each fading with distance into
  // slope variance; their displacement gradients give the Jacobian of seed 000 eq. (3.39)-(3.44).
  float extra_variance = 0.0;
  vec4 gradient = vec4(0.0);  // dDx/dx, dDy/dy, dDx/dy, dDy/dx
  for (int c = 0; c < u_cascade_count; ++c) {
    float texel_m = u_tile_length_m[c] / float(u_deep_size);
    float detail = 1.0 - smoothstep(texel_m, 4.0 * texel_m, footprint_m);
    bool over_harbour = u_has_site && u_tile_length_m[c] < 32.0 * max(u_spacing_m.x, u_spacing_m.y);
    float share = (1.0 - weight) + (over_harbour ? weight : 0.0);
    extra_variance += share * (1.0 - detail) * u_cascade_slope_variance[c];
    if (detail <= 0.0 || share <= 0.0) continue;
    vec3 uvw = vec3(p / u_tile_length_m[c] + 0.5 / float(u_deep_size), float(c));  // sample i at x = i L / N
    slope += share * detail * mix(vec2(texture(u_deep_slope_x_from, uvw).r, texture(u_deep_slope_y_from, uvw).r),
                                  vec2(texture(u_deep_slope_x_to, uvw).r, texture(u_deep_slope_y_to, uvw).r), u_deep_fraction);
    if (weight < 1.0) {
      vec3 dx = vec3(1.0 / float(u_deep_size), 0.0, 0.0), dy = vec3(0.0, 1.0 / float(u_deep_size), 0.0);
      vec4 from = vec4(texture(u_deep_dx_from, uvw + dx).r - texture(u_deep_dx_from, uvw - dx).r,
                       texture(u_deep_dy_from, uvw + dy).r - texture(u_deep_dy_from, uvw - dy).r,
                       texture(u_deep_dx_from, uvw + dy).r - texture(u_deep_dx_from, uvw - dy).r,
                       texture(u_deep_dy_from, uvw + dx).r - texture(u_deep_dy_from, uvw - dx).r);
      vec4 to = vec4(texture(u_deep_dx_to, uvw + dx).r - texture(u_deep_dx_to, uvw - dx).r,
                     texture(u_deep_dy_to, uvw + dy).r - texture(u_deep_dy_to, uvw - dy).r,
                     texture(u_deep_dx_to, uvw + dy).r - texture(u_deep_dx_to, uvw - dy).r,
                     texture(u_deep_dy_to, uvw + dx).r - texture(u_deep_dy_to, uvw - dx).r);
      gradient += detail * mix(from, to, u_deep_fraction) / (2.0 * texel_m);
    }
  }
  slope += patch_slope(p);  // the height patches (bow waves) tilt the normal as they lift the surface
  float lambda = u_choppiness;
  float jacobian = (1.0 + lambda * gradient.x) * (1.0 + lambda * gradient.y) - lambda * lambda * gradient.z * gradient.w;
  float deep_foam = (1.0 - weight) * clamp(u_jacobian_foam_onset - jacobian, 0.0, 1.0);  // seed 000 eq. (3.45)
  float still_depth = still_water_depth_at(p);
  float shore_foam = 0.0;
  shoreline_waves(p, still_depth, slope, shore_foam);
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
  float foam = max(max(breaking, crest_foam), max(deep_foam, shore_foam));
  if (u_has_decal_foam) {  // the wakes' decals, shaded as the sea's own foam
    vec2 uv = (p - u_decal_foam_rect_m.xy) / u_decal_foam_rect_m.zw;
    if (all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)))) foam = max(foam, texture(u_decal_foam, uv).r);
  }
  float crest_thinness = clamp(eta / max(u_foam_onset_m, 0.1), 0.0, 1.0);
  vec3 to_eye = normalize(u_eye_m - v_position_m);
  // Land and structures seen in the water: the mirrored terrain at this pixel, displaced by the
  // surface's slope (a planar reflection's usual distortion, 3 % of the picture per unit slope).
  vec4 local = vec4(0.0);
  if (u_has_reflection) local = texture(u_reflection, gl_FragCoord.xy / u_viewport_px + 0.03 * normal.xy);
  fragment_colour = vec4(to_display(shade_water(normal, to_eye, total_depth, foam, extra_variance, crest_thinness, local)), 1.0);
}
