// The slope moments' pyramid and its sampler (playback/slope_moments.hpp): the CPU side of the
// baked field's filtered slopes, which the renderer uploads as they are and the shader samples
// with textureLod (tests/playback/baked_slope_render_test.cpp compares the two).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "nearshore/playback/slope_moments.hpp"

namespace nearshore {
namespace {
using playback::SlopeMomentLevel;

// Mean of channel c over a level.
double level_mean(const SlopeMomentLevel& level, int c) {
  double sum = 0;
  for (int k = 0; k < level.columns * level.rows; ++k) sum += level.texels[std::size_t(k) * 4 + c];
  return sum / (level.columns * level.rows);
}

// The halving slope_moment_pyramid used before it took plain 2 x 2 means for even sizes (commit
// ad22e11, playback/src/slope_moments.cpp): the general box weights per axis as lists, a
// level-sized buffer of doubles, x then y. The reference the faster one must equal bit for bit.
SlopeMomentLevel box_halved_before(const SlopeMomentLevel& fine) {
  const auto box_weights = [](int n, int m) {
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
  };
  SlopeMomentLevel coarse;
  coarse.columns = std::max(1, fine.columns / 2);
  coarse.rows = std::max(1, fine.rows / 2);
  const auto along_x = box_weights(fine.columns, coarse.columns), along_y = box_weights(fine.rows, coarse.rows);
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

TEST(SlopeMoments, TheHalvingByMeansIsTheBoxFilterBitForBit) {
  // Even and odd sizes each way, one-texel-wide grids, and a harbour grid's own (571 x 513); a
  // rough field (swell and noise, some -0 and flat stretches) and one of signed zeros, whose zero
  // slopes must keep the sign the box filter's sums from 0 give them; every level against the
  // box filter of the level before it.
  std::mt19937 random(41);
  std::uniform_real_distribution<float> noise(-1.f, 1.f);
  for (const auto& [columns, rows] : std::vector<std::pair<int, int>>{
           {16, 12}, {37, 23}, {64, 33}, {33, 64}, {1, 9}, {9, 1}, {2, 1}, {1, 1}, {3, 3}, {134, 120}, {571, 513}}) {
    Raster<float> rough(columns, rows), zeros(columns, rows);
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < columns; ++i) {
        rough(i, j) = (i + j) % 7 == 0 ? -0.f : i % 11 == 0 ? 0.f : float(0.8 * std::sin(0.7 * i + 0.2 * j)) + 0.1f * noise(random);
        // +0, +0, -0, -0 along x (flipped on alternate row pairs): g = (-0) - (+0) = -0 on both
        // texels of a pair, whose means must come out +0 as the box filter's sums from 0 give them
        zeros(i, j) = (i % 4 == 1 || i % 4 == 2) != (j % 4 == 1 || j % 4 == 2) ? -0.f : 0.f;
      }
    for (const Raster<float>* eta : {&rough, &zeros}) {
      const auto pyramid = playback::slope_moment_pyramid(*eta);
      const auto sizes = playback::slope_moment_level_sizes(columns, rows);
      ASSERT_EQ(pyramid.size(), sizes.size());
      for (std::size_t level = 0; level < pyramid.size(); ++level) {
        EXPECT_EQ(pyramid[level].columns, sizes[level].first);
        EXPECT_EQ(pyramid[level].rows, sizes[level].second);
        if (level == 0) continue;
        const SlopeMomentLevel expected = box_halved_before(pyramid[level - 1]);
        ASSERT_EQ(pyramid[level].texels.size(), expected.texels.size());
        EXPECT_EQ(std::memcmp(pyramid[level].texels.data(), expected.texels.data(), expected.texels.size() * sizeof(float)), 0)
            << columns << " x " << rows << ", level " << level << (eta == &zeros ? ", signed zeros" : "");
      }
    }
  }
}

TEST(SlopeMoments, APlaneHasItsSlopeAndNoVarianceInside) {
  Raster<float> eta(16, 12);
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 16; ++i) eta(i, j) = float(0.05 * i - 0.02 * j);  // rise per cell
  const auto pyramid = playback::slope_moment_pyramid(eta);
  ASSERT_EQ(pyramid.size(), 5u);  // 16x12, 8x6, 4x3, 2x1, 1x1
  EXPECT_EQ(pyramid[2].columns, 4);
  EXPECT_EQ(pyramid[2].rows, 3);
  EXPECT_EQ(pyramid[4].columns * pyramid[4].rows, 1);
  // an interior texel of level 1 (cells 2..5 x 2..5 of level 0, away from the clamped edges)
  const double u = 2.5 / 8.0, v = 2.5 / 6.0;
  const auto m = playback::sample_slope_moments(pyramid, u, v, 1.0);
  const auto s = playback::filtered_baked_slope(m, m, 0.3, 4.0, 2.0);  // cells 4 m x 2 m
  EXPECT_NEAR(s.slope_x, 0.05 / 4.0, 1e-6);
  EXPECT_NEAR(s.slope_y, -0.02 / 2.0, 1e-6);
  EXPECT_NEAR(s.variance_per_axis, 0.0, 1e-9);
}

TEST(SlopeMoments, AnUnresolvedSwellLeavesNoMeanSlopeAndItsWholeVariance) {
  // eta = A cos(k x), 4 cells a wavelength: the central difference g_x = -A sin(k dx) sin(k x),
  // k dx = pi / 2, so g_x = -A sin(k x): mean 0, mean square A^2 / 2. A footprint of 32 cells
  // (lod 5) holds 8 wavelengths: no mean slope, the variance per axis (x and y averaged)
  // A^2 / 4 / dx^2.
  const double A = 0.4, dx = 8.0;
  Raster<float> eta(128, 64);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 128; ++i) eta(i, j) = float(A * std::cos(std::numbers::pi / 2.0 * i));
  const auto pyramid = playback::slope_moment_pyramid(eta);
  for (double u : {0.375, 0.5, 0.625}) {  // texels 1 and 2 of 4: cells 32..95, away from the clamped edges
    const auto m = playback::sample_slope_moments(pyramid, u, 0.5, 5.0);
    const auto s = playback::filtered_baked_slope(m, m, 0.0, dx, dx);
    EXPECT_NEAR(s.slope_x, 0.0, 1e-6);
    EXPECT_NEAR(s.variance_per_axis, A * A / 4.0 / (dx * dx), 1e-3 * A * A / (dx * dx));
  }
  // At lod 0 (a cell a pixel) the slope is resolved: the sample's own, no variance at a centre.
  const auto m0 = playback::sample_slope_moments(pyramid, 1.5 / 128.0, 0.5, 0.0);  // cell 1: sin(pi/2)
  const auto s0 = playback::filtered_baked_slope(m0, m0, 0.0, dx, dx);
  EXPECT_NEAR(s0.slope_x, -A / dx, 1e-6);
  EXPECT_NEAR(s0.variance_per_axis, 0.0, 1e-9);
}

TEST(SlopeMoments, EveryLevelKeepsTheMeanSquareSlopeOfTheField) {
  // The box filter, also over odd sizes (37 x 23: levels 18 x 11, 9 x 5, ...), is an average:
  // each level's mean of g, g^2 is level 0's (law of total variance: the variance the mean slope
  // loses reappears inside the footprint).
  Raster<float> eta(37, 23);
  for (int j = 0; j < 23; ++j)
    for (int i = 0; i < 37; ++i) eta(i, j) = float(std::sin(0.9 * i + 0.3 * j) + 0.5 * std::cos(1.7 * j - 0.2 * i));
  const auto pyramid = playback::slope_moment_pyramid(eta);
  ASSERT_GT(pyramid.size(), 4u);
  for (std::size_t level = 1; level < pyramid.size(); ++level)
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(level_mean(pyramid[level], c), level_mean(pyramid[0], c), 1e-5) << "level " << level << " channel " << c;
}

TEST(SlopeMoments, TheLevelFollowsTheFootprintAndTheSamplerIsTrilinear) {
  EXPECT_EQ(playback::baked_slope_lod(3.0, 8.0), 0.0);
  EXPECT_NEAR(playback::baked_slope_lod(32.0, 8.0), 2.0, 1e-12);
  EXPECT_NEAR(playback::baked_slope_lod(8.0 * std::sqrt(2.0), 8.0), 0.5, 1e-12);
  Raster<float> eta(8, 8);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) eta(i, j) = float((i * 7 + j * 3) % 5);
  const auto pyramid = playback::slope_moment_pyramid(eta);
  const double u = 2.5 / 8.0, v = 5.5 / 8.0;  // texel (2, 5) of level 0, inside texel (1, 2) of level 1
  const auto at0 = playback::sample_slope_moments(pyramid, u, v, 0.0), at1 = playback::sample_slope_moments(pyramid, u, v, 1.0);
  const auto half = playback::sample_slope_moments(pyramid, u, v, 0.5);
  EXPECT_NEAR(at0[0], pyramid[0].texels[(5 * 8 + 2) * 4], 1e-6);
  for (std::size_t c = 0; c < 4; ++c) EXPECT_NEAR(half[c], 0.5 * (at0[c] + at1[c]), 1e-6);
  // beyond the last level: the last level
  const auto beyond = playback::sample_slope_moments(pyramid, u, v, 10.0);
  EXPECT_NEAR(beyond[2], pyramid.back().texels[2], 1e-6);
}

TEST(SlopeMoments, EachKeyframesVarianceIsInterpolatedNotTheBlendsOne) {
  // from: slope +g everywhere, to: -g everywhere; half way the mean is 0 and the variance 0 (each
  // frame is a plane), not g^2 (the variance of the two frames pooled).
  const std::array<double, 4> from = {0.1, 0.0, 0.01, 0.0}, to = {-0.1, 0.0, 0.01, 0.0};
  const auto s = playback::filtered_baked_slope(from, to, 0.5, 1.0, 1.0);
  EXPECT_NEAR(s.slope_x, 0.0, 1e-12);
  EXPECT_NEAR(s.variance_per_axis, 0.0, 1e-12);
}

}  // namespace
}  // namespace nearshore
