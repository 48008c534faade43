// Positions in the three frames a person gives them (issue 14 item 2), and cells outside a chart's
// coverage kept as no data (item 3): core/geo_position.hpp and build_harbour_grid.
#include <gtest/gtest.h>

#include <gdal_priv.h>

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/geo_position.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/progress.hpp"
#include "test_folder.hpp"

namespace nb = nearshore::bathymetry;
using nearshore::GridGeometry;
using nearshore::HarbourGrid;
using nearshore::LonLat;
using nearshore::MapProjection;
using nearshore::ProjectedPoint;

namespace {

// 40 x 30 cells of 10 m in UTM zone 10N over Commencement Bay (Tacoma), open water 6 m deep.
GridGeometry tacoma_geometry() {
  GridGeometry g;
  g.columns = 40;
  g.rows = 30;
  g.spacing_m = 10.0;
  g.origin_x_m = 541000.0;
  g.origin_y_m = 5236000.0;
  g.projection = MapProjection::utm(10, true).to_json();
  return g;
}

std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const nearshore::Error& error) {
    return error.what();
  }
  return "(no error)";
}

}  // namespace

TEST(GeoPosition, TheThreeFramesPlaceTheSamePoint) {
  const GridGeometry g = tacoma_geometry();
  // A point 123.4 m east and 234.5 m north of the south-west corner, given three ways.
  const ProjectedPoint expected{g.origin_x_m + 123.4, g.origin_y_m + 234.5};
  const LonLat place = MapProjection::utm(10, true).reverse(expected);
  const nearshore::GeoPosition metres = nearshore::geo_position_from_keys({{"x_m", 123.4}, {"y_m", 234.5}}, "case.toml", "gauges[0]");
  const nearshore::GeoPosition crs =
      nearshore::geo_position_from_keys({{"easting_m", expected.x_m}, {"northing_m", expected.y_m}}, "case.toml", "gauges[0]");
  const nearshore::GeoPosition lat_lon =
      nearshore::geo_position_from_keys({{"lat", place.latitude_deg}, {"lon", place.longitude_deg}}, "case.toml", "gauges[0]");
  for (const nearshore::GeoPosition& position : {metres, crs, lat_lon}) {
    const ProjectedPoint point = nearshore::place_in_grid(position, g, "case.toml", "gauges[0]");
    // GeographicLib's UTM round trip is exact to nanometres (Karney 2011); 1 mm leaves room for the
    // double printing of nothing here and is far below a cell.
    EXPECT_NEAR(point.x_m, expected.x_m, 1e-3);
    EXPECT_NEAR(point.y_m, expected.y_m, 1e-3);
  }
  // 0..360 longitudes (NOAA grids) are the same place.
  const nearshore::GeoPosition wrapped =
      nearshore::geo_position_from_keys({{"lat", place.latitude_deg}, {"lon", place.longitude_deg + 360.0}}, "case.toml", "gauges[0]");
  EXPECT_NEAR(nearshore::place_in_grid(wrapped, g, "case.toml", "gauges[0]").x_m, expected.x_m, 1e-3);
}

TEST(GeoPosition, TextFormsAreTheSameParser) {
  std::map<std::string, double> extras;
  const nearshore::GeoPosition plain = nearshore::parse_geo_position("800,300,30", "--eye", {"z_m"}, &extras);
  EXPECT_EQ(plain.frame, nearshore::GeoPosition::Frame::kFromSouthWestCorner);
  EXPECT_EQ(plain.first, 800.0);
  EXPECT_EQ(plain.second, 300.0);
  EXPECT_EQ(extras.at("z_m"), 30.0);
  extras.clear();
  const nearshore::GeoPosition named = nearshore::parse_geo_position("lat=47.2706, lon=-122.4345, z_m=12", "--eye", {"z_m"}, &extras);
  EXPECT_EQ(named.frame, nearshore::GeoPosition::Frame::kLatLon);
  EXPECT_DOUBLE_EQ(named.first, 47.2706);
  EXPECT_DOUBLE_EQ(named.second, -122.4345);
  EXPECT_EQ(extras.at("z_m"), 12.0);
  const nearshore::GeoPosition crs = nearshore::parse_geo_position("easting_m=541200,northing_m=5236100", "--target");
  EXPECT_EQ(crs.frame, nearshore::GeoPosition::Frame::kGridCrs);
  // Each malformed form is one message naming the flag and the forms it takes.
  for (const auto& [text, fragment] : std::vector<std::pair<std::string, std::string>>{
           {"lat=47.27", "gives lat without lon"},
           {"lat=47.27,lon=-122.4,x_m=3,y_m=4", "gives its position twice"},
           {"lat=95,lon=-122.4", "is not a latitude"},
           {"north=3,east=4", "not a position key"},
           {"800", "one number"},
           {"800,abc", "is not a number"}}) {
    const std::string message = message_of([&] { nearshore::parse_geo_position(text, "--target"); });
    EXPECT_NE(message.find("--target"), std::string::npos) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << text << ": " << message;
  }
}

TEST(GeoPosition, OutsideTheGridNamesTheEntryAndTheExtentInLatLon) {
  const GridGeometry g = tacoma_geometry();
  const std::string message = message_of([&] {
    nearshore::place_in_grid(nearshore::geo_position_from_keys({{"lat", 47.30}, {"lon", -122.52}}, "tacoma.toml", "gauge \"defiance\""), g,
                      "tacoma.toml", "gauge \"defiance\"");
  });
  EXPECT_NE(message.find("tacoma.toml"), std::string::npos) << message;
  EXPECT_NE(message.find("gauge \"defiance\""), std::string::npos) << message;
  EXPECT_NE(message.find("lies outside the grid"), std::string::npos) << message;
  // The grid's own extent in lat/lon, as a chart shows it.
  const LonLat south_west = MapProjection::utm(10, true).reverse({g.origin_x_m, g.origin_y_m});
  EXPECT_NE(message.find(fmt::format("{:.3f}", south_west.latitude_deg).substr(0, 5)), std::string::npos) << message;
  EXPECT_NE(message.find("lat 47."), std::string::npos) << message;
  EXPECT_NE(message.find("lon -122."), std::string::npos) << message;
  // A camera may look in from beyond the grid.
  EXPECT_NO_THROW(nearshore::place_in_grid(nearshore::geo_position_from_keys({{"lat", 47.30}, {"lon", -122.52}}, "--eye", "the camera"), g,
                                    "--eye", "the camera", false));
  // lat/lon on a laboratory grid (no projection) is refused with the metres form as the fix.
  GridGeometry flume = g;
  flume.projection = nullptr;
  const std::string local = message_of([&] {
    nearshore::place_in_grid(nearshore::geo_position_from_keys({{"lat", 47.2}, {"lon", -122.4}}, "flume.toml", "gauges[1]"), flume,
                      "flume.toml", "gauges[1]");
  });
  EXPECT_NE(local.find("no map projection"), std::string::npos) << local;
  EXPECT_NE(local.find("x_m and y_m"), std::string::npos) << local;
}

TEST(GeoPosition, LandAndNoDataCellsWarnWithTheirDepth) {
  HarbourGrid grid = HarbourGrid::open_water(tacoma_geometry(), 6.0f);
  grid.land(20, 10) = nearshore::kLandCell;
  grid.still_water_depth_m(20, 10) = -3.5f;
  grid.land(0, 0) = nearshore::kOutsideChartCell;
  const auto centre = [&](int column, int row) {
    return ProjectedPoint{grid.geometry.cell_centre_x_m(column), grid.geometry.cell_centre_y_m(row)};
  };
  EXPECT_FALSE(nearshore::land_warning(grid, centre(5, 5), "case.toml", "gauge \"a\""));
  const auto on_land = nearshore::land_warning(grid, centre(20, 10), "case.toml", "gauge \"quay\"");
  ASSERT_TRUE(on_land);
  EXPECT_NE(on_land->find("gauge \"quay\""), std::string::npos) << *on_land;
  EXPECT_NE(on_land->find("lies on land"), std::string::npos) << *on_land;
  EXPECT_NE(on_land->find("3.50 m above still water"), std::string::npos) << *on_land;
  const auto outside = nearshore::land_warning(grid, centre(0, 0), "case.toml", "gauge \"b\"");
  ASSERT_TRUE(outside);
  EXPECT_NE(outside->find("outside the chart's coverage"), std::string::npos) << *outside;
}

// A bbox wider than the demo survey raster: the cells beyond it are no data (land channel 2), not
// land, in depth.exr (read back), nodata in depth.tif (GDAL), and counted apart in the summary.
TEST(BathyNoData, CellsOutsideTheInputsAreNoDataNotLand) {
  nearshore::ProgressBar::set_quiet(true);
  const auto folder = fresh_test_folder("");
  nb::DemoHarbourOptions site;
  const auto files = nb::write_demo_harbour(folder / "demo", site);
  const ProjectedPoint centre = MapProjection::utm(51, true).forward({site.centre_longitude_deg, site.centre_latitude_deg});
  nb::BathyRequest request;
  request.inputs = {files.depth_geotiff};
  request.spacing_m = 40.0;
  request.projection = "utm:51N";
  // 400 m beyond the survey's eastern edge.
  request.bbox_projected_m = std::array<double, 4>{centre.x_m - 0.5 * site.width_m, centre.y_m - 0.5 * site.height_m,
                                                   centre.x_m + 0.5 * site.width_m + 400.0, centre.y_m + 0.5 * site.height_m};
  const nb::BathyResult result = nb::build_harbour_grid(request);
  const HarbourGrid& grid = result.grid;
  const int east = grid.geometry.columns - 1, row = grid.geometry.rows / 2;
  EXPECT_EQ(grid.land(east, row), nearshore::kOutsideChartCell);
  std::size_t outside = 0;
  for (const auto land : grid.land.values()) outside += land == nearshore::kOutsideChartCell;
  EXPECT_GE(outside, static_cast<std::size_t>(grid.geometry.rows) * 9);  // 400 m = 10 columns of 40 m, less the edge cell
  EXPECT_EQ(result.summary["cells"]["outside_chart"].get<std::size_t>(), outside);
  const nlohmann::json summary = nb::write_bathymetry_outputs(folder / "out", result);
  const HarbourGrid back = nearshore::read_harbour_grid(folder / "out" / "depth.exr");
  EXPECT_EQ(back.land.values(), grid.land.values());
  // depth.tif: GDAL sees nodata there (north-up: row 0 of the file is the northern row).
  GDALAllRegister();
  std::unique_ptr<GDALDataset> tif(GDALDataset::Open((folder / "out" / "depth.tif").c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  ASSERT_TRUE(tif);
  int has_nodata = 0;
  const double nodata = tif->GetRasterBand(1)->GetNoDataValue(&has_nodata);
  ASSERT_TRUE(has_nodata);
  float value = 0.f;
  ASSERT_EQ(tif->GetRasterBand(1)->RasterIO(GF_Read, east, grid.geometry.rows - 1 - row, 1, 1, &value, 1, 1, GDT_Float32, 0, 0),
            CE_None);
  EXPECT_EQ(value, static_cast<float>(nodata));
  EXPECT_TRUE(std::filesystem::exists(folder / "out" / "preview.png"));
}
