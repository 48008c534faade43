#include "nearshore/runtime/surface_snapshot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"
#include "harbour_ramp.hpp"

namespace nearshore::runtime {

namespace {
using detail::Ramp;
using detail::sin2_ramp;

// The weight of a site point is the product of the maker's ramp (along the source axis, inland of
// the source line) and the three other edges' fades; the source side's edge takes no fade (it
// fades by the record). Written as the source ramp times an x pair (west, east) and a y pair
// (south, north), so the product rule's gradient is three terms, with no arrays to clear (perf:
// the cleared arrays and loops of the general product cost more than the sines).
struct SiteRamps {
  Ramp source, west, east, south, north;
};
bool site_ramps(const HarbourSite& site, double x_m, double y_m, bool with_slope, SiteRamps& r) {
  if (x_m < 0.0 || y_m < 0.0 || x_m > site.width_m || y_m > site.height_m) return false;
  const double along = site.source_axis == 0 ? x_m : y_m;
  // Distance inland of the source line along the maker's inward normal.
  const double inland = site.inward_sign * (along - site.source_line_m);
  r.source = sin2_ramp(inland - site.blend_start_m, site.blend_width_m, with_slope);
  const Ramp none{1.0, 0.0};
  // Farther than the fade from every edge (most of the site) the four fades are 1: one test
  // instead of four ramps (sin2_ramp gives 1 exactly where s >= width > 0; a NaN fails the test
  // and takes the ramps).
  const double fade = site.edge_fade_m;
  if (fade > 0.0 && x_m >= fade && y_m >= fade && site.width_m - x_m >= fade && site.height_m - y_m >= fade) {
    r.west = r.east = r.south = r.north = none;
    return true;
  }
  const int source_edge = site.source_axis == 0 ? (site.inward_sign > 0 ? 0 : 1) : (site.inward_sign > 0 ? 2 : 3);
  r.west = source_edge == 0 ? none : sin2_ramp(x_m, site.edge_fade_m, with_slope);
  r.east = source_edge == 1 ? none : sin2_ramp(site.width_m - x_m, site.edge_fade_m, with_slope);
  r.south = source_edge == 2 ? none : sin2_ramp(y_m, site.edge_fade_m, with_slope);
  r.north = source_edge == 3 ? none : sin2_ramp(site.height_m - y_m, site.edge_fade_m, with_slope);
  return true;
}
}  // namespace

double harbour_weight(const HarbourSite& site, double x_m, double y_m) {
  SiteRamps r;
  if (!site_ramps(site, x_m, y_m, false, r)) return 0.0;
  return r.source.value * (r.west.value * r.east.value) * (r.south.value * r.north.value);
}

HarbourWeight harbour_weight_and_gradient(const HarbourSite& site, double x_m, double y_m) {
  SiteRamps r;
  HarbourWeight result;
  if (!site_ramps(site, x_m, y_m, true, r)) return result;
  const double across_x = r.west.value * r.east.value, across_y = r.south.value * r.north.value;
  result.weight = r.source.value * across_x * across_y;
  // Product rule; the east and north ramps' arguments fall as x and y grow.
  const double source_slope = r.source.slope * site.inward_sign * across_x * across_y;
  result.d_dx_per_m = r.source.value * (r.west.slope * r.east.value - r.west.value * r.east.slope) * across_y;
  result.d_dy_per_m = r.source.value * across_x * (r.south.slope * r.north.value - r.south.value * r.north.slope);
  (site.source_axis == 0 ? result.d_dx_per_m : result.d_dy_per_m) += source_slope;
  return result;
}

void pack_query_tile(const ocean::DeepWaterFrame& frame, QueryTile& tile) {
  tile.grid_size = frame.grid_size;
  tile.tile_length_m = frame.tile_length_m;
  const std::size_t nodes = frame.surface_elevation_m.size();
  const bool displaced = frame.displacement_x_m.size() == nodes && frame.displacement_y_m.size() == nodes;
  const float* channels[3] = {displaced ? frame.displacement_x_m.data() : nullptr,
                              displaced ? frame.displacement_y_m.data() : nullptr, frame.surface_elevation_m.data()};
  float inverse[3] = {0.0f, 0.0f, 0.0f};
  for (int k = 0; k < 4; ++k) tile.scale[k] = 0.0f;
  for (int k = 0; k < 3; ++k) {
    if (!channels[k]) continue;
    float largest = 0.0f;
    for (std::size_t i = 0; i < nodes; ++i) largest = std::max(largest, std::abs(channels[k][i]));
    if (!(largest > 0.0f) || !std::isfinite(largest)) continue;  // a zero (or broken) channel stays 0
    // value = scale x integer with the float scale the sampler reads; |value| / scale <= 32767.
    tile.scale[k] = largest / 32767.0f;
    inverse[k] = 1.0f / tile.scale[k];
  }
  // Rows of N + 1 nodes: node N repeats node 0 of its row (the tile is periodic), so the two nodes
  // of a tap's row, (i0, j) and (i0 + 1, j), are always 16 bytes side by side: one load.
  const std::size_t n = static_cast<std::size_t>(std::max(frame.grid_size, 0));
  if (n * n != nodes)
    throw Error("query tile", fmt::format("a cascade of grid size {} holds {} nodes", frame.grid_size, nodes),
                "give a deep-water frame whose channels hold grid_size^2 nodes");
  tile.nodes.resize(4 * (n + 1) * n);  // keeps a pooled keyframe's allocation
  std::int16_t* out = tile.nodes.data();
  // Rounded to nearest (half away from 0), clamped against the 1-ulp overshoot of v / scale.
  // A NaN (a broken synthesis) becomes 0 rather than an undefined conversion.
  const auto quantise = [](float v, float inverse_scale) {
    const float r = v * inverse_scale;
    return static_cast<std::int16_t>(r == r ? std::clamp(r + (r >= 0.0f ? 0.5f : -0.5f), -32767.0f, 32767.0f) : 0.0f);
  };
  const float* eta = channels[2];
  const float* dx = channels[0];
  const float* dy = channels[1];
  for (std::size_t row = 0; row < n; ++row)
    for (std::size_t column = 0; column <= n; ++column) {
      const std::size_t i = row * n + (column == n ? 0 : column);
      std::int16_t* node = out + 4 * (row * (n + 1) + column);
      node[0] = displaced ? quantise(dx[i], inverse[0]) : std::int16_t{0};
      node[1] = displaced ? quantise(dy[i], inverse[1]) : std::int16_t{0};
      node[2] = quantise(eta[i], inverse[2]);
      node[3] = 0;
    }
}

void pack_query_tiles(DeepWaterKeyframe& keyframe) {
  std::size_t count = 0;
  for (const ocean::DeepWaterFrame& frame : keyframe.cascades) count += frame.surface_elevation_m.empty() ? 0 : 1;
  keyframe.query_tiles.resize(count);
  std::size_t next = 0;
  for (const ocean::DeepWaterFrame& frame : keyframe.cascades)
    if (!frame.surface_elevation_m.empty()) pack_query_tile(frame, keyframe.query_tiles[next++]);
}

}  // namespace nearshore::runtime
