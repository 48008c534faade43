in vec2 v_grid_uv;
in vec3 v_position_m;
in float v_structure;
out vec4 fragment_colour;

void main() {
  vec3 normal = normalize(cross(dFdx(v_position_m), dFdy(v_position_m)));
  if (normal.z < 0.0) normal = -normal;
  float elevation = v_position_m.z;
  vec3 sand = u_seabed_albedo;
  vec3 grass = vec3(0.24, 0.33, 0.16);
  vec3 rock = vec3(0.45, 0.44, 0.42);
  vec3 albedo = elevation < 1.0 ? sand : mix(sand, grass, clamp((elevation - 1.0) / 3.0, 0.0, 1.0));
  if (v_structure > 0.5) albedo = rock;
  fragment_colour = vec4(to_display(albedo * diffuse_irradiance(normal)), 1.0);
}
