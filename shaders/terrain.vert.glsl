// The harbour's seabed and land as a height field over the site rectangle: z = -d. Porous
// structures and walls (porosity < 1: breakwaters, quays) stand at least u_structure_crest_m
// above still water. Prepended with surface.glsl (its depth and porosity textures, and the
// Earth's curvature the projected grid bends the sea with).
layout(location = 0) in vec2 a_grid_uv;
uniform mat4 u_view_projection;
uniform float u_structure_crest_m;
out vec2 v_grid_uv;
out vec3 v_position_m;
out float v_structure;

void main() {
  vec2 position = a_grid_uv * u_site_size_m;
  float z = -texture(u_still_water_depth, a_grid_uv).r;
  bool structure = texture(u_porosity, a_grid_uv).r < 0.99;
  if (structure) z = max(z, u_structure_crest_m);
  v_grid_uv = a_grid_uv;
  v_position_m = vec3(position, z);
  v_structure = structure ? 1.0 : 0.0;
  gl_Position = u_view_projection * vec4(position, z - curvature_drop_m(position), 1.0);
}
