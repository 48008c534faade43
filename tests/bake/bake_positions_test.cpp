// Positions in a case file in lat/lon or the grid's CRS (issue 14 item 2: gauges, the source line),
// warnings for positions on land, and the cells outside a chart's coverage treated as the case says
// (item 3: bathymetry.outside_chart = "land" or "sea"). A small UTM harbour grid written here
// stands for what `nearshore bathy` writes; every case goes through the parser as a user's would.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <fmt/core.h>

#include "bake_test_support.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/map_projection.hpp"

namespace nearshore::bake::testing {
namespace {

// 40 x 30 cells of 10 m in UTM zone 10N (Commencement Bay). Water deepens northwards (5 m + 0.1 m
// per row), so a nearest-water rule is checked by value; columns 0-3 are outside the chart (no
// data), column 30-39 of rows 0-19 land 2.5 m high (a quay), the rest water.
constexpr double kOriginX = 541000.0, kOriginY = 5236000.0;

std::filesystem::path write_grid(const std::filesystem::path& folder) {
  GridGeometry g;
  g.columns = 40;
  g.rows = 30;
  g.spacing_m = 10.0;
  g.origin_x_m = kOriginX;
  g.origin_y_m = kOriginY;
  g.projection = MapProjection::utm(10, true).to_json();
  HarbourGrid grid = HarbourGrid::open_water(g, 5.0f);
  for (int row = 0; row < g.rows; ++row)
    for (int column = 0; column < g.columns; ++column) {
      grid.still_water_depth_m(column, row) = 5.0f + 0.1f * row;
      if (column < 4) grid.land(column, row) = kOutsideChartCell, grid.still_water_depth_m(column, row) = -2.0f;
      if (column >= 30 && row < 20) grid.land(column, row) = kLandCell, grid.still_water_depth_m(column, row) = -2.5f;
    }
  write_harbour_grid(folder / "depth.exr", grid);
  return folder / "depth.exr";
}

LonLat lon_lat_at(double x_from_corner_m, double y_from_corner_m) {
  return MapProjection::utm(10, true).reverse({kOriginX + x_from_corner_m, kOriginY + y_from_corner_m});
}

// A short case over that grid: regular 4 s waves from the north, source line and gauges as given.
std::string harbour_case(const std::string& bathymetry_extra, const std::string& source_line, const std::string& gauges) {
  return "[bathymetry]\nkind = \"harbour_grid\"\nfile = \"depth.exr\"\n" + bathymetry_extra +
         "\n[time]\nduration_s = 2.0\noutput_interval_s = 1.0\n"
         "[wave_maker]\nkind = \"regular\"\nfacing = \"north\"\n" + source_line +
         "\nheight_m = 0.2\nperiod_s = 4.0\n" + gauges;
}

TEST(BakePositions, GaugesAndSourceLineInLatLonLandWhereTheirMetresSay) {
  const auto folder = scratch_folder();
  write_grid(folder);
  const LonLat gauge = lon_lat_at(150.0, 120.0);
  const LonLat line = lon_lat_at(200.0, 250.0);
  const std::string text = harbour_case(
      "", fmt::format("source_line = {{ lat = {:.10f}, lon = {:.10f} }}", line.latitude_deg, line.longitude_deg),
      fmt::format("[[gauges]]\nname = \"by_lat_lon\"\nlat = {:.10f}\nlon = {:.10f}\n"
                  "[[gauges]]\nname = \"by_crs\"\neasting_m = {}\nnorthing_m = {}\n"
                  "[[gauges]]\nname = \"by_metres\"\nx_m = 150.0\ny_m = 120.0\n",
                  gauge.latitude_deg, gauge.longitude_deg, kOriginX + 150.0, kOriginY + 120.0));
  const BakeCase bake_case = read_bake_case(write_text(folder / "case.toml", text));
  ASSERT_EQ(bake_case.gauges.size(), 3u);
  // Ten decimals of a degree are 1e-5 m on the ground; GeographicLib's round trip is nanometres.
  for (const GaugeSpec& spec : bake_case.gauges) {
    EXPECT_NEAR(spec.x_m, kOriginX + 150.0, 1e-3) << spec.name;
    EXPECT_NEAR(spec.y_m, kOriginY + 120.0, 1e-3) << spec.name;
  }
  // Facing north: the line runs east-west through the point, so only its y counts.
  EXPECT_NEAR(bake_case.wave_maker.source_line_m, kOriginY + 250.0, 1e-3);
  EXPECT_TRUE(bake_case.warnings.empty()) << bake_case.warnings.front();
}

TEST(BakePositions, AGaugeOutsideTheGridNamesItAndTheGridsExtent) {
  const auto folder = scratch_folder();
  write_grid(folder);
  const LonLat far = lon_lat_at(-2000.0, 100.0);
  expect_case_error(harbour_case("", "source_line_m = 250.0",
                                 fmt::format("[[gauges]]\nname = \"defiance\"\nlat = {}\nlon = {}\n", far.latitude_deg,
                                             far.longitude_deg)),
                    {"gauge \"defiance\" (gauges[0])", "lies outside the grid", "the grid covers lat 47.", "lon -122."});
}

TEST(BakePositions, AGaugeOrASourceLineOnLandIsWarnedWithItsDepth) {
  const auto folder = scratch_folder();
  write_grid(folder);
  const LonLat quay = lon_lat_at(355.0, 55.0);  // column 35, row 5: land 2.5 m high
  // The source line at y = 250 m (row 25) crosses 4 no-data cells of 40: no line warning.
  const BakeCase bake_case = read_bake_case(write_text(
      folder / "case.toml",
      harbour_case("", "source_line_m = 250.0",
                   fmt::format("[[gauges]]\nname = \"quay\"\nlat = {}\nlon = {}\n[[gauges]]\nname = \"water\"\nx_m = 150\ny_m = 150\n",
                               quay.latitude_deg, quay.longitude_deg))));
  ASSERT_EQ(bake_case.warnings.size(), 1u);
  const std::string& warning = bake_case.warnings.front();
  EXPECT_NE(warning.find("case.toml"), std::string::npos) << warning;
  EXPECT_NE(warning.find("gauge \"quay\""), std::string::npos) << warning;
  EXPECT_NE(warning.find("lies on land"), std::string::npos) << warning;
  EXPECT_NE(warning.find("2.50 m above still water"), std::string::npos) << warning;
  EXPECT_NE(warning.find("N, 122."), std::string::npos) << warning;  // said in lat/lon too

  // A source line given by a point on the quay: the point warns; the line is mostly water, so no
  // second warning.
  const BakeCase on_quay = read_bake_case(write_text(
      folder / "case2.toml",
      harbour_case("", fmt::format("source_line = {{ lat = {}, lon = {} }}", quay.latitude_deg, quay.longitude_deg), "")));
  ASSERT_EQ(on_quay.warnings.size(), 1u);
  EXPECT_NE(on_quay.warnings[0].find("wave_maker.source_line"), std::string::npos) << on_quay.warnings[0];
  EXPECT_NE(on_quay.warnings[0].find("lies on land"), std::string::npos) << on_quay.warnings[0];
}

TEST(BakePositions, ASourceLineMostlyOverLandIsWarned) {
  const auto folder = scratch_folder();
  write_grid(folder);
  // Facing east: the line runs north-south at x = 355 m (column 35): land for rows 0-19, 20 of 30.
  const std::string text =
      "[bathymetry]\nkind = \"harbour_grid\"\nfile = \"depth.exr\"\n[time]\nduration_s = 2.0\noutput_interval_s = 1.0\n"
      "[wave_maker]\nkind = \"regular\"\nfacing = \"east\"\nsource_line_m = 355.0\nheight_m = 0.2\nperiod_s = 4.0\n";
  const BakeCase bake_case = read_bake_case(write_text(folder / "case.toml", text));
  ASSERT_EQ(bake_case.warnings.size(), 1u);
  EXPECT_NE(bake_case.warnings[0].find("wave_maker.source_line_m"), std::string::npos) << bake_case.warnings[0];
  EXPECT_NE(bake_case.warnings[0].find("20 of its 30 cells"), std::string::npos) << bake_case.warnings[0];
}

TEST(BakePositions, OutsideTheChartIsLandByDefaultOrSeaAsAsked) {
  const auto folder = scratch_folder();
  write_grid(folder);
  const std::string gauges = "[[gauges]]\nname = \"g\"\nx_m = 150\ny_m = 150\n";
  // Default: land, as before nodata existed (a reflecting wall at the bathy's land elevation).
  const BakeCase as_land = read_bake_case(write_text(folder / "land.toml", harbour_case("", "source_line_m = 250.0", gauges)));
  EXPECT_EQ(as_land.harbour.land(0, 15), kLandCell);
  EXPECT_EQ(as_land.harbour.still_water_depth_m(0, 15), -2.0f);
  EXPECT_EQ(as_land.harbour.land(35, 5), kLandCell);
  // "sea": the nearest charted water cell's depth. Nearest to (column 0, row r) is (column 4, row
  // r), whose depth is 5 + 0.1 r: exact, since the feature transform is the exact Euclidean one.
  const BakeCase as_sea = read_bake_case(
      write_text(folder / "sea.toml", harbour_case("outside_chart = \"sea\"", "source_line_m = 250.0", gauges)));
  for (int row : {0, 15, 29}) {
    EXPECT_EQ(as_sea.harbour.land(0, row), kWaterCell);
    EXPECT_FLOAT_EQ(as_sea.harbour.still_water_depth_m(0, row), 5.0f + 0.1f * row) << row;
    EXPECT_EQ(as_sea.harbour.porosity(0, row), 1.0f);
    EXPECT_GT(as_sea.harbour.coast_distance_m(0, row), 0.0f);  // the coast moved: recomputed
  }
  EXPECT_EQ(as_sea.harbour.land(35, 5), kLandCell);  // real land stays land
  // "sea" at a constant depth.
  const BakeCase constant = read_bake_case(write_text(
      folder / "constant.toml",
      harbour_case("outside_chart = \"sea\"\noutside_chart_depth_m = 7.5", "source_line_m = 250.0", gauges)));
  EXPECT_EQ(constant.harbour.still_water_depth_m(2, 3), 7.5f);
  EXPECT_EQ(constant.harbour.land(2, 3), kWaterCell);
  // A depth without "sea", and an unknown treatment, are refused by key.
  expect_case_error(harbour_case("outside_chart_depth_m = 7.5", "source_line_m = 250.0", gauges),
                    {"bathymetry.outside_chart_depth_m", "outside_chart is not \"sea\""});
  expect_case_error(harbour_case("outside_chart = \"water\"", "source_line_m = 250.0", gauges),
                    {"bathymetry.outside_chart", "\"water\" is not known"});
}

}  // namespace
}  // namespace nearshore::bake::testing
