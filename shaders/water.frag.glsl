uniform vec3 u_eye_m;
uniform sampler2D u_surface_elevation;  // eta (m)
uniform sampler2D u_still_water_depth;  // d (m, positive down; land negative)
uniform sampler2D u_breaking;           // breaking indicator 0..1
uniform vec2 u_texel_m;                 // grid spacing (m) along x and y
uniform float u_open_sea_depth_m;       // depth assumed beyond the harbour grid
uniform float u_foam_onset_m;           // h0 of eq. (16)
uniform float u_foam_full_m;            // h_max of eq. (16)
in vec2 v_position_m;
in vec2 v_grid_uv;
out vec4 fragment_colour;

void main() {
  bool inside = all(greaterThanEqual(v_grid_uv, vec2(0.0))) && all(lessThanEqual(v_grid_uv, vec2(1.0)));
  float eta = 0.0, depth = u_open_sea_depth_m, breaking = 0.0;
  vec3 normal = vec3(0.0, 0.0, 1.0);
  if (inside) {
    eta = texture(u_surface_elevation, v_grid_uv).r;
    depth = texture(u_still_water_depth, v_grid_uv).r;
    breaking = texture(u_breaking, v_grid_uv).r;
    vec2 du = vec2(1.0 / float(textureSize(u_surface_elevation, 0).x), 0.0);
    vec2 dv = vec2(0.0, 1.0 / float(textureSize(u_surface_elevation, 0).y));
    float slope_x = (texture(u_surface_elevation, v_grid_uv + du).r - texture(u_surface_elevation, v_grid_uv - du).r) / (2.0 * u_texel_m.x);
    float slope_y = (texture(u_surface_elevation, v_grid_uv + dv).r - texture(u_surface_elevation, v_grid_uv - dv).r) / (2.0 * u_texel_m.y);
    normal = normalize(vec3(-slope_x, -slope_y, 1.0));
  }
  float total_depth = depth + eta;
  if (total_depth < 0.02) discard;  // dry: the terrain shows
  // eq. (16), with the foam concentration growing with the surface elevation as seed 003's text
  // says ("the higher the sea surface, the denser the foam"), combined with the solver's breaking.
  float crest_foam = clamp((eta - u_foam_onset_m) / (u_foam_full_m - u_foam_onset_m), 0.0, 1.0);
  float foam = max(breaking, crest_foam);
  vec3 to_eye = normalize(u_eye_m - vec3(v_position_m, eta));
  fragment_colour = vec4(to_display(shade_water(normal, to_eye, total_depth, foam)), 1.0);
}
