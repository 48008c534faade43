// The deep water's persistent foam, seed 000 eq. (3.45)-(3.46), one texel per sample of the
// largest cascade's tile (x = (i + 0.5) L_0 / M, repeating with the tile): f_b from the Jacobian
// of every cascade the texel can resolve (the water shader's detail weights with a footprint of
// one texel), then f_t = exp(-dt / decay time) f_t_previous + f_b, clamped to [0, 1]
// (ocean::turbulent_foam, the CPU twin). Drawn with the full-screen triangle of sky.vert.glsl.
uniform sampler2D u_previous_foam;   // f_t of the last update (R32F, texelFetch)
uniform float u_foam_persistence;    // exp(-dt / decay time); 0 starts afresh
uniform float u_jacobian_foam_onset; // J_b of eq. (3.45)
uniform float u_map_texel_m;         // L_0 / M
in vec2 v_ndc;
out vec4 fragment_colour;
void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  vec2 p = gl_FragCoord.xy * u_map_texel_m;  // the texel's centre (gl_FragCoord is at i + 0.5)
  vec4 gradient = vec4(0.0);
  for (int c = 0; c < u_cascade_count; ++c) {
    float detail = detail_normal_weight(u_tile_length_m[c] / float(u_deep_size), u_map_texel_m);
    if (detail > 0.0) gradient += detail * cascade_displacement_gradient(p, c);
  }
  float breaking = clamp(u_jacobian_foam_onset - jacobian_of(gradient), 0.0, 1.0);
  float previous = texelFetch(u_previous_foam, texel, 0).r;
  fragment_colour = vec4(clamp(u_foam_persistence * previous + breaking, 0.0, 1.0), 0.0, 0.0, 1.0);
}
