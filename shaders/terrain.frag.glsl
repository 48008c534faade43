// Land, seabed and structures: Lambertian under the sun and the sky dome (common.glsl).
in vec2 v_grid_uv;
in vec3 v_position_m;
in float v_structure;
uniform bool u_mirror;  // the reflection pass: linear radiance of what stands above still water
out vec4 fragment_colour;

void main() {
  vec3 normal = normalize(cross(dFdx(v_position_m), dFdy(v_position_m)));
  if (normal.z < 0.0) normal = -normal;
  float elevation = v_position_m.z;
  vec3 sand = u_seabed_albedo * seabed_texture(v_position_m.xy);  // the same sand as seen through the water
  vec3 grass = vec3(0.16, 0.22, 0.10);
  vec3 rock = vec3(0.38, 0.37, 0.35);
  vec3 albedo = elevation < 1.0 ? sand : mix(sand, grass, clamp((elevation - 1.0) / 3.0, 0.0, 1.0));
  if (v_structure > 0.5) albedo = rock;
  if (u_mirror) {
    if (v_position_m.z < 0.0) discard;  // only what stands above the water is mirrored in it
    fragment_colour = vec4(shade_lambertian(normal, albedo), 1.0);
    return;
  }
  fragment_colour = vec4(to_display(through_air(shade_lambertian(normal, albedo), u_eye_m, v_position_m)), 1.0);
}
