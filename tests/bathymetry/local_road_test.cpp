// Issue 19, "the road for any laboratory or survey grid": what `nearshore bathy` says to a
// researcher setting up a laboratory case (a positive-down raster read as elevations, a basin
// shallower than the minimum depth, soundings in local metres, NOAA's 0..360 longitudes, no box
// given), and the local-metres grid reader the bake uses instead (local_grid.hpp).
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/bathymetry/local_grid.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "test_folder.hpp"

namespace nb = nearshore::bathymetry;
namespace fs = std::filesystem;

namespace {

// A one-band float GeoTIFF, row 0 NORTH as GDAL stores it; `crs` as GDAL's user input ("" = none).
void write_geotiff(const fs::path& path, int columns, int rows, const std::array<double, 6>& geotransform,
                   const std::string& crs, const std::vector<float>& values_north_first) {
  GDALAllRegister();
  GDALDataset* dataset =
      GetGDALDriverManager()->GetDriverByName("GTiff")->Create(path.c_str(), columns, rows, 1, GDT_Float32, nullptr);
  ASSERT_NE(dataset, nullptr);
  std::array<double, 6> gt = geotransform;
  if (gt[1] != 0.0) dataset->SetGeoTransform(gt.data());  // a zero pixel width: a bare TIFF
  if (!crs.empty()) {
    OGRSpatialReference reference;
    reference.SetFromUserInput(crs.c_str());
    dataset->SetSpatialRef(&reference);
  }
  std::vector<float> values = values_north_first;
  ASSERT_EQ(dataset->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, columns, rows, values.data(), columns, rows,
                                                GDT_Float32, 0, 0),
            CE_None);
  GDALClose(dataset);
}

std::string error_of(const nb::BathyRequest& request) {
  nearshore::ProgressBar::set_quiet(true);
  try {
    nb::build_harbour_grid(request);
  } catch (const nearshore::Error& e) {
    return e.what();
  }
  return {};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A 40 x 30 survey raster of a 0.45 m basin in UTM 10N (Tacoma), 5 m pixels, stored as depths
// (positive down) with no sign metadata.
fs::path basin_raster(const fs::path& folder, float depth_m = 0.45f) {
  const fs::path path = folder / "basin.tif";
  write_geotiff(path, 40, 30, {540000.0, 5.0, 0.0, 5235000.0, 0.0, -5.0}, "EPSG:32610",
                std::vector<float>(40 * 30, depth_m));
  return path;
}

// A request for the local-metres reader; the optional fields are set by the caller.
nb::LocalGridRequest local_request(const fs::path& file, nb::DepthSign sign = nb::DepthSign::kAuto) {
  nb::LocalGridRequest request;
  request.file = file;
  request.sign = sign;
  return request;
}

nb::LocalGridRequest with_spacing(nb::LocalGridRequest request, double dx_m, double dy_m) {
  request.spacing_m = std::array<double, 2>{dx_m, dy_m};
  return request;
}

}  // namespace

TEST(BathyLocalRoad, EveryCellLandOnAPositiveDownRasterSuggestsTheSign) {
  const auto folder = fresh_test_folder("");
  nb::BathyRequest request;
  request.inputs = {basin_raster(folder)};
  request.spacing_m = 10.0;
  const std::string message = error_of(request);
  RecordProperty("message", message);  // quoted in docs/commands/bathy.md ("Sign")
  EXPECT_TRUE(contains(message, "every cell is land")) << message;
  EXPECT_TRUE(contains(message, "basin.tif was read as elevations, positive up (default for rasters")) << message;
  EXPECT_TRUE(contains(message, "set BathyRequest::sign to DepthSign::kPositiveDown")) << message;
  // No box was given, so none is blamed (issue 19: "check --bbox" was said without one).
  EXPECT_FALSE(contains(message, "bbox")) << message;
  // With a box, it is named.
  request.bbox_projected_m = std::array<double, 4>{540010.0, 5234900.0, 540150.0, 5234990.0};
  EXPECT_TRUE(contains(error_of(request), "BathyRequest::bbox_lon_lat")) << error_of(request);
}

TEST(BathyLocalRoad, RaisingABasinToTheMinimumDepthWarns) {
  const auto folder = fresh_test_folder("");
  nb::BathyRequest request;
  request.inputs = {basin_raster(folder)};
  request.spacing_m = 10.0;
  request.sign = nb::DepthSign::kPositiveDown;
  nearshore::ProgressBar::set_quiet(true);
  // Default minimum depth 0.5 m: all 20 x 15 cells of the 0.45 m basin are raised by 0.05 m.
  const nb::BathyResult raised = nb::build_harbour_grid(request);
  ASSERT_EQ(raised.warnings.size(), 1u);
  const std::string& warning = raised.warnings.front();
  RecordProperty("warning", warning);
  EXPECT_TRUE(contains(warning, "300 of 300 water cells (100.0 %)")) << warning;
  EXPECT_TRUE(contains(warning, "BathyRequest::minimum_depth_m = 0.5 m")) << warning;
  EXPECT_TRUE(contains(warning, "by up to 0.05 m")) << warning;
  EXPECT_TRUE(contains(warning, "the shallowest was 0.45 m")) << warning;
  EXPECT_TRUE(contains(warning, "lower BathyRequest::minimum_depth_m")) << warning;
  EXPECT_EQ(raised.summary["warnings"].size(), 1u);
  EXPECT_FLOAT_EQ(raised.grid.still_water_depth_m(3, 3), 0.5f);
  // A lower minimum keeps the basin as surveyed, and says nothing.
  request.minimum_depth_m = 0.1;
  const nb::BathyResult kept = nb::build_harbour_grid(request);
  EXPECT_TRUE(kept.warnings.empty());
  EXPECT_FLOAT_EQ(kept.grid.still_water_depth_m(3, 3), 0.45f);
}

TEST(BathyLocalRoad, SoundingsInLocalMetresNameTheFileAndTheLocalGridRoad) {
  const auto folder = fresh_test_folder("");
  // A 20 m x 0.6 m flume in its own metres: read as degrees, near 0 N 0 E.
  std::ofstream(folder / "flume.xyz") << "x y depth\n0 0 0.45\n20 0 0.45\n0 0.6 0.45\n20 0.6 0.45\n10 0.3 0.2\n";
  // A basin surveyed in site metres beyond 180.
  std::ofstream(folder / "basin.xyz") << "1000 2000 0.45\n1030 2000 0.45\n1000 2025 0.40\n";
  for (const char* name : {"flume.xyz", "basin.xyz"}) {
    nb::BathyRequest request;
    request.inputs = {folder / name};
    request.spacing_m = 0.1;
    const std::string message = error_of(request);
    EXPECT_TRUE(contains(message, name)) << message;
    EXPECT_TRUE(contains(message, "so these are metres, not longitude/latitude")) << message;
    EXPECT_TRUE(contains(message, "kind = \"local_grid\"")) << message;
    EXPECT_TRUE(contains(message, "ReadOptions::text_crs")) << message;
    EXPECT_FALSE(contains(message, "out of legal range")) << message;
  }
  nb::BathyRequest flume;
  flume.inputs = {folder / "flume.xyz"};
  flume.spacing_m = 0.1;
  EXPECT_TRUE(contains(error_of(flume), "Gulf of Guinea"));
}

TEST(BathyLocalRoad, LongitudesFrom0To360AreRead) {
  const auto folder = fresh_test_folder("");
  // The same 0.01-degree raster of a sloping bed off Tacoma twice: at lon -122.46 and at 237.54.
  const int columns = 6, rows = 4;
  std::vector<float> depth(columns * rows);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) depth[r * columns + c] = 5.0f + 2.0f * c + 0.5f * r;
  write_geotiff(folder / "west.tif", columns, rows, {-122.46, 0.01, 0.0, 47.30, 0.0, -0.01}, "EPSG:4326", depth);
  write_geotiff(folder / "east.tif", columns, rows, {237.54, 0.01, 0.0, 47.30, 0.0, -0.01}, "EPSG:4326", depth);
  const auto grid_of = [&](const fs::path& input) {
    nb::BathyRequest request;
    request.inputs = {input};
    request.spacing_m = 100.0;
    request.sign = nb::DepthSign::kPositiveDown;
    nearshore::ProgressBar::set_quiet(true);
    return nb::build_harbour_grid(request).grid;
  };
  const nearshore::HarbourGrid west = grid_of(folder / "west.tif"), east = grid_of(folder / "east.tif");
  ASSERT_EQ(west.geometry.columns, east.geometry.columns);
  ASSERT_EQ(west.geometry.rows, east.geometry.rows);
  // 237.54 - 360 differs from -122.46 in the last bit (1e-14 degrees, 1e-9 m): equal to a micrometre.
  EXPECT_NEAR(west.geometry.origin_x_m, east.geometry.origin_x_m, 1e-6);
  for (std::size_t i = 0; i < west.still_water_depth_m.size(); ++i)
    ASSERT_NEAR(west.still_water_depth_m.values()[i], east.still_water_depth_m.values()[i], 1e-5) << i;
  // Text soundings in 0..360 are wrapped too.
  std::ofstream(folder / "east.xyz") << "237.55 47.28 6\n237.57 47.28 10\n237.56 47.29 8\n";
  const nb::SourceData text = nb::read_source(folder / "east.xyz", {});
  ASSERT_EQ(text.soundings.size(), 3u);
  EXPECT_NEAR(text.soundings[0].place.longitude_deg, -122.45, 1e-9);
  // A whole-globe raster at 0..360 is turned to -180..180: its column at 185 E comes first.
  std::vector<float> globe(36 * 2);
  for (int c = 0; c < 36; ++c) globe[c] = globe[36 + c] = 100.0f + c;  // column c spans 10c .. 10c + 10 E
  write_geotiff(folder / "globe.tif", 36, 2, {0.0, 10.0, 0.0, 10.0, 0.0, -10.0}, "EPSG:4326", globe);
  const nb::SourceData wrapped = nb::read_source(folder / "globe.tif", {nb::DepthSign::kPositiveDown, ""});
  ASSERT_TRUE(wrapped.raster);
  EXPECT_DOUBLE_EQ(wrapped.raster->geotransform[0], -180.0);
  EXPECT_FLOAT_EQ(wrapped.raster->depth_m[0], 118.0f);   // 180..190 E = -180..-170
  EXPECT_FLOAT_EQ(wrapped.raster->depth_m[35], 117.0f);  // 170..180 E stays last
  // A regional raster across the antimeridian is refused with the fix.
  write_geotiff(folder / "fiji.tif", 4, 2, {178.0, 1.0, 0.0, -16.0, 0.0, -1.0}, "EPSG:4326", std::vector<float>(8, 50.0f));
  try {
    nb::read_source(folder / "fiji.tif", {});
    ADD_FAILURE() << "a raster across the antimeridian was read";
  } catch (const nearshore::Error& e) {
    EXPECT_TRUE(contains(e.what(), "fiji.tif")) << e.what();
    EXPECT_TRUE(contains(e.what(), "across the antimeridian")) << e.what();
  }
}

// --- The local-metres reader (local_grid.hpp) ------------------------------------------------------

TEST(LocalGrid, AsciiGridKeepsItsCellsOriginAndRows) {
  const auto folder = fresh_test_folder("");
  // 4 columns x 3 rows of 0.5 m x 0.5 m from (2, 1); the first line of values is the NORTH row.
  std::ofstream(folder / "basin.asc") << "ncols 4\nnrows 3\nxllcorner 2.0\nyllcorner 1.0\ncellsize 0.5\n"
                                         "NODATA_value -9999\n"
                                         "0.30 0.31 0.32 0.33\n"
                                         "0.20 0.21 -9999 0.23\n"
                                         "0.10 0.11 0.12 -0.05\n";
  const nb::LocalGrid local = nb::read_local_grid(local_request(folder / "basin.asc", nb::DepthSign::kPositiveDown));
  const nearshore::HarbourGrid& grid = local.grid;
  EXPECT_EQ(local.format, "AAIGrid");
  EXPECT_EQ(grid.geometry.columns, 4);
  EXPECT_EQ(grid.geometry.rows, 3);
  EXPECT_DOUBLE_EQ(grid.geometry.spacing_x_m(), 0.5);
  EXPECT_DOUBLE_EQ(grid.geometry.origin_x_m, 2.0);
  EXPECT_DOUBLE_EQ(grid.geometry.origin_y_m, 1.0);
  EXPECT_TRUE(grid.geometry.crs_wkt.empty());
  EXPECT_FLOAT_EQ(grid.still_water_depth_m(0, 0), 0.10f);  // row 0 is the south row
  EXPECT_FLOAT_EQ(grid.still_water_depth_m(3, 2), 0.33f);
  // Above still water: land. Nodata: a wall as high as the deepest water is deep.
  EXPECT_EQ(grid.land(3, 0), 1);
  EXPECT_EQ(grid.land(2, 1), 1);
  EXPECT_FLOAT_EQ(grid.still_water_depth_m(2, 1), -0.33f);
  EXPECT_EQ(local.filled_cells, 1u);
  EXPECT_EQ(grid.land(0, 0), 0);
  EXPECT_LT(grid.coast_distance_m(3, 0), 0.0f);
  EXPECT_GT(grid.coast_distance_m(0, 2), 0.0f);
  // The minimum depth, when asked for, raises shallow water and counts it.
  nb::LocalGridRequest shallow = local_request(folder / "basin.asc", nb::DepthSign::kPositiveDown);
  shallow.minimum_depth_m = 0.2;
  const nb::LocalGrid raised = nb::read_local_grid(shallow);
  EXPECT_EQ(raised.raised_cells, 3u);
  EXPECT_FLOAT_EQ(raised.grid.still_water_depth_m(0, 0), 0.2f);
}

TEST(LocalGrid, SoundingsOfAPlaneAreGriddedExactly) {
  // Sibson interpolation reproduces a linear function exactly (natural_neighbour.hpp), so a plane
  // bed sounded on a coarse 0.25 m lattice is recovered at every 0.1 m cell centre to float precision.
  const auto folder = fresh_test_folder("");
  const auto plane = [](double x, double y) { return 0.5 - 0.02 * x + 0.1 * y; };
  {
    std::ofstream xyz(folder / "flume.xyz");
    xyz << "x_m,y_m,depth_m\n";
    for (int i = 0; i <= 48; ++i)
      for (int j = 0; j <= 4; ++j) xyz << i * 0.25 << "," << j * 0.15 << "," << plane(i * 0.25, j * 0.15) << "\n";
  }
  const nb::LocalGrid local =
      nb::read_local_grid(with_spacing(local_request(folder / "flume.xyz", nb::DepthSign::kPositiveDown), 0.1, 0.1));
  const auto& g = local.grid.geometry;
  EXPECT_EQ(g.columns, 120);
  EXPECT_EQ(g.rows, 6);
  EXPECT_EQ(local.filled_cells, 0u);
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c)
      ASSERT_NEAR(local.grid.still_water_depth_m(c, r), plane(g.cell_centre_x_m(c), g.cell_centre_y_m(r)), 2e-6)
          << c << ", " << r;
}

TEST(LocalGrid, BadInputsNameTheFileAndTheField) {
  const auto folder = fresh_test_folder("");
  const auto message_of = [](const nb::LocalGridRequest& request) {
    try {
      nb::read_local_grid(request);
    } catch (const nearshore::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::ofstream(folder / "flume.xyz") << "0 0 0.4\n1 0 0.4\n0 1 0.4\n";
  EXPECT_TRUE(contains(message_of(local_request(folder / "flume.xyz")), "LocalGridRequest::spacing_m"));
  // A depth file read with the wrong sign: every cell is land, and the fix is the sign.
  const std::string wrong_sign =
      message_of(with_spacing(local_request(folder / "flume.xyz", nb::DepthSign::kPositiveUp), 0.1, 0.1));
  EXPECT_TRUE(contains(wrong_sign, "every cell is land")) << wrong_sign;
  EXPECT_TRUE(contains(wrong_sign, "DepthSign::kPositiveDown")) << wrong_sign;
  // A bare TIFF has no pixel size; a lon/lat raster belongs to the chart road.
  write_geotiff(folder / "bare.tif", 3, 2, {}, "", std::vector<float>(6, 0.3f));
  nb::LocalGridRequest bare_request = local_request(folder / "bare.tif", nb::DepthSign::kPositiveDown);
  EXPECT_TRUE(contains(message_of(bare_request), "LocalGridRequest::pixel_size_m"));
  bare_request.pixel_size_m = std::array<double, 2>{0.2, 0.1};
  const nb::LocalGrid bare = nb::read_local_grid(bare_request);
  EXPECT_EQ(bare.grid.geometry.columns, 3);
  EXPECT_DOUBLE_EQ(bare.grid.geometry.spacing_y_m(), 0.1);
  EXPECT_DOUBLE_EQ(bare.grid.geometry.origin_y_m, 0.0);
  write_geotiff(folder / "lonlat.tif", 3, 2, {-122.4, 0.01, 0.0, 47.3, 0.0, -0.01}, "EPSG:4326", std::vector<float>(6, 3.0f));
  EXPECT_TRUE(contains(message_of(local_request(folder / "lonlat.tif")), "longitude/latitude"));
  EXPECT_TRUE(contains(message_of(local_request(folder / "nowhere.asc")), "does not exist"));
}
