// What a hostile or careless case file does (issue 44), each refused with one message naming the
// case file, the key or entry and the fix, before anything is allocated or written: a JSON case
// nested 150 000 levels deep (it overflowed the stack), a key given twice in JSON (TOML refuses it),
// values no sea or water has (a 1 km wave, a wet/dry threshold of most of the depth, a viscosity of
// treacle, a ramp of 1e308 s, a checkpoint every step), a resampling to millimetre cells
// (std::bad_alloc), 309-digit numbers (echoed in full), a gauge at lat 0, lon 0 on a grid in UTM
// zone 10N (GeographicLib's bare message), a GeoTIFF named as the harbour grid ("truncated or
// corrupt"), and a bake into the folder of the grid its case reads (the grid replaced by the
// bake's resampled copy).
#include <gdal_priv.h>

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include <fmt/core.h>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/map_projection.hpp"
#include "nearshore/sequence/checksum.hpp"

namespace nearshore::bake::testing {
namespace {
namespace fs = std::filesystem;

// 40 x 30 cells of 10 m in UTM zone 10N, open water 6 m deep: a harbour grid as bathy writes it.
fs::path write_hostile_grid(const fs::path& folder) {
  GridGeometry g;
  g.columns = 40;
  g.rows = 30;
  g.spacing_m = 10.0;
  g.origin_x_m = 541000.0;
  g.origin_y_m = 5236000.0;
  g.projection = MapProjection::utm(10, true).to_json();
  fs::create_directories(folder);
  write_harbour_grid(folder / "depth.exr", HarbourGrid::open_water(g, 6.0f));
  return folder / "depth.exr";
}

std::string hostile_grid_case(const std::string& grid_file, const std::string& bathymetry_extra = "",
                              const std::string& gauges = "") {
  return "[bathymetry]\nkind = \"harbour_grid\"\nfile = \"" + grid_file + "\"\n" + bathymetry_extra +
         "\n[time]\nduration_s = 2.0\noutput_interval_s = 1.0\n"
         "[wave_maker]\nkind = \"regular\"\nfacing = \"north\"\nsource_line_m = 250.0\nheight_m = 0.2\nperiod_s = 4.0\n" +
         gauges;
}

std::string flume_with(const std::string& from, const std::string& to) {
  std::string text = small_flume_case();
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

std::string error_of_case(const fs::path& file) {
  try {
    read_bake_case(file);
  } catch (const Error& error) {
    return error.what();
  }
  return "read without error";
}

TEST(HostileCase, AJsonCaseNested150000LevelsDeepIsRefusedAtOnce) {
  const auto folder = scratch_folder();
  constexpr int kLevels = 150000;  // 100 000 passed; 150 000 overflowed the stack in a recursive copy
  const std::string nested = std::string(kLevels, '[') + std::string(kLevels, ']');
  const auto start = std::chrono::steady_clock::now();
  const std::string message = error_of_case(write_text(folder / "case.json", "{\"title\": " + nested + "}"));
  EXPECT_NE(message.find("case.json"), std::string::npos) << message.substr(0, 400);
  EXPECT_NE(message.find("levels deep (at title)"), std::string::npos) << message.substr(0, 400);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  // TOML's parser has its own limit (256 nested values): refused cleanly too.
  const std::string toml = error_of_case(write_text(folder / "case.toml", "title = " + nested + "\n"));
  EXPECT_NE(toml.find("is not valid TOML"), std::string::npos) << toml.substr(0, 400);
}

TEST(HostileCase, AKeyGivenTwiceInJsonIsRefusedAsInToml) {
  const auto folder = scratch_folder();
  const std::string message = error_of_case(write_text(
      folder / "case.json",
      R"({"bathymetry": {"kind": "profile", "length_m": 12, "width_m": 0.6, "spacing_m": 0.1, "profile": [[0, 0.5], [12, 0.5]]},
          "time": {"duration_s": 8, "output_interval_s": 0.5, "duration_s": 80},
          "wave_maker": {"kind": "regular", "facing": "west", "source_line_m": 3, "height_m": 0.02, "period_s": 2}})"));
  EXPECT_NE(message.find("the key `time.duration_s` is given twice"), std::string::npos) << message;
  const std::string toml = error_of_case(write_text(folder / "case.toml", flume_with("spin_up_s = 2.0\n", "spin_up_s = 2.0\nspin_up_s = 3.0\n")));
  EXPECT_NE(toml.find("is not valid TOML"), std::string::npos) << toml;
}

TEST(HostileCase, ValuesNoSeaOrWaterHasAreRefusedWithTheirReason) {
  // A kilometre wave (the solver blew up and the message blamed the time step).
  expect_case_error(flume_with("height_m = 0.02", "height_m = 1000.0"),
                    {"wave_maker.height_m", "= 1000 m is above 40 m", "Draupner"});
  // A wet/dry threshold of most of the 0.5 m flume's depth.
  expect_case_error(small_flume_case() + "[solver]\ndry_depth_m = 0.3\n",
                    {"solver.dry_depth_m", "more than a tenth of the deepest still water (0.5 m)", "<= 0.05 m"});
  // The viscosity of treacle.
  expect_case_error(small_flume_case() + "[solver]\nkinematic_viscosity_m2_s = 1.0\n",
                    {"solver.kinematic_viscosity_m2_s", "= 1 is out of range", "1.8e-6 at 0 degC"});
  // A ramp no bake ever gets through.
  expect_case_error(flume_with("ramp_time_s = 2.0", "ramp_time_s = 1e308"), {"wave_maker.ramp_time_s", "is above 86400 s"});
  // Within the bounds, all of them read.
  EXPECT_NO_THROW(read_bake_case(write_text(current_scratch_folder() / "fine.toml",
                                            flume_with("height_m = 0.02", "height_m = 0.05") +
                                                "[solver]\ndry_depth_m = 0.002\nkinematic_viscosity_m2_s = 1.8e-6\n")));
}

TEST(HostileCase, ACheckpointEveryStepIsRefusedBeforeTheFolderIsTouched) {
  const auto folder = scratch_folder();
  const BakeCase bake_case = read_bake_case(write_text(folder / "case.toml", small_flume_case(8.0, 0.001)));
  BakeOptions options;
  options.output_folder = folder / "out";
  try {
    run_bake(bake_case, options);
    ADD_FAILURE() << "a checkpoint every step was accepted";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("time.checkpoint_interval_s` = 0.001 s is 1 time step"), std::string::npos) << message;
    EXPECT_NE(message.find("give time.checkpoint_interval_s >="), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(options.output_folder));
}

TEST(HostileCase, MillimetreCellsOnAHarbourGridAreRefusedBeforeTheyAreAllocated) {
  const auto folder = scratch_folder();
  write_hostile_grid(folder);
  const auto start = std::chrono::steady_clock::now();
  // 400 x 300 m at 1 mm: 1.2e11 cells (was std::bad_alloc after the allocation was tried).
  const std::string message = error_of_case(write_text(folder / "case.toml", hostile_grid_case("depth.exr", "spacing_m = 0.001")));
  EXPECT_NE(message.find("bathymetry.spacing_m` = 0.001 x 0.001 m resamples the 400 x 300 m grid to 4e+05 x 3e+05 cells"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("the grid's own cells are 10 x 10 m"), std::string::npos) << message;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(HostileCase, A309DigitNumberIsNotEchoedInFull) {
  const auto folder = scratch_folder();
  const std::string digits = "1" + std::string(308, '0');  // 1e308: a double, but no wave height
  for (const auto& [name, text] :
       {std::pair{"integer.toml", flume_with("height_m = 0.02", "height_m = " + digits)},
        std::pair{"float.toml", flume_with("height_m = 0.02", "height_m = " + digits + ".0")},
        std::pair{"string.toml", flume_with("height_m = 0.02", "height_m = \"" + digits + "\"")}}) {
    const std::string message = error_of_case(write_text(folder / name, text));
    // The key, or (toml++ refuses numbers over 126 characters itself) the line and column.
    EXPECT_TRUE(message.find("height_m") != std::string::npos || message.find("is not valid TOML at line 18") != std::string::npos)
        << message;
    EXPECT_EQ(message.find(std::string(30, '0')), std::string::npos) << name << ": " << message;
    EXPECT_LT(message.size(), 600u) << message;
  }
  const std::string json = error_of_case(write_text(folder / "case.json", "{\"title\": 1" + std::string(309, '0') + "}"));
  EXPECT_NE(json.find("(310 digits)"), std::string::npos) << json;
  EXPECT_EQ(json.find(std::string(30, '0')), std::string::npos) << json;
}

TEST(HostileCase, AGaugeTheGridsProjectionCannotReachIsNamed) {
  const auto folder = scratch_folder();
  write_hostile_grid(folder);
  // lat 0, lon 0 is 123 degrees of longitude from zone 10N's central meridian.
  const std::string message = error_of_case(write_text(
      folder / "case.toml", hostile_grid_case("depth.exr", "", "[[gauges]]\nname = \"null island\"\nlat = 0.0\nlon = 0.0\n")));
  EXPECT_NE(message.find("case.toml"), std::string::npos) << message;
  EXPECT_NE(message.find("gauge \"null island\""), std::string::npos) << message;
  EXPECT_NE(message.find("cannot place lat 0, lon 0"), std::string::npos) << message;
  EXPECT_NE(message.find("UTM zone 10N"), std::string::npos) << message;
}

TEST(HostileCase, AGeoTiffGivenAsTheHarbourGridIsCalledWhatItIs) {
  const auto folder = scratch_folder();
  GDALAllRegister();
  GDALDataset* tiff = GetGDALDriverManager()->GetDriverByName("GTiff")->Create((folder / "depth.tif").c_str(), 8, 8, 1,
                                                                             GDT_Float32, nullptr);
  ASSERT_NE(tiff, nullptr);
  double geotransform[6] = {541000.0, 10.0, 0.0, 5236080.0, 0.0, -10.0};
  tiff->SetGeoTransform(geotransform);
  GDALClose(tiff);
  const std::string message = error_of_case(write_text(folder / "case.toml", hostile_grid_case("depth.tif")));
  EXPECT_NE(message.find("bathymetry.file"), std::string::npos) << message;
  EXPECT_NE(message.find("is a TIFF (a GeoTIFF such as depth.tif), not a harbour grid"), std::string::npos) << message;
  EXPECT_EQ(message.find("truncated or corrupt"), std::string::npos) << message;
}

TEST(HostileCase, ABakeNeverWritesIntoTheFolderOfTheGridItReads) {
  const auto folder = scratch_folder();
  const fs::path harbour = folder / "harbour";
  const fs::path grid_file = write_hostile_grid(harbour);
  write_text(harbour / "summary.json", "{}\n");  // as bathy leaves it
  const std::string grid_bytes = sequence::read_file_bytes(grid_file);
  // The case resamples the 10 m grid to 20 m; baked into the harbour folder, its depth.exr would
  // replace the grid with a quarter of the cells for every later case.
  const BakeCase bake_case =
      read_bake_case(write_text(folder / "case.toml", hostile_grid_case("harbour/depth.exr", "spacing_m = 20.0")));
  for (const bool overwrite : {false, true}) {
    BakeOptions options;
    options.output_folder = harbour;
    options.overwrite = overwrite;
    try {
      run_bake(bake_case, options);
      ADD_FAILURE() << "baked into the harbour grid's folder, overwrite = " << overwrite;
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("is the folder the grid depth.exr that the case reads comes from"), std::string::npos) << message;
      EXPECT_NE(message.find("choose another BakeOptions::output_folder"), std::string::npos) << message;
    }
  }
  EXPECT_EQ(sequence::read_file_bytes(grid_file), grid_bytes);
  // Another harbour grid's folder (bathy's outputs, not this case's input) only with overwrite.
  const fs::path other = folder / "other_harbour";
  write_hostile_grid(other);
  write_text(other / "summary.json", "{}\n");
  BakeOptions options;
  options.output_folder = other;
  try {
    run_bake(bake_case, options);
    ADD_FAILURE() << "baked into another harbour grid's folder unasked";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("holds a harbour grid (written by nearshore bathy) (summary.json)"), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("or set BakeOptions::overwrite"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace nearshore::bake::testing
