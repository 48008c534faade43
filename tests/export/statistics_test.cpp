// The two computations behind the exports, against their analytic values on a linear wave.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "export_test_support.hpp"
#include "nearshore/export/horizontal_excursion.hpp"
#include "nearshore/export/surface_statistics.hpp"

namespace nearshore::exports {
namespace {
using testing::TestWave;

// eta = a cos(k x - w t) sampled 20 times a period over whole periods: the sample mean of cos^2 is
// exactly 1/2 (any N >= 3 equally spaced samples of whole periods), so m0 = a^2 / 2 and
// Hs = 4 sqrt(m0) = 2 sqrt(2) a up to float rounding (1e-6 m on 0.28 m). A constant set-up s adds
// to the mean and nothing to Hs; a breaking indicator of 1 every other frame has fraction 1/2.
TEST(SurfaceStatistics, LinearWaveHasHsOfTwoRootTwoAmplitudeAndItsSetUp) {
  constexpr int kColumns = 7, kRows = 3, kFrames = 40;
  constexpr double kAmplitude_m = 0.4, kSetUp_m = 0.05;
  SurfaceStatistics statistics(kColumns, kRows);
  Raster<float> eta(kColumns, kRows), foam(kColumns, kRows);
  for (int n = 0; n < kFrames; ++n) {
    for (int row = 0; row < kRows; ++row)
      for (int column = 0; column < kColumns; ++column) {
        eta(column, row) = static_cast<float>(kSetUp_m + kAmplitude_m * std::cos(0.3 * column - 2.0 * std::numbers::pi * n / 20.0));
        foam(column, row) = (n % 2 == 0 && column == 3) ? 1.0f : 0.0f;
      }
    statistics.add_frame(eta, foam);
  }
  const Raster<float> hs = statistics.significant_wave_height_m();
  const Raster<float> mean = statistics.mean_surface_elevation_m();
  const Raster<float> fraction = statistics.breaking_fraction();
  for (int row = 0; row < kRows; ++row)
    for (int column = 0; column < kColumns; ++column) {
      EXPECT_NEAR(hs(column, row), 2.0 * std::numbers::sqrt2 * kAmplitude_m, 1e-5) << column << "," << row;
      EXPECT_NEAR(mean(column, row), kSetUp_m, 1e-6);
      EXPECT_FLOAT_EQ(fraction(column, row), column == 3 ? 0.5f : 0.0f);
    }
  EXPECT_EQ(statistics.frame_count(), kFrames);
}

// A cell of 0.2 m under eta = 0.4 cos(2 pi n / 20) holds water while 0.2 + eta > 0.01 (the dry
// depth), i.e. cos > -0.475: n = 0..6 and 14..19 of every 20 (cos(126 deg) = -0.588 and
// cos(108 deg) = -0.309 bracket it), 13 of 20 frames; the 5 m cells never dry. Without a depth every
// cell counts as wet.
TEST(SurfaceStatistics, AShoreCellThatDriesPartOfTheTimeHasItsWetFraction) {
  constexpr int kColumns = 3, kRows = 2, kFrames = 40;
  Raster<float> depth(kColumns, kRows, 5.0f);
  depth(1, 0) = 0.2f;
  SurfaceStatistics statistics(depth, 0.01);
  SurfaceStatistics without_depth(kColumns, kRows);
  Raster<float> eta(kColumns, kRows), foam(kColumns, kRows, 0.0f);
  for (int n = 0; n < kFrames; ++n) {
    for (float& value : eta.values()) value = static_cast<float>(0.4 * std::cos(2.0 * std::numbers::pi * n / 20.0));
    eta(1, 0) = std::max(eta(1, 0), -0.2f);  // the solver pins a dry cell's eta at -d
    statistics.add_frame(eta, foam);
    without_depth.add_frame(eta, foam);
  }
  const Raster<float> wet = statistics.wet_fraction();
  for (int row = 0; row < kRows; ++row)
    for (int column = 0; column < kColumns; ++column) {
      EXPECT_FLOAT_EQ(wet(column, row), column == 1 && row == 0 ? 0.65f : 1.0f) << column << "," << row;
      EXPECT_FLOAT_EQ(without_depth.wet_fraction()(column, row), 1.0f);
    }
}

// Over depth d, eta = a cos(k x - w t) with P = (w / k) eta gives the depth-averaged velocity
// U = (w a / (k d)) cos(k x - w t) and the excursion xi = -(a / (k d)) sin(k x - w t).
// Tolerance 1.5 % of a / (k d): the trapezoidal sum of a sampled cosine is low by (w dt)^2 / 12 =
// 0.82 % at 20 frames a period, and h = d + eta instead of d adds a second-order part of relative
// size a / (4 d) = 0.25 %.
TEST(HorizontalExcursion, LinearWaveMovesTheWaterByAOverKd) {
  const GridGeometry g = TestWave::geometry();
  HarbourGrid harbour = HarbourGrid::open_water(g, static_cast<float>(TestWave::kDepth_m));
  harbour.land(5, 5) = 1;
  HorizontalExcursion excursion(harbour, TestWave::kFrameInterval_s);
  auto frame = [&](int n, Raster<float>& eta, Raster<float>& p, Raster<float>& q) {
    eta = Raster<float>(g.columns, g.rows);
    p = Raster<float>(g.columns, g.rows);
    q = Raster<float>(g.columns, g.rows, 0.0f);
    for (int row = 0; row < g.rows; ++row)
      for (int column = 0; column < g.columns; ++column) {
        const double e = TestWave::elevation_m(column, row, TestWave::frame_time_s(n));
        eta(column, row) = static_cast<float>(e);
        p(column, row) = static_cast<float>(TestWave::omega_rad_s / TestWave::k_rad_m * e);
      }
  };
  Raster<float> eta, p, q, xi_x, xi_y;
  for (int n = 0; n < TestWave::kFrames; ++n) {
    frame(n, eta, p, q);
    excursion.accumulate(eta, p, q);
  }
  excursion.finish_accumulation();
  const double amplitude_m = TestWave::kAmplitude_m / (TestWave::k_rad_m * TestWave::kDepth_m);
  double worst_m = 0.0;
  for (int n = 0; n < TestWave::kFrames; ++n) {
    frame(n, eta, p, q);
    excursion.excursion(eta, p, q, xi_x, xi_y);
    for (int row = 0; row < g.rows; ++row)
      for (int column = 0; column < g.columns; ++column) {
        if (column == 5 && row == 5) {
          EXPECT_EQ(xi_x(column, row), 0.0f);  // land
          continue;
        }
        const double x = (column + 0.5) * TestWave::kSpacing_m;
        const double expected = -amplitude_m * std::sin(TestWave::k_rad_m * x - TestWave::omega_rad_s * TestWave::frame_time_s(n));
        worst_m = std::max(worst_m, std::abs(xi_x(column, row) - expected));
        EXPECT_NEAR(xi_y(column, row), 0.0, 1e-9);
      }
  }
  EXPECT_LT(worst_m, 0.015 * amplitude_m) << "a / (k d) = " << amplitude_m << " m";
}

// A uniform stretch xi_x = s x has J = 1 + s: it folds for s <= -1 and not above; a shear
// xi_x = s y alone never folds (J = 1). Rectangular cells (10 m by 4 m): the derivatives divide by
// each direction's own size.
TEST(HorizontalExcursion, FoldedCellsAreWhereTheJacobianTurnsNegative) {
  GridGeometry g = TestWave::geometry();
  g.set_spacing(10.0, 4.0);
  HarbourGrid harbour = HarbourGrid::open_water(g, 10.0f);
  harbour.land(3, 3) = 1;
  auto field = [&](double per_x, double per_y) {
    Raster<float> xi(g.columns, g.rows);
    for (int row = 0; row < g.rows; ++row)
      for (int column = 0; column < g.columns; ++column)
        xi(column, row) = static_cast<float>(per_x * (column + 0.5) * 10.0 + per_y * (row + 0.5) * 4.0);
    return xi;
  };
  const Raster<float> zero(g.columns, g.rows, 0.0f);
  const int water = g.columns * g.rows - 1;
  EXPECT_EQ(folded_cell_count(harbour, field(-1.5, 0.0), zero), water);
  EXPECT_EQ(folded_cell_count(harbour, field(-0.5, 0.0), zero), 0);
  EXPECT_EQ(folded_cell_count(harbour, zero, field(0.0, -1.2)), water);
  EXPECT_EQ(folded_cell_count(harbour, field(0.0, 3.0), zero), 0);
}

}  // namespace
}  // namespace nearshore::exports
