// The wave statistics GeoTIFF read back by GDAL: georeference, Hs and mean level of a linear wave,
// the breaking fraction, nodata on land.
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "export_test_support.hpp"
#include "nearshore/export/export_sequence.hpp"

namespace nearshore::exports {
namespace {
using testing::TestWave;
namespace fs = std::filesystem;

// Frames 10 .. 49: two whole periods of eta = a cos(k x - w t), 20 frames each, so Hs = 2 sqrt(2) a
// and the mean level 0 up to float rounding (statistics_test.cpp explains why the discrete sums are
// exact); breaking is 1 in columns 0-1 on even frames, a fraction of 1/2.
TEST(ExportGeotiff, GdalReadsHsMeanLevelAndBreakingFractionWithLandNodata) {
  const fs::path folder = testing::scratch_folder();
  TestWave::write(folder / "sequence");
  const ExportSummary summary = export_sequence({folder / "sequence", folder / "out", ExportFormat::kGeotiff, {10, 50}});
  ASSERT_EQ(summary.files.size(), 1u);
  const fs::path file = folder / "out" / "wave_statistics.tif";
  EXPECT_EQ(summary.files[0].file, file);
  EXPECT_EQ(summary.to_json()["frames"]["count"], 40);

  GDALAllRegister();
  GDALDataset* dataset = GDALDataset::Open(file.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
  ASSERT_NE(dataset, nullptr);
  const int columns = TestWave::kColumns, rows = TestWave::kRows;
  EXPECT_EQ(dataset->GetRasterXSize(), columns);
  EXPECT_EQ(dataset->GetRasterYSize(), rows);
  ASSERT_EQ(dataset->GetRasterCount(), 3);
  double geotransform[6] = {};
  ASSERT_EQ(dataset->GetGeoTransform(geotransform), CE_None);
  EXPECT_DOUBLE_EQ(geotransform[0], TestWave::kOriginX_m);
  EXPECT_DOUBLE_EQ(geotransform[1], TestWave::kSpacing_m);
  EXPECT_DOUBLE_EQ(geotransform[3], TestWave::kOriginY_m + rows * TestWave::kSpacing_m);
  EXPECT_DOUBLE_EQ(geotransform[5], -TestWave::kSpacing_m);
  OGRSpatialReference utm51;
  utm51.importFromEPSG(32651);
  ASSERT_NE(dataset->GetSpatialRef(), nullptr);
  EXPECT_TRUE(dataset->GetSpatialRef()->IsSame(&utm51));
  EXPECT_EQ(std::string(dataset->GetMetadataItem("NEARSHORE_FRAMES")), "10:50");

  std::vector<float> bands[3];
  for (int b = 0; b < 3; ++b) {
    GDALRasterBand* band = dataset->GetRasterBand(b + 1);
    int has_nodata = 0;
    EXPECT_EQ(band->GetNoDataValue(&has_nodata), -9999.0);
    EXPECT_TRUE(has_nodata);
    EXPECT_EQ(std::string(band->GetUnitType()), b == 2 ? "1" : "m");
    bands[b].resize(static_cast<std::size_t>(columns) * rows);
    ASSERT_EQ(band->RasterIO(GF_Read, 0, 0, columns, rows, bands[b].data(), columns, rows, GDT_Float32, 0, 0), CE_None);
  }
  EXPECT_NE(std::string(dataset->GetRasterBand(1)->GetDescription()).find("significant_wave_height"), std::string::npos);
  GDALClose(dataset);

  const double hs_m = 2.0 * std::numbers::sqrt2 * TestWave::kAmplitude_m;
  for (int row = 0; row < rows; ++row)
    for (int column = 0; column < columns; ++column) {
      const std::size_t pixel = static_cast<std::size_t>(rows - 1 - row) * columns + column;  // line 0 north
      if (TestWave::is_land(column, row)) {
        for (const auto& band : bands) EXPECT_EQ(band[pixel], -9999.0f) << column << ", " << row;
        continue;
      }
      EXPECT_NEAR(bands[0][pixel], hs_m, 1e-5) << column << ", " << row;
      EXPECT_NEAR(bands[1][pixel], 0.0, 1e-6);
      EXPECT_FLOAT_EQ(bands[2][pixel], column < 2 ? 0.5f : 0.0f);
    }
}

// Rectangular cells (10 m east by 4 m north): the GeoTIFF's pixels keep both sizes, and the
// statistics sit in the same cells.
TEST(ExportGeotiff, RectangularCellsKeepBothSizes) {
  const fs::path folder = testing::scratch_folder();
  TestWave::write(folder / "sequence", 4.0);
  export_sequence({folder / "sequence", folder / "out", ExportFormat::kGeotiff, {0, 20}});
  GDALAllRegister();
  GDALDataset* dataset =
      GDALDataset::Open((folder / "out" / "wave_statistics.tif").c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
  ASSERT_NE(dataset, nullptr);
  double geotransform[6] = {};
  ASSERT_EQ(dataset->GetGeoTransform(geotransform), CE_None);
  EXPECT_DOUBLE_EQ(geotransform[1], 10.0);
  EXPECT_DOUBLE_EQ(geotransform[5], -4.0);
  EXPECT_DOUBLE_EQ(geotransform[3], TestWave::kOriginY_m + TestWave::kRows * 4.0);
  float hs = 0.0f;
  ASSERT_EQ(dataset->GetRasterBand(1)->RasterIO(GF_Read, 5, 3, 1, 1, &hs, 1, 1, GDT_Float32, 0, 0), CE_None);
  EXPECT_NEAR(hs, 2.0 * std::numbers::sqrt2 * TestWave::kAmplitude_m, 1e-5);
  GDALClose(dataset);
}

}  // namespace
}  // namespace nearshore::exports
