// Checkpoints and the stability guard (issue 4): save_state/load_state continue bit-identically
// and refuse a foreign or damaged state; check_stability names the cell of a NaN.
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include <gtest/gtest.h>

#include "boussinesq_test_support.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::boussinesq {

using namespace nearshore::ocean;
namespace {

WaveMaker regular_waves() {
  WaveMaker maker;
  maker.kind = WaveMaker::Kind::kComponents;
  maker.sea_state.components = {{0.15, 2.0 * 3.14159265 / 4.0, 0.2, 0.5}};
  maker.source_line_m = 12.0;
  maker.facing = Side::kWest;
  maker.ramp_time_s = 4.0;
  return maker;
}

SolverParameters all_on() {
  SolverParameters parameters;
  parameters.dispersion_cutoff_depth_m = 0.3;
  parameters.sponges = {{Side::kWest, 6.0}};
  return parameters;
}

TEST(BoussinesqState, SaveAndLoadContinueBitIdentically) {
  const HarbourGrid harbour = testing::rough_basin();
  BoussinesqSolver uninterrupted(harbour, all_on(), regular_waves());
  for (int i = 0; i < 120; ++i) uninterrupted.step();

  std::stringstream state;
  {
    BoussinesqSolver first_half(harbour, all_on(), regular_waves());
    for (int i = 0; i < 60; ++i) first_half.step();
    first_half.save_state(state);
  }
  BoussinesqSolver resumed(harbour, all_on(), regular_waves());
  resumed.load_state(state);
  EXPECT_EQ(resumed.step_count(), 60);
  for (int i = 0; i < 60; ++i) resumed.step();
  EXPECT_EQ(resumed.time_s(), uninterrupted.time_s());
  const std::vector<float> a = testing::solver_snapshot(uninterrupted), b = testing::solver_snapshot(resumed);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
}

// With the sweep order alternating, a state saved after an odd number of steps resumes with the
// y sweep first, as the uninterrupted run does (the step count is part of the state).
TEST(BoussinesqState, AlternatingSweepOrderResumesInOrder) {
  const HarbourGrid harbour = testing::rough_basin();
  SolverParameters parameters = all_on();
  parameters.alternate_sweep_order = true;
  BoussinesqSolver uninterrupted(harbour, parameters, regular_waves());
  for (int i = 0; i < 90; ++i) uninterrupted.step();
  std::stringstream state;
  {
    BoussinesqSolver first_part(harbour, parameters, regular_waves());
    for (int i = 0; i < 45; ++i) first_part.step();
    first_part.save_state(state);
  }
  BoussinesqSolver resumed(harbour, parameters, regular_waves());
  resumed.load_state(state);
  for (int i = 0; i < 45; ++i) resumed.step();
  const std::vector<float> a = testing::solver_snapshot(uninterrupted), b = testing::solver_snapshot(resumed);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
}

TEST(BoussinesqState, RefusesDamagedOrForeignState) {
  const HarbourGrid harbour = testing::rough_basin();
  BoussinesqSolver solver(harbour, all_on(), regular_waves());
  for (int i = 0; i < 5; ++i) solver.step();
  std::stringstream state;
  solver.save_state(state);
  std::string bytes = state.str();

  std::string damaged = bytes;
  damaged[damaged.size() / 2] ^= 0x40;
  std::istringstream damaged_stream(damaged);
  EXPECT_THROW(solver.load_state(damaged_stream), Error);

  std::istringstream truncated(bytes.substr(0, bytes.size() - 100));
  EXPECT_THROW(solver.load_state(truncated), Error);

  SolverParameters other = all_on();
  other.time_step_s = 0.9 * solver.time_step_s();  // a different time step: not the same run
  BoussinesqSolver foreign(harbour, other, regular_waves());
  std::istringstream intact(bytes);
  try {
    foreign.load_state(intact);
    FAIL() << "a state of another time step was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("time step"), std::string::npos) << error.what();
  }
}

TEST(BoussinesqStability, ReportsTheCellOfANaN) {
  const HarbourGrid harbour = testing::rough_basin();
  BoussinesqSolver solver(harbour, all_on(), WaveMaker{});
  EXPECT_FALSE(solver.check_stability().has_value());
  const int column = 7, row = 33;
  const double x = harbour.geometry.cell_centre_x_m(column), y = harbour.geometry.cell_centre_y_m(row);
  solver.set_surface_elevation([&](double px, double py) {
    return (px == x && py == y) ? std::numeric_limits<double>::quiet_NaN() : 0.0;
  });
  const auto report = solver.check_stability();
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->column, column);
  EXPECT_EQ(report->row, row);
  EXPECT_DOUBLE_EQ(report->x_m, x);
  EXPECT_DOUBLE_EQ(report->y_m, y);
  EXPECT_DOUBLE_EQ(report->depth_m, harbour.still_water_depth_m(column, row));
  EXPECT_NE(report->what.find("not a number"), std::string::npos) << report->what;
}

TEST(BoussinesqStability, ReportsAnElevationBeyondTheDepthRatio) {
  const HarbourGrid harbour = testing::rough_basin();
  BoussinesqSolver solver(harbour, all_on(), WaveMaker{});
  const int column = 30, row = 12;
  const double x = harbour.geometry.cell_centre_x_m(column), y = harbour.geometry.cell_centre_y_m(row);
  const double depth = harbour.still_water_depth_m(column, row);
  solver.set_surface_elevation([&](double px, double py) { return (px == x && py == y) ? 6.0 * std::max(depth, 1.0) : 0.0; });
  const auto report = solver.check_stability();
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->column, column);
  EXPECT_EQ(report->row, row);
}

}  // namespace
}  // namespace nearshore::boussinesq
