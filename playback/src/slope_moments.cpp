#include "nearshore/playback/slope_moments.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace nearshore::playback {

namespace {

// Per coarse sample of one axis (n fine samples to m = max(1, n / 2)), the fine samples it
// averages and their weights, in the order they are summed. An even n halves by plain means
// (samples 2k, 2k + 1, each 1/2); an odd n (m < n / 2) by the exact box filter: sample k
// averages [k n / m, (k + 1) n / m) of the fine ones weighted by overlap (up to 4 taps: a window
// of 2 + 1/m samples starting between two). Both give the same weights where both apply (the box
// of an even n is the 2-tap mean), so the pyramid is the box filter's at every size.
struct AxisTaps {
  static constexpr int kMaxTaps = 4;
  std::vector<int> first;       // per coarse sample: its first fine sample
  std::vector<int> count;       // how many
  std::vector<double> weights;  // kMaxTaps per coarse sample
};
AxisTaps halving_taps(int n, int m) {
  AxisTaps taps;
  taps.first.assign(std::size_t(m), 0);
  taps.count.assign(std::size_t(m), 0);
  taps.weights.assign(std::size_t(m) * AxisTaps::kMaxTaps, 0.0);
  if (n == 2 * m) {
    for (int k = 0; k < m; ++k) {
      taps.first[std::size_t(k)] = 2 * k;
      taps.count[std::size_t(k)] = 2;
      taps.weights[std::size_t(k) * AxisTaps::kMaxTaps] = taps.weights[std::size_t(k) * AxisTaps::kMaxTaps + 1] = 0.5;
    }
    return taps;
  }
  const double ratio = double(n) / double(m);
  for (int k = 0; k < m; ++k) {
    const double low = k * ratio, high = (k + 1) * ratio;
    int& count = taps.count[std::size_t(k)];
    for (int i = int(std::floor(low)); i < n && i < high; ++i) {
      const double overlap = std::min(high, double(i + 1)) - std::max(low, double(i));
      if (overlap <= 0.0) continue;
      if (count == 0) taps.first[std::size_t(k)] = i;
      taps.weights[std::size_t(k) * AxisTaps::kMaxTaps + count++] = overlap / ratio;
    }
  }
  return taps;
}

// The next level: coarse row l sums its fine rows' x-halved rows (each summed from 0 in tap
// order) weighted along y, in double, then rounds to float: the separable box filter, x first.
// Row by row, so the x-halved rows stay in cache (no level-sized buffer of doubles); a fine row
// two coarse rows share (odd heights) is halved once.
void halve(const SlopeMomentLevel& fine, int columns, int rows, SlopeMomentLevel& coarse) {
  coarse.columns = columns;
  coarse.rows = rows;
  coarse.texels.resize(std::size_t(columns) * rows * 4);
  const AxisTaps along_x = halving_taps(fine.columns, columns), along_y = halving_taps(fine.rows, rows);
  const bool x_by_means = fine.columns == 2 * columns;
  const std::size_t width = std::size_t(columns) * 4;
  std::vector<double> sums(width), halved_row(width), previous_row(width);
  int previous_j = -1;
  const auto halve_row = [&](int j, std::vector<double>& out) {
    const float* row = &fine.texels[std::size_t(j) * fine.columns * 4];
    if (x_by_means) {
      for (std::size_t k = 0; k < std::size_t(columns); ++k)
        for (std::size_t c = 0; c < 4; ++c) {
          double sum = 0.0;  // from 0, in tap order, as the general filter below sums
          sum += 0.5 * double(row[8 * k + c]);
          sum += 0.5 * double(row[8 * k + 4 + c]);
          out[4 * k + c] = sum;
        }
      return;
    }
    for (std::size_t k = 0; k < std::size_t(columns); ++k) {
      const float* first = row + std::size_t(along_x.first[k]) * 4;
      const double* weights = &along_x.weights[k * AxisTaps::kMaxTaps];
      for (std::size_t c = 0; c < 4; ++c) {
        double sum = 0.0;
        for (int t = 0; t < along_x.count[k]; ++t) sum += weights[t] * double(first[4 * t + c]);
        out[4 * k + c] = sum;
      }
    }
  };
  for (int l = 0; l < rows; ++l) {
    std::fill(sums.begin(), sums.end(), 0.0);
    const int taps = along_y.count[std::size_t(l)];
    for (int t = 0; t < taps; ++t) {
      const int j = along_y.first[std::size_t(l)] + t;
      const double weight = along_y.weights[std::size_t(l) * AxisTaps::kMaxTaps + t];
      const std::vector<double>* row = &previous_row;
      if (j != previous_j) {
        halve_row(j, halved_row);
        row = &halved_row;
      }
      for (std::size_t e = 0; e < width; ++e) sums[e] += weight * (*row)[e];
      if (t == taps - 1 && row == &halved_row) {  // the next coarse row may start on it
        std::swap(previous_row, halved_row);
        previous_j = j;
      }
    }
    float* out = &coarse.texels[std::size_t(l) * width];
    for (std::size_t e = 0; e < width; ++e) out[e] = float(sums[e]);
  }
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
  slope_moment_pyramid(eta, pyramid);
  return pyramid;
}

void slope_moment_pyramid(const Raster<float>& eta, std::vector<SlopeMomentLevel>& pyramid) {
  const int n = eta.columns(), m = eta.rows();
  const auto sizes = slope_moment_level_sizes(n, m);
  pyramid.resize(sizes.size());  // the levels' storage kept where it is (resize reuses it)
  if (sizes.empty()) return;
  SlopeMomentLevel& base = pyramid.front();
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
  for (std::size_t level = 1; level < sizes.size(); ++level)
    halve(pyramid[level - 1], sizes[level].first, sizes[level].second, pyramid[level]);
}

std::vector<std::pair<int, int>> slope_moment_level_sizes(int columns, int rows) {
  std::vector<std::pair<int, int>> sizes;
  if (columns <= 0 || rows <= 0) return sizes;
  sizes.emplace_back(columns, rows);
  while (columns > 1 || rows > 1) {
    columns = std::max(1, columns / 2);
    rows = std::max(1, rows / 2);
    sizes.emplace_back(columns, rows);
  }
  return sizes;
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
