// Seed 002 section 3: a screen-space grid cast onto the sphere of the Earth that touches still
// water under the eye, so the sea ends at the sphere's horizon. playback::project_to_sphere is
// the CPU twin; playback::layout_projected_grid chooses the screen rectangle u_ndc_rect.
layout(location = 0) in vec2 a_screen;           // 0..1 across the rectangle
uniform vec4 u_ndc_rect;                         // x0, y0, x1, y1 (normalised device coordinates)
uniform mat4 u_inverse_rotation_projection;      // screen -> eye-relative direction

void main() {
  vec2 ndc = mix(u_ndc_rect.xy, u_ndc_rect.zw, a_screen);
  vec4 far_point = u_inverse_rotation_projection * vec4(ndc, 1.0, 1.0);
  vec3 d = normalize(far_point.xyz / far_point.w);
  float r = u_earth_radius_m, h = max(u_eye_m.z, 1e-3);
  // |o + t d - c|^2 = R^2 with o - c = (0, 0, R + h): the near root without cancellation.
  float b = d.z * (r + h), c = h * (2.0 * r + h);
  float discriminant = b * b - c;
  float t;
  if (d.z < 0.0 && discriminant >= 0.0) {
    t = c / (-b + sqrt(discriminant));
  } else {
    // Above the horizon: the tangent ray at the same bearing (dip acos(R / (R + h))).
    t = sqrt(c);
    vec2 bearing = length(d.xy) > 0.0 ? normalize(d.xy) : vec2(0.0, 1.0);
    float dip = atan(t, r);
    d = vec3(cos(dip) * bearing, -sin(dip));
  }
  emit_water_vertex(u_eye_m.xy + t * d.xy, 0.0);
}
