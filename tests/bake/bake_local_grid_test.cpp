// [bathymetry] kind = "local_grid" (issue 19): a laboratory flume given as a grid file in local
// metres with no CRS (an ESRI ASCII grid, "x y depth" soundings) is baked directly, with no
// projection invented for it. The same flume given as a profile is the reference: the grid file
// must give the same grid and so the same gauge records.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_bathymetry.hpp"
#include "nearshore/bake/bake_gauges.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::bake::testing {
namespace {

namespace fs = std::filesystem;

// small_flume_case's flat 0.5 m bed, turned into a bed sloping from 0.5 m to 0.3 m over its 12 m,
// so that a grid read with its rows or columns reversed would differ.
const std::string kFlatSection =
    "[bathymetry]\nkind = \"profile\"\nlength_m = 12.0\nwidth_m = 0.6\nspacing_m = 0.1\n"
    "profile = [[0.0, 0.5], [12.0, 0.5]]\n";
const std::vector<std::pair<double, double>> kSlope = {{0.0, 0.5}, {12.0, 0.3}};

std::string flume_case_with(const std::string& bathymetry_section, double duration_s = 6.0) {
  std::string text = small_flume_case(duration_s);
  const auto at = text.find(kFlatSection);
  EXPECT_NE(at, std::string::npos) << "small_flume_case changed its [bathymetry]";
  return text.replace(at, kFlatSection.size(), bathymetry_section);
}

std::string profile_section() {
  return "[bathymetry]\nkind = \"profile\"\nlength_m = 12.0\nwidth_m = 0.6\nspacing_m = 0.1\n"
         "profile = [[0.0, 0.5], [12.0, 0.3]]\n";
}

// The sloping flume as an ESRI ASCII grid of 0.1 m cells: each value the profile at the cell's
// centre, as the float flume_from_profile stores, printed with all of its digits.
fs::path write_ascii_flume(const fs::path& folder) {
  const fs::path path = folder / "flume.asc";
  std::ofstream out(path);
  out << "ncols 120\nnrows 6\nxllcorner 0\nyllcorner 0\ncellsize 0.1\nNODATA_value -9999\n";
  for (int row = 0; row < 6; ++row) {
    for (int column = 0; column < 120; ++column)
      out << fmt::format("{:.9g} ", static_cast<float>(profile_depth_m(kSlope, (column + 0.5) * 0.1)));
    out << "\n";
  }
  return path;
}

// The same bed sounded on a coarser lattice (0.25 m along, 0.15 m across) as "x y depth" text.
fs::path write_soundings(const fs::path& folder) {
  const fs::path path = folder / "soundings.xyz";
  std::ofstream out(path);
  out << "x_m y_m depth_m\n";
  for (int i = 0; i <= 48; ++i)
    for (int j = 0; j <= 4; ++j) out << fmt::format("{} {} {:.12g}\n", i * 0.25, j * 0.15, profile_depth_m(kSlope, i * 0.25));
  return path;
}

GaugeTable bake_gauges(const BakeCase& bake_case, const fs::path& folder) {
  BakeOptions options;
  options.output_folder = folder;
  run_bake(bake_case, options);
  return read_gauges_csv(folder / "gauges.csv");
}

class LocalGridCase : public ::testing::Test {
 protected:
  void SetUp() override { ProgressBar::set_quiet(true); }
};

TEST_F(LocalGridCase, AnAsciiGridBakesTheSameFlumeAsItsProfile) {
  const auto folder = scratch_folder();
  write_ascii_flume(folder);
  const BakeCase reference = read_bake_case(write_text(folder / "profile.toml", flume_case_with(profile_section())));
  const BakeCase local = read_bake_case(write_text(
      folder / "local.toml",
      flume_case_with("[bathymetry]\nkind = \"local_grid\"\nfile = \"flume.asc\"\ndepth_sign = \"positive_down\"\n")));
  const GridGeometry& g = local.harbour.geometry;
  ASSERT_EQ(g.columns, reference.harbour.geometry.columns);
  ASSERT_EQ(g.rows, reference.harbour.geometry.rows);
  EXPECT_DOUBLE_EQ(g.spacing_x_m(), 0.1);
  EXPECT_TRUE(g.crs_wkt.empty());
  EXPECT_EQ(local.harbour.still_water_depth_m.values(), reference.harbour.still_water_depth_m.values());
  // The same grid bakes the same sea: the gauge records agree to the last digit written.
  const GaugeTable expected = bake_gauges(reference, folder / "profile_out");
  const GaugeTable baked = bake_gauges(local, folder / "local_out");
  ASSERT_EQ(baked.names, expected.names);
  ASSERT_EQ(baked.time_s.size(), expected.time_s.size());
  double highest = 0.0, lowest = 0.0;
  for (std::size_t k = 0; k < baked.names.size(); ++k)
    for (std::size_t n = 0; n < baked.time_s.size(); ++n) {
      ASSERT_EQ(baked.elevation_m[k][n], expected.elevation_m[k][n]) << baked.names[k] << " at " << baked.time_s[n] << " s";
      highest = std::max(highest, baked.elevation_m[k][n]), lowest = std::min(lowest, baked.elevation_m[k][n]);
    }
  EXPECT_GT(highest - lowest, 0.01);  // the 0.02 m waves reached the gauges
}

TEST_F(LocalGridCase, SoundingsAreGriddedAtSpacingAndBakeAsTheProfile) {
  const auto folder = scratch_folder();
  write_soundings(folder);
  const BakeCase reference = read_bake_case(write_text(folder / "profile.toml", flume_case_with(profile_section())));
  const BakeCase local = read_bake_case(write_text(
      folder / "local.toml", flume_case_with("[bathymetry]\nkind = \"local_grid\"\nfile = \"soundings.xyz\"\n"
                                             "depth_sign = \"positive_down\"\nspacing_m = 0.1\n")));
  const GridGeometry& g = local.harbour.geometry;
  ASSERT_EQ(g.columns, 120);
  ASSERT_EQ(g.rows, 6);
  // Sibson interpolation is exact on a plane (natural_neighbour.hpp): float rounding only.
  for (std::size_t i = 0; i < g.cell_count(); ++i)
    ASSERT_NEAR(local.harbour.still_water_depth_m.values()[i], reference.harbour.still_water_depth_m.values()[i], 2e-6);
  // Depths within 2e-6 m of 0.3-0.5 m (5e-6 relative) move the 0.02 m waves' phase and height by
  // about as much relative: 1e-6 m bounds the difference at the gauges with a margin of ten.
  const GaugeTable expected = bake_gauges(reference, folder / "profile_out");
  const GaugeTable baked = bake_gauges(local, folder / "local_out");
  ASSERT_EQ(baked.time_s.size(), expected.time_s.size());
  for (std::size_t k = 0; k < baked.names.size(); ++k)
    for (std::size_t n = 0; n < baked.time_s.size(); ++n)
      ASSERT_NEAR(baked.elevation_m[k][n], expected.elevation_m[k][n], 1e-6) << baked.names[k] << " at " << baked.time_s[n] << " s";
}

TEST_F(LocalGridCase, ARasterIsResampledToSpacing) {
  const auto folder = scratch_folder();
  write_ascii_flume(folder);
  const BakeCase local = read_bake_case(write_text(
      folder / "local.toml", flume_case_with("[bathymetry]\nkind = \"local_grid\"\nfile = \"flume.asc\"\n"
                                             "depth_sign = \"positive_down\"\nspacing_m = [0.2, 0.1]\n")));
  const GridGeometry& g = local.harbour.geometry;
  EXPECT_EQ(g.columns, 60);
  EXPECT_EQ(g.rows, 6);
  EXPECT_DOUBLE_EQ(g.spacing_x_m(), 0.2);
  // A linear bed stays linear under bilinear resampling (bake_bathymetry.hpp).
  EXPECT_NEAR(local.harbour.still_water_depth_m(10, 2), profile_depth_m(kSlope, g.cell_centre_x_m(10)), 1e-6);
}

TEST_F(LocalGridCase, BadTablesNameTheKeyAndTheFix) {
  const auto folder = scratch_folder();
  write_ascii_flume(folder);
  write_soundings(folder);
  expect_case_error(flume_case_with("[bathymetry]\nkind = \"local_grid\"\nfile = \"flume.asc\"\n"),
                    {"bathymetry.depth_sign", "is missing"});
  expect_case_error(flume_case_with("[bathymetry]\nkind = \"local_grid\"\nfile = \"soundings.xyz\"\n"
                                    "depth_sign = \"positive_down\"\n"),
                    {"bathymetry.spacing_m", "is missing"});
  // Depths read as elevations: every cell is land, and the fix names the key and its value.
  expect_case_error(flume_case_with("[bathymetry]\nkind = \"local_grid\"\nfile = \"flume.asc\"\n"
                                    "depth_sign = \"positive_up\"\n"),
                    {"bathymetry.file", "every cell is land", "flume.asc", "set bathymetry.depth_sign to \"positive_down\""});
  expect_case_error(flume_case_with("[bathymetry]\nkind = \"local_grid\"\nfile = \"nowhere.asc\"\n"
                                    "depth_sign = \"positive_down\"\n"),
                    {"bathymetry.file", "does not exist"});
}

}  // namespace
}  // namespace nearshore::bake::testing
