// The bake's outputs for coastal modellers and the runtime (issues 14 and 19): the [output] section
// (frame codec and precision, recorded in the manifest and the estimate), and the wave statistics
// the bake accumulates at every solver step (wave_statistics.hpp): Hs of a sinusoid, the run-up of
// a solitary wave on a plane beach against the solver's own shoreline and Synolakis (1987), the
// GeoTIFF and the run-up line's GeoJSON read back with GDAL/OGR, the state carried through a checkpoint.
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_estimate.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/bake/wave_statistics.hpp"
#include "nearshore/boussinesq/initial_conditions.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::bake {
namespace {
namespace fs = std::filesystem;
using testing::current_scratch_folder;
using testing::expect_case_error;
using testing::scratch_folder;
using testing::small_flume_case;
using testing::write_text;
using boussinesq::BoussinesqSolver;
using boussinesq::start_solitary_wave;

// ---- [output] --------------------------------------------------------------------------------------

TEST(BakeOutput, DefaultsAreTheMeasuredCodecHalfChannelsAndNoStatistics) {
  const BakeCase c = read_bake_case(write_text(scratch_folder() / "case.toml", small_flume_case()));
  EXPECT_EQ(c.output.frame_encoding.compression, sequence::FrameEncoding{}.compression);
  EXPECT_EQ(c.output.frame_encoding.surface_elevation, sequence::Precision::kHalf);
  EXPECT_EQ(c.output.frame_encoding.flux, sequence::Precision::kHalf);
  EXPECT_FALSE(c.output.wave_statistics);  // on request only: 24 B per cell (bake_case.hpp)
}

TEST(BakeOutput, CodecAndPrecisionReachTheManifestAndTheEstimate) {
  const fs::path folder = scratch_folder();
  const BakeCase half = read_bake_case(write_text(folder / "half.toml", small_flume_case()));
  const BakeCase c = read_bake_case(write_text(
      folder / "case.toml", small_flume_case() + "[output]\nframe_compression = \"zips\"\n"
                                                 "frame_precision = { surface_elevation = \"float\" }\n"));
  EXPECT_EQ(c.output.frame_encoding.compression, sequence::Compression::kZips);
  EXPECT_EQ(c.output.frame_encoding.surface_elevation, sequence::Precision::kFloat);
  EXPECT_EQ(c.output.frame_encoding.flux, sequence::Precision::kHalf);
  // One float channel of four: 2 more bytes per cell in every frame of the estimate.
  const double cells = static_cast<double>(c.harbour.geometry.cell_count());
  EXPECT_DOUBLE_EQ(estimate_bake_resources(c).frame_bytes - estimate_bake_resources(half).frame_bytes, 2.0 * cells);

  ProgressBar::set_quiet(true);
  BakeOptions options;
  options.output_folder = folder / "out";
  run_bake(c, options);
  const sequence::SequenceReader reader(options.output_folder);
  EXPECT_EQ(reader.manifest().encoding.compression, sequence::Compression::kZips);
  EXPECT_EQ(reader.manifest().encoding.surface_elevation, sequence::Precision::kFloat);
  EXPECT_EQ(reader.manifest().encoding.breaking, sequence::Precision::kHalf);
  EXPECT_NO_THROW(reader.read_frame(reader.frame_count() - 1, sequence::ChannelSelection::all(), sequence::Verify::kYes));
  EXPECT_FALSE(fs::exists(options.output_folder / "wave_statistics.tif"));  // not asked for
}

TEST(BakeOutput, FloatForEveryChannelAndNoStatistics) {
  const fs::path folder = scratch_folder();
  const BakeCase c = read_bake_case(write_text(
      folder / "case.toml", small_flume_case() + "[output]\nframe_precision = \"float\"\nwave_statistics = false\n"));
  EXPECT_EQ(c.output.frame_encoding.flux, sequence::Precision::kFloat);
  EXPECT_EQ(c.output.frame_encoding.breaking, sequence::Precision::kFloat);
  ProgressBar::set_quiet(true);
  BakeOptions options;
  options.output_folder = folder / "out";
  const BakeSummary summary = run_bake(c, options);
  EXPECT_TRUE(summary.wave_statistics.is_null());
  EXPECT_FALSE(fs::exists(options.output_folder / "wave_statistics.tif"));
  EXPECT_EQ(sequence::SequenceReader(options.output_folder).manifest().encoding.flux, sequence::Precision::kFloat);
}

TEST(BakeOutput, UnknownValuesNameTheKeyAndEveryAcceptedName) {
  scratch_folder();
  std::vector<std::string> codecs = {"output.frame_compression", "\"zstd\""};
  for (sequence::Compression compression : sequence::all_compressions())
    codecs.emplace_back(sequence::compression_name(compression));
  expect_case_error(small_flume_case() + "[output]\nframe_compression = \"zstd\"\n", codecs);
  expect_case_error(small_flume_case() + "[output]\nframe_precision = \"double\"\n",
                    {"output.frame_precision", "\"double\"", "half, float"});
  expect_case_error(small_flume_case() + "[output]\nframe_precision = { eta = \"float\" }\n",
                    {"output.frame_precision.eta", "surface_elevation", "flux", "breaking"});
  expect_case_error(small_flume_case() + "[output]\nframe_codec = \"zip\"\n", {"output.frame_codec", "frame_compression"});
}

// ---- wave statistics --------------------------------------------------------------------------------

// A sinusoid eta = a sin(2 pi t / T) sampled at T/50 over ten whole periods: its variance is a^2 / 2
// (the discrete sum of sin^2 over whole periods is exactly N/2), so Hs = 4 sqrt(a^2 / 2) =
// 2 sqrt(2) a. The 1 % bound of the brief is far above the float rounding of eta (1e-7 relative).
TEST(WaveStatistics, SignificantHeightOfASinusoidIsTwoRootTwoTimesItsAmplitude) {
  GridGeometry geometry;
  geometry.columns = 5;
  geometry.rows = 4;
  geometry.spacing_m = 2.0;
  HarbourGrid harbour = HarbourGrid::open_water(geometry, 5.0f);
  harbour.still_water_depth_m(4, 3) = -1.0f;  // one land cell: no Hs there, never wet by 0.7 m waves
  harbour.land(4, 3) = 1;
  constexpr double kAmplitude_m = 0.7, kSetUp_m = 0.05;
  WaveStatistics statistics(harbour, 0.01);
  Raster<float> eta(geometry.columns, geometry.rows);
  for (int step = 0; step < 500; ++step) {
    const double phase = 2 * std::numbers::pi * step / 50.0;
    for (int row = 0; row < geometry.rows; ++row)
      for (int column = 0; column < geometry.columns; ++column)
        eta(column, row) = static_cast<float>(kSetUp_m + kAmplitude_m * std::sin(phase + 0.3 * column));
    statistics.add_step(eta);
  }
  const Raster<float> hs = statistics.significant_wave_height_m(), mean = statistics.mean_surface_elevation_m();
  const Raster<float> maximum = statistics.maximum_surface_elevation_m();
  for (int column = 0; column < 4; ++column) {
    EXPECT_NEAR(hs(column, 0), 2 * std::sqrt(2.0) * kAmplitude_m, 0.01 * 2 * std::sqrt(2.0) * kAmplitude_m);
    EXPECT_NEAR(mean(column, 0), kSetUp_m, 1e-6);
    // The highest sample of a sinusoid sampled at T/50 lies within 1 - cos(pi/50) = 0.2 % of its crest.
    EXPECT_NEAR(maximum(column, 0), kSetUp_m + kAmplitude_m, 0.002 * kAmplitude_m);
  }
  EXPECT_TRUE(std::isnan(hs(4, 3)));
  EXPECT_TRUE(std::isnan(maximum(4, 3)));
  EXPECT_FALSE(statistics.highest_runup().has_value());  // the land cell never got wet
}

// A checkpoint carries the statistics: continued after save/load they equal an uninterrupted run's.
TEST(WaveStatistics, StateSurvivesACheckpoint) {
  GridGeometry geometry;
  geometry.columns = 6;
  geometry.rows = 3;
  geometry.spacing_m = 1.0;
  const HarbourGrid harbour = HarbourGrid::open_water(geometry, 2.0f);
  WaveStatistics whole(harbour, 0.01), first(harbour, 0.01);
  Raster<float> eta(geometry.columns, geometry.rows);
  const auto fill = [&](int step) {
    for (std::size_t cell = 0; cell < eta.size(); ++cell) eta.values()[cell] = static_cast<float>(0.3 * std::cos(0.7 * step + cell));
  };
  std::stringstream stored;
  for (int step = 0; step < 40; ++step) {
    fill(step);
    whole.add_step(eta);
    first.add_step(eta);
    if (step == 19) first.save(stored);
  }
  WaveStatistics resumed(harbour, 0.01);
  resumed.load(stored, "checkpoint.bin");
  for (int step = 20; step < 40; ++step) {
    fill(step);
    resumed.add_step(eta);
  }
  EXPECT_EQ(resumed.step_count(), whole.step_count());
  EXPECT_EQ(resumed.significant_wave_height_m().values(), whole.significant_wave_height_m().values());
  EXPECT_EQ(resumed.maximum_surface_elevation_m().values(), whole.maximum_surface_elevation_m().values());
  std::stringstream truncated(stored.str().substr(0, 30));
  EXPECT_THROW(WaveStatistics(harbour, 0.01).load(truncated, "checkpoint.bin"), Error);
}

// Synolakis (1987) on his 1:19.85 beach (data/cases/synolakis.toml at d/10): the run-up the
// bake reports, the maximum of its envelope landward of the shoreline and the highest water level
// the solver's moving shoreline reached at any step (tracked here, independently, by driving the
// solver from the same case) are the same number; the GeoTIFF read back with GDAL holds it. Then
// physics: R/d between 10 % below the measured 0.0738 and 10 % above the non-breaking law
// R/d = 2.831 sqrt(cot b) (H/d)^(5/4) = 0.0861 (NTHMP's 10 % for laboratory benchmarks, OAR PMEL-135;
// docs/validation.md has the model at +6.8 % at d/20 from frames every 0.05 s).
TEST(WaveStatistics, RunupOnAPlaneBeachIsTheHighestShorelineTheSolverReached) {
  const fs::path folder = scratch_folder();
  const fs::path case_file = fs::path(NEARSHORE_SOURCE_DIR) / "data" / "cases" / "synolakis.toml";
  // At d/10 (0.03 m cells, three across) instead of the case file's d/20: four times fewer cell
  // updates, so the test takes seconds; docs/validation.md has R/d +6.8 % at d/20 from frames.
  nlohmann::json document = read_case_document(case_file);
  document["bathymetry"]["spacing_m"] = 0.03;
  document["bathymetry"]["width_m"] = 0.09;
  document["output"]["wave_statistics"] = true;
  const BakeCase c = parse_bake_case(document, case_file);
  constexpr double kDepth_m = 0.30, kHeightRatio = 0.0185, kCotBeta = 19.85;

  // 1. The solver's shoreline, step by step.
  BoussinesqSolver solver(c.harbour, c.solver, c.wave_maker);
  start_solitary_wave(solver, c.harbour, *c.solitary_wave);
  const long steps = std::lround(c.timing.duration_s / solver.time_step_s());
  const double dry_depth_m = c.solver.dry_depth_m;
  const Raster<float>& depth = c.harbour.still_water_depth_m;
  double shoreline_runup_m = -1, frames_runup_m = -1;
  const long per_frame = std::lround(c.timing.output_interval_s / solver.time_step_s());
  for (long step = 0; step <= steps; ++step) {
    if (step > 0) solver.step();
    const Raster<float>& eta = solver.surface_elevation_m();
    for (std::size_t cell = 0; cell < eta.size(); ++cell)
      if (depth.values()[cell] <= 0 && depth.values()[cell] + eta.values()[cell] > dry_depth_m) {
        shoreline_runup_m = std::max(shoreline_runup_m, double(eta.values()[cell]));
        if (step % per_frame == 0) frames_runup_m = std::max(frames_runup_m, double(eta.values()[cell]));
      }
  }
  ASSERT_GT(shoreline_runup_m, 0.0);

  // 2. The bake's statistics and its GeoTIFF.
  ProgressBar::set_quiet(true);
  BakeOptions options;
  options.output_folder = folder / "out";
  const BakeSummary summary = run_bake(c, options);
  ASSERT_TRUE(summary.wave_statistics.contains("runup"));
  const double bake_runup_m = summary.wave_statistics["runup"]["water_level_m"].get<double>();
  EXPECT_EQ(bake_runup_m, shoreline_runup_m);  // the same solver, the same steps: the same float
  EXPECT_GE(bake_runup_m, frames_runup_m);     // frames are a subset of the steps
  EXPECT_LT(summary.wave_statistics["runup"]["ground_elevation_m"].get<double>(), bake_runup_m);

  GDALAllRegister();
  GDALDataset* tiff = static_cast<GDALDataset*>(GDALOpen((options.output_folder / "wave_statistics.tif").c_str(), GA_ReadOnly));
  ASSERT_NE(tiff, nullptr);
  const GridGeometry& g = c.harbour.geometry;
  ASSERT_EQ(tiff->GetRasterCount(), 4);
  ASSERT_EQ(tiff->GetRasterXSize(), g.columns);
  double transform[6];
  ASSERT_EQ(tiff->GetGeoTransform(transform), CE_None);
  EXPECT_DOUBLE_EQ(transform[0], g.origin_x_m);
  EXPECT_DOUBLE_EQ(transform[3], g.origin_y_m + g.height_m());
  EXPECT_DOUBLE_EQ(transform[5], -g.spacing_y_m());
  std::vector<float> envelope(g.cell_count()), line(g.cell_count()), hs(g.cell_count());
  ASSERT_EQ(tiff->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, g.columns, g.rows, envelope.data(), g.columns, g.rows, GDT_Float32, 0, 0), CE_None);
  ASSERT_EQ(tiff->GetRasterBand(2)->RasterIO(GF_Read, 0, 0, g.columns, g.rows, hs.data(), g.columns, g.rows, GDT_Float32, 0, 0), CE_None);
  ASSERT_EQ(tiff->GetRasterBand(4)->RasterIO(GF_Read, 0, 0, g.columns, g.rows, line.data(), g.columns, g.rows, GDT_Float32, 0, 0), CE_None);
  const double no_data = tiff->GetRasterBand(1)->GetNoDataValue();
  EXPECT_EQ(no_data, -9999.0);
  double envelope_max_on_land_m = -1, line_max_m = -1;
  int line_cells = 0;
  for (int line_index = 0; line_index < g.rows; ++line_index)  // GeoTIFF line 0 is the northern row
    for (int column = 0; column < g.columns; ++column) {
      const std::size_t k = static_cast<std::size_t>(line_index) * g.columns + column;
      const float d = depth(column, g.rows - 1 - line_index);
      if (d <= 0 && envelope[k] != no_data) envelope_max_on_land_m = std::max(envelope_max_on_land_m, double(envelope[k]));
      if (line[k] != no_data) {
        ++line_cells;
        line_max_m = std::max(line_max_m, double(line[k]));
      }
    }
  GDALClose(tiff);
  EXPECT_EQ(envelope_max_on_land_m, shoreline_runup_m);
  // The flume is a 1-D beach, a few cells across: the front is one cell in each row at its furthest
  // reach. The water there is at most R, and within one cell's rise of the beach (dx / cot b) of it:
  // the thin film at the tip may peak one cell seaward of the front (it does at d/10, by 0.1 mm).
  EXPECT_EQ(line_cells, g.rows);
  EXPECT_LE(line_max_m, shoreline_runup_m);
  EXPECT_NEAR(line_max_m, shoreline_runup_m, g.spacing_x_m() / kCotBeta);

  // The run-up line as lines (wave_statistics_runup.geojson, read back with OGR): one open line
  // across the flume whose vertices are the band's cells at their centres (the tif's georeference)
  // with z = the band's level, so its highest z is the band's highest, and R at most one cell's rise
  // (dx / cot b) above it, as for the band (at d/10 the film peaks 0.1 mm seaward of the front; at the
  // case's d/20 the line's highest z is R itself, docs/formats/wave-statistics.md). Exact comparisons:
  // a float written with 15 significant figures reads back as the same float.
  ASSERT_EQ(summary.wave_statistics.value("runup_line_file", ""), (options.output_folder / "wave_statistics_runup.geojson").string());
  GDALDatasetUniquePtr geojson(
      GDALDataset::Open((options.output_folder / "wave_statistics_runup.geojson").c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  ASSERT_NE(geojson, nullptr);
  ASSERT_EQ(geojson->GetLayerCount(), 1);
  OGRLayer* layer = geojson->GetLayer(0);
  // A flume in local metres: no "crs" member (GDAL's reader then assumes WGS 84; the description says
  // local metres).
  EXPECT_FALSE(nlohmann::json::parse(std::ifstream(options.output_folder / "wave_statistics_runup.geojson")).contains("crs"));
  ASSERT_EQ(layer->GetFeatureCount(), 1);
  const OGRFeatureUniquePtr feature(layer->GetNextFeature());
  const OGRLineString* runup_line = feature->GetGeometryRef()->toLineString();
  ASSERT_EQ(runup_line->getNumPoints(), g.rows);
  double vertices_max_m = -1;
  for (const OGRPoint& vertex : *runup_line) {
    const int column = static_cast<int>(std::floor((vertex.getX() - g.origin_x_m) / g.spacing_x_m()));
    const int row = static_cast<int>(std::floor((vertex.getY() - g.origin_y_m) / g.spacing_y_m()));
    ASSERT_TRUE(column >= 0 && column < g.columns && row >= 0 && row < g.rows);
    EXPECT_NEAR(vertex.getX(), g.cell_centre_x_m(column), 1e-9);
    EXPECT_NEAR(vertex.getY(), g.cell_centre_y_m(row), 1e-9);
    const float band_level = line[static_cast<std::size_t>(g.rows - 1 - row) * g.columns + column];
    ASSERT_NE(band_level, no_data) << "a vertex off the band's cells at column " << column << ", row " << row;
    EXPECT_EQ(static_cast<float>(vertex.getZ()), band_level);
    vertices_max_m = std::max(vertices_max_m, vertex.getZ());
  }
  EXPECT_EQ(static_cast<float>(vertices_max_m), static_cast<float>(line_max_m));
  EXPECT_EQ(static_cast<float>(feature->GetFieldAsDouble("water_level_max_m")), static_cast<float>(line_max_m));
  EXPECT_EQ(feature->GetFieldAsInteger("cells"), g.rows);  // one per row: every band cell is a vertex
  EXPECT_NEAR(vertices_max_m, shoreline_runup_m, g.spacing_x_m() / kCotBeta);

  // 3. Physics.
  const double runup_ratio = shoreline_runup_m / kDepth_m;
  const double law = 2.831 * std::sqrt(kCotBeta) * std::pow(kHeightRatio, 1.25);
  EXPECT_NEAR(law, 0.0861, 0.0005);
  EXPECT_GT(runup_ratio, 0.9 * 0.0738);
  EXPECT_LT(runup_ratio, 1.1 * law);
  std::printf("Synolakis H/d = %.4f at d/10: R/d every step %.4f, every frame %.4f, law %.4f, measured 0.0738\n", kHeightRatio,
              runup_ratio, frames_runup_m / kDepth_m, law);
}

}  // namespace
}  // namespace nearshore::bake
