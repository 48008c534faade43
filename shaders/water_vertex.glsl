// The end of every water vertex shader (radial, quadtree, projected) and of the height pass:
// the still-water site point p moves to the shown surface. Prepended after surface.glsl.
uniform mat4 u_view_projection;
out vec2 v_site_m;      // p: where the fields are looked up (before the choppy shift)
out vec3 v_position_m;  // the displaced surface point
out float v_lod;        // level of detail, for the LOD colouring
out float v_eta_m;      // shown(p), and w(p): the fragment shader interpolates them rather than
out float v_weight;     // evaluating the snapshot again per pixel (dozens of texel fetches)

// The split (issue 14 item 1; runtime/surface_snapshot.hpp inside(p), the CPU twin is
// SurfaceSampler formula 3): the deep water's components above the bake's band, which the frames
// do not hold, drawn inside the harbour rectangle on top of them: shown = w (harbour + inside) +
// (1 - w) deep. The deep arrays hold the field's u_cascade_count cascades, then
// u_inside_layer_count band-limited ones; bit c of u_inside_cascade_mask draws field cascade c
// inside as it is (it lies wholly above the split). No choppy shift for it (surface_sampler.hpp 4).
uniform int u_inside_cascade_mask;
uniform int u_inside_layer_count;

float inside_elevation(vec2 p) {
  float from = 0.0, to = 0.0;
  for (int c = 0; c < u_cascade_count + u_inside_layer_count; ++c) {
    if (c < u_cascade_count && ((u_inside_cascade_mask >> c) & 1) == 0) continue;
    DeepTaps t = deep_taps(p, c);
    from += deep_bilinear(u_deep_eta_from, t, c);
    to += deep_bilinear(u_deep_eta_to, t, c);
  }
  return mix(from, to, u_deep_fraction);
}

vec3 displaced_position(Surface s, vec2 p) {
  return vec3(p + s.shift, s.eta - curvature_drop_m(p));
}

void emit_water_vertex(vec2 p, float lod) {
  Surface s = surface_at(p);
  if (s.weight > 0.0 && (u_inside_cascade_mask != 0 || u_inside_layer_count > 0)) s.eta += s.weight * inside_elevation(p);
  vec3 position = displaced_position(s, p);
  v_site_m = p;
  v_position_m = position;
  v_lod = lod;
  v_eta_m = s.eta;
  v_weight = s.weight;
  gl_Position = u_view_projection * vec4(position, 1.0);
}
