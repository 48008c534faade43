// Land, seabed and structures: Lambertian under the sun and the sky dome (common.glsl), with a
// procedural albedo (no texture files; the value noise of common.glsl, deterministic):
//  - ground: the seabed's sand under water and on the beach (within about 20-35 m of the
//    still-water line, or less than about a metre above it), wet and darker within 0.4 m of the
//    water; above the beach grass and scrub in patches; rock where the slope passes 1 in 1.25 (all rock beyond 1 in 0.75);
//  - rubble (sloped structure faces and crests): grey stones about a metre and a half across,
//    darker and greener where the sea wets them;
//  - concrete (quays, piers, walls): a light grey with faint slabs.
in vec3 v_position_m;
in float v_inland_m;
in float v_material;
uniform bool u_mirror;  // the reflection pass: linear radiance of what stands above still water
out vec4 fragment_colour;

vec3 ground_albedo(vec3 p, float inland_m, float up) {
  vec3 sand = u_seabed_albedo * seabed_texture(p.xy);  // the same sand as seen through the water
  if (p.z < 0.0) return sand;
  float wet = 1.0 - smoothstep(0.0, 0.4, p.z);
  vec3 beach = sand * (1.0 - 0.35 * wet);
  float patches = value_noise(p.xy / 40.0), fine = value_noise(p.xy / 6.0 + 3.7);
  vec3 grass = vec3(0.14, 0.21, 0.09), scrub = vec3(0.21, 0.20, 0.12);
  vec3 vegetation = mix(grass, scrub, smoothstep(0.35, 0.75, patches)) * (0.8 + 0.4 * fine);
  float beach_width_m = 20.0 + 15.0 * value_noise(p.xy / 60.0 + 1.3);
  float beach_weight = max(1.0 - smoothstep(0.6 * beach_width_m, beach_width_m, inland_m),
                           1.0 - smoothstep(0.6, 1.4, p.z));
  vec3 rock = vec3(0.36, 0.35, 0.33) * (0.75 + 0.5 * fine);
  float steep = smoothstep(0.78, 0.6, up);  // the normal's z: 0.78 at 1 in 1.25, 0.6 at 1 in 0.75
  return mix(mix(vegetation, beach, beach_weight), rock, steep);
}

vec3 structure_albedo(vec3 p, bool rubble) {
  if (rubble) {
    float stones = value_noise(p.xy / 1.5 + vec2(p.z)) * 0.7 + 0.3 * value_noise(p.xy / 0.5 + 9.1);
    vec3 rock = vec3(0.40, 0.39, 0.37) * (0.6 + 0.7 * stones);
    float wet = 1.0 - smoothstep(0.0, 0.6, p.z);
    return mix(rock, rock * vec3(0.55, 0.62, 0.52), wet);
  }
  float slabs = value_noise(p.xy / 4.0) * 0.5 + 0.5 * value_noise(vec2(p.x + p.y, p.z) / 2.0);
  return vec3(0.50, 0.49, 0.46) * (0.9 + 0.2 * slabs);
}

void main() {
  vec3 normal = normalize(cross(dFdx(v_position_m), dFdy(v_position_m)));
  vec3 albedo;
  if (v_material < 0.5) {
    if (normal.z < 0.0) normal = -normal;
    albedo = ground_albedo(v_position_m, v_inland_m, normal.z);
  } else {
    if (dot(normal, u_eye_m - v_position_m) < 0.0) normal = -normal;  // walls: the face towards the eye
    albedo = structure_albedo(v_position_m, v_material < 1.5);
  }
  if (u_mirror) {
    if (v_position_m.z < 0.0) discard;  // only what stands above the water is mirrored in it
    fragment_colour = vec4(shade_lambertian(normal, albedo), 1.0);
    return;
  }
  fragment_colour = vec4(to_display(through_air(shade_lambertian(normal, albedo), u_eye_m, v_position_m)), 1.0);
}
