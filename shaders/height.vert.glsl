// The height pass: a lattice with one vertex per output pixel centre, through the water's own
// vertex path (water_vertex.glsl displaced_position), seen from straight above.
layout(location = 0) in vec2 a_grid;  // lattice vertex (i, j)
uniform vec4 u_lattice_m;             // x, y of vertex (0, 0) and the spacing along x, y

void main() {
  vec2 p = u_lattice_m.xy + a_grid * u_lattice_m.zw;
  emit_water_vertex(p, 0.0);
}
