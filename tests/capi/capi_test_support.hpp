#pragma once
// Shared by the C API tests: a small basin written as a real sequence (sequence::SequenceWriter,
// exported by libnearshore.so too) and a sea opened on it with a calm deep water.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "nearshore.h"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/sequence/sequence_writer.hpp"

namespace nearshore::capi_test {
namespace fs = std::filesystem;

constexpr double kAmplitudeM = 0.5, kWavelengthM = 40.0, kPeriodS = 6.0, kSpacingM = 4.0;
constexpr int kColumns = 40, kRows = 30, kFrames = 12;
constexpr double kFrameIntervalS = 0.5;

// This test process's own folder under the system's temporary folder, for every file the C API
// tests write (not the folder the test was started from: from the repository's root they were
// left in the source tree); removed when the process exits.
inline const fs::path& scratch_folder() {
  static const fs::path folder = [] {
    const fs::path made = fs::temp_directory_path() / ("nearshore-capi-tests-" + std::to_string(::getpid()));
    fs::create_directories(made);
    return made;
  }();
  // Registered after `folder` is made, so at exit it runs before `folder`'s destructor.
  static const bool removed_at_exit = std::atexit([] {
                                        std::error_code ignored;
                                        fs::remove_all(scratch_folder(), ignored);
                                      }) == 0;
  (void)removed_at_exit;
  return folder;
}

inline double analytic_eta(double x_m, double t_s, double amplitude_m = kAmplitudeM) {
  return amplitude_m * std::cos(2 * std::numbers::pi * (x_m / kWavelengthM - t_s / kPeriodS));
}

// A 160 m x 120 m basin of 10 m water in UTM zone 51N, a plane wave of `amplitude_m` travelling
// east, float frames; the eastern `land_columns` columns are land 2 m above still water.
inline fs::path write_sequence(const std::string& name, double amplitude_m = kAmplitudeM, int land_columns = 0) {
  const fs::path folder = scratch_folder() / ("capi_" + name);
  fs::remove_all(folder);
  nearshore::GridGeometry geometry;
  geometry.columns = kColumns;
  geometry.rows = kRows;
  geometry.spacing_m = kSpacingM;
  geometry.origin_x_m = 386000.0;
  geometry.origin_y_m = 4306400.0;
  geometry.projection = {{"kind", "utm"}, {"zone", 51}, {"north", true}, {"datum", "WGS84"}};
  nearshore::sequence::SequenceDescription description;
  description.frame_interval_s = kFrameIntervalS;
  description.encoding.surface_elevation = nearshore::sequence::Precision::kFloat;
  description.encoding.flux = nearshore::sequence::Precision::kFloat;
  nearshore::HarbourGrid harbour = nearshore::HarbourGrid::open_water(geometry, 10.f);
  for (int row = 0; row < kRows; ++row)
    for (int column = kColumns - land_columns; column < kColumns; ++column) {
      harbour.still_water_depth_m(column, row) = -2.f;
      harbour.land(column, row) = 1;
      harbour.coast_distance_m(column, row) = -kSpacingM * static_cast<float>(column - (kColumns - land_columns) + 1);
    }
  nearshore::sequence::SequenceWriter writer(folder, harbour, description);
  nearshore::Raster<float> eta(kColumns, kRows), flux(kColumns, kRows), zero(kColumns, kRows);
  for (int frame = 0; frame < kFrames; ++frame) {
    for (int row = 0; row < kRows; ++row)
      for (int column = 0; column < kColumns; ++column) {
        const bool on_land = column >= kColumns - land_columns;
        eta(column, row) = on_land ? 0.f : static_cast<float>(analytic_eta((column + 0.5) * kSpacingM, frame * kFrameIntervalS, amplitude_m));
        flux(column, row) = static_cast<float>(kWavelengthM / kPeriodS * eta(column, row));  // c eta
      }
    writer.write_frame(frame, {&eta, &flux, &zero, &zero});
  }
  writer.finish(kFrames);
  return folder;
}

/// The sequence in `folder` in frame order, lockstep, with a Beaufort `beaufort_force` sea beyond
/// the harbour.
inline nearshore_sea* open_in_frame_order(const fs::path& folder, int beaufort_force) {
  nearshore_sea_options options;
  nearshore_sea_options_init(&options);
  options.plan = NEARSHORE_PLAN_FRAME_ORDER;
  options.beaufort_force = beaufort_force;
  // Every advance shows the planned frames (made on the calling thread when the decoder is behind
  // on a loaded machine), so the tests may assert NEARSHORE_OK from each advance.
  options.time_mode = NEARSHORE_TIME_LOCKSTEP;
  nearshore_sea* sea = nullptr;
  EXPECT_EQ(nearshore_sea_open(folder.c_str(), &options, &sea), NEARSHORE_OK) << nearshore_last_error();
  return sea;
}

/// A calm sea beyond the harbour: the queries see the frames alone.
inline nearshore_sea* open_calm(const fs::path& folder) { return open_in_frame_order(folder, 0); }

}  // namespace nearshore::capi_test
