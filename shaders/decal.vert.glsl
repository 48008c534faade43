// Foam decals (playback::FoamDecal) drawn from straight above into the foam map the water shader
// reads: one instance per decal, a unit quad stretched along its track and across it.
layout(location = 0) in vec2 a_corner;    // -0.5..0.5 along, across
layout(location = 1) in vec4 a_placement; // centre x, y (m), yaw (rad, counter-clockwise from east), opacity
layout(location = 2) in vec3 a_size;      // length, width (m), variant
uniform vec4 u_rect_m;                    // the foam map's x0, y0, width, height
out vec2 v_local;                         // -0.5..0.5 along and across the decal
out vec2 v_site_m;
flat out float v_opacity;
flat out float v_variant;

void main() {
  vec2 along = vec2(cos(a_placement.z), sin(a_placement.z));
  vec2 across = vec2(-along.y, along.x);
  // The quad reaches kOverlap times the decal's length along the track: its soft ends overlap the
  // neighbours' (a decal is dropped every length_m), so a track reads as one trail.
  const float kOverlap = 1.8;
  vec2 p = a_placement.xy + a_corner.x * kOverlap * a_size.x * along + a_corner.y * a_size.y * across;
  v_local = a_corner;
  v_site_m = p;
  v_opacity = a_placement.w;
  v_variant = a_size.z;
  gl_Position = vec4(2.0 * (p - u_rect_m.xy) / u_rect_m.zw - 1.0, 0.0, 1.0);
}
