// Sibson natural-neighbour gridding: exact on planes (linear precision), O(h^2) convergence on a
// smooth surface, leave-one-out, priority among coincident points.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "nearshore/bathymetry/natural_neighbour.hpp"
#include "scattered_samples.hpp"

namespace nb = nearshore::bathymetry;

using nb::testing::jittered_samples;
using nb::testing::square_grid;

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
