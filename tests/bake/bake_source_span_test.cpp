// Wave makers that follow the water (issue 46): a source line keeps to one wet span. Over a chart
// whose old-style line crosses a headland and comes out in a cove (as Tacoma's crossed Browns
// Point), the line without a point to choose a span is refused naming both spans; a point keeps the
// source to its span; `boundary = "north"` puts the source in front of the north sponge over the
// boundary's whole wet span, and the bake then makes the incident wave height in the open water.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_gauges.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::bake::testing {
namespace {

// 90 x 100 cells of 3 m (270 m x 300 m), 8 m deep, the sea to the north. Land: a headland, columns
// 50-76 (x 150-231 m) of rows 37-53 (y 111-162 m), and the north-east coast east of it, columns
// 77-89 of rows 54-99. An east-west line at y = 135 m (row 45) runs over water for columns 0-49,
// over the headland, and over a cove for columns 77-89 (39 m: 1.1 wavelengths of the 5 s wave
// below), which opens southwards into the bay: Tacoma's line over Browns Point, in small.
std::filesystem::path write_headland_grid(const std::filesystem::path& folder) {
  GridGeometry g;
  g.columns = 90;
  g.rows = 100;
  g.spacing_m = 3.0;
  HarbourGrid grid = HarbourGrid::open_water(g, 8.0f);
  for (int row = 0; row < g.rows; ++row)
    for (int column = 0; column < g.columns; ++column) {
      const bool headland = column >= 50 && column <= 76 && row >= 37 && row <= 53;
      const bool coast = column >= 77 && row >= 54;
      if (headland || coast) grid.land(column, row) = kLandCell, grid.still_water_depth_m(column, row) = -2.0f;
    }
  write_harbour_grid(folder / "depth.exr", grid);
  return folder / "depth.exr";
}

// Regular 5 s waves 0.2 m high from the north (k d = 1.44 in 8 m: L = 34.9 m, 11.6 cells), a 40 m
// north sponge (1.15 L) and a south one; `source` places the line. Gauges in the open water between
// the boundary's source line and the headland, west of it.
std::string headland_case(const std::string& source, double duration_s = 2.0) {
  return "[bathymetry]\nkind = \"harbour_grid\"\nfile = \"depth.exr\"\n"
         "[time]\nduration_s = " + std::to_string(duration_s) + "\noutput_interval_s = 1.0\n"
         "[wave_maker]\nkind = \"regular\"\n" + source +
         "\nheight_m = 0.2\nperiod_s = 5.0\nramp_time_s = 5.0\n"
         "[[sponges]]\nside = \"north\"\nwidth_m = 40.0\n[[sponges]]\nside = \"south\"\nwidth_m = 40.0\n"
         "[[gauges]]\nname = \"west\"\nx_m = 45.0\ny_m = 195.0\n"
         "[[gauges]]\nname = \"middle\"\nx_m = 75.0\ny_m = 185.0\n"
         "[[gauges]]\nname = \"east\"\nx_m = 105.0\ny_m = 195.0\n";
}

TEST(BakeSourceSpan, ALineOverTwoWetSpansIsRefusedNamingThem) {
  const auto folder = scratch_folder();
  write_headland_grid(folder);
  // The old-style line: facing north at y = 135 m. Both spans, in cells and metres, and the fix.
  expect_case_error(headland_case("facing = \"north\"\nsource_line_m = 135.0"),
                    {"`wave_maker.source_line_m`", "2 wet spans", "cells 0-49 (x = 0-150 m from the south-west corner, 150 m long)",
                     "cells 77-89 (x = 231-270 m from the south-west corner, 39 m long)", "boundary", "source_line = {"});
}

TEST(BakeSourceSpan, APointKeepsTheSourceToItsSpan) {
  const auto folder = scratch_folder();
  write_headland_grid(folder);
  const BakeCase c = read_bake_case(
      write_text(folder / "case.toml", headland_case("facing = \"north\"\nsource_line = { x_m = 60.0, y_m = 135.0 }")));
  EXPECT_EQ(c.wave_maker.span_begin_cell, 0);
  EXPECT_EQ(c.wave_maker.span_end_cell, 50);
  // The cove's span is named as left without a source.
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("cells 77-89"), std::string::npos) << c.warnings[0];
  // A point on the headland holds neither span: refused, naming the line's spans.
  expect_case_error(headland_case("facing = \"north\"\nsource_line = { x_m = 180.0, y_m = 135.0 }"),
                    {"`wave_maker.source_line`", "on land", "holds none of the line's 2 wet spans", "cells 0-49", "cells 77-89"});
}

TEST(BakeSourceSpan, BoundaryNeedsItsSpongeAndKeysThatAgree) {
  const auto folder = scratch_folder();
  write_headland_grid(folder);
  std::string no_sponge = headland_case("boundary = \"north\"");
  no_sponge.replace(no_sponge.find("[[sponges]]\nside = \"north\"\nwidth_m = 40.0\n"), 42, "");
  expect_case_error(no_sponge, {"`wave_maker.boundary`", "no sponge", "side = \"north\""});
  expect_case_error(headland_case("boundary = \"north\"\nfacing = \"south\""), {"`wave_maker.facing`", "boundary"});
  expect_case_error(headland_case("boundary = \"north\"\nsource_line_m = 200.0"), {"`wave_maker.source_line_m`", "boundary"});
}

class BakeSourceSpanRun : public ::testing::Test {
 protected:
  void SetUp() override { ProgressBar::set_quiet(true); }
};

// The boundary's source: the line 40 m (sponge) + 39.0 m (the 5 s wave's deep-water wavelength)
// inside the north edge, y = 221 m (row 73), over columns 0-76, from the west edge to the coast:
// one span, both of whose ends are walls, which mirror it, so it makes the plane incident wave.
// Bound 5 %: the source's discrete transfer is within 1 % of the requested amplitude at 10-24 cells
// per wavelength (docs/solver.md, "Wave maker"), the 40 m sponge (1.15 wavelengths, Larsen & Dancy)
// sends back a few per cent of the half the source radiates into it, which crosses the gauges with
// the incident wave; 2 sqrt(2) times the standard deviation over two whole periods is the height of
// a sinusoid exactly. The window, 14-24 s, starts after the 5 s ramp has passed the gauges (the
// front travels at c_g = 4.6 m/s) and ends before the headland's reflection reaches them (its
// nearest corner is 115 m of path away for the east gauge: 25 s).
TEST_F(BakeSourceSpanRun, TheBoundarysSourceMakesTheIncidentHeight) {
  const auto folder = scratch_folder();
  write_headland_grid(folder);
  const BakeCase c = read_bake_case(write_text(folder / "case.toml", headland_case("boundary = \"north\"", 24.0)));
  EXPECT_NEAR(c.wave_maker.source_line_m, 300.0 - 40.0 - 9.81 * 25.0 / (2.0 * std::acos(-1.0)), 1e-9);
  EXPECT_EQ(c.wave_maker.span_begin_cell, 0);
  EXPECT_EQ(c.wave_maker.span_end_cell, 77);
  BakeOptions options;
  options.output_folder = folder / "out";
  run_bake(c, options);
  const GaugeTable gauges = read_gauges_csv(options.output_folder / "gauges.csv");
  for (const std::string name : {"west", "middle", "east"}) {
    const double height_m = gauge_four_sigma_m(gauges, name, 14.0, 24.0) / std::sqrt(2.0);  // H = 2 sqrt(2) sigma
    std::printf("gauge %s: H = %.4f m (incident 0.2 m)\n", name.c_str(), height_m);
    EXPECT_NEAR(height_m, 0.2, 0.05 * 0.2) << name;
  }
}

}  // namespace
}  // namespace nearshore::bake::testing
