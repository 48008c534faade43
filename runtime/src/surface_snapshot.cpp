#include "nearshore/runtime/surface_snapshot.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"

namespace nearshore::runtime {

namespace {
// sin^2 ramp from 0 at s = 0 to 1 at s = width (the bake's blending record's rule), and its
// derivative d/ds. Flat parts return without a sine: most query points lie there.
struct Ramp {
  double value = 0.0, slope = 0.0;
};
Ramp sin2_ramp(double s, double width, bool with_slope) {
  if (width <= 0.0) return {s > 0.0 ? 1.0 : 0.0, 0.0};
  if (s <= 0.0) return {0.0, 0.0};
  if (s >= width) return {1.0, 0.0};
  const double half_angle = 0.5 * std::numbers::pi * s / width;
  const double r = std::sin(half_angle);
  // d/ds sin^2(pi s / 2 W) = (pi / 2 W) sin(pi s / W) = (pi / W) sin cos of the half angle.
  return {r * r, with_slope ? std::numbers::pi / width * r * std::cos(half_angle) : 0.0};
}

// The ramps of a site point: the maker's (along the source axis) and the three other edges'.
// d_dx[i], d_dy[i]: how ramp i's argument changes with x and y.
struct Ramps {
  Ramp ramp[4];
  double d_dx[4] = {0, 0, 0, 0}, d_dy[4] = {0, 0, 0, 0};
  int count = 0;
};
bool site_ramps(const HarbourSite& site, double x_m, double y_m, bool with_slope, Ramps& ramps) {
  if (x_m < 0.0 || y_m < 0.0 || x_m > site.width_m || y_m > site.height_m) return false;
  const double along = site.source_axis == 0 ? x_m : y_m;
  // Distance inland of the source line along the maker's inward normal.
  const double inland = site.inward_sign * (along - site.source_line_m);
  ramps.ramp[0] = sin2_ramp(inland - site.blend_start_m, site.blend_width_m, with_slope);
  (site.source_axis == 0 ? ramps.d_dx[0] : ramps.d_dy[0]) = site.inward_sign;
  ramps.count = 1;
  // The three other edges fade over edge_fade_m (the source side fades by the record above).
  const double distances[4] = {x_m, site.width_m - x_m, y_m, site.height_m - y_m};  // west, east, south, north
  const double along_x[4] = {1.0, -1.0, 0.0, 0.0}, along_y[4] = {0.0, 0.0, 1.0, -1.0};
  const int source_edge = site.source_axis == 0 ? (site.inward_sign > 0 ? 0 : 1) : (site.inward_sign > 0 ? 2 : 3);
  for (int edge = 0; edge < 4; ++edge) {
    if (edge == source_edge) continue;
    ramps.ramp[ramps.count] = sin2_ramp(distances[edge], site.edge_fade_m, with_slope);
    ramps.d_dx[ramps.count] = along_x[edge];
    ramps.d_dy[ramps.count] = along_y[edge];
    ++ramps.count;
  }
  return true;
}
}  // namespace

double harbour_weight(const HarbourSite& site, double x_m, double y_m) {
  Ramps ramps;
  if (!site_ramps(site, x_m, y_m, false, ramps)) return 0.0;
  double weight = 1.0;
  for (int i = 0; i < ramps.count; ++i) weight *= ramps.ramp[i].value;
  return weight;
}

HarbourWeight harbour_weight_and_gradient(const HarbourSite& site, double x_m, double y_m) {
  Ramps ramps;
  HarbourWeight result;
  if (!site_ramps(site, x_m, y_m, true, ramps)) return result;
  result.weight = 1.0;
  for (int i = 0; i < ramps.count; ++i) result.weight *= ramps.ramp[i].value;
  // Product rule: d(prod r_i) = sum_i (prod_{j != i} r_j) dr_i.
  for (int i = 0; i < ramps.count; ++i) {
    if (ramps.ramp[i].slope == 0.0) continue;
    double others = 1.0;
    for (int j = 0; j < ramps.count; ++j)
      if (j != i) others *= ramps.ramp[j].value;
    result.d_dx_per_m += others * ramps.ramp[i].slope * ramps.d_dx[i];
    result.d_dy_per_m += others * ramps.ramp[i].slope * ramps.d_dy[i];
  }
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
