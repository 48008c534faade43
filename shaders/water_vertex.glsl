// The end of every water vertex shader (radial, quadtree, projected) and of the height pass:
// the still-water site point p moves to the shown surface. Prepended after surface.glsl.
uniform mat4 u_view_projection;
out vec2 v_site_m;      // p: where the fields are looked up (before the choppy shift)
out vec3 v_position_m;  // the displaced surface point
out float v_lod;        // level of detail, for the LOD colouring
out float v_eta_m;      // shown(p), and w(p): the fragment shader interpolates them rather than
out float v_weight;     // evaluating the snapshot again per pixel (dozens of texel fetches)

vec3 displaced_position(Surface s, vec2 p) {
  return vec3(p + s.shift, s.eta - curvature_drop_m(p));
}

void emit_water_vertex(vec2 p, float lod) {
  Surface s = surface_at(p);
  vec3 position = displaced_position(s, p);
  v_site_m = p;
  v_position_m = position;
  v_lod = lod;
  v_eta_m = s.eta;
  v_weight = s.weight;
  gl_Position = u_view_projection * vec4(position, 1.0);
}
