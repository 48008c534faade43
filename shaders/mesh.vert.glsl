// A rigid mesh (playback::SolidMesh, a ship's hull): body-frame vertices placed by its pose.
// Prepended with common.glsl and surface.glsl (the Earth's curvature of the projected grid).
layout(location = 0) in vec3 a_body_m;
uniform mat4 u_view_projection;
uniform mat3 u_rotation;     // body -> site frame
uniform vec3 u_position_m;   // where the body origin is
out vec3 v_position_m;
out float v_body_z_m;

void main() {
  vec3 p = u_position_m + u_rotation * a_body_m;
  v_position_m = p;
  v_body_z_m = a_body_m.z;
  gl_Position = u_view_projection * vec4(p.xy, p.z - curvature_drop_m(p.xy), 1.0);
}
