// The wave statistics GeoTIFF read back by GDAL: georeference, Hs and mean level of a linear wave,
// the breaking fraction, nodata on land.
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>

#include <gtest/gtest.h>

#include "export_test_support.hpp"
#include "nearshore/export/export_sequence.hpp"
#include "nearshore/plot/plot.hpp"

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
  ASSERT_EQ(summary.files.size(), 2u);  // the GeoTIFF and its Hs map
  const fs::path file = folder / "out" / "wave_statistics.tif";
  EXPECT_EQ(summary.files[0].file, file);
  EXPECT_EQ(summary.files[1].file, folder / "out" / "wave_statistics_hs.png");
  EXPECT_EQ(summary.to_json()["frames"]["count"], 40);

  GDALAllRegister();
  GDALDataset* dataset = GDALDataset::Open(file.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
  ASSERT_NE(dataset, nullptr);
  const int columns = TestWave::kColumns, rows = TestWave::kRows;
  EXPECT_EQ(dataset->GetRasterXSize(), columns);
  EXPECT_EQ(dataset->GetRasterYSize(), rows);
  ASSERT_EQ(dataset->GetRasterCount(), 4);
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

  std::vector<float> bands[4];
  for (int b = 0; b < 4; ++b) {
    GDALRasterBand* band = dataset->GetRasterBand(b + 1);
    int has_nodata = 0;
    EXPECT_EQ(band->GetNoDataValue(&has_nodata), -9999.0);
    EXPECT_TRUE(has_nodata);
    EXPECT_EQ(std::string(band->GetUnitType()), b >= 2 ? "1" : "m");
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
      EXPECT_FLOAT_EQ(bands[3][pixel], 1.0f);  // 10 m of water under a 0.1 m wave never dries
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

// wave_statistics_hs.png decoded with libpng (read_png): the size of the map with its axes, land in
// the land colour, and a water cell in the colour its Hs takes on the colour bar.
TEST(ExportGeotiff, HsMapShowsLandInItsColourAndHsOnTheColourBar) {
  const fs::path folder = testing::scratch_folder();
  TestWave::write(folder / "sequence");
  export_sequence({folder / "sequence", folder / "out", ExportFormat::kGeotiff, {10, 50}});
  const Image map = read_png(folder / "out" / "wave_statistics_hs.png");

  // 24 x 16 cells at 8 pixels a cell (plot's largest), the field at (100, 50) after the northing
  // labels and the title; to its right 25 px gap, the 24 px colour bar and 110 px for its labels;
  // below it the easting labels (48 px) and the 50 px margin for the legend.
  HeatMapStyle style;
  style.map_axes = MapAxes{};
  const HeatMapPlacement placement = heat_map_placement(TestWave::kColumns, TestWave::kRows, style);
  ASSERT_DOUBLE_EQ(placement.pixels_per_cell, 8.0);
  EXPECT_EQ(map.width(), 100 + 24 * 8 + 25 + 24 + 110);
  EXPECT_EQ(map.height(), 50 + 16 * 8 + 48 + 50);

  auto centre_of = [&](int column, int row) {  // north (the last row) at the top
    return map.get(static_cast<int>(placement.left_px + (column + 0.5) * 8),
                   static_cast<int>(placement.top_px + (TestWave::kRows - 1 - row + 0.5) * 8));
  };
  // PNG stores 8 bits a channel: a colour comes back within half a step (1/510); 1/255 allows it.
  auto expect_colour = [](const Rgb& actual, const Rgb& expected, const std::string& where) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], 1.0 / 255.0) << where << " channel " << c;
  };
  const Rgb land_colour = HeatMapStyle{}.mask_colour;
  // Every land cell but those under the north arrow's white plate (the field's upper-right 48 x 64
  // pixels: columns 18-23 of the northern rows).
  for (int row = 0; row < TestWave::kRows; ++row)
    for (int column = 0; column < 18; ++column)
      if (TestWave::is_land(column, row)) expect_colour(centre_of(column, row), land_colour, fmt::format("land ({}, {})", column, row));

  // Hs = 2 sqrt(2) a = 0.2828 m everywhere on the water; the colour bar runs from 0 to the 99.5th
  // percentile rounded up to a round number, 0.3 m, so a water cell is viridis at 0.2828 / 0.3.
  const double hs_m = 2.0 * std::numbers::sqrt2 * TestWave::kAmplitude_m;
  const Rgb water_colour = colour_at(ColourMap::kViridis, hs_m / 0.3);
  for (auto [column, row] : {std::pair{12, 8}, std::pair{20, 3}, std::pair{3, 10}})
    expect_colour(centre_of(column, row), water_colour, fmt::format("water ({}, {})", column, row));
}

}  // namespace
}  // namespace nearshore::exports
