// The sea surface of a runtime::SurfaceSnapshot at a site point (runtime/surface_snapshot.hpp):
//   harbour(p) = h00 H_from(p) + h10 T R_from(p) + h01 H_to(p) + h11 T R_to(p)   Hermite in time,
//                bilinear in the cell-centred rasters (R = d eta / dt; (1 - f_h) H_from + f_h H_to without)
//   deep(p)    = (1 - f_d) sum_c D_from,c(p) + f_d sum_c D_to,c(p) bilinear, periodic tiles
//   shown(p)   = w(p) harbour(p) + (1 - w(p)) deep(p)               w = harbour_weight(site, p)
// and the deep water's choppy shift (1 - w) lambda D(p) (ocean/deep_water.hpp: x -> x + lambda D).
// The CPU evaluates the same formulas (runtime's surface sampler); the height pass compares them.
// Prepended (after common.glsl) to the water and height-pass shaders. Site frame, metres.

// kPi: common.glsl

// u_eye_m, the viewer (site frame): common.glsl
uniform float u_earth_radius_m;    // > 0: the surface lies on a sphere touching still water under the eye

// Harbour (texture units 0-6): keyframes as R32F, cell (i, j) at texel (i, j), row 0 south.
uniform bool u_has_site;           // a harbour is shown (else: deep water only)
uniform bool u_has_keyframes;      // the snapshot holds harbour keyframes (else the harbour is still)
uniform sampler2D u_harbour_eta_from, u_harbour_eta_to;
uniform sampler2D u_harbour_breaking_from, u_harbour_breaking_to;
uniform sampler2D u_still_water_depth;  // d, positive down, land negative
uniform sampler2D u_porosity;
uniform sampler2D u_land;          // R8: 1 land
uniform sampler2D u_structure_mask;  // 1 inside a structure's outline at still water (site_terrain.hpp), over the site
uniform float u_harbour_fraction;  // f_h
uniform bool u_harbour_hermite;    // both keyframes carry d eta / dt (R): cubic Hermite in time
uniform float u_frame_interval_s;  // T: display seconds between the harbour keyframes
uniform sampler2D u_harbour_eta_rate_from, u_harbour_eta_rate_to;  // R, m/s
uniform ivec2 u_cells;             // columns, rows
uniform vec2 u_spacing_m;          // cell size dx, dy (rectangular cells: docs/solver.md)
uniform vec2 u_site_size_m;        // width, height
uniform int u_source_axis;         // HarbourSite: the bake's blending record
uniform float u_inward_sign, u_source_line_m, u_blend_start_m, u_blend_width_m, u_edge_fade_m;
uniform float u_open_sea_depth_m;  // depth assumed beyond the harbour (lighting only)
uniform float u_dry_depth_m;       // HarbourSite::dry_depth_m: total depth at or below which a point is dry

// Deep water (units 7-16): one layer per cascade, N x N, sample (i, j) at x = i L / N, periodic.
uniform int u_cascade_count;       // 0: a flat sea beyond the harbour
uniform int u_deep_size;           // N
uniform float u_tile_length_m[8];  // L per cascade
uniform float u_deep_fraction;     // f_d
uniform float u_choppiness;        // lambda
uniform sampler2DArray u_deep_eta_from, u_deep_eta_to;
uniform sampler2DArray u_deep_dx_from, u_deep_dx_to, u_deep_dy_from, u_deep_dy_to;
uniform sampler2DArray u_deep_slope_x_from, u_deep_slope_x_to, u_deep_slope_y_from, u_deep_slope_y_to;

// Bilinear interpolation written out with texelFetch and float weights: the texture units'
// own filtering keeps only 8 bits of the weights on most GPUs (a millimetre of error on a
// 5 m grid with a 10 % slope), and the height pass must agree with the CPU to well under that.
float harbour_bilinear(sampler2D field, vec2 p) {
  vec2 u = p / u_spacing_m - 0.5;  // cell centres at (i + 0.5) spacing
  vec2 base = floor(u);
  vec2 w = u - base;
  ivec2 i0 = clamp(ivec2(base), ivec2(0), u_cells - 1);
  ivec2 i1 = clamp(ivec2(base) + 1, ivec2(0), u_cells - 1);
  float south = mix(texelFetch(field, ivec2(i0.x, i0.y), 0).r, texelFetch(field, ivec2(i1.x, i0.y), 0).r, w.x);
  float north = mix(texelFetch(field, ivec2(i0.x, i1.y), 0).r, texelFetch(field, ivec2(i1.x, i1.y), 0).r, w.x);
  return mix(south, north, w.y);
}

struct DeepTaps {
  ivec2 i0, i1;
  vec2 w;
};
DeepTaps deep_taps(vec2 p, int cascade) {
  vec2 u = p * (float(u_deep_size) / u_tile_length_m[cascade]);  // samples at i L / N
  vec2 base = floor(u);
  DeepTaps t;
  t.w = u - base;
  t.i0 = ivec2(mod(base, float(u_deep_size)));
  t.i1 = (t.i0 + 1) % u_deep_size;
  return t;
}
float deep_bilinear(sampler2DArray field, DeepTaps t, int layer) {
  float south = mix(texelFetch(field, ivec3(t.i0.x, t.i0.y, layer), 0).r, texelFetch(field, ivec3(t.i1.x, t.i0.y, layer), 0).r, t.w.x);
  float north = mix(texelFetch(field, ivec3(t.i0.x, t.i1.y, layer), 0).r, texelFetch(field, ivec3(t.i1.x, t.i1.y, layer), 0).r, t.w.x);
  return mix(south, north, t.w.y);
}

// The lighting's reads of a cascade (hardware-filtered: they shade, they do not place the surface):
// the tile coordinate of p (sample i at x = i L / N) and the displacement gradient there,
// (dDx/dx, dDy/dy, dDx/dy, dDy/dx) by central differences, from/to blended: seed 000 eq. (3.41)-(3.44).
vec3 cascade_uvw(vec2 p, int c) { return vec3(p / u_tile_length_m[c] + 0.5 / float(u_deep_size), float(c)); }
vec4 cascade_displacement_gradient(vec2 p, int c) {
  vec3 uvw = cascade_uvw(p, c);
  vec3 dx = vec3(1.0 / float(u_deep_size), 0.0, 0.0), dy = vec3(0.0, 1.0 / float(u_deep_size), 0.0);
  vec4 from = vec4(texture(u_deep_dx_from, uvw + dx).r - texture(u_deep_dx_from, uvw - dx).r,
                   texture(u_deep_dy_from, uvw + dy).r - texture(u_deep_dy_from, uvw - dy).r,
                   texture(u_deep_dx_from, uvw + dy).r - texture(u_deep_dx_from, uvw - dy).r,
                   texture(u_deep_dy_from, uvw + dx).r - texture(u_deep_dy_from, uvw - dx).r);
  vec4 to = vec4(texture(u_deep_dx_to, uvw + dx).r - texture(u_deep_dx_to, uvw - dx).r,
                 texture(u_deep_dy_to, uvw + dy).r - texture(u_deep_dy_to, uvw - dy).r,
                 texture(u_deep_dx_to, uvw + dy).r - texture(u_deep_dx_to, uvw - dy).r,
                 texture(u_deep_dy_to, uvw + dx).r - texture(u_deep_dy_to, uvw - dx).r);
  return mix(from, to, u_deep_fraction) / (2.0 * u_tile_length_m[c] / float(u_deep_size));
}
// J of seed 000 eq. (3.39) from the summed gradient, lambda the choppiness (ocean::jacobian).
float jacobian_of(vec4 gradient) {
  float lambda = u_choppiness;
  return (1.0 + lambda * gradient.x) * (1.0 + lambda * gradient.y) - lambda * lambda * gradient.z * gradient.w;
}

// sin^2 ramp from 0 at s = 0 to 1 at s = width (runtime/src/surface_snapshot.cpp sin2_ramp).
float sin2_ramp(float s, float width) {
  if (width <= 0.0) return s > 0.0 ? 1.0 : 0.0;
  float r = sin(0.5 * kPi * clamp(s / width, 0.0, 1.0));
  return r * r;
}

// w(p): twin of runtime::harbour_weight (runtime/src/surface_snapshot.cpp).
float harbour_weight(vec2 p) {
  // No harbour keyframes: the deep water everywhere (runtime::SurfaceSampler does the same).
  if (!u_has_site || !u_has_keyframes || p.x < 0.0 || p.y < 0.0 || p.x > u_site_size_m.x || p.y > u_site_size_m.y)
    return 0.0;
  float along = u_source_axis == 0 ? p.x : p.y;
  float inland = u_inward_sign * (along - u_source_line_m);  // inland of the source line
  float weight = sin2_ramp(inland - u_blend_start_m, u_blend_width_m);
  float distances[4] = float[4](p.x, u_site_size_m.x - p.x, p.y, u_site_size_m.y - p.y);  // W, E, S, N
  int source_edge = u_source_axis == 0 ? (u_inward_sign > 0.0 ? 0 : 1) : (u_inward_sign > 0.0 ? 2 : 3);
  for (int edge = 0; edge < 4; ++edge)
    if (edge != source_edge) weight *= sin2_ramp(distances[edge], u_edge_fade_m);
  return weight;
}

// Height patches (playback::SurfaceLayers, a ship's bow wave): local fields added to the shown
// surface. All in one R32F atlas (unit 19), patch k in rows u_patch_row0[k] .. + rows - 1; texel
// (i, j) of a patch centred at origin + (i + 0.5, j + 0.5) spacing; bilinear between centres, 0
// outside them: ships::BowWave::elevation_m's rule, written out with texelFetch as the harbour is.
const int kMaxHeightPatches = 16;  // playback::SurfaceLayers::kMaxHeightPatches
uniform int u_patch_count;
uniform sampler2D u_patches;
uniform vec2 u_patch_origin_m[kMaxHeightPatches];
uniform float u_patch_spacing_m[kMaxHeightPatches];
uniform ivec2 u_patch_cells[kMaxHeightPatches];
uniform int u_patch_row0[kMaxHeightPatches];

float patch_elevation(vec2 p) {
  float sum = 0.0;
  for (int k = 0; k < u_patch_count; ++k) {
    vec2 u = (p - u_patch_origin_m[k]) / u_patch_spacing_m[k] - 0.5;
    ivec2 n = u_patch_cells[k];
    if (any(lessThan(u, vec2(0.0))) || any(greaterThan(u, vec2(n - 1)))) continue;
    ivec2 i0 = min(ivec2(u), n - 2);
    vec2 w = u - vec2(i0);
    i0.y += u_patch_row0[k];
    float south = mix(texelFetch(u_patches, i0, 0).r, texelFetch(u_patches, i0 + ivec2(1, 0), 0).r, w.x);
    float north = mix(texelFetch(u_patches, i0 + ivec2(0, 1), 0).r, texelFetch(u_patches, i0 + ivec2(1, 1), 0).r, w.x);
    sum += mix(south, north, w.y);
  }
  return sum;
}

// The patches' slope at p by central differences half a patch cell wide (for the normal).
vec2 patch_slope(vec2 p) {
  if (u_patch_count == 0) return vec2(0.0);
  float h = 0.5 * u_patch_spacing_m[0];
  return vec2(patch_elevation(p + vec2(h, 0.0)) - patch_elevation(p - vec2(h, 0.0)),
              patch_elevation(p + vec2(0.0, h)) - patch_elevation(p - vec2(0.0, h))) / (2.0 * h);
}

// H_eta at p: the Hermite of runtime/surface_snapshot.hpp (h00, h10, h01, h11 at f_h), else linear.
float harbour_in_time(vec2 p) {
  float from = harbour_bilinear(u_harbour_eta_from, p), to = harbour_bilinear(u_harbour_eta_to, p);
  float f = u_harbour_fraction;
  if (!u_harbour_hermite) return mix(from, to, f);
  float f2 = f * f, f3 = f2 * f;
  float T = u_frame_interval_s;
  return (2.0 * f3 - 3.0 * f2 + 1.0) * from + (f3 - 2.0 * f2 + f) * T * harbour_bilinear(u_harbour_eta_rate_from, p) +
         (-2.0 * f3 + 3.0 * f2) * to + (f3 - f2) * T * harbour_bilinear(u_harbour_eta_rate_to, p);
}

struct Surface {
  float eta;     // shown surface elevation (m)
  vec2 shift;    // horizontal displacement of the point (m)
  float weight;  // w(p)
};

Surface surface_at(vec2 p) {
  Surface s;
  s.weight = harbour_weight(p);
  float harbour = 0.0;
  if (s.weight > 0.0 && u_has_keyframes)
    harbour = harbour_in_time(p);
  float deep_from = 0.0, deep_to = 0.0;
  vec2 shift_from = vec2(0.0), shift_to = vec2(0.0);
  if (s.weight < 1.0) {
    for (int c = 0; c < u_cascade_count; ++c) {
      DeepTaps t = deep_taps(p, c);
      deep_from += deep_bilinear(u_deep_eta_from, t, c);
      deep_to += deep_bilinear(u_deep_eta_to, t, c);
      shift_from += vec2(deep_bilinear(u_deep_dx_from, t, c), deep_bilinear(u_deep_dy_from, t, c));
      shift_to += vec2(deep_bilinear(u_deep_dx_to, t, c), deep_bilinear(u_deep_dy_to, t, c));
    }
  }
  float deep = mix(deep_from, deep_to, u_deep_fraction);
  s.eta = s.weight * harbour + (1.0 - s.weight) * deep;
  s.shift = (1.0 - s.weight) * u_choppiness * mix(shift_from, shift_to, u_deep_fraction);
  // The height patches where this point is shown (after the shift): the CPU's displaced query
  // plus the patches at the same place (ships::ShipFleet::shown_elevation_m).
  if (u_patch_count > 0) s.eta += patch_elevation(p + s.shift);
  return s;
}

// Twin of playback::curvature_drop_m: the sphere's drop below the tangent plane under the eye.
float curvature_drop_m(vec2 p) {
  if (u_earth_radius_m <= 0.0) return 0.0;
  vec2 d = p - u_eye_m.xy;
  float rho2 = dot(d, d);
  return rho2 / (u_earth_radius_m + sqrt(max(u_earth_radius_m * u_earth_radius_m - rho2, 0.0)));
}

// The surroundings (playback::SurroundingGround, site_terrain.hpp): the chart's ground round the
// grid, RG = (w * elevation, w), w 0 where they have no data. At p, `beyond` metres past the grid's
// edge: (their elevation, how far the ground has turned to it: w * smoothstep(0,
// u_surroundings_blend_m, beyond)); y = 0 without them or where they have no data.
uniform bool u_has_surroundings;
uniform sampler2D u_surroundings;
uniform vec2 u_surroundings_origin_m, u_surroundings_size_m;  // their box, site frame
uniform float u_surroundings_blend_m;
vec2 surroundings_at(vec2 p, float beyond) {
  if (!u_has_surroundings) return vec2(0.0);
  vec2 around = texture(u_surroundings, (p - u_surroundings_origin_m) / u_surroundings_size_m).rg;
  float t = around.g * smoothstep(0.0, u_surroundings_blend_m, beyond);
  return t > 0.0 ? vec2(around.r / around.g, t) : vec2(0.0);
}

// Still-water depth d at p (m), for the water's colour: bilinear inside the harbour. Beyond it the
// seabed continues from the rectangle's nearest edge and deepens to the open sea's depth over one
// harbour extent, so the colour of the water (which sees the seabed through shallow water) shows
// no edge where the rectangle ends; where the surroundings have data, their depth instead, turned
// to as the skirt's ground turns to it (skirt_ground_m below).
float still_water_depth_at(vec2 p) {
  if (!u_has_site) return u_open_sea_depth_m;
  vec2 inside = clamp(p, vec2(0.0), u_site_size_m);
  float edge = texture(u_still_water_depth, inside / u_site_size_m).r;
  if (all(equal(inside, p))) return edge;
  float beyond = length(p - inside);
  float rule = mix(max(edge, 2.0), u_open_sea_depth_m, smoothstep(0.0, max(u_site_size_m.x, u_site_size_m.y), beyond));
  vec2 around = surroundings_at(p, beyond);
  return mix(rule, max(-around.x, 0.0), around.y);
}

// The skirt's ground beyond the grid (playback::skirt_ground_m, site_terrain.cpp: the same rule):
// the edge's ground averaged along the edge (9 taps over +-the distance beyond, at most a quarter
// of the shorter side) stays at that height on land and deepens to the open sea's depth on water;
// where the grid carries surroundings, their ground instead (surroundings_at above).
vec2 perimeter_point(float s) {
  float w = u_site_size_m.x, h = u_site_size_m.y, perimeter = 2.0 * (w + h);
  s = mod(s, perimeter);
  if (s < w) return vec2(s, 0.0);
  if ((s -= w) < h) return vec2(w, s);
  if ((s -= h) < w) return vec2(w - s, h);
  return vec2(0.0, h - (s - w));
}
float perimeter_position(vec2 q) {
  float w = u_site_size_m.x, h = u_site_size_m.y;
  if (q.y <= 0.0) return q.x;
  if (q.x >= w) return w + q.y;
  if (q.y >= h) return w + h + (w - q.x);
  return 2.0 * w + h + (h - q.y);
}
float skirt_ground_m(vec2 p) {
  vec2 q = clamp(p, vec2(0.0), u_site_size_m);
  float beyond = length(p - q);
  float s0 = perimeter_position(q), reach = min(beyond, 0.25 * min(u_site_size_m.x, u_site_size_m.y));
  float elevation = 0.0;
  for (int t = 0; t < 9; ++t)
    elevation -= harbour_bilinear(u_still_water_depth, perimeter_point(s0 + reach * (2.0 * float(t) / 8.0 - 1.0))) / 9.0;
  float drop = elevation + u_open_sea_depth_m;
  float as_water = elevation - drop * smoothstep(0.0, max(u_site_size_m.x, u_site_size_m.y), beyond);
  float edge_rule = mix(as_water, elevation, smoothstep(-1.0, 1.0, elevation));
  vec2 around = surroundings_at(p, beyond);
  return mix(edge_rule, around.x, around.y);
}
// Beyond the grid the sea is not drawn where the skirt's ground stands above still water: the land
// goes on to the horizon (and a sea drawn under it would fight it for depth kilometres off).
// u_edge_max_ground_m: the highest ground on each edge (south, east, north, west: perimeter
// order), so the sea off an all-water edge skips the nine taps (their mean is at most their max).
uniform float u_edge_max_ground_m[4];
bool on_skirt_land(vec2 p) {
  if (!u_has_site || all(greaterThanEqual(p, vec2(0.0))) && all(lessThan(p, u_site_size_m))) return false;
  vec2 q = clamp(p, vec2(0.0), u_site_size_m);
  float w = u_site_size_m.x, h = u_site_size_m.y, perimeter = 2.0 * (w + h);
  float reach = min(length(p - q), 0.25 * min(w, h)), s0 = perimeter_position(q);
  float ends[5] = float[5](0.0, w, w + h, 2.0 * w + h, perimeter);
  // Within the surroundings' box, land may stand anywhere (an island off an all-water edge).
  bool land_near = u_has_surroundings && all(greaterThanEqual(p, u_surroundings_origin_m)) &&
                   all(lessThan(p, u_surroundings_origin_m + u_surroundings_size_m));
  for (int side = 0; side < 4; ++side)
    for (int wrap = -1; wrap <= 1; ++wrap) {
      float a = s0 - reach + float(wrap) * perimeter, b = s0 + reach + float(wrap) * perimeter;
      if (b >= ends[side] && a <= ends[side + 1] && u_edge_max_ground_m[side] > 0.0) land_near = true;
    }
  return land_near && skirt_ground_m(p) > 0.0;
}

// Dry: no water is drawn where a structure stands above still water (its outline from the
// structure's geometry, or the half level of its porous cells read bilinearly: the mask the
// terrain is built with, SiteTextures), on land (d <= 0, d bilinear between the cell centres: the
// smooth line where the terrain's ground crosses still water, not the cells' edges; as before no
// water is drawn on land, whatever eta the deep water's blend or the bake's dry cells carry
// there), or where the wave leaves no water: d + eta <= the site's dry depth
// (docs/rendering.md, "Terrain").
bool is_dry(vec2 p, float eta) {
  if (!u_has_site || any(lessThan(p, vec2(0.0))) || any(greaterThanEqual(p, u_site_size_m))) return false;
  if (texture(u_structure_mask, p / u_site_size_m).r > 0.5) return true;
  float d = still_water_depth_at(p);
  return d <= 0.0 || d + eta <= u_dry_depth_m;
}
