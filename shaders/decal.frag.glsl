// A decal's foam cover: full along its centre line, falling to nothing at its sides (the wake's
// turbulent core spreading, seed 000 section 4.2.3 (2)), soft at its ends so the decals of a
// track overlap without seams, broken into streaks along the track by its variant (the seed's
// four foam textures, here a pattern rather than an image: no texture file to ship).
in vec2 v_local;
in vec2 v_site_m;
flat in float v_opacity;
flat in float v_variant;
out float fragment_cover;

float hash(vec2 q) { return fract(sin(dot(q, vec2(127.1, 311.7))) * 43758.5453); }
float value_noise(vec2 q) {
  vec2 i = floor(q), f = fract(q);
  f = f * f * (3.0 - 2.0 * f);
  return mix(mix(hash(i), hash(i + vec2(1.0, 0.0)), f.x), mix(hash(i + vec2(0.0, 1.0)), hash(i + vec2(1.0, 1.0)), f.x), f.y);
}

void main() {
  float across = 1.0 - smoothstep(0.15, 0.5, abs(v_local.y));
  float ends = 1.0 - smoothstep(0.15, 0.5, abs(v_local.x));  // full over the middle, overlapping the neighbours
  // Streaks: noise stretched along the track, in site metres so neighbouring decals continue it.
  float streaks = value_noise(v_site_m * 0.9 + 17.0 * v_variant) * 0.6 + value_noise(v_site_m * 2.7 - 5.0 * v_variant) * 0.4;
  fragment_cover = clamp(v_opacity * across * ends * (0.45 + 0.9 * streaks), 0.0, 1.0);
}
