// Other input formats through the same path: an ESRI ASCII grid (no sign metadata: the --sign flag
// decides), text soundings with priority over a raster, and the sign read from GeoTIFF metadata.
#include <gtest/gtest.h>

#include <gdal_priv.h>

#include <cmath>
#include <fstream>

#include <fmt/core.h>

#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/core/progress.hpp"
#include "test_folder.hpp"

namespace nb = nearshore::bathymetry;
namespace fs = std::filesystem;

namespace {

fs::path demo_as_esri_ascii(const fs::path& folder) {
  const auto files = nb::write_demo_harbour(folder / "demo");
  GDALAllRegister();
  GDALDataset* source = GDALDataset::Open(files.depth_geotiff.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
  const fs::path asc = folder / "depth.asc";
  GDALDataset* copy = GetGDALDriverManager()->GetDriverByName("AAIGrid")->CreateCopy(asc.c_str(), source, FALSE, nullptr, nullptr, nullptr);
  GDALClose(copy);
  GDALClose(source);
  // GDAL keeps the GeoTIFF's metadata in a side-car .aux.xml; a grid as users get it has only .prj.
  fs::remove(fs::path(asc.string() + ".aux.xml"));
  return asc;
}

}  // namespace

TEST(BathyFormats, EsriAsciiGridTakesItsSignFromTheFlag) {
  nearshore::ProgressBar::set_quiet(true);
  const auto folder = fresh_test_folder("");
  nb::BathyRequest request;
  request.inputs = {demo_as_esri_ascii(folder)};
  request.spacing_m = 40.0;
  request.sign = nb::DepthSign::kPositiveDown;
  const auto as_depth = nb::build_harbour_grid(request);
  request.sign = nb::DepthSign::kAuto;  // no metadata in .asc: read as elevation (GEBCO's convention)
  const auto as_elevation = nb::build_harbour_grid(request);
  EXPECT_EQ(as_depth.summary["inputs"][0]["sign"].get<std::string>().rfind("positive_down", 0), 0u);
  EXPECT_EQ(as_elevation.summary["inputs"][0]["sign"].get<std::string>().rfind("positive_up", 0), 0u);
  // The south-west corner is 15 m deep water; read as elevation it is a 15 m high hill (land).
  EXPECT_NEAR(as_depth.grid.still_water_depth_m(0, 0), 15.0, 0.5);
  EXPECT_FALSE(as_depth.grid.land(0, 0));
  EXPECT_TRUE(as_elevation.grid.land(0, 0));
}

TEST(BathyFormats, TextSoundingsListedFirstWinOverTheRaster) {
  nearshore::ProgressBar::set_quiet(true);
  const auto folder = fresh_test_folder("");
  const auto files = nb::write_demo_harbour(folder / "demo");
  // A 42 m "survey" over a 0.004 x 0.002 degree patch of open sea south of the harbour.
  const nb::DemoHarbourOptions site;
  const double lon0 = site.centre_longitude_deg - 0.004, lat0 = site.centre_latitude_deg - 0.005;
  std::ofstream xyz(folder / "survey.xyz");
  xyz << "lon,lat,depth\n";
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 2; ++j) xyz << fmt::format("{:.7f},{:.7f},42.0\n", lon0 + 0.001 * i, lat0 + 0.001 * j);
  xyz.close();
  nb::BathyRequest request;
  request.inputs = {folder / "survey.xyz", files.depth_geotiff};
  request.spacing_m = 20.0;
  const auto result = nb::build_harbour_grid(request);
  const auto& g = result.grid.geometry;
  const auto inside = nearshore::grid_position_of(g, {lon0 + 0.002, lat0 + 0.001});
  const auto outside = nearshore::grid_position_of(g, {lon0 - 0.002, lat0 + 0.001});
  // Natural-neighbour interpolation of equal soundings is exactly that value inside their hull.
  EXPECT_FLOAT_EQ(result.grid.still_water_depth_m(std::lround(inside.column), std::lround(inside.row)), 42.0f);
  EXPECT_LT(result.grid.still_water_depth_m(std::lround(outside.column), std::lround(outside.row)), 20.0f);
  EXPECT_EQ(result.summary["inputs"][0]["soundings_used"], 15);
}

TEST(BathyFormats, NetCdfCopyOfTheSurveyKeepsItsDepthSign) {
  nearshore::ProgressBar::set_quiet(true);
  const auto folder = fresh_test_folder("");
  const auto files = nb::write_demo_harbour(folder / "demo");
  GDALAllRegister();
  GDALDataset* source = GDALDataset::Open(files.depth_geotiff.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
  const fs::path nc = folder / "depth.nc";
  GDALDriver* netcdf = GetGDALDriverManager()->GetDriverByName("netCDF");
  ASSERT_NE(netcdf, nullptr);
  GDALClose(netcdf->CreateCopy(nc.c_str(), source, FALSE, nullptr, nullptr, nullptr));
  GDALClose(source);
  fs::remove(fs::path(nc.string() + ".aux.xml"));  // only what is inside the NetCDF file counts
  nb::BathyRequest request;
  request.inputs = {nc};
  request.spacing_m = 40.0;
  const auto result = nb::build_harbour_grid(request);
  // GDAL stores our tag as the global attribute GDAL_NEARSHORE_DEPTH_SIGN: read as depth.
  EXPECT_EQ(result.summary["inputs"][0]["sign"].get<std::string>().rfind("positive_down", 0), 0u)
      << result.summary["inputs"][0]["sign"];
  EXPECT_NEAR(result.grid.still_water_depth_m(0, 0), 15.0, 0.5);
}
