// Prepended with common.glsl and surface.glsl (u_eye_m). A rigid mesh lit as the land is (common.glsl shade_lambertian: the sun and the sky dome), with
// its face normal turned towards the eye (a hull is seen from outside; both sides are lit), and
// the bottom paint below the boot top. The sea, drawn after it with depth testing, covers what is
// under the water (the waterline is where they meet) and shows it through its surface by
// refraction (water.frag.glsl refracted_scene), attenuated by the water.
in vec3 v_position_m;
in float v_body_z_m;
uniform vec3 u_albedo_above, u_albedo_below;
uniform float u_boot_top_z_m;
uniform bool u_mirror;  // the reflection pass (as terrain.frag.glsl): linear radiance of what stands above still water
out vec4 fragment_colour;

void main() {
  vec3 normal = normalize(cross(dFdx(v_position_m), dFdy(v_position_m)));
  if (dot(normal, u_eye_m - v_position_m) < 0.0) normal = -normal;
  vec3 albedo = v_body_z_m < u_boot_top_z_m ? u_albedo_below : u_albedo_above;
  if (u_mirror) {
    if (v_position_m.z < 0.0) discard;  // the hull under the water is not mirrored in it
    fragment_colour = vec4(shade_lambertian(normal, albedo), 1.0);
    return;
  }
  fragment_colour = vec4(to_display(through_air(shade_lambertian(normal, albedo), u_eye_m, v_position_m)), 1.0);
}
