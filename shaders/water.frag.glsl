// The sea surface, lit by seed 003 eq. (12)-(16) (common.glsl), or coloured flat / by level of
// detail for tests and pictures of the grids.
uniform int u_colouring;                // 0 lit, 1 flat u_flat_colour, 2 level of detail, 3 wire (darker LOD colour)
uniform vec3 u_flat_colour;
uniform float u_foam_onset_m;           // h0 of eq. (16)
uniform float u_foam_full_m;            // h_max of eq. (16)
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

void main() {
  vec2 p = v_site_m;
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
  if (weight < 1.0) {
    vec2 deep_slope = vec2(0.0);
    for (int c = 0; c < u_cascade_count; ++c) {
      vec3 uvw = vec3(p / u_tile_length_m[c] + 0.5 / float(u_deep_size), float(c));  // sample i at x = i L / N
      deep_slope += mix(vec2(texture(u_deep_slope_x_from, uvw).r, texture(u_deep_slope_y_from, uvw).r),
                        vec2(texture(u_deep_slope_x_to, uvw).r, texture(u_deep_slope_y_to, uvw).r), u_deep_fraction);
    }
    slope += (1.0 - weight) * deep_slope;
  }
  vec3 normal = normalize(vec3(-slope, 1.0));
  float total_depth = still_water_depth_at(p) + eta;
  // eq. (16), with the foam concentration growing with the surface elevation as seed 003's text
  // says ("the higher the sea surface, the denser the foam"), combined with the solver's breaking.
  float crest_foam = clamp((eta - u_foam_onset_m) / (u_foam_full_m - u_foam_onset_m), 0.0, 1.0);
  float foam = max(breaking, crest_foam);
  vec3 to_eye = normalize(u_eye_m - v_position_m);
  fragment_colour = vec4(to_display(shade_water(normal, to_eye, total_depth, foam)), 1.0);
}
