// The NetCDF export read back by GDAL (what QGIS uses) and by ncdump: CF attributes, the grid's
// CRS, projected x/y and lat/lon, the frames' values at known cells, _FillValue on land.
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cstdio>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "export_test_support.hpp"
#include "nearshore/export/export_sequence.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::exports {
namespace {
using testing::TestWave;
namespace fs = std::filesystem;

struct GdalClose {
  void operator()(GDALDataset* dataset) const { GDALClose(dataset); }
};
using Dataset = std::unique_ptr<GDALDataset, GdalClose>;

Dataset open_variable(const fs::path& file, const std::string& variable) {
  GDALAllRegister();
  const std::string name = "NETCDF:\"" + file.string() + "\":" + variable;
  return Dataset(GDALDataset::Open(name.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
}

std::string metadata(GDALMajorObject& object, const char* key) {
  const char* value = object.GetMetadataItem(key);
  return value ? value : "";
}

fs::path export_netcdf(const fs::path& folder, FrameRange frames) {
  TestWave::write(folder / "sequence");
  const ExportSummary summary = export_sequence({folder / "sequence", folder / "out", ExportFormat::kNetcdf, frames});
  EXPECT_EQ(summary.files.size(), 1u);
  EXPECT_EQ(summary.files.at(0).bytes, fs::file_size(folder / "out" / "sequence.nc"));
  return folder / "out" / "sequence.nc";
}

TEST(ExportNetcdf, GdalReadsTheGeoreferencedFramesWithLandFilled) {
  const fs::path folder = testing::scratch_folder();
  const fs::path file = export_netcdf(folder, {5, 25});
  Dataset eta = open_variable(file, "surface_elevation");
  ASSERT_TRUE(eta) << CPLGetLastErrorMsg();
  const int rows = TestWave::kRows;
  ASSERT_EQ(eta->GetRasterXSize(), TestWave::kColumns);
  ASSERT_EQ(eta->GetRasterYSize(), rows);
  ASSERT_EQ(eta->GetRasterCount(), 20);  // one band per frame 5 .. 24

  // Georeference: the cells' outer corner and size from the x/y coordinates, north up, EPSG:32651.
  double geotransform[6] = {};
  ASSERT_EQ(eta->GetGeoTransform(geotransform), CE_None);
  EXPECT_NEAR(geotransform[0], TestWave::kOriginX_m, 1e-6);
  EXPECT_NEAR(geotransform[1], TestWave::kSpacing_m, 1e-9);
  EXPECT_NEAR(geotransform[3], TestWave::kOriginY_m + rows * TestWave::kSpacing_m, 1e-6);
  EXPECT_NEAR(geotransform[5], -TestWave::kSpacing_m, 1e-9);
  const OGRSpatialReference* crs = eta->GetSpatialRef();
  ASSERT_NE(crs, nullptr);
  OGRSpatialReference utm51;
  utm51.importFromEPSG(32651);
  EXPECT_TRUE(crs->IsSame(&utm51));

  // CF attributes as GDAL reports them.
  EXPECT_EQ(metadata(*eta, "NC_GLOBAL#Conventions"), "CF-1.8");
  EXPECT_EQ(metadata(*eta, "surface_elevation#standard_name"), "sea_surface_height_above_mean_sea_level");
  EXPECT_EQ(metadata(*eta, "surface_elevation#units"), "m");
  EXPECT_EQ(metadata(*eta, "surface_elevation#grid_mapping"), "crs");
  EXPECT_EQ(metadata(*eta, "surface_elevation#coordinates"), "lat lon");
  EXPECT_EQ(metadata(*eta, "time#units"), "seconds since 1970-01-01 00:00:00");

  // Values: band b is frame 4 + b at its own time; GDAL line 0 is the northern row.
  const sequence::SequenceReader reader(folder / "sequence");
  for (int band_number : {1, 7, 20}) {
    GDALRasterBand* band = eta->GetRasterBand(band_number);
    const int index = 4 + band_number;
    EXPECT_DOUBLE_EQ(std::stod(metadata(*band, "NETCDF_DIM_time")), TestWave::frame_time_s(index));
    int has_nodata = 0;
    EXPECT_EQ(band->GetNoDataValue(&has_nodata), -9999.0);
    EXPECT_TRUE(has_nodata);
    std::vector<float> lines(static_cast<std::size_t>(TestWave::kColumns) * rows);
    ASSERT_EQ(band->RasterIO(GF_Read, 0, 0, TestWave::kColumns, rows, lines.data(), TestWave::kColumns, rows,
                             GDT_Float32, 0, 0),
              CE_None);
    const sequence::Frame frame = reader.read_frame(index);
    for (int row = 0; row < rows; ++row)
      for (int column = 0; column < TestWave::kColumns; ++column) {
        const float read = lines[static_cast<std::size_t>(rows - 1 - row) * TestWave::kColumns + column];
        if (TestWave::is_land(column, row)) {
          EXPECT_EQ(read, -9999.0f) << "land (" << column << ", " << row << ") holds the terrain in the frame";
          EXPECT_EQ(frame.surface_elevation_m(column, row), TestWave::kTerrainHeight_m);
        } else {
          EXPECT_EQ(read, frame.surface_elevation_m(column, row)) << column << ", " << row;
          EXPECT_NEAR(read, TestWave::elevation_m(column, row, TestWave::frame_time_s(index)), 1e-6);
        }
      }
  }

  // The fluxes are there too, filled on land.
  Dataset flux = open_variable(file, "flux_x");
  ASSERT_TRUE(flux);
  float value = 0.0f;
  ASSERT_EQ(flux->GetRasterBand(1)->RasterIO(GF_Read, 3, rows - 1 - 4, 1, 1, &value, 1, 1, GDT_Float32, 0, 0), CE_None);
  EXPECT_EQ(value, reader.read_frame(5).flux_x_m2_s(3, 4));
  ASSERT_EQ(flux->GetRasterBand(1)->RasterIO(GF_Read, 3, 0, 1, 1, &value, 1, 1, GDT_Float32, 0, 0), CE_None);
  EXPECT_EQ(value, -9999.0f);
}

// lat/lon of the cell centres (GeographicLib in the export) against PROJ through GDAL, an
// independent implementation of the UTM inverse: within 1e-8 degrees (about 1 mm).
TEST(ExportNetcdf, LatitudeAndLongitudeAgreeWithProj) {
  const fs::path folder = testing::scratch_folder();
  const fs::path file = export_netcdf(folder, {0, 2});
  Dataset latitude = open_variable(file, "lat"), longitude = open_variable(file, "lon");
  ASSERT_TRUE(latitude && longitude);
  EXPECT_EQ(metadata(*latitude, "lat#standard_name"), "latitude");
  EXPECT_EQ(metadata(*longitude, "lon#units"), "degrees_east");
  OGRSpatialReference utm51, wgs84;
  utm51.importFromEPSG(32651);
  wgs84.importFromEPSG(4326);
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_geographic(OGRCreateCoordinateTransformation(&utm51, &wgs84));
  ASSERT_TRUE(to_geographic);
  for (const auto& [column, row] : {std::pair{0, 0}, std::pair{23, 15}, std::pair{11, 7}}) {
    double x = TestWave::kOriginX_m + (column + 0.5) * TestWave::kSpacing_m;
    double y = TestWave::kOriginY_m + (row + 0.5) * TestWave::kSpacing_m;
    ASSERT_TRUE(to_geographic->Transform(1, &x, &y));
    double lat = 0.0, lon = 0.0;
    const int line = TestWave::kRows - 1 - row;
    ASSERT_EQ(latitude->GetRasterBand(1)->RasterIO(GF_Read, column, line, 1, 1, &lat, 1, 1, GDT_Float64, 0, 0), CE_None);
    ASSERT_EQ(longitude->GetRasterBand(1)->RasterIO(GF_Read, column, line, 1, 1, &lon, 1, 1, GDT_Float64, 0, 0), CE_None);
    EXPECT_NEAR(lon, x, 1e-8);
    EXPECT_NEAR(lat, y, 1e-8);
  }
}

// Rectangular cells (10 m east by 4 m north): the coordinates carry both sizes, so GDAL's pixels do.
TEST(ExportNetcdf, RectangularCellsKeepBothSizes) {
  const fs::path folder = testing::scratch_folder();
  TestWave::write(folder / "sequence", 4.0);
  export_sequence({folder / "sequence", folder / "out", ExportFormat::kNetcdf, {0, 2}});
  Dataset eta = open_variable(folder / "out" / "sequence.nc", "surface_elevation");
  ASSERT_TRUE(eta);
  double geotransform[6] = {};
  ASSERT_EQ(eta->GetGeoTransform(geotransform), CE_None);
  EXPECT_NEAR(geotransform[1], 10.0, 1e-9);
  EXPECT_NEAR(geotransform[5], -4.0, 1e-9);
  EXPECT_NEAR(geotransform[3], TestWave::kOriginY_m + TestWave::kRows * 4.0, 1e-6);
}

// netCDF's own tool sees the CF header: conventions, the grid mapping, names, units, fill values.
TEST(ExportNetcdf, NcdumpShowsTheCfHeader) {
  if (std::string(NEARSHORE_NCDUMP).empty() || std::string(NEARSHORE_NCDUMP).find("NOTFOUND") != std::string::npos)
    GTEST_SKIP() << "ncdump not installed (Debian netcdf-bin; scripts/install-deps.sh installs it)";
  const fs::path folder = testing::scratch_folder();
  const fs::path file = export_netcdf(folder, {0, 3});
  const std::string command = std::string(NEARSHORE_NCDUMP) + " -h '" + file.string() + "'";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string header;
  char buffer[4096];
  while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) header.append(buffer, n);
  ASSERT_EQ(pclose(pipe), 0) << header;
  for (const char* expected :
       {":Conventions = \"CF-1.8\"", "time = 3 ;", "y = 16 ;", "x = 24 ;",
        "crs:grid_mapping_name = \"transverse_mercator\"", "crs:longitude_of_central_meridian = 123.",
        "crs:scale_factor_at_central_meridian = 0.9996", "x:standard_name = \"projection_x_coordinate\"",
        "float surface_elevation(time, y, x)", "surface_elevation:_FillValue = -9999.f",
        "surface_elevation:standard_name = \"sea_surface_height_above_mean_sea_level\"",
        "depth:standard_name = \"sea_floor_depth_below_sea_level\"", "double lat(y, x)", "flux_y:units = \"m2 s-1\""})
    EXPECT_NE(header.find(expected), std::string::npos) << "missing: " << expected << "\n" << header;
}

}  // namespace
}  // namespace nearshore::exports
