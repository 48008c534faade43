// CDLOD (Strugar 2009; seed 000 section 3.2): one instance per patch (playback::select_quadtree);
// odd vertices slide onto their even neighbours as the distance to the eye nears the end of the
// level's range, so a patch meets its coarser neighbour on the coarser lattice, without cracks.
// playback::quadtree_vertex is the CPU twin of the morph below.
layout(location = 0) in vec2 a_grid;   // vertex of the patch lattice, 0..patch_quads
layout(location = 1) in vec4 a_patch;  // origin x, origin y (m), vertex spacing (m), level
uniform vec2 u_morph_m[41];            // (morph start, morph end) per level, metres

void main() {
  int level = int(a_patch.w);
  float spacing = a_patch.z;
  vec2 p = a_patch.xy + a_grid * spacing;
  vec3 to_vertex = vec3(p - u_eye_m.xy, u_eye_m.z);
  float distance = sqrt(dot(to_vertex, to_vertex));
  vec2 range = u_morph_m[level];
  float morph = clamp((distance - range.x) / (range.y - range.x), 0.0, 1.0);
  vec2 odd = mod(a_grid, 2.0);
  p = a_patch.xy + (a_grid - odd * morph) * spacing;
  emit_water_vertex(p, float(level) + morph);
}
