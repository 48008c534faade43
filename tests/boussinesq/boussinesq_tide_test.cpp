// A tide over a run (BoussinesqSolver::set_still_water_level, docs/solver.md "Tides", issue 46): the
// basin rises and falls with the still-water level, by exactly the volume the level's change brings
// over its wet area, the sponges keep the level, and a beach floods as the level rises.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "boussinesq_test_support.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::boussinesq {
namespace {

// The level of a rising then falling tide over 40 s: 0 -> 0.05 m over 20 s, back to 0.02 m by 40 s.
double tide_level_m(double time_s) {
  if (time_s <= 20.0) return 0.05 * time_s / 20.0;
  return 0.05 - 0.03 * std::min(time_s - 20.0, 20.0) / 20.0;
}

TEST(BoussinesqTide, TheBasinFollowsTheLevelWithTheVolumeItBrings) {
  // 8 m x 0.4 m, 0.5 m deep, with sponges at both ends (which must relax towards the level, not 0).
  const HarbourGrid harbour = testing::flume(80, 4, 0.1, 0.5);
  SolverParameters parameters = testing::inviscid_parameters();
  parameters.sponges = {{Side::kWest, 2.0}, {Side::kEast, 2.0}};
  BoussinesqSolver solver(harbour, parameters, WaveMaker{});
  const double area_m2 = 8.0 * 0.4, volume_at_rest_m3 = solver.water_volume_m3();
  double largest_volume_error_m3 = 0.0, largest_level_error_m = 0.0;
  while (solver.time_s() < 40.0) {
    solver.set_still_water_level(tide_level_m(solver.time_s() + solver.time_step_s()));
    solver.step();
    const double level_m = tide_level_m(solver.time_s());
    largest_volume_error_m3 = std::max(largest_volume_error_m3, std::abs(solver.water_volume_m3() - volume_at_rest_m3 - area_m2 * level_m));
    for (int c = 0; c < 80; c += 10) largest_level_error_m = std::max(largest_level_error_m, std::abs(solver.surface_elevation_at(0.05 + 0.1 * c, 0.2) - level_m));
  }
  std::printf("largest volume error %.3g m^3 (of %.3g), largest level error %.3g m\n", largest_volume_error_m3, area_m2 * 0.05,
              largest_level_error_m);
  EXPECT_DOUBLE_EQ(solver.still_water_level_m(), tide_level_m(solver.time_s()));
  // The change is added to every wet cell: the volume is the level's to rounding (float output
  // aside), and the flat basin stays flat (no wave is made by a uniform rise).
  EXPECT_LT(largest_volume_error_m3, 1e-9 * volume_at_rest_m3);
  EXPECT_LT(largest_level_error_m, 1e-6);
}

TEST(BoussinesqTide, ARisingLevelFloodsTheBeach) {
  // A 1:10 beach rising from 0.3 m deep at x = 0 to 0.2 m above still water at x = 5 m: the
  // shoreline starts at x = 3 m, and a level 0.1 m higher moves it 1 m up the beach. (A cell is wet
  // with more than the dry depth, 1 cm, on it: 29 cells at the start, 39 under the new level.)
  HarbourGrid harbour = testing::flume(50, 1, 0.1, 0.3);
  for (int c = 0; c < 50; ++c) {
    const float depth = static_cast<float>(0.3 - 0.1 * ((c + 0.5) * 0.1));  // 1:10 from 0.3 m at x = 0
    harbour.still_water_depth_m(c, 0) = depth;
    harbour.land(c, 0) = depth <= 0.0f;
  }
  SolverParameters parameters = testing::inviscid_parameters();
  BoussinesqSolver solver(harbour, parameters, WaveMaker{});
  auto wet_cells = [&] {
    int wet = 0;
    for (int c = 0; c < 50; ++c) wet += harbour.still_water_depth_m(c, 0) + solver.surface_elevation_m()(c, 0) > parameters.dry_depth_m;
    return wet;
  };
  EXPECT_EQ(wet_cells(), 29);
  while (solver.time_s() < 30.0) {
    solver.set_still_water_level(0.1 * std::min(solver.time_s() + solver.time_step_s(), 20.0) / 20.0);
    solver.step();
  }
  EXPECT_FALSE(solver.check_stability().has_value());
  const double level_m = solver.surface_elevation_at(1.0, 0.05);
  std::printf("wet cells %d of 50 after a rise of 0.1 m (39 expected), level %.4f m\n", wet_cells(), level_m);
  EXPECT_NEAR(wet_cells(), 39, 1);
  // The level's change is added to the cells wet at each step; the beach it floods is filled from
  // them, so the basin ends below the level by at most the flooded wedge (0.5 x 1 m x 0.1 m) over
  // the wet length (3.9 m): 13 mm.
  EXPECT_LT(level_m, 0.1 + 1e-3);
  EXPECT_GT(level_m, 0.1 - 0.013);
}

TEST(BoussinesqTide, RefusesALevelThatIsNotANumber) {
  BoussinesqSolver solver(testing::flume(10, 1, 0.1, 0.5), testing::inviscid_parameters(), WaveMaker{});
  EXPECT_THROW(solver.set_still_water_level(std::nan("")), Error);
}

}  // namespace
}  // namespace nearshore::boussinesq
