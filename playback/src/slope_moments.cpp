#include "nearshore/playback/slope_moments.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace nearshore::playback {

namespace {

// One axis of the box filter: n samples to m, sample k averaging [k n / m, (k + 1) n / m) of
// the fine ones by overlap. Returns (index, weight) lists per coarse sample.
std::vector<std::vector<std::pair<int, double>>> box_weights(int n, int m) {
  std::vector<std::vector<std::pair<int, double>>> weights(static_cast<std::size_t>(m));
  const double ratio = double(n) / double(m);
  for (int k = 0; k < m; ++k) {
    const double low = k * ratio, high = (k + 1) * ratio;
    for (int i = int(std::floor(low)); i < n && i < high; ++i) {
      const double overlap = std::min(high, double(i + 1)) - std::max(low, double(i));
      if (overlap > 0.0) weights[std::size_t(k)].emplace_back(i, overlap / ratio);
    }
  }
  return weights;
}

SlopeMomentLevel halved(const SlopeMomentLevel& fine) {
  SlopeMomentLevel coarse;
  coarse.columns = std::max(1, fine.columns / 2);
  coarse.rows = std::max(1, fine.rows / 2);
  const auto along_x = box_weights(fine.columns, coarse.columns), along_y = box_weights(fine.rows, coarse.rows);
  // x first (fine rows, coarse columns), then y
  std::vector<double> rows_done(std::size_t(coarse.columns) * fine.rows * 4, 0.0);
  for (int j = 0; j < fine.rows; ++j)
    for (int k = 0; k < coarse.columns; ++k)
      for (const auto& [i, w] : along_x[std::size_t(k)])
        for (int c = 0; c < 4; ++c)
          rows_done[(std::size_t(j) * coarse.columns + k) * 4 + c] += w * fine.texels[(std::size_t(j) * fine.columns + i) * 4 + c];
  coarse.texels.assign(std::size_t(coarse.columns) * coarse.rows * 4, 0.f);
  for (int l = 0; l < coarse.rows; ++l)
    for (int k = 0; k < coarse.columns; ++k) {
      double sum[4] = {0, 0, 0, 0};
      for (const auto& [j, w] : along_y[std::size_t(l)])
        for (int c = 0; c < 4; ++c) sum[c] += w * rows_done[(std::size_t(j) * coarse.columns + k) * 4 + c];
      for (int c = 0; c < 4; ++c) coarse.texels[(std::size_t(l) * coarse.columns + k) * 4 + c] = float(sum[c]);
    }
  return coarse;
}

std::array<double, 4> bilinear(const SlopeMomentLevel& level, double u, double v) {
  const double x = u * level.columns - 0.5, y = v * level.rows - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double wx = x - fx, wy = y - fy;
  const auto texel = [&](int i, int j, int c) {
    i = std::clamp(i, 0, level.columns - 1);
    j = std::clamp(j, 0, level.rows - 1);
    return double(level.texels[(std::size_t(j) * level.columns + i) * 4 + c]);
  };
  std::array<double, 4> out{};
  const int i0 = int(fx), j0 = int(fy);
  for (int c = 0; c < 4; ++c)
    out[std::size_t(c)] = (1 - wy) * ((1 - wx) * texel(i0, j0, c) + wx * texel(i0 + 1, j0, c)) +
                          wy * ((1 - wx) * texel(i0, j0 + 1, c) + wx * texel(i0 + 1, j0 + 1, c));
  return out;
}

}  // namespace

std::vector<SlopeMomentLevel> slope_moment_pyramid(const Raster<float>& eta) {
  std::vector<SlopeMomentLevel> pyramid;
  const int n = eta.columns(), m = eta.rows();
  if (n <= 0 || m <= 0) return pyramid;
  SlopeMomentLevel base;
  base.columns = n;
  base.rows = m;
  base.texels.resize(std::size_t(n) * m * 4);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const float gx = 0.5f * (eta(std::min(i + 1, n - 1), j) - eta(std::max(i - 1, 0), j));
      const float gy = 0.5f * (eta(i, std::min(j + 1, m - 1)) - eta(i, std::max(j - 1, 0)));
      float* t = &base.texels[(std::size_t(j) * n + i) * 4];
      t[0] = gx;
      t[1] = gy;
      t[2] = gx * gx;
      t[3] = gy * gy;
    }
  pyramid.push_back(std::move(base));
  while (pyramid.back().columns > 1 || pyramid.back().rows > 1) pyramid.push_back(halved(pyramid.back()));
  return pyramid;
}

double baked_slope_lod(double footprint_m, double cell_m) {
  if (!(footprint_m > cell_m) || !(cell_m > 0.0)) return 0.0;
  return std::log2(footprint_m / cell_m);
}

std::array<double, 4> sample_slope_moments(const std::vector<SlopeMomentLevel>& pyramid, double u, double v, double lod) {
  if (pyramid.empty()) return {0, 0, 0, 0};
  const double last = double(pyramid.size() - 1);
  lod = std::clamp(lod, 0.0, last);
  const int low = int(std::floor(lod));
  const int high = std::min(low + 1, int(last));
  const double f = lod - low;
  const auto a = bilinear(pyramid[std::size_t(low)], u, v), b = bilinear(pyramid[std::size_t(high)], u, v);
  std::array<double, 4> out{};
  for (std::size_t c = 0; c < 4; ++c) out[c] = (1 - f) * a[c] + f * b[c];
  return out;
}

FilteredSlope filtered_baked_slope(const std::array<double, 4>& from, const std::array<double, 4>& to, double fraction,
                                   double spacing_x_m, double spacing_y_m) {
  const double f = fraction;
  FilteredSlope s;
  s.slope_x = ((1 - f) * from[0] + f * to[0]) / spacing_x_m;
  s.slope_y = ((1 - f) * from[1] + f * to[1]) / spacing_y_m;
  const double variance_x = ((1 - f) * (from[2] - from[0] * from[0]) + f * (to[2] - to[0] * to[0])) / (spacing_x_m * spacing_x_m);
  const double variance_y = ((1 - f) * (from[3] - from[1] * from[1]) + f * (to[3] - to[1] * to[1])) / (spacing_y_m * spacing_y_m);
  s.variance_per_axis = std::max(0.5 * (variance_x + variance_y), 0.0);
  return s;
}

}  // namespace nearshore::playback
