// Seed 003 section 2.2: a radial grid centred under the viewer (dense near, sparse far: level of
// detail for free), displaced in the vertex shader by the baked surface elevation (vertex texture).
layout(location = 0) in vec2 a_polar;  // (radius in metres, angle in radians) around the viewer
uniform mat4 u_view_projection;
uniform vec3 u_eye_m;
uniform sampler2D u_surface_elevation;  // eta, metres, harbour grid cells (row 0 south)
uniform vec2 u_grid_origin_m;           // south-west corner of the harbour grid
uniform vec2 u_grid_size_m;             // extent of the harbour grid
out vec2 v_position_m;
out vec2 v_grid_uv;

void main() {
  vec2 position = u_eye_m.xy + a_polar.x * vec2(cos(a_polar.y), sin(a_polar.y));
  vec2 uv = (position - u_grid_origin_m) / u_grid_size_m;
  bool inside = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
  float eta = inside ? texture(u_surface_elevation, uv).r : 0.0;  // open sea beyond: still (deep water later)
  v_position_m = position;
  v_grid_uv = uv;
  gl_Position = u_view_projection * vec4(position, eta, 1.0);
}
