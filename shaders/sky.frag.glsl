// The sky behind everything: Preetham's clear sky (common.glsl sky_radiance) and the sun's disc.
uniform mat4 u_inverse_view_projection;
in vec2 v_ndc;
out vec4 fragment_colour;
void main() {
  vec4 far_point = u_inverse_view_projection * vec4(v_ndc, 1.0, 1.0);
  vec3 direction = normalize(far_point.xyz / far_point.w - u_eye_m);
  vec3 radiance = sky_seen(u_eye_m, direction);
  // The sun's disc, 0.53 degree across (6.8e-5 sr): its illuminance spread over that solid angle,
  // dimmed by the fog above the eye as the sky is.
  if (dot(direction, u_sun_direction) > 0.99998930)
    radiance += u_sun_illuminance / 6.8e-5 * exp(-u_fog_extinction_per_m * max(u_fog_top_m - u_eye_m.z, 0.0) / max(direction.z, 0.01));
  fragment_colour = vec4(to_display(radiance), 1.0);
}
