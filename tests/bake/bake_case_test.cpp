// The case file parser: a valid case in TOML and JSON gives the same BakeCase, and every bad key or
// value gives ONE nearshore::Error that names the case file, the key and a fix.
#include <cmath>
#include <numbers>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_case.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bake {

using namespace nearshore::ocean;
using namespace nearshore::boussinesq;
namespace {
using testing::expect_case_error;
using testing::scratch_folder;
using testing::small_flume_case;
using testing::write_text;

// Replaces the first occurrence of `from` in the small flume case (so each error case is one edit).
std::string edited(const std::string& from, const std::string& to) {
  std::string text = small_flume_case();
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(BakeCase, ReadsTheSmallFlume) {
  const auto file = write_text(scratch_folder() / "case.toml", small_flume_case());
  const BakeCase c = read_bake_case(file);
  EXPECT_EQ(c.harbour.geometry.columns, 120);
  EXPECT_EQ(c.harbour.geometry.rows, 6);
  EXPECT_FLOAT_EQ(c.harbour.still_water_depth_m(60, 3), 0.5f);
  // Courant 0.5 at d = 0.5 m, dx = 0.1 m gives 0.0226 s; reduced to divide 0.5 s: 23 steps.
  EXPECT_EQ(whole_steps(c.timing.output_interval_s, c.solver.time_step_s), 23);
  EXPECT_LE(c.solver.time_step_s, 0.5 * 0.1 / std::sqrt(kGravity_m_s2 * 0.5) + 1e-12);
  ASSERT_EQ(c.wave_maker.kind, WaveMaker::Kind::kComponents);
  ASSERT_EQ(c.wave_maker.sea_state.components.size(), 1u);
  EXPECT_DOUBLE_EQ(c.wave_maker.sea_state.components[0].amplitude_m, 0.01);
  EXPECT_DOUBLE_EQ(c.wave_maker.sea_state.components[0].angular_frequency_rad_s, std::numbers::pi);
  EXPECT_DOUBLE_EQ(c.wave_maker.sea_state.components[0].direction_rad, 0.0);  // away from the west side
  EXPECT_EQ(c.wave_maker.facing, Side::kWest);
  ASSERT_EQ(c.solver.sponges.size(), 2u);
  EXPECT_EQ(c.solver.sponges[1].side, Side::kEast);
  ASSERT_EQ(c.gauges.size(), 2u);
  EXPECT_EQ(c.gauges[1].name, "g2");
  EXPECT_EQ(c.wave_conditions["case"]["kind"], "regular");
  // The water's viscosity (docs/solver.md, "Bed friction"): fresh water at 20 C unless the case says.
  EXPECT_DOUBLE_EQ(c.solver.kinematic_viscosity_m2_s, 1.0e-6);
  EXPECT_DOUBLE_EQ(c.solver_record["kinematic_viscosity_m2_s"].get<double>(), 1.0e-6);
}

// Issue 15: spacing_m = [dx, dy] gives rectangular cells; the time step follows the smaller size.
TEST(BakeCase, ReadsRectangularCells) {
  const auto file = write_text(scratch_folder() / "case.toml", edited("spacing_m = 0.1", "spacing_m = [0.1, 0.2]"));
  const BakeCase c = read_bake_case(file);
  EXPECT_EQ(c.harbour.geometry.columns, 120);
  EXPECT_EQ(c.harbour.geometry.rows, 3);
  EXPECT_DOUBLE_EQ(c.harbour.geometry.spacing_x_m(), 0.1);
  EXPECT_DOUBLE_EQ(c.harbour.geometry.spacing_y_m(), 0.2);
  EXPECT_EQ(whole_steps(c.timing.output_interval_s, c.solver.time_step_s), 23);  // as the square 0.1 m flume
  const BakeCase tall = read_bake_case(write_text(scratch_folder() / "tall.toml", edited("spacing_m = 0.1", "spacing_m = [0.2, 0.05]")));
  EXPECT_LE(tall.solver.time_step_s, 0.5 * 0.05 / std::sqrt(kGravity_m_s2 * 0.5) + 1e-12);  // min(dx, dy) = 0.05 m
  expect_case_error(edited("spacing_m = 0.1", "spacing_m = [0.1]"), {"key `bathymetry.spacing_m`", "[dx_m, dy_m]"});
  expect_case_error(edited("spacing_m = 0.1", "spacing_m = [0.1, -0.2]"), {"key `bathymetry.spacing_m`", "not a cell size"});
}

TEST(BakeCase, JsonAndTomlGiveTheSameCase) {
  const auto folder = scratch_folder();
  const BakeCase from_toml = read_bake_case(write_text(folder / "case.toml", small_flume_case()));
  const auto json_file = write_text(folder / "case.json", from_toml.source.dump(2));
  const BakeCase from_json = read_bake_case(json_file);
  EXPECT_EQ(from_json.source, from_toml.source);
  EXPECT_EQ(from_json.solver.time_step_s, from_toml.solver.time_step_s);
  EXPECT_EQ(from_json.harbour.still_water_depth_m.values(), from_toml.harbour.still_water_depth_m.values());
  EXPECT_EQ(from_json.solver_record, from_toml.solver_record);
}

TEST(BakeCase, ResolvedTimeStepDividesTheOutputInterval) {
  HarbourGrid grid = HarbourGrid::open_water(GridGeometry{10, 10, 2.0, 0, 0, {}, {}}, 10.f);
  for (double interval : {0.1, 0.25, 1.0, 0.7}) {
    const double dt = resolve_time_step(0.0, 0.5, grid, interval);
    EXPECT_GT(whole_steps(interval, dt), 0) << interval;
    EXPECT_LE(dt, 0.5 * 2.0 / std::sqrt(kGravity_m_s2 * 10.0) * (1 + 1e-12));
  }
  EXPECT_DOUBLE_EQ(resolve_time_step(0.03, 0.5, grid, 0.1), 0.025);  // 0.03 -> 4 steps per 0.1 s
  EXPECT_DOUBLE_EQ(resolve_time_step(0.05, 0.5, grid, 0.1), 0.05);
  // With a [current] the Courant number is (|U| + sqrt(g d_max)) dt / dx (docs/solver.md, "Currents"):
  // 3 m/s beside sqrt(g 10 m) = 9.9 m/s makes the step shorter by that ratio (1 s divided in whole steps).
  const double still = resolve_time_step(0.0, 0.5, grid, 1.0);
  const double on_current = resolve_time_step(0.0, 0.5, grid, 1.0, {3.0, 0.0});
  EXPECT_LE(on_current, 0.5 * 2.0 / (3.0 + std::sqrt(kGravity_m_s2 * 10.0)) * (1 + 1e-12));
  EXPECT_GT(on_current, 0.9 * 0.5 * 2.0 / (3.0 + std::sqrt(kGravity_m_s2 * 10.0)));
  EXPECT_LT(on_current, still);
  EXPECT_EQ(resolve_time_step(0.0, 0.5, grid, 1.0, {}), still);
}

TEST(BakeCase, UnknownKeysAreErrors) {
  expect_case_error(edited("title =", "titel ="), {"key `titel`", "not a known key"});
  expect_case_error(edited("spin_up_s", "spinup_s"), {"key `time.spinup_s`"});
  expect_case_error(small_flume_case() + "[solver.breaking]\nonset_celerity = 0.5\n", {"key `solver.breaking.onset_celerity`"});
  expect_case_error(edited("name = \"g1\"", "name = \"g1\"\nz_m = 1.0"), {"key `gauges[0].z_m`"});
}

TEST(BakeCase, MissingTablesAndKeysAreErrors) {
  expect_case_error("[time]\nduration_s = 1\noutput_interval_s = 0.1\n", {"key `bathymetry`", "is missing"});
  expect_case_error(edited("duration_s = ", "length_s = "), {"key `time.duration_s`", "is missing"});
  expect_case_error(edited("height_m = 0.02\n", ""), {"key `wave_maker.height_m`", "is missing"});
  expect_case_error(edited("kind = \"profile\"\n", ""), {"key `bathymetry.kind`", "is missing"});
  expect_case_error("bathymetry = 3\n", {"key `bathymetry` is not a table"});
}

TEST(BakeCase, BadValuesAreErrors) {
  expect_case_error(edited("spacing_m = 0.1", "spacing_m = -0.1"), {"key `bathymetry.spacing_m`", "out of range"});
  expect_case_error(edited("spacing_m = 0.1", "spacing_m = \"fine\""), {"key `bathymetry.spacing_m`", "must be a number"});
  expect_case_error(edited("kind = \"profile\"", "kind = \"profil\""), {"key `bathymetry.kind`", "\"profil\" is not known", "profile"});
  expect_case_error(edited("facing = \"west\"", "facing = \"up\""), {"key `wave_maker.facing`"});
  expect_case_error(edited("spin_up_s = 2.0", "spin_up_s = 20.0"), {"key `time.spin_up_s`", "not shorter"});
  expect_case_error(edited("courant_number = 0.5", "courant_number = 0.5\ntime_step_s = 0.01"), {"time_step_s", "both given"});
  expect_case_error(edited("[[0.0, 0.5], [12.0, 0.5]]", "[[0.0, 0.5], [0.0, 0.4]]"), {"key `bathymetry.profile`", "strictly increasing"});
  expect_case_error(edited("[[0.0, 0.5], [12.0, 0.5]]", "[0.0, 0.5]"), {"key `bathymetry.profile`", "not a pair"});
  expect_case_error(edited("x_m = 5.0", "x_m = 50.0"), {"key `gauges[0].x_m`", "out of range"});
  expect_case_error(edited("name = \"g2\"", "name = \"g1\""), {"key `gauges[1].name`", "another gauge"});
  expect_case_error(edited("name = \"g2\"", "name = \"a,b\""), {"key `gauges[1].name`", "comma"});
  expect_case_error(edited("width_m = 3.0", "width_m = 9.0"), {"key `sponges[1].width_m`", "out of range"});
  expect_case_error(edited("side = \"east\"", "side = \"eats\""), {"key `sponges[1].side`"});
  expect_case_error(edited("source_line_m = 3.0", "source_line_m = 30.0"), {"key `wave_maker.source_line_m`", "out of range"});
  expect_case_error(small_flume_case() + "[solver.breaking]\nonset_celerity_fraction = 0.1\nstop_celerity_fraction = 0.2\n",
                    {"key `solver.breaking.stop_celerity_fraction`", "larger than onset"});
  expect_case_error(small_flume_case() + "[solver]\nnonlinear_iterations = 1.5\n", {"key `solver.nonlinear_iterations`", "whole number"});
  expect_case_error(small_flume_case() + "[solver]\nkinematic_viscosity_m2_s = -1e-6\n",
                    {"key `solver.kinematic_viscosity_m2_s`", "out of range", "kinematic viscosity"});
  expect_case_error(small_flume_case() + "[[porous_blocks]]\nx_range_m = [100.0, 101.0]\ny_range_m = [0.0, 1.0]\nporosity = 0.4\n",
                    {"key `porous_blocks[0].x_range_m`", "no cell centre"});
  expect_case_error(small_flume_case() + "[[porous_blocks]]\nx_range_m = [1.0, 2.0]\ny_range_m = [0.0, 1.0]\nporosity = 1.4\n",
                    {"key `porous_blocks[0].porosity`", "out of range"});
}

TEST(BakeCase, LoopPeriodMustHoldWholePeriodsAndFrames) {
  expect_case_error(edited("period_s = 2.0", "period_s = 2.0\nloop_period_s = 7.0"), {"key `wave_maker.period_s`", "does not repeat", "loop_period_s = 8"});
}

TEST(BakeCase, OutputIntervalMustDivideTheLoop) {
  std::string text = edited("period_s = 2.0", "period_s = 2.0\nloop_period_s = 8.0");
  text.replace(text.find("output_interval_s = 0.5"), 23, "output_interval_s = 0.3");
  expect_case_error(text, {"key `time.output_interval_s`", "does not divide"});
  const auto ok = write_text(scratch_folder() / "ok.toml", edited("period_s = 2.0", "period_s = 2.0\nloop_period_s = 8.0"));
  EXPECT_DOUBLE_EQ(read_bake_case(ok).wave_maker.sea_state.loop_period_s, 8.0);
}

TEST(BakeCase, SyntaxErrorsNameTheLine) {
  expect_case_error(small_flume_case() + "[time\n", {"not valid TOML at line"});
  expect_case_error("{\"bathymetry\": ", {"not valid JSON"}, ".json");
  expect_case_error("x = 1\n", {"neither a .toml nor a .json"}, ".yaml");
}

TEST(BakeCase, MissingFilesAreNamed) {
  EXPECT_THROW(read_bake_case(scratch_folder() / "absent.toml"), Error);
  expect_case_error(edited("kind = \"profile\"", "kind = \"harbour_grid\"\nfile = \"nowhere/depth.exr\""), {"depth.exr", "does not exist"});
}

TEST(BakeCase, GaugeIntervalFallsOnWholeSteps) {
  const BakeCase c = read_bake_case(write_text(scratch_folder() / "case.toml", edited("courant_number = 0.5", "courant_number = 0.5\ngauge_interval_s = 0.05")));
  EXPECT_GT(whole_steps(0.05, c.solver.time_step_s), 0);
  EXPECT_GT(whole_steps(0.5, c.solver.time_step_s), 0);
  expect_case_error(edited("courant_number = 0.5", "courant_number = 0.5\ngauge_interval_s = 0.3"), {"key `time.gauge_interval_s`", "neither divides"});
}

TEST(BakeCase, TimeSeriesWaveMakerReadsItsTable) {
  const auto folder = scratch_folder();
  write_text(folder / "eta.dat", "1.0\n2.0\n-3.0\n");
  std::string text = small_flume_case();
  text.replace(text.find("kind = \"regular\""), 16, "kind = \"time_series\"\nfile = \"eta.dat\"\nsample_interval_s = 0.05\nelevation_scale_to_m = 0.01");
  text.replace(text.find("height_m = 0.02\nperiod_s = 2.0\n"), 31, "");
  const BakeCase c = read_bake_case(write_text(folder / "case.toml", text));
  ASSERT_EQ(c.wave_maker.kind, WaveMaker::Kind::kTimeSeries);
  ASSERT_EQ(c.wave_maker.series_elevation_m.size(), 3u);
  EXPECT_NEAR(c.wave_maker.series_elevation_m[0], 0.01, 1e-15);  // remove_mean by default: (1 + 2 - 3) / 3 = 0
  EXPECT_DOUBLE_EQ(c.wave_maker.series_time_s[2], 0.1);
  std::string missing = text;
  missing.replace(missing.find("eta.dat"), 7, "none.dat");
  expect_case_error(missing, {"key `wave_maker.file`", "none.dat", "does not exist"});
  write_text(folder / "bad.dat", "1.0\nx\n");
  std::string bad = text;
  bad.replace(bad.find("eta.dat"), 7, "bad.dat");
  expect_case_error(bad, {"key `wave_maker.file`", "line 2"});
}

TEST(BakeCase, HarbourGridPositionsAreFromTheSouthWestCorner) {
  const auto folder = scratch_folder();
  // A 400 m x 300 m grid at 10 m in UTM, origin at easting 500000, northing 4300000.
  HarbourGrid grid = HarbourGrid::open_water(GridGeometry{40, 30, 10.0, 500000.0, 4300000.0, {}, {}}, 12.f);
  write_harbour_grid(folder / "depth.exr", grid);
  const std::string text =
      "[bathymetry]\nkind = \"harbour_grid\"\nfile = \"depth.exr\"\nspacing_m = 20.0\n"
      "[time]\nduration_s = 60\noutput_interval_s = 1\n"
      "[wave_maker]\nkind = \"regular\"\nfacing = \"south\"\nsource_line_m = 50.0\nheight_m = 1.0\nperiod_s = 8.0\n"
      "[[gauges]]\nname = \"mid\"\nx_m = 200.0\ny_m = 150.0\n";
  const BakeCase c = read_bake_case(write_text(folder / "case.toml", text));
  EXPECT_EQ(c.harbour.geometry.columns, 20);  // resampled to 20 m
  EXPECT_DOUBLE_EQ(c.gauges[0].x_m, 500200.0);
  EXPECT_DOUBLE_EQ(c.gauges[0].y_m, 4300150.0);
  EXPECT_DOUBLE_EQ(c.wave_maker.source_line_m, 4300050.0);
  EXPECT_NEAR(c.wave_maker.sea_state.components[0].direction_rad, std::numbers::pi / 2, 1e-12);  // travels north
  std::string outside = text;
  outside.replace(outside.find("x_m = 200.0"), 11, "x_m = 500200.0");
  expect_case_error(outside, {"key `gauges[0].x_m`", "south-west corner"});
}

TEST(BakeCase, IrregularSeaFromTheSpectrumBuilder) {
  std::string text = small_flume_case();
  text.replace(text.find("kind = \"regular\""), 16, "kind = \"irregular\"\nspectrum = \"jonswap\"\nsignificant_height_m = 0.03\n"
                                                     "peak_period_s = 1.5\nfrequency_count = 32\nseed = 42\nloop_period_s = 64.0");
  text.replace(text.find("height_m = 0.02\nperiod_s = 2.0\n"), 31, "");
  // The automatic band reaches 2-3 Hz: waves of 0.2-0.4 m that 0.1 m cells cannot carry. They are
  // split off for the deep-water layer (issue 14), not refused, and the split is recorded.
  {
    const BakeCase split = read_bake_case(write_text(scratch_folder() / "split.toml", text));
    ASSERT_TRUE(split.wave_conditions.contains("spectrum_split"));
    EXPECT_LT(split.wave_maker.sea_state.components.size(), 32u);
    EXPECT_GT(split.wave_conditions["spectrum_split"]["deep_water_components"].get<int>(), 0);
  }
  text.replace(text.find("seed = 42"), 9, "seed = 42\nmin_frequency_hz = 0.25\nmax_frequency_hz = 1.2");
  const BakeCase c = read_bake_case(write_text(scratch_folder() / "case.toml", text));
  EXPECT_EQ(c.wave_maker.sea_state.seed, 42u);
  EXPECT_EQ(c.wave_maker.sea_state.components.size(), 32u);
  EXPECT_DOUBLE_EQ(c.wave_maker.sea_state.loop_period_s, 64.0);
  for (const auto& component : c.wave_maker.sea_state.components)  // every frequency a harmonic of 1/T_loop
    EXPECT_GT(whole_steps(64.0, 2 * std::numbers::pi / component.angular_frequency_rad_s), 0);
  EXPECT_EQ(c.wave_conditions["seed"], 42);
}

// Left out, the wet/dry threshold is a 300th of the deepest water, at most the solver's centimetre
// (docs/solver.md, "Wet and dry"): a flume of a few decimetres gets a millimetre-scale film, a harbour
// keeps the centimetre, a given value is kept as given, and the manifest's solver record says which.
TEST(BakeCase, TheDryDepthIsAThreeHundredthOfTheDeepestWaterUpToACentimetre) {
  const auto folder = scratch_folder();
  const std::string flat = "profile = [[0.0, 0.5], [12.0, 0.5]]";
  const std::string beach = "profile = [[0.0, 0.5], [9.0, 0.5], [12.0, -0.1]]";
  const BakeCase flume = read_bake_case(write_text(folder / "case.toml", edited(flat, beach)));
  EXPECT_DOUBLE_EQ(flume.solver.dry_depth_m, 0.5 / 300.0);
  EXPECT_DOUBLE_EQ(flume.solver_record["dry_depth_m"].get<double>(), 0.5 / 300.0);
  EXPECT_TRUE(flume.warnings.empty()) << flume.warnings.front();
  const std::string report = describe_derived_solver_settings(flume);
  RecordProperty("report", report);
  EXPECT_NE(report.find("wet/dry threshold: 1.7 mm, a 300th of the 0.5 m deepest water (solver.dry_depth_m left out"),
            std::string::npos) << report;
  const BakeCase given = read_bake_case(write_text(folder / "given.toml", edited(flat, beach) + "[solver]\ndry_depth_m = 0.002\n"));
  EXPECT_DOUBLE_EQ(given.solver.dry_depth_m, 0.002);
  EXPECT_EQ(describe_derived_solver_settings(given), "");  // given, not derived
  // Three metres and deeper: a 300th is a centimetre or more, and the harbour's centimetre stands.
  const BakeCase harbour = read_bake_case(
      write_text(folder / "harbour.toml", edited(flat, "profile = [[0.0, 4.0], [9.0, 4.0], [12.0, -0.1]]")));
  EXPECT_DOUBLE_EQ(harbour.solver.dry_depth_m, boussinesq::SolverParameters{}.dry_depth_m);
  EXPECT_DOUBLE_EQ(harbour.solver.dry_depth_m, 0.01);
  EXPECT_EQ(describe_derived_solver_settings(harbour), "");  // the solver's own default
}

// Left out, the grid-scale filter follows the grid (docs/solver.md, "Grid-scale filter"): the
// solver's order 8 on cells finer than a quarter of the deepest water (a laboratory grid, where the
// fine-grid mode it removes arises), off on coarser ones (a harbour grid, where its mask's edge
// beside a quay grows a mode of its own); a given order is kept, and the solver record says which.
TEST(BakeCase, TheGridScaleFilterIsOnForGridsFinerThanAQuarterOfTheDepth) {
  const auto folder = scratch_folder();
  const std::string flat = "profile = [[0.0, 0.5], [12.0, 0.5]]";
  const BakeCase fine = read_bake_case(write_text(folder / "fine.toml", edited(flat, flat)));
  const double spacing_m = fine.harbour.geometry.smaller_spacing_m();
  ASSERT_LT(spacing_m, 0.5 / 4.0);
  EXPECT_EQ(fine.solver.shapiro_filter_order, boussinesq::SolverParameters{}.shapiro_filter_order);
  EXPECT_EQ(fine.solver.shapiro_filter_order, 8);
  // The same cells under water 3 cells deep: a harbour's proportions.
  const std::string depth = std::to_string(3.0 * spacing_m);
  const std::string shallow = "profile = [[0.0, " + depth + "], [12.0, " + depth + "]]";
  const BakeCase coarse = read_bake_case(write_text(folder / "coarse.toml", edited(flat, shallow)));
  EXPECT_EQ(coarse.solver.shapiro_filter_order, 0);
  EXPECT_EQ(coarse.solver_record["shapiro_filter_order"].get<int>(), 0);
  const std::string report = describe_derived_solver_settings(coarse);
  RecordProperty("report", report);
  EXPECT_NE(report.find("grid-scale filter: off"), std::string::npos) << report;
  EXPECT_NE(report.find("solver.shapiro_filter_order left out"), std::string::npos) << report;
  const BakeCase given =
      read_bake_case(write_text(folder / "given.toml", edited(flat, shallow) + "[solver]\nshapiro_filter_order = 8\n"));
  EXPECT_EQ(given.solver.shapiro_filter_order, 8);
  EXPECT_EQ(describe_derived_solver_settings(given).find("grid-scale filter"), std::string::npos);
}

// solver.wall_dispersion (docs/solver.md, "Walls and the dispersive terms"): the solver's default
// when left out, the option when given, both in the solver record; any other value is refused with
// the key and the choices named.
TEST(BakeCase, TheWallDispersionIsReadAndRecorded) {
  const auto folder = scratch_folder();
  const std::string flat = "profile = [[0.0, 0.5], [12.0, 0.5]]";
  const BakeCase left_out = read_bake_case(write_text(folder / "default.toml", edited(flat, flat)));
  EXPECT_EQ(left_out.solver.wall_dispersion, boussinesq::SolverParameters::WallDispersion::kEndBeforeWalls);
  EXPECT_EQ(left_out.solver_record["wall_dispersion"].get<std::string>(), "end_before_walls");
  const BakeCase mirrored =
      read_bake_case(write_text(folder / "mirror.toml", edited(flat, flat) + "[solver]\nwall_dispersion = \"mirror_at_walls\"\n"));
  EXPECT_EQ(mirrored.solver.wall_dispersion, boussinesq::SolverParameters::WallDispersion::kMirrorAtWalls);
  EXPECT_EQ(mirrored.solver_record["wall_dispersion"].get<std::string>(), "mirror_at_walls");
  expect_case_error(edited(flat, flat) + "[solver]\nwall_dispersion = \"mirror\"\n",
                    {"key `solver.wall_dispersion`", "mirror_at_walls"});
}

TEST(BakeCase, AnImposedCurrentIsReadAndRecorded) {
  const auto folder = scratch_folder();
  const BakeCase still = read_bake_case(write_text(folder / "still.toml", small_flume_case()));
  EXPECT_FALSE(still.solver.current.any());
  EXPECT_FALSE(still.solver_record.contains("current"));  // the record of a bake without one is as before
  const BakeCase against = read_bake_case(write_text(folder / "current.toml", small_flume_case() + "[current]\nu_m_s = -0.5\n"));
  EXPECT_EQ(against.solver.current.velocity_x_m_s, -0.5);
  EXPECT_EQ(against.solver.current.velocity_y_m_s, 0.0);
  EXPECT_EQ(against.solver_record["current"]["u_m_s"].get<double>(), -0.5);
  expect_case_error(small_flume_case() + "[current]\nu_m_s = 9.0\n", {"key `current.u_m_s`", "out of range"});
  expect_case_error(small_flume_case() + "[current]\nspeed_m_s = 1.0\n", {"current.speed_m_s"});
}
}  // namespace
}  // namespace nearshore::bake
