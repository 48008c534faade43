// Seed 003 section 2.2, seed 000 eq. 2.20: rings round the point under the eye (the mesh holds
// radius and angle; playback::build_radial_grid), displaced by the snapshot's surface.
layout(location = 0) in vec2 a_polar;  // (radius m, angle rad)
uniform float u_lod_unit_m;            // radius of the first ring, for the LOD colouring

void main() {
  vec2 p = u_eye_m.xy + a_polar.x * vec2(cos(a_polar.y), sin(a_polar.y));
  emit_water_vertex(p, log2(1.0 + a_polar.x / u_lod_unit_m) * 0.5);
}
