// Bad inputs: each gives one nearshore::Error naming the file (or the BathyRequest field, never a
// command-line flag) and the problem, and nothing is written to the output folder.
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <gdal_utils.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "test_folder.hpp"

namespace nb = nearshore::bathymetry;
namespace fs = std::filesystem;

namespace {

const fs::path kTacoma = fs::path(NEARSHORE_SHARED_DIR) / "charts/tacoma_us5wa22m/US5WA22M.000";

// Runs the whole command's library path; returns the error message (empty if none was thrown)
// and checks that the output folder was not even created.
std::string bathy_error(const nb::BathyRequest& request, const fs::path& out) {
  nearshore::ProgressBar::set_quiet(true);
  std::string message;
  try {
    const nb::BathyResult result = nb::build_harbour_grid(request);
    nb::write_bathymetry_outputs(out, result);
  } catch (const nearshore::Error& e) {
    message = e.what();
  }
  EXPECT_FALSE(fs::exists(out)) << "something was written for: " << message;
  return message;
}

nb::BathyRequest request_for(std::vector<fs::path> inputs, double spacing_m = 20.0) {
  nb::BathyRequest request;
  request.inputs = std::move(inputs);
  request.spacing_m = spacing_m;
  return request;
}

}  // namespace

TEST(BathyBadInput, MissingFile) {
  const auto folder = fresh_test_folder("");
  const std::string message = bathy_error(request_for({folder / "nowhere.000"}), folder / "out");
  EXPECT_NE(message.find("nowhere.000"), std::string::npos) << message;
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
}

TEST(BathyBadInput, NotAChart) {
  const auto folder = fresh_test_folder("");
  std::ofstream(folder / "notes.000") << "This is a text file, not an ISO 8211 S-57 cell.\n";
  const std::string message = bathy_error(request_for({folder / "notes.000"}), folder / "out");
  EXPECT_NE(message.find("notes.000"), std::string::npos) << message;
  EXPECT_NE(message.find("not an S-57 chart"), std::string::npos) << message;
}

TEST(BathyBadInput, ChartWithEmptySoundg) {
  // A real S-57 cell written by GDAL's S57 driver from Tacoma's land and depth areas, no SOUNDG.
  const auto folder = fresh_test_folder("");
  GDALAllRegister();
  GDALDatasetH source = GDALOpenEx(kTacoma.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
  ASSERT_NE(source, nullptr);
  const char* arguments[] = {"-f", "S57", "LNDARE", "DEPARE", "M_COVR", nullptr};
  GDALVectorTranslateOptions* options = GDALVectorTranslateOptionsNew(const_cast<char**>(arguments), nullptr);
  const fs::path chart = folder / "NOSOUNDG.000";
  GDALDatasetH written = GDALVectorTranslate(chart.c_str(), nullptr, 1, &source, options, nullptr);
  GDALVectorTranslateOptionsFree(options);
  ASSERT_NE(written, nullptr);
  GDALClose(written);
  GDALClose(source);
  const std::string message = bathy_error(request_for({chart}), folder / "out");
  EXPECT_NE(message.find("NOSOUNDG.000"), std::string::npos) << message;
  EXPECT_NE(message.find("no soundings"), std::string::npos) << message;
}

TEST(BathyBadInput, BoundingBoxOutsideTheData) {
  const auto folder = fresh_test_folder("");
  auto request = request_for({kTacoma});
  request.bbox_lon_lat = std::array<double, 4>{-70.0, 41.0, -69.9, 41.1};  // Cape Cod, not Tacoma
  const std::string message = bathy_error(request, folder / "out");
  EXPECT_NE(message.find("BathyRequest::bbox_lon_lat"), std::string::npos) << message;
  EXPECT_NE(message.find("outside the data"), std::string::npos) << message;
}

TEST(BathyBadInput, NaNCellsInARaster) {
  const auto folder = fresh_test_folder("");
  const auto files = nb::write_demo_harbour(folder / "demo");
  // Copy the survey, then punch NaN holes into it without declaring NaN as nodata.
  GDALAllRegister();
  const fs::path holed = folder / "holed.tif";
  {
    GDALDataset* source = GDALDataset::Open(files.depth_geotiff.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
    ASSERT_NE(source, nullptr);
    GDALDataset* copy = GetGDALDriverManager()->GetDriverByName("GTiff")->CreateCopy(holed.c_str(), source, FALSE, nullptr, nullptr, nullptr);
    GDALClose(source);
    ASSERT_NE(copy, nullptr);
    std::vector<float> nan_block(12 * 3, std::numeric_limits<float>::quiet_NaN());
    ASSERT_EQ(copy->GetRasterBand(1)->RasterIO(GF_Write, 40, 20, 12, 3, nan_block.data(), 12, 3, GDT_Float32, 0, 0), CE_None);
    GDALClose(copy);
  }
  const std::string message = bathy_error(request_for({holed}), folder / "out");
  EXPECT_NE(message.find("holed.tif"), std::string::npos) << message;
  EXPECT_NE(message.find("36 cells are NaN"), std::string::npos) << message;
  EXPECT_NE(message.find("pixel (40, 20)"), std::string::npos) << message;
}

TEST(BathyBadInput, GridLargerThanTheMachinesMemory) {
  // The demo site (1.6 x 1.2 km) at 1 mm: 1.9e12 cells, ~190 TB; refused before any allocation.
  const auto folder = fresh_test_folder("");
  const auto files = nb::write_demo_harbour(folder / "demo");
  const std::string message = bathy_error(request_for({files.depth_geotiff}, 0.001), folder / "out");
  EXPECT_NE(message.find("memory"), std::string::npos) << message;
  EXPECT_NE(message.find("BathyRequest::spacing_m"), std::string::npos) << message;
}

// Issue 13 item 6: a GeoTIFF holding depths up to 6e28 m (an undeclared fill value) passed, and the
// bake then ran with a 1e-14 s time step. Depths are bounded by the Challenger Deep (sources.hpp).
TEST(BathyBadInput, AbsurdDepthsInARaster) {
  const auto folder = fresh_test_folder("");
  const auto files = nb::write_demo_harbour(folder / "demo");
  GDALAllRegister();
  const fs::path absurd = folder / "absurd.tif";
  {
    GDALDataset* source = GDALDataset::Open(files.depth_geotiff.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
    ASSERT_NE(source, nullptr);
    GDALDataset* copy = GetGDALDriverManager()->GetDriverByName("GTiff")->CreateCopy(absurd.c_str(), source, FALSE, nullptr, nullptr, nullptr);
    GDALClose(source);
    ASSERT_NE(copy, nullptr);
    std::vector<float> block(5 * 2, 6.0e28f);  // the demo survey is positive down: depths of 6e28 m
    block[7] = 2.0e4f;                         // and one of 20 km
    ASSERT_EQ(copy->GetRasterBand(1)->RasterIO(GF_Write, 30, 10, 5, 2, block.data(), 5, 2, GDT_Float32, 0, 0), CE_None);
    GDALClose(copy);
  }
  const std::string message = bathy_error(request_for({absurd}), folder / "out");
  EXPECT_NE(message.find("absurd.tif"), std::string::npos) << message;
  EXPECT_NE(message.find("10 cells hold depths"), std::string::npos) << message;
  EXPECT_NE(message.find("up to 6e+28 m"), std::string::npos) << message;
  EXPECT_NE(message.find("deeper than 11000 m, the deepest water on Earth"), std::string::npos) << message;
  EXPECT_NE(message.find("pixel (30, 10)"), std::string::npos) << message;
}

TEST(BathyBadInput, AbsurdSoundingInATextFile) {
  const auto folder = fresh_test_folder("");
  std::ofstream(folder / "soundings.xyz") << "lon lat depth\n-122.42 47.27 12.5\n-122.41 47.28 -95000\n";
  const std::string message = bathy_error(request_for({folder / "soundings.xyz"}), folder / "out");
  EXPECT_NE(message.find("soundings.xyz"), std::string::npos) << message;
  EXPECT_NE(message.find("line 3 gives a depth of -95000 m"), std::string::npos) << message;
  EXPECT_NE(message.find("higher than 9000 m above the datum"), std::string::npos) << message;
}

TEST(BathyBadInput, ImplausibleLevelsNameTheField) {
  const auto folder = fresh_test_folder("");
  const auto files = nb::write_demo_harbour(folder / "demo");
  auto request = request_for({files.depth_geotiff});
  request.water_level_m = 150.0;
  std::string message = bathy_error(request, folder / "out");
  EXPECT_NE(message.find("BathyRequest::water_level_m = 150 m"), std::string::npos) << message;
  EXPECT_NE(message.find("outside -30 .. 30 m"), std::string::npos) << message;
  request = request_for({files.depth_geotiff});
  request.minimum_depth_m = 2e4;
  message = bathy_error(request, folder / "out");
  EXPECT_NE(message.find("BathyRequest::minimum_depth_m = 20000 m"), std::string::npos) << message;
  request = request_for({files.depth_geotiff});
  request.land_elevation_m = std::numeric_limits<double>::quiet_NaN();
  message = bathy_error(request, folder / "out");
  EXPECT_NE(message.find("BathyRequest::land_elevation_m = nan m"), std::string::npos) << message;
}

// A GeoTIFF cut short after its header (300 bytes of it): GDAL opens it and finds no georeference
// in what is left, which the message used to say (issue 44); it is a truncated file.
TEST(BathyBadInput, ATruncatedGeoTiffIsCalledTruncated) {
  const auto folder = fresh_test_folder("");
  const auto files = nb::write_demo_harbour(folder / "demo");
  {
    std::ifstream in(files.depth_geotiff, std::ios::binary);
    std::string head(300, '\0');
    in.read(head.data(), 300);
    std::ofstream(folder / "cut.tif", std::ios::binary) << head;
  }
  const std::string message = bathy_error(request_for({folder / "cut.tif"}), folder / "out");
  EXPECT_NE(message.find("cut.tif"), std::string::npos) << message;
  EXPECT_NE(message.find("truncated or corrupt"), std::string::npos) << message;
  EXPECT_EQ(message.find("no georeference"), std::string::npos) << message;
}

// The output folder rules (core/output_folder.hpp, issue 44): `bathy ... -o SEQ` replaced the
// sequence's depth.exr, on which its frames were baked; a harbour grid written into the folder of
// one of its inputs would replace that input (depth.tif read again at another spacing).
TEST(BathyBadInput, NeverWritesIntoASequenceNorIntoTheFolderOfAnInput) {
  nearshore::ProgressBar::set_quiet(true);
  const auto folder = fresh_test_folder("");
  const auto files = nb::write_demo_harbour(folder / "demo");
  const nb::BathyResult result = nb::build_harbour_grid(request_for({files.depth_geotiff}, 40.0));
  const fs::path sequence = folder / "sequence";
  fs::create_directories(sequence);
  std::ofstream(sequence / "manifest.json") << "{}";
  std::ofstream(sequence / "depth.exr") << "the grid the frames were baked on";
  const auto message_of = [&](const fs::path& out) {
    try {
      nb::write_bathymetry_outputs(out, result);
    } catch (const nearshore::Error& e) {
      return std::string(e.what());
    }
    return std::string("written");
  };
  std::string message = message_of(sequence);
  EXPECT_NE(message.find("holds a baked sequence (written by nearshore bake) (manifest.json)"), std::string::npos) << message;
  std::ifstream kept(sequence / "depth.exr");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "the grid the frames were baked on");
  EXPECT_FALSE(fs::exists(sequence / "depth.tif"));
  message = message_of(folder / "demo");
  EXPECT_NE(message.find("is the folder the input"), std::string::npos) << message;
  EXPECT_NE(message.find("write_bathymetry_outputs(folder)"), std::string::npos) << message;
  EXPECT_EQ(message_of(folder / "harbour"), "written");
}
