// Gauges (BoussinesqSolver::surface_elevation_at, the bake's gauges.csv): bilinear between the cell
// centres that hold water, so a gauge beside a quay, a breakwater of porosity 0 or a dry beach reads
// the water surface and not the ground's height (docs/commands/bake.md, "[[gauges]]").
#include <cmath>

#include <gtest/gtest.h>

#include "boussinesq_test_support.hpp"

namespace nearshore::boussinesq {
namespace {

// A still basin 10 x 4 cells of 1 m, 2 m deep, with a quay 3 m high filling the eastern two columns
// and a wall (porosity 0) on the cell (4, 3): every wet cell has eta = 0.
HarbourGrid basin_with_quay_and_wall() {
  HarbourGrid harbour = testing::flume(10, 4, 1.0, 2.0);
  for (int r = 0; r < 4; ++r)
    for (int c = 8; c < 10; ++c) harbour.still_water_depth_m(c, r) = -3.0f;
  harbour.porosity(4, 3) = 0.0f;
  return harbour;
}

TEST(BoussinesqGauge, ReadsTheWaterBesideAQuayAndAWallNotTheGround) {
  const HarbourGrid harbour = basin_with_quay_and_wall();
  BoussinesqSolver solver(harbour, testing::inviscid_parameters(), WaveMaker{});
  solver.set_surface_elevation([](double x, double) { return 0.01 * x; });  // a tilt: the weights show
  // Between the last water column (centre x = 7.5 m) and the quay (8.5 m): the quay's cell is dry
  // ground 3 m up; the gauge reads the water column's surface, 0.075 m, for any share of the quay.
  for (const double x : {7.6, 8.0, 8.4})
    EXPECT_NEAR(solver.surface_elevation_at(x, 1.0), 0.075, 1e-6) << "gauge at x = " << x << " m";
  // Between water cells the interpolation stays bilinear: 0.01 x exactly.
  EXPECT_NEAR(solver.surface_elevation_at(3.2, 1.3), 0.032, 1e-6);
  // Beside the wall cell (4, 3), centre (4.5, 3.5): its eta is no surface; the three wet cells share
  // its weight, bilinear in x on the row below and the wet neighbour (3, 3) on the wall's row.
  const double a = 0.5, b = 0.5;  // the gauge at (4.0, 3.0): a quarter of the weight on each cell
  const double expected = ((1 - a) * (1 - b) * 0.035 + a * (1 - b) * 0.045 + (1 - a) * b * 0.035) / (1 - a * b);
  EXPECT_NEAR(solver.surface_elevation_at(4.0, 3.0), expected, 1e-6);
  // On the quay itself, with no water in any of the four cells, the gauge reads the ground it stands on.
  EXPECT_NEAR(solver.surface_elevation_at(9.5, 2.0), 3.0, 1e-6);
}

}  // namespace
}  // namespace nearshore::boussinesq
