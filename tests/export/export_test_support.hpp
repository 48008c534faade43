#pragma once
// The small sequence every export test reads: a linear wave travelling east over a 10 m deep
// basin in UTM zone 51N (24 x 16 cells of 10 m), its northern three rows and one cell of the
// south-west corner land (the frames hold the terrain height there, 2 m, as the solver's frames
// do), a breaking indicator of 1 in the two western columns every other frame. Written with the
// real sequence writer (float channels, so the analytic checks are not limited by half rounding).
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/sequence/sequence_writer.hpp"

namespace nearshore::exports::testing {

namespace fs = std::filesystem;

/// The current test's scratch folder, emptied.
inline fs::path scratch_folder(const std::string& suffix = {}) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path folder = fs::path(NEARSHORE_BINARY_DIR) / "tests" / "export" / "scratch" /
                          (std::string(info->test_suite_name()) + "." + info->name() + suffix);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

struct TestWave {
  static constexpr int kColumns = 24, kRows = 16, kLandRows = 3;
  static constexpr double kSpacing_m = 10.0, kDepth_m = 10.0, kTerrainHeight_m = 2.0;
  static constexpr double kAmplitude_m = 0.1, kPeriod_s = 8.0, kWavelength_m = 80.0;
  static constexpr int kFramesPerPeriod = 20, kFrames = 60;  // three periods
  static constexpr double kFrameInterval_s = kPeriod_s / kFramesPerPeriod, kFirstFrameTime_s = 100.0;
  static constexpr double kOriginX_m = 386000.0, kOriginY_m = 4306000.0;  // UTM 51N, near Dalian
  static constexpr double k_rad_m = 2.0 * std::numbers::pi / kWavelength_m;
  static constexpr double omega_rad_s = 2.0 * std::numbers::pi / kPeriod_s;

  /// Square cells of kSpacing_m, or rectangular ones kSpacing_m east by `spacing_y_m` north.
  static GridGeometry geometry(double spacing_y_m = kSpacing_m) {
    GridGeometry g;
    g.columns = kColumns;
    g.rows = kRows;
    g.set_spacing(kSpacing_m, spacing_y_m);
    g.origin_x_m = kOriginX_m;
    g.origin_y_m = kOriginY_m;
    g.projection = {{"kind", "utm"}, {"zone", 51}, {"north", true}, {"datum", "WGS84"}};
    OGRSpatialReference crs;
    crs.importFromEPSG(32651);
    char* wkt = nullptr;
    crs.exportToWkt(&wkt);
    g.crs_wkt = wkt;
    CPLFree(wkt);
    return g;
  }
  static bool is_land(int column, int row) { return row >= kRows - kLandRows || (column == 0 && row == 0); }
  /// eta of the wave at the centre of (column, row) at simulated time t (the bake's clock).
  static double elevation_m(int column, int row, double time_s) {
    (void)row;
    const double x = (column + 0.5) * kSpacing_m;
    return kAmplitude_m * std::cos(k_rad_m * x - omega_rad_s * time_s);
  }
  static double frame_time_s(int index) { return kFirstFrameTime_s + index * kFrameInterval_s; }
  static bool breaking(int column, int index) { return column < 2 && index % 2 == 0; }

  /// Writes the sequence into `folder` and returns it.
  static fs::path write(const fs::path& folder, double spacing_y_m = kSpacing_m) {
    ProgressBar::set_quiet(true);
    const GridGeometry g = geometry(spacing_y_m);
    HarbourGrid harbour = HarbourGrid::open_water(g, static_cast<float>(kDepth_m));
    for (int row = 0; row < kRows; ++row)
      for (int column = 0; column < kColumns; ++column)
        if (is_land(column, row)) {
          harbour.land(column, row) = 1;
          harbour.still_water_depth_m(column, row) = static_cast<float>(-kTerrainHeight_m);
        }
    sequence::SequenceDescription description;
    description.frame_interval_s = kFrameInterval_s;
    description.first_frame_time_s = kFirstFrameTime_s;
    description.seed = 3;
    description.wave_conditions = {{"kind", "one linear wave for the export tests"}};
    description.encoding = {sequence::Compression::kNone, sequence::Precision::kFloat, sequence::Precision::kFloat,
                            sequence::Precision::kFloat};
    sequence::SequenceWriter writer(folder, harbour, description);
    Raster<float> eta(kColumns, kRows), p(kColumns, kRows), q(kColumns, kRows, 0.0f), foam(kColumns, kRows);
    for (int index = 0; index < kFrames; ++index) {
      for (int row = 0; row < kRows; ++row)
        for (int column = 0; column < kColumns; ++column) {
          const bool land = is_land(column, row);
          const double e = elevation_m(column, row, frame_time_s(index));
          // The flux of a progressive linear wave, P = c eta with c = omega / k (d eta/dt + dP/dx = 0).
          eta(column, row) = static_cast<float>(land ? kTerrainHeight_m : e);
          p(column, row) = static_cast<float>(land ? 0.0 : omega_rad_s / k_rad_m * e);
          foam(column, row) = breaking(column, index) && !land ? 1.0f : 0.0f;
        }
      writer.write_frame(index, {&eta, &p, &q, &foam});
    }
    writer.finish(kFrames);
    return folder;
  }
};

}  // namespace nearshore::exports::testing
