// The inputs and outputs of a bake that need no solver: flume bathymetries, the Berkhoff shoal,
// resampling, time-series tables, and gauges.csv.
#include <cmath>

#include <gtest/gtest.h>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_bathymetry.hpp"
#include "nearshore/bake/bake_gauges.hpp"
#include "nearshore/bake/bake_time_series.hpp"
#include "nearshore/boussinesq/boussinesq_solver.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bake {

using namespace nearshore::ocean;
using namespace nearshore::boussinesq;
namespace {
using testing::scratch_folder;
using testing::write_text;

TEST(FlumeProfile, InterpolatesLinearlyAndMarksDryCellsAsLand) {
  const std::vector<std::pair<double, double>> profile = {{10.0, 0.47}, {20.0, -0.03}};  // 1:20 beach
  EXPECT_DOUBLE_EQ(profile_depth_m(profile, 0.0), 0.47);
  EXPECT_DOUBLE_EQ(profile_depth_m(profile, 15.0), 0.22);
  EXPECT_DOUBLE_EQ(profile_depth_m(profile, 30.0), -0.03);
  const HarbourGrid grid = flume_from_profile(20.0, 0.12, 0.04, profile, "test");
  EXPECT_EQ(grid.geometry.columns, 500);
  EXPECT_EQ(grid.geometry.rows, 3);
  EXPECT_NEAR(grid.still_water_depth_m(374, 1), 0.47 - (374.5 * 0.04 - 10.0) / 20.0, 1e-6);
  EXPECT_EQ(grid.land(490, 0), 1);  // x = 19.62 m, beyond the still-water line at 19.4 m
  EXPECT_EQ(grid.land(400, 0), 0);
}

TEST(BerkhoffShoal, DepthsOfThePaper) {
  const BerkhoffShoal shoal;  // centre (13.15, 10), 20 degrees
  // Far up-wave: the flat 0.45 m part; at the centre: the slope's 0.45 - 0.02 * 5.84 plus the shoal
  // 0.3 - 0.5 = -0.2 m, i.e. 0.1332 m (Berkhoff et al. 1982: about 0.13 m over the top).
  EXPECT_DOUBLE_EQ(berkhoff_shoal_depth_m(shoal, 2.0, 10.0), 0.45);
  EXPECT_NEAR(berkhoff_shoal_depth_m(shoal, 13.15, 10.0), 0.45 - 0.02 * 5.84 - 0.2, 1e-12);
  // Far down-wave the slope is clipped at 0.07 m.
  EXPECT_DOUBLE_EQ(berkhoff_shoal_depth_m(shoal, 29.9, 10.0), 0.07);
  // The contours are rotated: along the line x = x_c + 2 m the depth changes across the flume.
  EXPECT_NE(berkhoff_shoal_depth_m(shoal, 20.0, 5.0), berkhoff_shoal_depth_m(shoal, 20.0, 15.0));
}

TEST(Resample, KeepsALinearBedAndTheExtent) {
  HarbourGrid grid = flume_from_profile(40.0, 20.0, 1.0, {{0.0, 10.0}, {40.0, 2.0}}, "test");
  grid.porosity(20, 10) = 0.f;  // a wall cell stays a wall
  const HarbourGrid fine = resample_harbour_grid(grid, 0.5);
  EXPECT_EQ(fine.geometry.columns, 80);
  EXPECT_EQ(fine.geometry.rows, 40);
  for (int column = 2; column < 78; column += 7)  // interior: bilinear is exact on a linear bed
    EXPECT_NEAR(fine.still_water_depth_m(column, 5), 10.0 - 0.2 * fine.geometry.cell_centre_x_m(column), 1e-5);
  EXPECT_EQ(fine.porosity(41, 21), 0.f);
  EXPECT_EQ(resample_harbour_grid(grid, 1.0).geometry.columns, 40);
}

// Issue 15: to rectangular cells and back, each axis interpolated on its own spacing.
TEST(Resample, ToAndFromRectangularCells) {
  // A bed linear in x and y: bilinear resampling is exact in the interior.
  HarbourGrid grid = flume_from_profile(40.0, 20.0, 1.0, {{0.0, 10.0}, {40.0, 2.0}}, "test");
  for (int row = 0; row < grid.geometry.rows; ++row)
    for (int column = 0; column < grid.geometry.columns; ++column)
      grid.still_water_depth_m(column, row) += static_cast<float>(0.1 * grid.geometry.cell_centre_y_m(row));
  const auto bed = [](double x, double y) { return 10.0 - 0.2 * x + 0.1 * y; };
  const HarbourGrid rectangular = resample_harbour_grid(grid, CellSize(0.5, 2.0));
  EXPECT_EQ(rectangular.geometry.columns, 80);
  EXPECT_EQ(rectangular.geometry.rows, 10);
  EXPECT_DOUBLE_EQ(rectangular.geometry.height_m(), 20.0);
  for (int column = 2; column < 78; column += 7)
    for (int row = 1; row < 9; row += 3)
      EXPECT_NEAR(rectangular.still_water_depth_m(column, row),
                  bed(rectangular.geometry.cell_centre_x_m(column), rectangular.geometry.cell_centre_y_m(row)), 1e-5);
  const HarbourGrid back = resample_harbour_grid(rectangular, 1.0);
  EXPECT_TRUE(back.geometry.square_cells());
  for (int column = 2; column < 38; column += 5)
    for (int row = 2; row < 18; row += 5)
      EXPECT_NEAR(back.still_water_depth_m(column, row), bed(back.geometry.cell_centre_x_m(column), back.geometry.cell_centre_y_m(row)), 1e-5);
  // The same cells again: the grid itself.
  EXPECT_EQ(resample_harbour_grid(rectangular, CellSize(0.5, 2.0)).geometry.rows, 10);
}

// Issue 41: the surroundings (the ground round the grid, for the renderer) are in projected
// metres with cells of their own: resampling the grid keeps them as they are; a still-water level
// above the datum deepens them as it deepens the grid (no data, NaN, stays NaN).
TEST(Resample, KeepsTheSurroundingsAndTheWaterLevelDeepensThem) {
  HarbourGrid grid = flume_from_profile(40.0, 20.0, 1.0, {{0.0, 10.0}, {40.0, 2.0}}, "test");
  grid.surroundings.geometry = grid.geometry;
  grid.surroundings.geometry.spacing_m = 4.0;
  grid.surroundings.geometry.columns = 20;
  grid.surroundings.geometry.rows = 10;
  grid.surroundings.geometry.origin_x_m -= 20.0;
  grid.surroundings.geometry.origin_y_m -= 10.0;
  grid.surroundings.still_water_depth_m = Raster<float>(20, 10, -3.0f);
  grid.surroundings.still_water_depth_m(0, 0) = NAN;
  const HarbourGrid fine = resample_harbour_grid(grid, 0.5);
  EXPECT_EQ(nlohmann::json(fine.surroundings.geometry), nlohmann::json(grid.surroundings.geometry));
  EXPECT_EQ(fine.surroundings.still_water_depth_m(5, 5), -3.0f);
  raise_still_water_level(grid, 1.25);
  EXPECT_EQ(grid.surroundings.still_water_depth_m(5, 5), -1.75f);
  EXPECT_TRUE(std::isnan(grid.surroundings.still_water_depth_m(0, 0)));
}

TEST(TimeSeries, ReadsOneColumnInCentimetresAndTimedColumns) {
  const auto folder = scratch_folder();
  const auto one = write_text(folder / "r2d.dat", "   -2.5\n   1.5\n# comment\n\n   3.0\n");
  TimeSeriesLayout layout;
  layout.sample_interval_s = 0.05;
  layout.elevation_scale_to_m = 0.01;
  TimeSeries series = read_time_series(one, layout);
  ASSERT_EQ(series.time_s.size(), 3u);
  EXPECT_DOUBLE_EQ(series.time_s[2], 0.1);
  EXPECT_DOUBLE_EQ(series.elevation_m[0], -0.025);
  layout.remove_mean = true;
  series = read_time_series(one, layout);
  EXPECT_NEAR(series.elevation_m[0] + series.elevation_m[1] + series.elevation_m[2], 0.0, 1e-15);

  const auto timed = write_text(folder / "timed.csv", "t,eta\n0.0,0.1\n0.5,0.2\n1.0,0.3\n");
  TimeSeriesLayout columns;
  columns.time_column = 1;
  columns.elevation_column = 2;
  series = read_time_series(timed, columns);
  EXPECT_DOUBLE_EQ(series.time_s[1], 0.5);
  EXPECT_DOUBLE_EQ(series.elevation_m[2], 0.3);
}

TEST(TimeSeries, BadTablesNameTheLine) {
  const auto folder = scratch_folder();
  TimeSeriesLayout columns;
  columns.time_column = 1;
  columns.elevation_column = 2;
  const auto expect_error = [&](const std::string& text, const std::string& fragment) {
    try {
      read_time_series(write_text(folder / "bad.csv", text), columns);
      ADD_FAILURE() << fragment;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("bad.csv"), std::string::npos) << error.what();
    }
  };
  expect_error("0 0.1\n1 x\n", "line 2 is not a row of numbers");
  expect_error("0 0.1\n1\n", "line 2 has 1 columns");
  expect_error("0 0.1\n0 0.2\n", "line 2: time 0 s does not increase");
  expect_error("0 0.1\n", "holds 1 samples");
}

TEST(Gauges, CsvRoundTripAndCheckpointState) {
  const auto folder = scratch_folder();
  GaugeTable table;
  // GaugeRecorder needs a solver to sample; the file format is exercised through its writer with
  // a recorder restored from a hand-made state.
  GaugeRecorder recorder({{"north", 1.0, 2.0}, {"south", 3.0, 4.0}});
  std::stringstream state;
  {
    const std::uint64_t names = 2, samples = 3;
    state.write(reinterpret_cast<const char*>(&names), 8);
    for (std::string name : {"north", "south"}) {
      const std::uint64_t length = name.size();
      state.write(reinterpret_cast<const char*>(&length), 8);
      state.write(name.data(), static_cast<std::streamsize>(length));
    }
    state.write(reinterpret_cast<const char*>(&samples), 8);
    // times, then each gauge's elevations, then each gauge's P, then each gauge's Q (bake_gauges.cpp)
    const double values[21] = {0.0, 0.025, 0.05, 0.1234567891234, -1e-7, 0.0, 1.0 / 3.0, 2.5e-3, -0.75,
                               0.5,  -0.5,  1.5,  2.0,             2.5,   3.0, -1.0,      -2.0,   -3.0,
                               4.0,  5.0,   6.0};
    state.write(reinterpret_cast<const char*>(values), sizeof values);
  }
  recorder.load(state, "state");
  recorder.write_csv(folder / "gauges.csv");
  recorder.write_fluxes_csv(folder / "gauge_fluxes.csv");
  GaugeTable read = read_gauges_csv(folder / "gauges.csv");
  EXPECT_TRUE(read.flux_x_m2_s.empty());  // gauges.csv alone holds no fluxes
  read_gauge_fluxes_csv(folder / "gauge_fluxes.csv", read);
  EXPECT_EQ(read.flux_x_m2_s, (std::vector<std::vector<double>>{{0.5, -0.5, 1.5}, {2.0, 2.5, 3.0}}));
  EXPECT_EQ(read.flux_y_m2_s, (std::vector<std::vector<double>>{{-1.0, -2.0, -3.0}, {4.0, 5.0, 6.0}}));
  // A fluxes file of other gauges, or of other times, is refused naming the file.
  GaugeTable other_gauges = read;
  other_gauges.names = {"north", "east"};
  EXPECT_THROW(read_gauge_fluxes_csv(folder / "gauge_fluxes.csv", other_gauges), Error);
  GaugeTable other_times = read;
  other_times.time_s[2] = 0.075;
  EXPECT_THROW(read_gauge_fluxes_csv(folder / "gauge_fluxes.csv", other_times), Error);
  ASSERT_EQ(read.names, (std::vector<std::string>{"north", "south"}));
  ASSERT_EQ(read.time_s.size(), 3u);
  EXPECT_DOUBLE_EQ(read.time_s[1], 0.025);
  // %.9g: nine significant digits, far below the float precision of the solver's fields.
  EXPECT_NEAR(gauge_column(read, "north")[0], 0.1234567891234, 1e-9 * 0.1234567891234);
  EXPECT_DOUBLE_EQ(gauge_column(read, "south")[2], -0.75);
  EXPECT_THROW(gauge_column(read, "east"), Error);
  // Saving and loading the binary state is exact.
  std::stringstream again;
  recorder.save(again);
  GaugeRecorder copy({{"north", 1.0, 2.0}, {"south", 3.0, 4.0}});
  copy.load(again, "again");
  EXPECT_EQ(copy.table().elevation_m, recorder.table().elevation_m);
  EXPECT_EQ(copy.table().flux_x_m2_s, recorder.table().flux_x_m2_s);
  EXPECT_EQ(copy.table().flux_y_m2_s, recorder.table().flux_y_m2_s);
  // A recorder for other gauges refuses the state.
  std::stringstream other;
  recorder.save(other);
  GaugeRecorder different({{"east", 1.0, 2.0}});
  EXPECT_THROW(different.load(other, "other"), Error);
  // No temporary file is left beside the output.
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    EXPECT_TRUE(entry.path().filename() == "gauges.csv" || entry.path().filename() == "gauge_fluxes.csv") << entry.path();
}

TEST(Gauges, DamagedCsvIsNamed) {
  const auto folder = scratch_folder();
  EXPECT_THROW(read_gauges_csv(write_text(folder / "a.csv", "time,g\n0,1\n")), Error);
  EXPECT_THROW(read_gauges_csv(write_text(folder / "b.csv", "t,g\n0,1,2\n")), Error);
  EXPECT_THROW(read_gauges_csv(write_text(folder / "c.csv", "t,g\n0,x\n")), Error);
}

// ---- Issue 13 item 6 and 9: absurd values in a case are refused with the value, the bound and why,
// naming the case file's key, before the solver (or the bake) starts. ---------------------------------

// The small flume case with its first `from` replaced by `to`.
std::string flume_with(const std::string& from, const std::string& to) {
  std::string text = testing::small_flume_case();
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(CaseBounds, ATinyTimeStepIsRefusedForItsStepCount) {
  testing::expect_case_error(flume_with("courant_number = 0.5", "time_step_s = 1e-9"),
                             {"key `time.time_step_s` = 1e-09 s", "makes 8e+09 solver steps over time.duration_s = 8 s",
                              "more than the limit of 10000000", "give a longer time.time_step_s"});
}

TEST(CaseBounds, AHugeDurationIsRefusedForItsFrameCount) {
  // As in the issue: duration_s = 1e9 s at 2 frames a second would be 5e8 frame files.
  testing::expect_case_error(flume_with("duration_s = 8.000000", "duration_s = 1e9"),
                             {"key `time.duration_s` = 1000000000 s", "time.output_interval_s = 0.5 s makes 2e+09 frames",
                              "more than the limit of 1000000", "shorten time.duration_s"});
  // Below the frame limit (8e5 frames) but 1.8e7 steps of the Courant-derived 0.0217 s step.
  testing::expect_case_error(flume_with("duration_s = 8.000000", "duration_s = 4e5"),
                             {"key `time.duration_s` = 400000 s makes 1.84e+07 solver steps", "time.courant_number = 0.5",
                              "more than the limit of 10000000"});
}

TEST(CaseBounds, ATimeStepAboveTheStabilityLimitNamesTheKey) {
  // sqrt(g 0.5 m) 0.2 s / 0.1 m = 4.4; the step is first reduced to 0.5 s / 3 to divide the frames.
  testing::expect_case_error(flume_with("courant_number = 0.5", "time_step_s = 0.2"),
                             {"key `time.time_step_s` = 0.2 s (reduced to 0.166667 s", "Courant number",
                              "= 3.69", "above 2, the solver's stability limit", "give time.time_step_s <= 0.0903 s"});
  testing::expect_case_error(flume_with("courant_number = 0.5", "courant_number = 3"),
                             {"key `time.courant_number` = 3 is above 2, the solver's stability limit",
                              "give time.courant_number <= 2"});
}

TEST(CaseBounds, TheSolverStillRefusesAnUnstableStepNamingItsField) {
  // The library-level guard behind the case reader, for callers that build SolverParameters themselves.
  const HarbourGrid harbour = flume_from_profile(12.0, 0.6, 0.1, {{0.0, 0.5}, {12.0, 0.5}}, "test");
  SolverParameters parameters;
  parameters.time_step_s = 0.2;
  try {
    BoussinesqSolver solver(harbour, parameters, WaveMaker{});
    ADD_FAILURE() << "an unstable time step was accepted";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("SolverParameters::time_step_s = 0.2 s gives a Courant number"), std::string::npos) << message;
    EXPECT_NE(message.find("above the stability limit 2"), std::string::npos) << message;
  }
}

TEST(CaseBounds, DepthsBeyondTheDeepestOceanAreRefused) {
  // A flume profile 20 km deep.
  testing::expect_case_error(flume_with("profile = [[0.0, 0.5], [12.0, 0.5]]", "profile = [[0.0, 20000.0], [12.0, 0.5]]"),
                             {"key `bathymetry.profile` gives a depth of", "deeper than 11000 m, the deepest water on Earth"});
  // A harbour grid (depth.exr) with a 6e28 m deep cell, as a GeoTIFF with an undeclared fill value
  // gave before `bathy` refused it: the bake ran with a 1e-14 s step and never finished.
  const auto folder = testing::scratch_folder();
  HarbourGrid grid = flume_from_profile(12.0, 0.6, 0.1, {{0.0, 0.5}, {12.0, 0.5}}, "test");
  grid.still_water_depth_m(40, 2) = 6.0e28f;
  write_harbour_grid(folder / "depth.exr", grid);
  testing::expect_case_error(flume_with("kind = \"profile\"\nlength_m = 12.0\nwidth_m = 0.6\nspacing_m = 0.1\n"
                                        "profile = [[0.0, 0.5], [12.0, 0.5]]",
                                        "kind = \"harbour_grid\"\nfile = \"depth.exr\""),
                             {"key `bathymetry.file` gives a depth of 6e+28 m at cell (column 40, row 2; 4.05 m, 0.25 m "
                              "from the south-west corner), deeper than 11000 m"});
}

}  // namespace
}  // namespace nearshore::bake
