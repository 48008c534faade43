// The agitation export (issue 39; export/include/nearshore/export/agitation.hpp): the coefficient
// against a sequence of known Hs (a sinusoid of amplitude a sampled over whole periods has Hs =
// 4 a / sqrt(2) exactly), from the frames and from a bake statistics file, written and read back
// with GDAL; the wet-cell bilinear reading against hand-computed values; the berth files and
// their refusals. Milliseconds each.
#include <gdal_priv.h>

#include <array>
#include <cmath>
#include <fstream>
#include <limits>

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "export_test_support.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/map_projection.hpp"
#include "nearshore/export/agitation.hpp"
#include "nearshore/export/export_sequence.hpp"
#include "nearshore/plot/plot.hpp"

namespace nearshore::exports {
namespace {

using testing::scratch_folder;
using testing::TestWave;
namespace fs = std::filesystem;

fs::path write_agitation_text(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

// The test wave's manifest with a wave maker of one component of amplitude `maker_amplitude_m`
// recorded, as a bake records its maker (bake/src/case_wave_maker.cpp, wave_record).
fs::path wave_with_maker(const fs::path& folder, double maker_amplitude_m) {
  TestWave::write(folder);
  nlohmann::json manifest;
  std::ifstream(folder / "manifest.json") >> manifest;
  manifest["wave_conditions"] = {{"components", {{{"amplitude_m", maker_amplitude_m}, {"angular_frequency_rad_s", 0.785},
                                                   {"direction_rad", 0.0}, {"phase_rad", 0.0}}}}};
  std::ofstream(folder / "manifest.json") << manifest.dump(1);
  return folder;
}

// Reads a one-band GeoTIFF into a row-0-south raster; returns its geotransform too.
Raster<float> read_band(const fs::path& file, int band_number, std::array<double, 6>& geotransform) {
  GDALAllRegister();
  GDALDataset* dataset = static_cast<GDALDataset*>(GDALOpen(file.c_str(), GA_ReadOnly));
  EXPECT_NE(dataset, nullptr) << file;
  if (!dataset) return {};
  dataset->GetGeoTransform(geotransform.data());
  const int columns = dataset->GetRasterXSize(), rows = dataset->GetRasterYSize();
  std::vector<float> lines(static_cast<std::size_t>(columns) * rows);
  EXPECT_EQ(dataset->GetRasterBand(band_number)->RasterIO(GF_Read, 0, 0, columns, rows, lines.data(), columns, rows,
                                                          GDT_Float32, 0, 0),
            CE_None);
  GDALClose(dataset);
  Raster<float> raster(columns, rows);
  for (int row = 0; row < rows; ++row)
    for (int column = 0; column < columns; ++column)
      raster(column, row) = lines[static_cast<std::size_t>(rows - 1 - row) * columns + column];
  return raster;
}

TEST(Agitation, IncidentHeightIsTheBakedPartOfASplitElseTheComponents) {
  // Two components of 0.3 m and 0.4 m: m0 = (0.09 + 0.16) / 2, Hm0 = 4 sqrt(0.125).
  const nlohmann::json components = {{"components", {{{"amplitude_m", 0.3}}, {{"amplitude_m", 0.4}}}}};
  EXPECT_NEAR(*recorded_incident_significant_wave_height_m(components), 4.0 * std::sqrt(0.125), 1e-12);
  nlohmann::json split = components;
  split["spectrum_split"] = {{"bake_significant_wave_height_m", 1.23}, {"total_significant_wave_height_m", 1.5}};
  EXPECT_DOUBLE_EQ(*recorded_incident_significant_wave_height_m(split), 1.23);
  EXPECT_FALSE(recorded_incident_significant_wave_height_m({{"kind", "time series"}}).has_value());
  EXPECT_FALSE(recorded_incident_significant_wave_height_m(nlohmann::json()).has_value());
}

TEST(Agitation, CoefficientOfAKnownSinusoidFromTheFrames) {
  // The frames: a = 0.1 m over three whole periods at T/20, Hs = 2 sqrt(2) a; the maker's component
  // a = 0.25 m, Hs_incident = 2 sqrt(2) 0.25: K = 0.4 in every water cell. The frames hold floats:
  // eta to 1e-8 m, sums in double (core/elevation_moments.hpp), so K to 1e-5.
  const fs::path sequence = wave_with_maker(scratch_folder() / "sequence", 0.25);
  const fs::path output = sequence.parent_path() / "agitation";
  ExportRequest request;
  request.sequence_folder = sequence;
  request.output_folder = output;
  request.format = ExportFormat::kAgitation;
  const ExportSummary summary = export_sequence(request);
  EXPECT_NEAR(summary.agitation["incident_significant_wave_height_m"].get<double>(), 2.0 * std::sqrt(2.0) * 0.25, 1e-12);
  EXPECT_NE(summary.agitation["significant_wave_height_source"].get<std::string>().find("frames 0-59"), std::string::npos);
  std::array<double, 6> geotransform{};
  const Raster<float> k = read_band(output / "agitation.tif", 1, geotransform);
  ASSERT_EQ(k.columns(), TestWave::kColumns);
  ASSERT_EQ(k.rows(), TestWave::kRows);
  // Georeferenced as the other exports: the north-west corner, cells of 10 m, north up.
  EXPECT_DOUBLE_EQ(geotransform[0], TestWave::kOriginX_m);
  EXPECT_DOUBLE_EQ(geotransform[3], TestWave::kOriginY_m + TestWave::kRows * TestWave::kSpacing_m);
  EXPECT_DOUBLE_EQ(geotransform[1], TestWave::kSpacing_m);
  EXPECT_DOUBLE_EQ(geotransform[5], -TestWave::kSpacing_m);
  for (int row = 0; row < TestWave::kRows; ++row)
    for (int column = 0; column < TestWave::kColumns; ++column)
      if (TestWave::is_land(column, row))
        EXPECT_TRUE(std::isnan(k(column, row))) << column << ", " << row;
      else
        EXPECT_NEAR(k(column, row), 0.4, 1e-5) << column << ", " << row;
  // The map: a PNG with axes, larger than the field.
  const Image map = read_png(output / "agitation.png");
  EXPECT_GT(map.width(), TestWave::kColumns);
  EXPECT_FALSE(fs::exists(output / "berths.csv"));  // no berths asked for
}

TEST(Agitation, BakeStatisticsAreReadWhereTheSequenceHasThemAndTheFramesWhenARangeIsAsked) {
  // A wave_statistics.tif as the bake writes it (4 bands, north first, nodata -9999): band 2 holds
  // Hs = 0.01 (column + 1) m, unlike the frames' 2 sqrt(2) 0.1 m, so the source shows in K.
  const fs::path sequence = wave_with_maker(scratch_folder() / "sequence", 0.25);
  const GridGeometry g = TestWave::geometry();
  GDALAllRegister();
  GDALDataset* dataset = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(
      (sequence / "wave_statistics.tif").c_str(), g.columns, g.rows, 4, GDT_Float32, nullptr);
  ASSERT_NE(dataset, nullptr);
  std::vector<float> lines(g.cell_count());
  for (int band = 1; band <= 4; ++band) {
    for (int row = 0; row < g.rows; ++row)
      for (int column = 0; column < g.columns; ++column)
        lines[static_cast<std::size_t>(g.rows - 1 - row) * g.columns + column] =
            TestWave::is_land(column, row) ? -9999.0f : (band == 2 ? 0.01f * (column + 1) : 7.0f);
    dataset->GetRasterBand(band)->SetNoDataValue(-9999.0);
    ASSERT_EQ(dataset->GetRasterBand(band)->RasterIO(GF_Write, 0, 0, g.columns, g.rows, lines.data(), g.columns, g.rows,
                                                     GDT_Float32, 0, 0),
              CE_None);
  }
  dataset->SetMetadataItem("NEARSHORE_STEPS", "1234");
  GDALClose(dataset);

  ExportRequest request;
  request.sequence_folder = sequence;
  request.output_folder = sequence.parent_path() / "whole";
  request.format = ExportFormat::kAgitation;
  request.agitation.incident_significant_wave_height_m = 0.5;  // overrides the maker's
  const ExportSummary whole = export_sequence(request);
  EXPECT_EQ(whole.agitation["incident_source"], "given");
  EXPECT_NE(whole.agitation["significant_wave_height_source"].get<std::string>().find("1234 steps"), std::string::npos);
  std::array<double, 6> geotransform{};
  const Raster<float> k = read_band(request.output_folder / "agitation.tif", 1, geotransform);
  EXPECT_NEAR(k(5, 4), 0.01 * 6 / 0.5, 1e-6);
  EXPECT_TRUE(std::isnan(k(0, 0)));  // land

  request.output_folder = sequence.parent_path() / "window";
  request.frames = {20, 60};  // a window: the bake's file covers the whole run, so the frames decide
  const ExportSummary window = export_sequence(request);
  EXPECT_NE(window.agitation["significant_wave_height_source"].get<std::string>().find("frames 20-59"), std::string::npos);
  const Raster<float> k_window = read_band(request.output_folder / "agitation.tif", 1, geotransform);
  EXPECT_NEAR(k_window(5, 4), 2.0 * std::sqrt(2.0) * 0.1 / 0.5, 1e-5);
}

// A 3 x 3 harbour of 10 m cells, cell (2, 2) land (the north-east corner), and a field f = column
// + 10 row on the water (land holds 1000, which must never leak into a value).
HarbourGrid small_harbour(Raster<float>& field) {
  GridGeometry g;
  g.columns = 3;
  g.rows = 3;
  g.set_spacing(10.0, 10.0);
  HarbourGrid harbour = HarbourGrid::open_water(g, 5.0f);
  harbour.land(2, 2) = kLandCell;
  field = Raster<float>(3, 3);
  for (int row = 0; row < 3; ++row)
    for (int column = 0; column < 3; ++column)
      field(column, row) = harbour.land(column, row) ? 1000.0f : static_cast<float>(column + 10 * row);
  return harbour;
}

TEST(Agitation, BilinearReadingUsesTheWetCellsOnly) {
  Raster<float> field;
  const HarbourGrid harbour = small_harbour(field);
  // Between the centres of (0, 0), (1, 0), (0, 1), (1, 1) (at 5 and 15 m): f is linear, so bilinear
  // is exact: x = 8 m is column 0.3, y = 12 m row 0.7: 0.3 + 7.
  EXPECT_NEAR(*wet_bilinear_value(field, harbour, 8.0, 12.0), 7.3, 1e-6);
  // On a cell centre: its value.
  EXPECT_NEAR(*wet_bilinear_value(field, harbour, 15.0, 15.0), 11.0, 1e-6);
  // Beside the land corner: x = 22 m (column 1.7), y = 18 m (row 1.3). Weights (1,1) 0.3*0.7 =
  // 0.21, (2,1) 0.7*0.7 = 0.49, (1,2) 0.3*0.3 = 0.09, (2,2) land 0.21 dropped: (0.21*11 + 0.49*12 +
  // 0.09*21) / 0.79.
  EXPECT_NEAR(*wet_bilinear_value(field, harbour, 22.0, 18.0), (0.21 * 11 + 0.49 * 12 + 0.09 * 21) / 0.79, 1e-6);
  // Within the outer half cell: the edge cells' values (clamped), here the centre (0, 0)'s.
  EXPECT_NEAR(*wet_bilinear_value(field, harbour, 1.0, 2.0), 0.0, 1e-6);
  EXPECT_FALSE(wet_bilinear_value(field, harbour, 25.0, 25.0).has_value());   // on the land cell
  EXPECT_FALSE(wet_bilinear_value(field, harbour, -1.0, 5.0).has_value());    // west of the grid
  EXPECT_FALSE(wet_bilinear_value(field, harbour, 5.0, 30.5).has_value());    // north of it
}

TEST(Agitation, BerthValuesAndTheirRefusals) {
  Raster<float> field;
  const HarbourGrid harbour = small_harbour(field);
  const fs::path folder = scratch_folder();
  const auto berths = read_berths(write_agitation_text(folder / "berths.csv", "# the quay\nname,x_m,y_m\nquay 1, 8, 12\n\nquay 2,15,15\n"),
                                  harbour.geometry);
  ASSERT_EQ(berths.size(), 2u);
  EXPECT_EQ(berths[0].name, "quay 1");
  EXPECT_EQ(berths[1].place, "berths.csv:5");
  const auto values = berth_values(berths, field, 2.0, harbour);
  EXPECT_NEAR(values[0].significant_wave_height_m, 7.3, 1e-6);
  EXPECT_NEAR(values[0].agitation_coefficient, 3.65, 1e-6);

  const auto message_of = [&](const std::string& text) {
    try {
      read_berths(write_agitation_text(folder / "bad.csv", text), harbour.geometry);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message_of("berth,x,y\na,1,2\n").find("bad.csv: line 1: the header is 'berth,x,y'"), std::string::npos)
      << message_of("berth,x,y\na,1,2\n");
  EXPECT_NE(message_of("name,x_m,y_m\na,1\n").find("line 2: 'a,1' has 2 fields"), std::string::npos);
  EXPECT_NE(message_of("name,x_m,y_m\na,1,2m\n").find("line 2: berth 'a': '2m' is not a number"), std::string::npos);
  EXPECT_NE(message_of("name,x_m,y_m\n,1,2\n").find("line 2: the berth has no name"), std::string::npos);
  EXPECT_NE(message_of("name,x_m,y_m\na,1,2\na,3,4\n").find("bad.csv:3: the name 'a' is given to two berths"),
            std::string::npos);
  EXPECT_NE(message_of("name,x_m,y_m\n").find("names no berth"), std::string::npos);
  EXPECT_NE(message_of("").find("is empty"), std::string::npos);
  EXPECT_NE(message_of("name,longitude,latitude\na,121.7,38.9\n").find("has no map projection"), std::string::npos);

  // On land, and outside: the berth, its place and its position are named.
  const auto land = read_berths(write_agitation_text(folder / "land.csv", "name,x_m,y_m\nshed,25,25\n"), harbour.geometry);
  try {
    berth_values(land, field, 2.0, harbour);
    ADD_FAILURE() << "a berth on land was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("berth 'shed' (land.csv:2): at x = 25.0 m, y = 25.0 m lies on land"),
              std::string::npos)
        << error.what();
  }
  const auto outside = read_berths(write_agitation_text(folder / "out.csv", "name,x_m,y_m\nfar,5,95\n"), harbour.geometry);
  EXPECT_THROW(berth_values(outside, field, 2.0, harbour), Error);
}

TEST(Agitation, BerthsByLongitudeAndLatitudeInCsvAndGeoJson) {
  // The test wave's UTM 51N grid: the place of cell (7, 4)'s centre by longitude and latitude must
  // come back as that centre in the grid frame, (75, 45) m, within a millimetre.
  const GridGeometry g = TestWave::geometry();
  const LonLat place = lon_lat_of(g, GridPosition{7.0, 4.0});
  const fs::path folder = scratch_folder();
  const auto csv = read_berths(
      write_agitation_text(folder / "b.csv", fmt::format("name,longitude,latitude\npier,{:.10f},{:.10f}\n", place.longitude_deg,
                                                         place.latitude_deg)),
      g);
  EXPECT_NEAR(csv[0].x_m, 75.0, 1e-3);
  EXPECT_NEAR(csv[0].y_m, 45.0, 1e-3);
  const auto geojson = read_berths(
      write_agitation_text(folder / "b.geojson",
                           fmt::format(R"({{"type": "FeatureCollection", "features": [{{"type": "Feature",
                             "properties": {{"name": "pier"}}, "geometry": {{"type": "Point", "coordinates": [{:.10f}, {:.10f}]}}}}]}})",
                                       place.longitude_deg, place.latitude_deg)),
      g);
  EXPECT_NEAR(geojson[0].x_m, 75.0, 1e-3);
  EXPECT_NEAR(geojson[0].y_m, 45.0, 1e-3);
  EXPECT_THROW(read_berths(write_agitation_text(folder / "c.geojson",
                                                R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {},
                                                    "geometry": {"type": "Point", "coordinates": [121.7, 38.9]}}]})"),
                           g),
               Error);
}

TEST(Agitation, BerthsFileWritesTheTableAndABadOneWritesNothing) {
  const fs::path sequence = wave_with_maker(scratch_folder() / "sequence", 0.25);
  ExportRequest request;
  request.sequence_folder = sequence;
  request.output_folder = sequence.parent_path() / "out";
  request.format = ExportFormat::kAgitation;
  request.agitation.berths_file = write_agitation_text(sequence.parent_path() / "berths.csv", "name,x_m,y_m\nA,55,35\n");
  const ExportSummary summary = export_sequence(request);
  ASSERT_EQ(summary.agitation["berths"].size(), 1u);
  EXPECT_NEAR(summary.agitation["berths"][0]["agitation_coefficient"].get<double>(), 0.4, 1e-5);
  std::ifstream csv(request.output_folder / "berths.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(header, "name,x_m,y_m,longitude,latitude,significant_wave_height_m,agitation_coefficient");
  EXPECT_EQ(row.substr(0, 15), "A,55.00,35.00,,");

  request.output_folder = sequence.parent_path() / "bad";
  request.agitation.berths_file = write_agitation_text(sequence.parent_path() / "land.csv", "name,x_m,y_m\nA,55,155\n");
  EXPECT_THROW(export_sequence(request), Error);  // the northern rows are land
  EXPECT_FALSE(fs::exists(request.output_folder / "agitation.tif"));
}

}  // namespace
}  // namespace nearshore::exports
