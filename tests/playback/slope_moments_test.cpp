// The slope moments' pyramid and its sampler (playback/slope_moments.hpp): the CPU side of the
// baked field's filtered slopes, which the renderer uploads as they are and the shader samples
// with textureLod (tests/playback/baked_slope_render_test.cpp compares the two).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

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
