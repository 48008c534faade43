#include "nearshore/runtime/surface_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"
#include "harbour_ramp.hpp"

namespace nearshore::runtime {

namespace {

// Formula 1 of surface_sampler.hpp: the four texels and weights of a cell-centred raster.
struct Tap {
  std::size_t i00 = 0, i10 = 0, i01 = 0, i11 = 0;
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  double a = 0.0, b = 0.0;
};

inline void axis_tap(double texel, int count, int& lo, int& hi, double& fraction) {
  if (count < 2) {
    lo = hi = 0;
    fraction = 0.0;
    return;
  }
  texel = std::clamp(texel, 0.0, static_cast<double>(count - 1));
  lo = std::min(static_cast<int>(texel), count - 2);  // texel >= 0: the cast is floor
  hi = lo + 1;
  fraction = texel - lo;
}

// Rectangular cells (dx != dy): each axis scaled by its own inverse spacing.
inline Tap harbour_tap(double x_m, double y_m, double inverse_spacing_x, double inverse_spacing_y, int columns, int rows) {
  Tap t;
  axis_tap(x_m * inverse_spacing_x - 0.5, columns, t.i0, t.i1, t.a);
  axis_tap(y_m * inverse_spacing_y - 0.5, rows, t.j0, t.j1, t.b);
  const std::size_t c = static_cast<std::size_t>(columns);
  t.i00 = static_cast<std::size_t>(t.j0) * c + static_cast<std::size_t>(t.i0);
  t.i10 = static_cast<std::size_t>(t.j0) * c + static_cast<std::size_t>(t.i1);
  t.i01 = static_cast<std::size_t>(t.j1) * c + static_cast<std::size_t>(t.i0);
  t.i11 = static_cast<std::size_t>(t.j1) * c + static_cast<std::size_t>(t.i1);
  return t;
}

inline double bilinear(const float* f, const Tap& t) {
  return (1.0 - t.b) * ((1.0 - t.a) * f[t.i00] + t.a * f[t.i10]) + t.b * ((1.0 - t.a) * f[t.i01] + t.a * f[t.i11]);
}

// Formula 2: the periodic tap of a cascade tile (nodes at i L / N).
inline Tap cascade_tap(double x_m, double y_m, double inverse_tile_length, int n) {
  Tap t;
  const auto axis = [n, inverse_tile_length](double p, int& lo, int& hi, double& fraction) {
    double cycles = p * inverse_tile_length;
    cycles -= std::floor(cycles);
    const double u = cycles * n;
    lo = std::min(static_cast<int>(u), n - 1);
    fraction = u - lo;
    hi = (lo + 1) & (n - 1);  // n is a power of two
  };
  axis(x_m, t.i0, t.i1, t.a);
  axis(y_m, t.j0, t.j1, t.b);
  const std::size_t c = static_cast<std::size_t>(n);
  t.i00 = static_cast<std::size_t>(t.j0) * c + static_cast<std::size_t>(t.i0);
  t.i10 = static_cast<std::size_t>(t.j0) * c + static_cast<std::size_t>(t.i1);
  t.i01 = static_cast<std::size_t>(t.j1) * c + static_cast<std::size_t>(t.i0);
  t.i11 = static_cast<std::size_t>(t.j1) * c + static_cast<std::size_t>(t.i1);
  return t;
}

// Formula 6: per-texel central differences (clamped, one-sided at the edge), bilinear.
struct Gradient {
  double x = 0.0, y = 0.0;
};
inline Gradient texel_gradient(const float* f, int i, int j, int columns, int rows, double spacing_x_m, double spacing_y_m) {
  Gradient g;
  const int west = std::max(i - 1, 0), east = std::min(i + 1, columns - 1);
  const int south = std::max(j - 1, 0), north = std::min(j + 1, rows - 1);
  const std::size_t c = static_cast<std::size_t>(columns);
  if (east > west)
    g.x = (f[static_cast<std::size_t>(j) * c + east] - f[static_cast<std::size_t>(j) * c + west]) / ((east - west) * spacing_x_m);
  if (north > south)
    g.y = (f[static_cast<std::size_t>(north) * c + i] - f[static_cast<std::size_t>(south) * c + i]) /
          ((north - south) * spacing_y_m);
  return g;
}
inline Gradient bilinear_gradient(const float* f, const Tap& t, int columns, int rows, double spacing_x_m, double spacing_y_m) {
  const Gradient g00 = texel_gradient(f, t.i0, t.j0, columns, rows, spacing_x_m, spacing_y_m);
  const Gradient g10 = texel_gradient(f, t.i1, t.j0, columns, rows, spacing_x_m, spacing_y_m);
  const Gradient g01 = texel_gradient(f, t.i0, t.j1, columns, rows, spacing_x_m, spacing_y_m);
  const Gradient g11 = texel_gradient(f, t.i1, t.j1, columns, rows, spacing_x_m, spacing_y_m);
  const double w00 = (1 - t.a) * (1 - t.b), w10 = t.a * (1 - t.b), w01 = (1 - t.a) * t.b, w11 = t.a * t.b;
  return {w00 * g00.x + w10 * g10.x + w01 * g01.x + w11 * g11.x, w00 * g00.y + w10 * g10.y + w01 * g01.y + w11 * g11.y};
}

// Formula 4's hot loop on the query layout (surface_snapshot.hpp QueryTile): a tap's four nodes
// as {D_x, D_y, eta, 0} vectors, each keyframe's integers times its weighted scales, so one
// bilinear in float4 gives D, eta and (from the same nodes) the gradient of D. A row of the
// padded tile holds (i0, j) and (i0 + 1, j) side by side: one 16-byte read and one conversion give
// both. GCC/Clang vector extensions (SSE2 on any x86-64, NEON on ARM), no intrinsics.
// The helpers pass 32-byte vectors by value; inlined into the solve, so the ABI of such calls
// without AVX (GCC's -Wpsabi note) never applies.
#pragma GCC diagnostic ignored "-Wpsabi"
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define NEARSHORE_SOLVE_CLONES __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
#else
#define NEARSHORE_SOLVE_CLONES
#endif
typedef float Float4 __attribute__((vector_size(16)));
typedef float Float8 __attribute__((vector_size(32)));
typedef std::int16_t Short8 __attribute__((vector_size(16)));
typedef std::int32_t Int8 __attribute__((vector_size(32)));
typedef std::int16_t Short16 __attribute__((vector_size(32)));
// A row's eight int16 as eight floats. Each value goes to the high half of a 32-bit lane and an
// arithmetic shift by 16 brings it down with its sign: GCC 12 expands __builtin_convertvector from
// 8 x int16 to 8 x int32 as two 4-lane extensions, a byte shift and a lane insert (five
// instructions, not AVX2's one vpmovsxwd), where this shuffle is one permute (vpermw with AVX-512,
// vperm2i128 + vpshufb with AVX2) and one shift. The same integers, so the same bits: open-sea
// displaced queries 9.05 -> 9.73 M/s (sampler probe, six alternations, load 8).
inline Float8 load_row(const std::int16_t* tile, std::size_t node) {
  Short8 raw;
  std::memcpy(&raw, tile + 4 * node, sizeof raw);
  const Short16 in_high_halves = __builtin_shufflevector(raw, raw, 8, 0, 9, 1, 10, 2, 11, 3, 12, 4, 13, 5, 14, 6, 15, 7);
  Int8 lanes;
  std::memcpy(&lanes, &in_high_halves, sizeof lanes);
  return __builtin_convertvector(lanes >> 16, Float8);
}
inline Float8 load_weights(const float* w) {
  Float8 v;
  std::memcpy(&v, w, sizeof v);
  return v;
}
inline Float4 low_half(Float8 v) { return __builtin_shufflevector(v, v, 0, 1, 2, 3); }
inline Float4 high_half(Float8 v) { return __builtin_shufflevector(v, v, 4, 5, 6, 7); }
// A cascade tap as the solve keeps it between its two sweeps: the padded tile's node indices of
// (i0, j0) and (i0, j1), and the fractions (no initialisers: a block's array of them is written
// before it is read, and zeroing it would cost more than a point's solve).
struct BlockTap {
  std::size_t row0, row1;
  float a, b;
};
// Formula 2 split for the solve: (u, v) = frac(q / L) N + (p - q) N / L, the fraction of the
// query point taken once in double, the solve's offset added per step; floor by truncation and a
// correction (u may be negative), both axes in one packed double.
typedef double Double2 __attribute__((vector_size(16)));
typedef std::int32_t Int2 __attribute__((vector_size(8)));
typedef std::int64_t Long2 __attribute__((vector_size(16)));
inline BlockTap block_tap(Double2 uv, int n) {
  const Int2 truncated = __builtin_convertvector(uv, Int2);
  const Long2 went_up = uv < __builtin_convertvector(truncated, Double2);  // -1 where a negative u was rounded up
  const Int2 floor_uv = truncated + __builtin_convertvector(went_up, Int2);
  const Double2 fraction = uv - __builtin_convertvector(floor_uv, Double2);
  const std::uint32_t mask = static_cast<std::uint32_t>(n) - 1, stride = static_cast<std::uint32_t>(n) + 1;
  const std::uint32_t i0 = static_cast<std::uint32_t>(floor_uv[0]) & mask, j0 = static_cast<std::uint32_t>(floor_uv[1]) & mask;
  return {std::size_t{j0} * stride + i0, std::size_t{(j0 + 1) & mask} * stride + i0, static_cast<float>(fraction[0]),
          static_cast<float>(fraction[1])};
}
inline Double2 as_double2(SitePoint p) { return Double2{p.x_m, p.y_m}; }
inline double texel_of_fraction(double p_m, double inverse_tile_length, int n) {
  double cycles = p_m * inverse_tile_length;
  cycles -= std::floor(cycles);
  return cycles * n;
}
struct PackedSum {  // no initialisers: a block's array of them is zeroed for its active points only
  Float4 value, d_dx, d_dy, d_dxdy;  // per metre (d_dxdy per m^2: the bilinear's cross term)
};

const float* data_or_null(const Raster<float>& raster, int columns, int rows) {
  if (raster.empty()) return nullptr;
  if (raster.columns() != columns || raster.rows() != rows)
    throw Error("surface snapshot", fmt::format("a keyframe raster is {} x {} but the site's grid is {} x {}",
                                                raster.columns(), raster.rows(), columns, rows),
                "give the sampler keyframes of the snapshot's own sequence");
  return raster.data();
}

}  // namespace

SurfaceSampler::SurfaceSampler(SurfaceSnapshot snapshot) : snapshot_(std::move(snapshot)) {
  const SurfaceSnapshot& s = snapshot_;
  if (s.site && s.harbour_from) {
    const HarbourSite& site = *s.site;
    columns_ = site.harbour.geometry.columns;
    rows_ = site.harbour.geometry.rows;
    spacing_x_m_ = site.harbour.geometry.spacing_x_m();
    spacing_y_m_ = site.harbour.geometry.spacing_y_m();
    inverse_spacing_x_ = 1.0 / spacing_x_m_;
    inverse_spacing_y_ = 1.0 / spacing_y_m_;
    const HarbourKeyframe& from = *s.harbour_from;
    const HarbourKeyframe& to = s.harbour_to ? *s.harbour_to : from;
    eta_ = {data_or_null(from.surface_elevation_m, columns_, rows_), data_or_null(to.surface_elevation_m, columns_, rows_)};
    flux_x_ = {data_or_null(from.flux_x_m2_s, columns_, rows_), data_or_null(to.flux_x_m2_s, columns_, rows_)};
    flux_y_ = {data_or_null(from.flux_y_m2_s, columns_, rows_), data_or_null(to.flux_y_m2_s, columns_, rows_)};
    has_harbour_ = eta_.from && eta_.to;
    if (!site.harbour.still_water_depth_m.empty()) depth_ = data_or_null(site.harbour.still_water_depth_m, columns_, rows_);
    if (!site.harbour.land.empty() && site.harbour.land.columns() == columns_ && site.harbour.land.rows() == rows_)
      land_ = site.harbour.land.data();
    harbour_fraction_ = std::clamp(s.harbour_fraction, 0.0, 1.0);
    frame_interval_s_ = site.frame_interval_s > 0.0 && std::isfinite(site.frame_interval_s) ? site.frame_interval_s : 0.0;
    if (harbour_joined_by_hermite(s))
      eta_rate_ = {data_or_null(from.surface_elevation_rate_m_s, columns_, rows_), data_or_null(to.surface_elevation_rate_m_s, columns_, rows_)};
    hermite_ = hermite_weights(harbour_fraction_);
    const double weights[4] = {hermite_.from, hermite_.from_rate * frame_interval_s_, hermite_.to, hermite_.to_rate * frame_interval_s_};
    for (int k = 0; k < 8; ++k) hermite_by_channel_[k] = static_cast<float>(weights[k / 2]);
  }
  if (s.deep_from) {
    const DeepWaterKeyframe& from = *s.deep_from;
    const DeepWaterKeyframe& to = s.deep_to ? *s.deep_to : from;
    if (from.cascades.size() != to.cascades.size())
      throw Error("surface snapshot", "its two deep-water keyframes have different cascade counts",
                  "give the sampler keyframes of one field");
    has_deep_flux_ = from.still_water_depth_m > 0.0;
    for (std::size_t c = 0; c < from.cascades.size(); ++c) {
      const ocean::DeepWaterFrame& a = from.cascades[c];
      const ocean::DeepWaterFrame& b = to.cascades[c];
      if (a.surface_elevation_m.empty()) continue;
      cascades_.push_back({a.grid_size, a.tile_length_m, 1.0 / a.tile_length_m, &a, &b});
      has_deep_flux_ = has_deep_flux_ && !a.flux_x_m2_s.empty() && !b.flux_x_m2_s.empty();
    }
    has_deep_ = !cascades_.empty();
    // The query layout: the keyframes' own tiles (packed by the engine's worker) where they match
    // the cascades, else a copy packed here for this sampler's lifetime.
    const auto usable = [&](const DeepWaterKeyframe& keyframe) {
      if (keyframe.query_tiles.size() != cascades_.size()) return false;
      for (std::size_t c = 0; c < cascades_.size(); ++c) {
        const QueryTile& tile = keyframe.query_tiles[c];
        const std::size_t n = static_cast<std::size_t>(cascades_[c].n);
        if (tile.grid_size != cascades_[c].n || tile.tile_length_m != cascades_[c].tile_length_m || tile.nodes.size() != 4 * (n + 1) * n)
          return false;
      }
      return true;
    };
    const bool from_usable = usable(from), to_usable = usable(to);
    if (!from_usable || !to_usable) own_tiles_.resize(2 * cascades_.size());
    const double f = std::clamp(s.deep_fraction, 0.0, 1.0);
    for (std::size_t c = 0; c < cascades_.size(); ++c) {
      if (!from_usable) pack_query_tile(*cascades_[c].from, own_tiles_[2 * c]);
      if (!to_usable) pack_query_tile(*cascades_[c].to, own_tiles_[2 * c + 1]);
      const QueryTile& a = from_usable ? from.query_tiles[c] : own_tiles_[2 * c];
      const QueryTile& b = to_usable ? to.query_tiles[c] : own_tiles_[2 * c + 1];
      PackedCascade packed;
      packed.n = cascades_[c].n;
      packed.inverse_tile_length = cascades_[c].inverse_tile_length;
      packed.texels_per_m = static_cast<float>(cascades_[c].n * cascades_[c].inverse_tile_length);
      packed.from = a.nodes.data();
      packed.to = b.nodes.data();
      packed.texels_per_m_d = cascades_[c].n * cascades_[c].inverse_tile_length;
      for (int k = 0; k < 8; ++k) {  // the two nodes of a row read at once: the weights twice
        packed.from_weight[k] = static_cast<float>((1.0 - f) * a.scale[k % 4]);
        packed.to_weight[k] = static_cast<float>(f * b.scale[k % 4]);
      }
      packed_.push_back(packed);
    }
    // The split's inside layer (surface_snapshot.hpp): the field's cascades wholly above the
    // bake's band as they are, then the straddling ones band-limited.
    if (from.inside_cascade_mask != to.inside_cascade_mask || from.inside_cascades.size() != to.inside_cascades.size())
      throw Error("surface snapshot", "its two deep-water keyframes have different inside layers (the split)",
                  "give the sampler keyframes of one field");
    has_inside_flux_ = from.still_water_depth_m > 0.0;
    const auto add_inside = [&](const ocean::DeepWaterFrame& a, const ocean::DeepWaterFrame& b) {
      if (a.surface_elevation_m.empty() || b.surface_elevation_m.size() != a.surface_elevation_m.size()) return;
      inside_.push_back({a.grid_size, a.tile_length_m, 1.0 / a.tile_length_m, &a, &b});
      has_inside_flux_ = has_inside_flux_ && !a.flux_x_m2_s.empty() && !b.flux_x_m2_s.empty();
    };
    for (std::size_t c = 0; c < from.cascades.size() && c < 32; ++c)
      if ((from.inside_cascade_mask >> c) & 1u) add_inside(from.cascades[c], to.cascades[c]);
    for (std::size_t c = 0; c < from.inside_cascades.size(); ++c) add_inside(from.inside_cascades[c], to.inside_cascades[c]);
    has_inside_ = !inside_.empty();
    deep_fraction_ = std::clamp(s.deep_fraction, 0.0, 1.0);
    const double deep_interval_s = to.display_time_s - from.display_time_s;
    inverse_deep_interval_ = deep_interval_s > 0.0 && std::isfinite(deep_interval_s) ? 1.0 / deep_interval_s : 0.0;
  }
  choppiness_ = s.site ? s.site->choppiness : 1.0;
  if (has_harbour_) {
    // The box where every ramp is 1 (surface_snapshot.cpp): fade from each edge, and on the
    // maker's side the zone's end too.
    const HarbourSite& site = *s.site;
    const double fade = std::max(site.edge_fade_m, 0.0);
    site_width_m_ = site.width_m;
    site_height_m_ = site.height_m;
    ramp_axis_ = site.source_axis;
    ramp_inward_sign_ = site.inward_sign;
    ramp_line_m_ = site.source_line_m;
    ramp_start_m_ = site.blend_start_m;
    ramp_width_m_ = site.blend_width_m;
    edge_fade_m_ = site.edge_fade_m;
    full_x0_ = fade;
    full_x1_ = site.width_m - fade;
    full_y0_ = fade;
    full_y1_ = site.height_m - fade;
    const double zone_end = site.source_line_m + site.inward_sign * (site.blend_start_m + std::max(site.blend_width_m, 0.0));
    double& near = site.source_axis == 0 ? (site.inward_sign > 0 ? full_x0_ : full_x1_) : (site.inward_sign > 0 ? full_y0_ : full_y1_);
    near = site.source_axis == 0 ? (site.inward_sign > 0 ? std::max(zone_end, 0.0) : std::min(zone_end, site.width_m))
                                 : (site.inward_sign > 0 ? std::max(zone_end, 0.0) : std::min(zone_end, site.height_m));
    // A zero-width ramp is a step at its start: keep such points on the slow path.
    if (!(site.blend_width_m > 0.0) || !(site.edge_fade_m > 0.0)) full_x1_ = -1.0;
  }
}

// Farther than the edge fade from every edge only the maker's ramp varies: there w is that ramp,
// computed with the operations of surface_snapshot.cpp's site_ramps and the product rule (the four
// fades exactly 1, so the same bits), without the call and the five ramps' bookkeeping: a displaced
// query in the blending zone takes w at every Newton step (a sixth of its time in the call).
inline HarbourWeight SurfaceSampler::site_weight(double x_m, double y_m, bool with_slope) const {
  const double fade = edge_fade_m_;
  if (fade > 0.0 && x_m >= fade && y_m >= fade && site_width_m_ - x_m >= fade && site_height_m_ - y_m >= fade) {
    const double inland = ramp_inward_sign_ * ((ramp_axis_ == 0 ? x_m : y_m) - ramp_line_m_);
    const detail::Ramp ramp = detail::sin2_ramp(inland - ramp_start_m_, ramp_width_m_, with_slope);
    HarbourWeight w{ramp.value, 0.0, 0.0};
    (ramp_axis_ == 0 ? w.d_dx_per_m : w.d_dy_per_m) = ramp.slope * ramp_inward_sign_;
    return w;
  }
  if (with_slope) return harbour_weight_and_gradient(*snapshot_.site, x_m, y_m);
  return {harbour_weight(*snapshot_.site, x_m, y_m), 0.0, 0.0};
}

double SurfaceSampler::weight(double x_m, double y_m) const {
  if (!has_harbour_ || !in_site(x_m, y_m)) return 0.0;
  if (x_m > full_x0_ && x_m < full_x1_ && y_m > full_y0_ && y_m < full_y1_) return 1.0;
  return site_weight(x_m, y_m, false).weight;
}

SurfaceSampler::EtaAndRate SurfaceSampler::harbour_in_time(double from, double to, double from_rate, double to_rate) const {
  const HermiteWeights& h = hermite_;
  const double T = frame_interval_s_;
  if (!(T > 0.0)) return {(1.0 - harbour_fraction_) * from + harbour_fraction_ * to, 0.0};
  if (!eta_rate_.from) from_rate = to_rate = (to - from) / T;  // the secant: the straight line
  return {h.from * from + h.from_rate * T * from_rate + h.to * to + h.to_rate * T * to_rate,
          (h.d_from * from + h.d_to * to) / T + h.d_from_rate * from_rate + h.d_to_rate * to_rate};
}

double SurfaceSampler::harbour_eta(double x_m, double y_m) const {
  const Tap t = harbour_tap(x_m, y_m, inverse_spacing_x_, inverse_spacing_y_, columns_, rows_);
  if (!eta_rate_.from) return (1.0 - harbour_fraction_) * bilinear(eta_.from, t) + harbour_fraction_ * bilinear(eta_.to, t);
  if (columns_ < 2) return harbour_in_time(bilinear(eta_.from, t), bilinear(eta_.to, t), bilinear(eta_rate_.from, t), bilinear(eta_rate_.to, t)).eta;
  // The Hermite in time and the bilinear in space are both linear in the four rasters: one float
  // vector per row holds {eta_from, rate_from, eta_to, rate_to} at columns i0 and i0 + 1 (adjacent:
  // harbour_tap keeps i1 = i0 + 1 when there are two columns or more), weighted by the Hermite's
  // {h00, h10 T, h01, h11 T} (hermite_by_channel_), then summed: a third of the scalar code's
  // instructions, float round-off (1e-7 of the height) where the scalar sums were in double.
  const auto row = [&](std::size_t i0, Float8& corners) {
    float values[8];
    std::memcpy(values + 0, eta_.from + i0, 2 * sizeof(float));
    std::memcpy(values + 2, eta_rate_.from + i0, 2 * sizeof(float));
    std::memcpy(values + 4, eta_.to + i0, 2 * sizeof(float));
    std::memcpy(values + 6, eta_rate_.to + i0, 2 * sizeof(float));
    std::memcpy(&corners, values, sizeof corners);
  };
  Float8 south, north;
  row(t.i00, south);
  row(t.i01, north);
  Float8 hermite;
  std::memcpy(&hermite, hermite_by_channel_, sizeof hermite);
  const Float8 along_y = (south + static_cast<float>(t.b) * (north - south)) * hermite;
  const float c0 = (along_y[0] + along_y[2]) + (along_y[4] + along_y[6]);
  const float c1 = (along_y[1] + along_y[3]) + (along_y[5] + along_y[7]);
  return c0 + t.a * (c1 - c0);
}

double SurfaceSampler::cascades_eta(const std::vector<Cascade>& cascades, double x_m, double y_m) const {
  double from = 0.0, to = 0.0;
  for (const Cascade& c : cascades) {
    const Tap t = cascade_tap(x_m, y_m, c.inverse_tile_length, c.n);
    from += bilinear(c.from->surface_elevation_m.data(), t);
    to += bilinear(c.to->surface_elevation_m.data(), t);
  }
  return (1.0 - deep_fraction_) * from + deep_fraction_ * to;
}

double SurfaceSampler::deep_eta(double x_m, double y_m) const { return cascades_eta(cascades_, x_m, y_m); }

SurfaceSampler::CascadeSum SurfaceSampler::cascades_sum(const std::vector<Cascade>& cascades, double x_m, double y_m,
                                                        bool with_flux) const {
  const double f = deep_fraction_;
  CascadeSum from, to;
  for (const Cascade& c : cascades) {
    const Tap t = cascade_tap(x_m, y_m, c.inverse_tile_length, c.n);
    for (int which = 0; which < 2; ++which) {
      const ocean::DeepWaterFrame& frame = which == 0 ? *c.from : *c.to;
      CascadeSum& sum = which == 0 ? from : to;
      sum.eta += bilinear(frame.surface_elevation_m.data(), t);
      sum.slope_x += bilinear(frame.slope_x.data(), t);
      sum.slope_y += bilinear(frame.slope_y.data(), t);
      if (with_flux) {
        sum.flux_x += bilinear(frame.flux_x_m2_s.data(), t);
        sum.flux_y += bilinear(frame.flux_y_m2_s.data(), t);
      }
    }
  }
  return {(1.0 - f) * from.eta + f * to.eta, (1.0 - f) * from.slope_x + f * to.slope_x,
          (1.0 - f) * from.slope_y + f * to.slope_y, (1.0 - f) * from.flux_x + f * to.flux_x,
          (1.0 - f) * from.flux_y + f * to.flux_y, (to.eta - from.eta) * inverse_deep_interval_};
}

// One clone per instruction set (the sweep's practice, boussinesq_sweep.cpp): with AVX2 and FMA a
// row's conversion is a permute and a shift, a Float8 one register, and the bilinear's multiply-adds
// fused, about 1.25 x the portable code's rate on the open sea (docs/runtime.md "Measured"). The
// fused clones round differently from the portable one (by float round-off, 1e-7 of a metre): two
// processes on one machine give the same bits; machines of different instruction sets need not
// (the deep water's FFTs already differ there: FFTW picks its kernels per machine).
NEARSHORE_SOLVE_CLONES
void SurfaceSampler::solve_block(const SitePoint* q, int count, Solution* out) const {
  // Formula 4: solve F(p) = p + (1 - w(p)) lambda D(p) - q = 0 from p = q. Newton's method with
  // the exact Jacobian of what is sampled (D bilinear in each cascade tile: its derivative comes
  // from the same four nodes, so a step costs what a fixed-point step costs):
  //   J = I + lambda ((1 - w) grad D - D grad w^T)
  // where J is near singular (a folding crest, det J < 0.2) the step falls back to the fixed
  // point p - F(p). Stops when the residual |F(p)| is at most the tolerance: the surface point
  // returned then lies that close to q, and the sample that measured it gave D_eta(p) too.
  // The points of a block iterate side by side: each sweep first finds every point's taps and
  // asks for their cache lines, then sums them, so the memory latencies of up to kSolveBlock
  // points overlap (one point's solve is a dependent chain: alone it waits on every miss).
  // Field by field: a whole Solution written from a temporary is copied through the stack in
  // overlapping pieces, which stalls the store forwarding (measured: 9 % of the solve).
  const auto set = [out](int i, SitePoint lattice, double deep_eta, double weight, bool has_deep_eta) {
    out[i].lattice = lattice;
    out[i].deep_eta = deep_eta;
    out[i].harbour_weight = weight;
    out[i].has_deep_eta = has_deep_eta;
  };
  for (int i = 0; i < count; ++i) set(i, q[i], 0.0, 0.0, false);
  if (!has_deep_ || choppiness_ == 0.0) return;
  const double lambda = choppiness_;
  const std::size_t cascade_count = packed_.size();
  const std::size_t stored = std::min<std::size_t>(cascade_count, kStoredTaps);
  SitePoint p[kSolveBlock];
  HarbourWeight w[kSolveBlock];
  BlockTap taps[kSolveBlock][kStoredTaps];
  Double2 base[kSolveBlock][kStoredTaps];  // frac(q / L) N of each stored cascade
  int active[kSolveBlock];
  int active_count = 0;
  for (int i = 0; i < count; ++i) {
    p[i] = q[i];
    for (std::size_t c = 0; c < stored; ++c) {
      const PackedCascade& cascade = packed_[c];
      base[i][c] = Double2{texel_of_fraction(q[i].x_m, cascade.inverse_tile_length, cascade.n),
                           texel_of_fraction(q[i].y_m, cascade.inverse_tile_length, cascade.n)};
    }
    active[active_count++] = i;
  }
  const auto tap_of = [&](int i, std::size_t c) {
    const PackedCascade& cascade = packed_[c];
    if (c < stored) return block_tap(base[i][c] + (as_double2(p[i]) - as_double2(q[i])) * cascade.texels_per_m_d, cascade.n);
    return block_tap(Double2{texel_of_fraction(p[i].x_m, cascade.inverse_tile_length, cascade.n),
                             texel_of_fraction(p[i].y_m, cascade.inverse_tile_length, cascade.n)},
                     cascade.n);
  };
  // A step that stays inside the cell of every cascade lands where the sampled field is the same
  // bilinear polynomial as at the sample just taken, so F and D_eta at the new p follow from that
  // sample exactly (f(p + s) = f + f_x s_x + f_y s_y + f_xy s_x s_y, each cascade bilinear in its
  // cell): the check costs no new sample. True when that check passes (out[i] set).
  const auto checked_in_cells = [&](int i, double step_x, double step_y, const PackedSum& sum) {
    if (stored != cascade_count) return false;
    bool inside = true;  // every cascade, without a branch per cascade
    for (std::size_t c = 0; c < stored; ++c) {
      const double a = static_cast<double>(taps[i][c].a) + step_x * packed_[c].texels_per_m_d;
      const double b = static_cast<double>(taps[i][c].b) + step_y * packed_[c].texels_per_m_d;
      inside &= (a >= 0.0) & (a < 1.0) & (b >= 0.0) & (b < 1.0);
    }
    if (!inside) return false;
    double weight = 0.0;
    if (has_harbour_) {
      if (in_full_box(p[i].x_m, p[i].y_m)) return false;
      if (in_site(p[i].x_m, p[i].y_m)) weight = site_weight(p[i].x_m, p[i].y_m, false).weight;
      if (1.0 - weight <= 0.0) return false;
    }
    const double fade = 1.0 - weight;
    const double cross = step_x * step_y;
    const auto at_step = [&](int channel) {
      return sum.value[channel] + sum.d_dx[channel] * step_x + sum.d_dy[channel] * step_y + sum.d_dxdy[channel] * cross;
    };
    const double fx = p[i].x_m + fade * lambda * at_step(0) - q[i].x_m, fy = p[i].y_m + fade * lambda * at_step(1) - q[i].y_m;
    if (fx * fx + fy * fy > kDisplacementTolerance_m * kDisplacementTolerance_m) return false;
    set(i, p[i], at_step(2), weight, true);
    return true;
  };
  for (int iteration = 0; iteration <= kDisplacementIterations && active_count > 0; ++iteration) {
    int kept = 0;
    for (int k = 0; k < active_count; ++k) {
      const int i = active[k];
      w[i] = {};
      if (has_harbour_) {
        // Inside the full-weight box, or wherever w reaches 1, nothing moves: p = q.
        if (in_full_box(p[i].x_m, p[i].y_m)) {
          set(i, q[i], 0.0, 0.0, false);
          continue;
        }
        // Off the site w = 0 (surface_snapshot.cpp site_ramps): no call for the open sea's points.
        if (in_site(p[i].x_m, p[i].y_m)) w[i] = site_weight(p[i].x_m, p[i].y_m, true);
        if (1.0 - w[i].weight <= 0.0) {
          set(i, q[i], 0.0, 0.0, false);
          continue;
        }
      }
      for (std::size_t c = 0; c < stored; ++c) {
        const PackedCascade& cascade = packed_[c];
        const BlockTap& t = taps[i][c] = tap_of(i, c);
        __builtin_prefetch(cascade.from + 4 * t.row0);
        __builtin_prefetch(cascade.from + 4 * t.row1);
        __builtin_prefetch(cascade.to + 4 * t.row0);
        __builtin_prefetch(cascade.to + 4 * t.row1);
      }
      active[kept++] = i;
    }
    active_count = kept;
    kept = 0;
    PackedSum sums[kSolveBlock];
    for (int k = 0; k < active_count; ++k) sums[k].value = sums[k].d_dx = sums[k].d_dy = sums[k].d_dxdy = Float4{0, 0, 0, 0};
    // Cascade by cascade across the block: each iteration of the inner loop is independent of the
    // others, so the processor overlaps several points' loads and arithmetic (one point's sample
    // is a dependent chain).
    for (std::size_t c = 0; c < cascade_count; ++c) {
      const PackedCascade& cascade = packed_[c];
      const Float8 wf = load_weights(cascade.from_weight), wt = load_weights(cascade.to_weight);
      const float texels_per_m_squared = cascade.texels_per_m * cascade.texels_per_m;
      for (int k = 0; k < active_count; ++k) {
        const int i = active[k];
        PackedSum& sum = sums[k];
        const BlockTap t = c < stored ? taps[i][c] : tap_of(i, c);
        const Float8 south = load_row(cascade.from, t.row0) * wf + load_row(cascade.to, t.row0) * wt;  // (i0, j0), (i1, j0)
        const Float8 north = load_row(cascade.from, t.row1) * wf + load_row(cascade.to, t.row1) * wt;  // (i0, j1), (i1, j1)
        // Along y first, both columns at once: C = (c0 | c1) = south + b (north - south); then the
        // value c0 + a (c1 - c0), d/dx = (c1 - c0) N / L, d/dy from the rise north - south taken
        // across x the same way, and the cross term d2/dxdy from the two columns' rises.
        const Float8 rise = north - south;
        const Float8 along_y = south + t.b * rise;
        const Float4 c0 = low_half(along_y), across = high_half(along_y) - c0;
        const Float4 rise0 = low_half(rise), rise_across = high_half(rise) - rise0;
        sum.value += c0 + t.a * across;
        sum.d_dx += across * cascade.texels_per_m;
        sum.d_dy += (rise0 + t.a * rise_across) * cascade.texels_per_m;
        sum.d_dxdy += rise_across * texels_per_m_squared;
      }
    }
    for (int k = 0; k < active_count; ++k) {
      const int i = active[k];
      const PackedSum& sum = sums[k];
      const double fade = 1.0 - w[i].weight;
      const double dx = sum.value[0], dy = sum.value[1];
      const double fx = p[i].x_m + fade * lambda * dx - q[i].x_m, fy = p[i].y_m + fade * lambda * dy - q[i].y_m;
      if (fx * fx + fy * fy <= kDisplacementTolerance_m * kDisplacementTolerance_m) {
        set(i, p[i], sum.value[2], w[i].weight, true);
        continue;
      }
      if (iteration == kDisplacementIterations) {
        set(i, p[i], 0.0, 0.0, false);
        continue;
      }
      const double dxx = sum.d_dx[0], dxy = sum.d_dy[0], dyx = sum.d_dx[1], dyy = sum.d_dy[1];
      const HarbourWeight& wi = w[i];
      const double jxx = 1.0 + lambda * (fade * dxx - dx * wi.d_dx_per_m), jxy = lambda * (fade * dxy - dx * wi.d_dy_per_m);
      const double jyx = lambda * (fade * dyx - dy * wi.d_dx_per_m), jyy = 1.0 + lambda * (fade * dyy - dy * wi.d_dy_per_m);
      const double det = jxx * jyy - jxy * jyx;
      double step_x, step_y;
      if (det > 0.2) {
        step_x = -(jyy * fx - jxy * fy) / det;
        step_y = -(-jyx * fx + jxx * fy) / det;
      } else {
        step_x = -fx;
        step_y = -fy;
      }
      p[i].x_m += step_x;
      p[i].y_m += step_y;
      // After the first step (a jump across many cells of the finest cascade) the next usually
      // stays in every cell: checked without a new sample.
      if (iteration > 0 && checked_in_cells(i, step_x, step_y, sum)) continue;
      active[kept++] = i;
    }
    active_count = kept;
  }
}

SurfaceSampler::Solution SurfaceSampler::solve(double x_m, double y_m) const {
  const SitePoint q{x_m, y_m};
  Solution solution;
  solve_block(&q, 1, &solution);
  return solution;
}

SitePoint SurfaceSampler::lattice_point(double x_m, double y_m) const { return solve(x_m, y_m).lattice; }

double SurfaceSampler::harbour_elevation_m(double x_m, double y_m) const {
  return has_harbour_ ? harbour_eta(x_m, y_m) : 0.0;
}

double SurfaceSampler::deep_elevation_m(double x_m, double y_m) const { return has_deep_ ? deep_eta(x_m, y_m) : 0.0; }

double SurfaceSampler::inside_elevation_m(double x_m, double y_m) const {
  return has_inside_ ? cascades_eta(inside_, x_m, y_m) : 0.0;
}

double SurfaceSampler::elevation_m(double x_m, double y_m, ChoppyPoint point) const {
  if (point == ChoppyPoint::kDisplaced) return elevation_at_solution(solve(x_m, y_m));
  return elevation_at_lattice({x_m, y_m});
}

double SurfaceSampler::elevation_at_solution(const Solution& solution) const {
  if (!solution.has_deep_eta) return elevation_at_lattice(solution.lattice);
  // elevation_at_lattice with D_eta from the solve's last sample (the query layout: equal to
  // the float channels' sum within its int16 rounding, surface_sampler.hpp formula 4).
  // w at p too, from the solve (what weight(p) gives: p lies off the full-weight box).
  const SitePoint p = solution.lattice;
  const double w = solution.harbour_weight;
  double eta = 0.0;
  if (w > 0.0) eta += w * harbour_eta(p.x_m, p.y_m);
  if (w > 0.0 && has_inside_) eta += w * cascades_eta(inside_, p.x_m, p.y_m);
  if (w < 1.0) eta += (1.0 - w) * solution.deep_eta;
  return eta;
}

double SurfaceSampler::elevation_at_lattice(SitePoint p) const {
  const double w = weight(p.x_m, p.y_m);
  double eta = 0.0;
  if (w > 0.0) eta += w * harbour_eta(p.x_m, p.y_m);
  if (w > 0.0 && has_inside_) eta += w * cascades_eta(inside_, p.x_m, p.y_m);
  if (w < 1.0 && has_deep_) eta += (1.0 - w) * deep_eta(p.x_m, p.y_m);
  return eta;
}

void SurfaceSampler::elevations_m(std::span<const SitePoint> points, std::span<double> out, ChoppyPoint point) const {
  if (out.size() < points.size())
    throw Error("SurfaceSampler::elevations_m", fmt::format("{} points but room for {} results", points.size(), out.size()),
                "give an output span at least as long as the points");
  if (point == ChoppyPoint::kLattice) {
    for (std::size_t i = 0; i < points.size(); ++i) out[i] = elevation_at_lattice(points[i]);
    return;
  }
  // Blocks of points solved side by side (solve_block): the same arithmetic per point as a single
  // query, so a batch gives the single calls' heights bit for bit, in any order.
  // Points inside the full-weight box (p = q at once, what solve_block would say) skip the block.
  Solution solutions[kSolveBlock];
  SitePoint block[kSolveBlock];
  std::size_t index[kSolveBlock];
  int count = 0;
  const auto flush = [&] {
    solve_block(block, count, solutions);
    for (int i = 0; i < count; ++i) out[index[i]] = elevation_at_solution(solutions[i]);
    count = 0;
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SitePoint q = points[i];
    if (in_full_box(q.x_m, q.y_m)) {
      out[i] = elevation_at_lattice(q);
      continue;
    }
    block[count] = q;
    index[count++] = i;
    if (count == kSolveBlock) flush();
  }
  if (count > 0) flush();
}

SurfaceState SurfaceSampler::state(double x_m, double y_m, ChoppyPoint point) const {
  const SitePoint p = point == ChoppyPoint::kDisplaced ? solve(x_m, y_m).lattice : SitePoint{x_m, y_m};
  SurfaceState s;
  HarbourWeight w;
  if (has_harbour_) w = harbour_weight_and_gradient(*snapshot_.site, p.x_m, p.y_m);
  s.harbour_weight = w.weight;
  double harbour_eta_m = 0.0, deep_eta_m = 0.0;
  double harbour_u = 0.0, harbour_v = 0.0, deep_u = 0.0, deep_v = 0.0, harbour_rate = 0.0, deep_rate = 0.0;
  Gradient harbour_slope, deep_slope;
  if (w.weight > 0.0) {
    const Tap t = harbour_tap(p.x_m, p.y_m, inverse_spacing_x_, inverse_spacing_y_, columns_, rows_);
    const double f = harbour_fraction_;
    const double eta_from = bilinear(eta_.from, t), eta_to = bilinear(eta_.to, t);
    const EtaAndRate in_time = eta_rate_.from ? harbour_in_time(eta_from, eta_to, bilinear(eta_rate_.from, t), bilinear(eta_rate_.to, t))
                                              : harbour_in_time(eta_from, eta_to, 0.0, 0.0);
    // The height as elevation_m gives it (harbour_eta: the same bits), the rate from the Hermite.
    harbour_eta_m = harbour_eta(p.x_m, p.y_m);
    harbour_rate = in_time.rate;
    const Gradient a = bilinear_gradient(eta_.from, t, columns_, rows_, spacing_x_m_, spacing_y_m_);
    const Gradient b = bilinear_gradient(eta_.to, t, columns_, rows_, spacing_x_m_, spacing_y_m_);
    harbour_slope = {(1.0 - f) * a.x + f * b.x, (1.0 - f) * a.y + f * b.y};
    // Formula 5: dry where the cell is land or the total depth is at most the dry depth.
    const int column = std::clamp(static_cast<int>(std::floor(p.x_m * inverse_spacing_x_)), 0, columns_ - 1);
    const int row = std::clamp(static_cast<int>(std::floor(p.y_m * inverse_spacing_y_)), 0, rows_ - 1);
    const bool land = land_ && land_[static_cast<std::size_t>(row) * static_cast<std::size_t>(columns_) + column] != 0;
    const double depth_m = depth_ ? bilinear(depth_, t) : 0.0;
    const double total_depth_m = depth_m + harbour_eta_m;
    s.dry = land || total_depth_m <= snapshot_.site->dry_depth_m;
    if (!s.dry && flux_x_.from && flux_x_.to && flux_y_.from && flux_y_.to) {
      harbour_u = ((1.0 - f) * bilinear(flux_x_.from, t) + f * bilinear(flux_x_.to, t)) / total_depth_m;
      harbour_v = ((1.0 - f) * bilinear(flux_y_.from, t) + f * bilinear(flux_y_.to, t)) / total_depth_m;
    }
  }
  if (w.weight > 0.0 && has_inside_) {
    // The split's inside layer rides on the harbour's part (formulas 3, 5, 6).
    const CascadeSum inside = cascades_sum(inside_, p.x_m, p.y_m, has_inside_flux_);
    harbour_eta_m += inside.eta;
    harbour_rate += inside.eta_rate;
    harbour_slope.x += inside.slope_x;
    harbour_slope.y += inside.slope_y;
    const double total_depth_m = snapshot_.deep_from->still_water_depth_m + inside.eta;
    if (!s.dry && has_inside_flux_ && total_depth_m > 0.0) {
      harbour_u += inside.flux_x / total_depth_m;
      harbour_v += inside.flux_y / total_depth_m;
    }
  }
  if (w.weight < 1.0 && has_deep_) {
    const CascadeSum deep = cascades_sum(cascades_, p.x_m, p.y_m, has_deep_flux_);
    deep_eta_m = deep.eta;
    deep_rate = deep.eta_rate;
    deep_slope = {deep.slope_x, deep.slope_y};
    if (has_deep_flux_) {
      const double total_depth_m = snapshot_.deep_from->still_water_depth_m + deep_eta_m;
      if (total_depth_m > 0.0) {
        deep_u = deep.flux_x / total_depth_m;
        deep_v = deep.flux_y / total_depth_m;
      }
    }
  }
  const double ww = w.weight;
  s.surface_elevation_m = ww * harbour_eta_m + (1.0 - ww) * deep_eta_m;
  s.vertical_velocity_m_s = ww * harbour_rate + (1.0 - ww) * deep_rate;
  s.velocity_x_m_s = ww * harbour_u + (1.0 - ww) * deep_u;
  s.velocity_y_m_s = ww * harbour_v + (1.0 - ww) * deep_v;
  s.slope_x = ww * harbour_slope.x + (1.0 - ww) * deep_slope.x + (harbour_eta_m - deep_eta_m) * w.d_dx_per_m;
  s.slope_y = ww * harbour_slope.y + (1.0 - ww) * deep_slope.y + (harbour_eta_m - deep_eta_m) * w.d_dy_per_m;
  const double norm = std::sqrt(1.0 + s.slope_x * s.slope_x + s.slope_y * s.slope_y);
  s.normal_x = -s.slope_x / norm;
  s.normal_y = -s.slope_y / norm;
  s.normal_z = 1.0 / norm;
  if (ww <= 0.0) s.dry = false;
  return s;
}

void SurfaceSampler::states(std::span<const SitePoint> points, std::span<SurfaceState> out, ChoppyPoint point) const {
  if (out.size() < points.size())
    throw Error("SurfaceSampler::states", fmt::format("{} points but room for {} results", points.size(), out.size()),
                "give an output span at least as long as the points");
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = state(points[i].x_m, points[i].y_m, point);
}

}  // namespace nearshore::runtime
