// Rasterisation of polygons and structure lines, and the exact Euclidean distance transform.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "nearshore/bathymetry/distance_transform.hpp"
#include "nearshore/bathymetry/rasterise.hpp"

namespace nb = nearshore::bathymetry;

namespace {
nearshore::GridGeometry grid(int columns, int rows, double spacing_m) {
  nearshore::GridGeometry g;
  g.columns = columns;
  g.rows = rows;
  g.spacing_m = spacing_m;
  g.origin_x_m = 1000.0;
  g.origin_y_m = 2000.0;
  return g;
}
}  // namespace

TEST(Rasterise, PolygonWithHoleCoversTheCellCentresInside) {
  const auto g = grid(100, 80, 2.0);
  // A 100 m x 60 m square with a 20 m x 20 m hole: 50 x 30 cells minus 10 x 10.
  const nb::PlaneLine outer{{1020, 2020}, {1120, 2020}, {1120, 2080}, {1020, 2080}};
  const nb::PlaneLine hole{{1040, 2040}, {1060, 2040}, {1060, 2060}, {1040, 2060}};
  const std::vector<nb::PlaneLine> rings{outer, hole};
  int count = 0;
  bool only_inside = true;
  nb::for_each_cell_in_polygon(g, rings, [&](int c, int r) {
    ++count;
    const double x = g.cell_centre_x_m(c), y = g.cell_centre_y_m(r);
    only_inside = only_inside && x > 1020 && x < 1120 && y > 2020 && y < 2080 && !(x > 1040 && x < 1060 && y > 2040 && y < 2060);
  });
  EXPECT_EQ(count, 50 * 30 - 10 * 10);
  EXPECT_TRUE(only_inside);
}

TEST(Rasterise, LineBandHasTheCrestWidth) {
  const auto g = grid(200, 200, 1.0);
  const nb::PlaneLine breakwater{{1020.0, 2100.3}, {1180.0, 2100.3}};
  int count = 0;
  nb::for_each_cell_near_line(g, breakwater, 10.0, [&](int, int) { ++count; });
  // A 20 m wide band over 160 m, plus two half discs of radius 10 m at the ends: 3200 + 314 m^2,
  // one cell per m^2; the band edges cut through cell centres at most one row each side.
  EXPECT_NEAR(count, 3200 + 314, 2 * 160 + 40);
}

TEST(DistanceTransform, MatchesBruteForceExactly) {
  const int columns = 61, rows = 47;
  nearshore::Raster<std::uint8_t> seed(columns, rows, 0);
  std::mt19937 random(11);
  std::vector<std::pair<int, int>> seeds;
  for (int k = 0; k < 25; ++k) {
    const int c = static_cast<int>(random() % columns), r = static_cast<int>(random() % rows);
    seed(c, r) = 1;
    seeds.push_back({c, r});
  }
  const auto result = nb::nearest_seed_transform(seed, 2.5);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      double best = INFINITY;
      for (auto [sc, sr] : seeds) best = std::min(best, std::hypot(sc - c, sr - r) * 2.5);
      ASSERT_NEAR(result.distance_m(c, r), best, 1e-4) << c << "," << r;  // float storage
      const int nc = result.nearest_column(c, r), nr = result.nearest_row(c, r);
      ASSERT_TRUE(seed(nc, nr));
      ASSERT_NEAR(std::hypot(nc - c, nr - r) * 2.5, best, 1e-4);
    }
}

TEST(DistanceTransform, SignedCoastDistanceIsNegativeOnLandAndMeasuredToTheEdge) {
  nearshore::Raster<std::uint8_t> land(40, 10, 0);
  for (int r = 0; r < 10; ++r)
    for (int c = 20; c < 40; ++c) land(c, r) = 1;  // land east of x = 20 cells
  const auto d = nb::signed_coast_distance(land, 5.0);
  EXPECT_FLOAT_EQ(d(19, 5), 2.5f);   // first water cell: half a cell from the edge
  EXPECT_FLOAT_EQ(d(20, 5), -2.5f);  // first land cell
  EXPECT_FLOAT_EQ(d(10, 5), 47.5f);  // 10 cells to the first land cell, minus half a cell
  EXPECT_FLOAT_EQ(d(30, 5), -52.5f);
  const auto open = nb::signed_coast_distance(nearshore::Raster<std::uint8_t>(5, 5, 0), 1.0);
  EXPECT_TRUE(std::isinf(open(2, 2)) && open(2, 2) > 0);
}
