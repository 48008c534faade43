// Sibson natural-neighbour gridding: exact on planes (linear precision), O(h^2) convergence on a
// smooth surface, leave-one-out, priority among coincident points.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "nearshore/bathymetry/natural_neighbour.hpp"

namespace nb = nearshore::bathymetry;

namespace {

// Jittered points at spacing h over [0, L]^2 (+ one spacing outside so the hull covers the square).
template <class Surface>
std::vector<nb::ScatteredDepth> jittered_samples(double h, double length_m, Surface&& f, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.35 * h, 0.35 * h);
  std::vector<nb::ScatteredDepth> points;
  for (double y = -h; y <= length_m + h + 1e-9; y += h)
    for (double x = -h; x <= length_m + h + 1e-9; x += h) {
      const double px = x + jitter(random), py = y + jitter(random);
      points.push_back({px, py, f(px, py)});
    }
  return points;
}

nearshore::GridGeometry square_grid(double length_m, double spacing_m) {
  nearshore::GridGeometry g;
  g.columns = g.rows = static_cast<int>(length_m / spacing_m);
  g.spacing_m = spacing_m;
  return g;
}

}  // namespace

TEST(NaturalNeighbour, ReproducesAPlaneExactly) {
  auto plane = [](double x, double y) { return 12.0 + 0.013 * x - 0.021 * y; };
  const auto points = jittered_samples(40.0, 1000.0, plane, 1);
  const nb::NaturalNeighbourSurface surface(points);
  const auto g = square_grid(1000.0, 7.0);
  const auto depth = surface.sample(g);
  double worst = 0;
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c) worst = std::max(worst, std::abs(depth(c, r) - plane(g.cell_centre_x_m(c), g.cell_centre_y_m(r))));
  // Sibson coordinates have linear precision (Sibson 1981): the only error is rounding, in double
  // for the coordinates and float for the stored depth (~1e-6 relative of ~20 m = 2e-5 m).
  EXPECT_LT(worst, 5e-5);
  EXPECT_NEAR(surface.depth_at(500.5, 333.3), plane(500.5, 333.3), 1e-9);
}

TEST(NaturalNeighbour, ConvergesAtSecondOrderOnASmoothSurface) {
  const double length_m = 1000.0, k = 2.0 * std::numbers::pi / 500.0;
  auto surface_depth = [&](double x, double y) { return 20.0 + 6.0 * std::sin(k * x) * std::cos(k * y); };
  const auto g = square_grid(length_m, 5.0);
  std::vector<double> rms;
  for (double h : {40.0, 20.0, 10.0}) {
    const nb::NaturalNeighbourSurface surface(jittered_samples(h, length_m, surface_depth, 3));
    const auto depth = surface.sample(g);
    double sum = 0;
    for (int r = 0; r < g.rows; ++r)
      for (int c = 0; c < g.columns; ++c) {
        const double e = depth(c, r) - surface_depth(g.cell_centre_x_m(c), g.cell_centre_y_m(r));
        sum += e * e;
      }
    rms.push_back(std::sqrt(sum / g.cell_count()));
  }
  // Linear precision gives O(h^2) (Sibson's C1 interpolant); jittered data make the ratio noisy,
  // so we require an observed order of at least 1.7 per halving (2^1.7 = 3.2) and a small error.
  for (std::size_t i = 0; i + 1 < rms.size(); ++i) {
    const double order = std::log2(rms[i] / rms[i + 1]);
    EXPECT_GT(order, 1.7) << "h=" << 40.0 / (1 << i) << " rms " << rms[i] << " -> " << rms[i + 1];
    RecordProperty("order_" + std::to_string(i), std::to_string(order));
  }
  EXPECT_LT(rms.back(), 0.05);  // 6 m amplitude, 500 m wavelength, 10 m data: < 1 % of the amplitude
}

TEST(NaturalNeighbour, OutsideTheHullIsNaN) {
  const std::vector<nb::ScatteredDepth> points{{0, 0, 1}, {100, 0, 1}, {0, 100, 1}, {100, 100, 1}};
  const nb::NaturalNeighbourSurface surface(points);
  EXPECT_TRUE(std::isnan(surface.depth_at(150, 50)));
  EXPECT_NEAR(surface.depth_at(50, 50), 1.0, 1e-12);
}

TEST(NaturalNeighbour, LeaveOneOutOnAPlaneIsExactAndRestoresThePoint) {
  auto plane = [](double x, double y) { return 5.0 + 0.01 * x + 0.02 * y; };
  auto points = jittered_samples(50.0, 500.0, plane, 5);
  const std::size_t inner = points.size() / 2;  // an interior point
  points[inner].depth_m += 3.0;                 // an outlier: its neighbours predict the plane
  nb::NaturalNeighbourSurface surface(points);
  EXPECT_NEAR(surface.leave_one_out(inner), plane(points[inner].x_m, points[inner].y_m), 1e-9);
  EXPECT_NEAR(surface.depth_at(points[inner].x_m, points[inner].y_m), points[inner].depth_m, 1e-9);  // put back
  EXPECT_EQ(surface.vertex_count(), points.size());
}

TEST(NaturalNeighbour, TheFirstOfCoincidentPointsWins) {
  std::vector<nb::ScatteredDepth> points{{0, 0, 1}, {100, 0, 1}, {0, 100, 1}, {100, 100, 1}, {50, 50, 7}};
  points.push_back({50, 50, 99});  // a later duplicate (e.g. a contour vertex on a sounding)
  points.insert(points.begin(), {100, 100, 3});  // an earlier duplicate of a corner
  const nb::NaturalNeighbourSurface surface(points);
  EXPECT_EQ(surface.vertex_count(), 5u);
  EXPECT_NEAR(surface.depth_at(50, 50), 7.0, 1e-12);
  EXPECT_NEAR(surface.depth_at(100, 100), 3.0, 1e-12);
}
