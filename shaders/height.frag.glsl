// The height pass: the shown surface elevation (m) where there is water, judged dry as the
// water's fragments are (water.frag.glsl); dry pixels keep the clear value (NaN).
in vec2 v_site_m;
in vec3 v_position_m;
in float v_lod;
in float v_eta_m;
in float v_weight;
out float fragment_height_m;

void main() {
  if (is_dry(v_site_m, v_eta_m)) discard;
  fragment_height_m = v_position_m.z;
}
