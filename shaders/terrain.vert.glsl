// The harbour's seabed, land, the skirt beyond the grid and the structures: the mesh
// build_site_terrain makes (playback/site_terrain.hpp), positions in metres of the site frame,
// z up from still water. Prepended with surface.glsl (for the Earth's curvature the projected
// grid bends the sea with).
layout(location = 0) in vec3 a_position_m;
layout(location = 1) in float a_inland_m;  // distance from the still-water line, positive on land
layout(location = 2) in float a_material;  // TerrainMaterial: 0 ground, 1 rubble, 2 concrete
uniform mat4 u_view_projection;
out vec3 v_position_m;
out float v_inland_m;
out float v_material;

void main() {
  v_position_m = a_position_m;
  v_inland_m = a_inland_m;
  v_material = a_material;
  gl_Position = u_view_projection * vec4(a_position_m.xy, a_position_m.z - curvature_drop_m(a_position_m.xy), 1.0);
}
