// The harbour's seabed and land as a height field: z = -d. Porous structures and walls
// (porosity < 1: breakwaters, quays) stand at least u_structure_crest_m above still water.
layout(location = 0) in vec2 a_grid_uv;
uniform mat4 u_view_projection;
uniform sampler2D u_still_water_depth;
uniform sampler2D u_porosity;
uniform vec2 u_grid_origin_m;
uniform vec2 u_grid_size_m;
uniform float u_structure_crest_m;
out vec2 v_grid_uv;
out vec3 v_position_m;
out float v_structure;

float terrain_height_m(vec2 uv) {
  float z = -texture(u_still_water_depth, uv).r;
  return texture(u_porosity, uv).r < 0.99 ? max(z, u_structure_crest_m) : z;
}

void main() {
  vec2 position = u_grid_origin_m + a_grid_uv * u_grid_size_m;
  float z = terrain_height_m(a_grid_uv);
  v_grid_uv = a_grid_uv;
  v_position_m = vec3(position, z);
  v_structure = texture(u_porosity, a_grid_uv).r < 0.99 ? 1.0 : 0.0;
  gl_Position = u_view_projection * vec4(position, z, 1.0);
}
