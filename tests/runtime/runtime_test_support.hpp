#pragma once
// Shared by the runtime tests and the soak: sequences of linear waves written with the real
// sequence writer, loops.json tables written with the real loops writer, and scratch folders.
#include <cmath>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nearshore/sequence/checksum.hpp"
#include "nearshore/sequence/loops_file.hpp"
#include "nearshore/sequence/sequence_format.hpp"
#include "nearshore/sequence/sequence_writer.hpp"
#include "nearshore/sequence/library_index.hpp"

namespace nearshore::runtime::testing {

namespace fs = std::filesystem;

/// The current test's scratch folder, emptied.
inline fs::path scratch_folder(const std::string& suffix = {}) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path folder = fs::path(NEARSHORE_BINARY_DIR) / "tests" / "runtime" / "scratch" /
                          (std::string(info->test_suite_name()) + "." + info->name() + suffix);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

/// One linear wave a cos(k . x - w t + phi) (site frame, m, s).
struct PlaneWave {
  double amplitude_m = 0.0, wavenumber_x_rad_m = 0.0, wavenumber_y_rad_m = 0.0, angular_frequency_rad_s = 0.0,
         phase_rad = 0.0;
};

inline GridGeometry wave_geometry(int columns, int rows, double spacing_m) {
  GridGeometry geometry;
  geometry.columns = columns;
  geometry.rows = rows;
  geometry.spacing_m = spacing_m;
  geometry.origin_x_m = 386000.0;
  geometry.origin_y_m = 4306000.0;
  geometry.projection = {{"kind", "utm"}, {"zone", 51}, {"north", true}};
  return geometry;
}

/// eta of `waves` at site point (x, y) and time t.
inline double wave_elevation_m(const std::vector<PlaneWave>& waves, double x_m, double y_m, double t_s) {
  double eta = 0.0;
  for (const PlaneWave& w : waves)
    eta += w.amplitude_m * std::cos(w.wavenumber_x_rad_m * x_m + w.wavenumber_y_rad_m * y_m -
                                    w.angular_frequency_rad_s * t_s + w.phase_rad);
  return eta;
}

/// A sequence of `frames` frames of linear waves over open water `depth_m` deep: eta as above at
/// cell centres, fluxes (P, Q) = (w / |k|^2) k eta_wave (the flux that carries the wave's volume:
/// d eta / dt + div(P, Q) = 0), breaking 0. Frame n is at first_frame_time_s + n frame_interval_s.
inline void write_wave_sequence(const fs::path& folder, const GridGeometry& geometry, const std::vector<PlaneWave>& waves,
                                int frames, double frame_interval_s, double first_frame_time_s = 0.0,
                                float depth_m = 10.0f) {
  sequence::SequenceDescription description;
  description.frame_interval_s = frame_interval_s;
  description.first_frame_time_s = first_frame_time_s;
  description.seed = 7;
  description.wave_conditions = {{"kind", "synthetic linear waves"}, {"components", waves.size()}};
  sequence::SequenceWriter writer(folder, HarbourGrid::open_water(geometry, depth_m), description);
  Raster<float> eta(geometry.columns, geometry.rows), p(geometry.columns, geometry.rows),
      q(geometry.columns, geometry.rows), breaking(geometry.columns, geometry.rows, 0.0f);
  for (int n = 0; n < frames; ++n) {
    const double t = first_frame_time_s + n * frame_interval_s;
    for (int row = 0; row < geometry.rows; ++row)
      for (int column = 0; column < geometry.columns; ++column) {
        const double x = (column + 0.5) * geometry.spacing_m, y = (row + 0.5) * geometry.spacing_m;
        double e = 0.0, fx = 0.0, fy = 0.0;
        for (const PlaneWave& w : waves) {
          const double c = w.amplitude_m * std::cos(w.wavenumber_x_rad_m * x + w.wavenumber_y_rad_m * y -
                                                    w.angular_frequency_rad_s * t + w.phase_rad);
          const double k2 = w.wavenumber_x_rad_m * w.wavenumber_x_rad_m + w.wavenumber_y_rad_m * w.wavenumber_y_rad_m;
          e += c;
          fx += w.angular_frequency_rad_s * w.wavenumber_x_rad_m / k2 * c;
          fy += w.angular_frequency_rad_s * w.wavenumber_y_rad_m / k2 * c;
        }
        eta(column, row) = static_cast<float>(e);
        p(column, row) = static_cast<float>(fx);
        q(column, row) = static_cast<float>(fy);
      }
    writer.write_frame(n, {&eta, &p, &q, &breaking});
  }
  writer.finish(frames);
}

/// A loops.json for the sequence in `folder` (its manifest checksum and frame count): every frame
/// but the last has its natural successor, with probability 1 minus the jumps' out of it; `jumps`
/// (from, to, probability, crossfade frames) are added; the walk starts at `start_frame`.
inline sequence::LoopsFile tables_for(const fs::path& folder) {
  const std::string manifest = sequence::read_file_bytes(folder / "manifest.json");
  sequence::LoopsFile tables;
  tables.sequence_manifest_checksum = sequence::checksum_text(std::as_bytes(std::span(manifest.data(), manifest.size())));
  const sequence::SequenceManifest parsed = sequence::parse_manifest(manifest, "manifest.json");
  tables.report.frame_count = parsed.frame_count;
  tables.report.frame_interval_s = parsed.frame_interval_s;
  return tables;
}

struct Jump {
  int from = 0, to = 0;
  double probability = 0.0;
  int crossfade_frames = 0;
};

inline sequence::LoopsFile walk_tables_for(const fs::path& folder, const std::vector<Jump>& jumps, int start_frame,
                                           std::uint64_t seed) {
  sequence::LoopsFile tables = tables_for(folder);
  const int n = tables.report.frame_count;
  for (int from = 0; from < n; ++from) {
    double jump_probability = 0.0;
    for (const Jump& j : jumps)
      if (j.from == from) jump_probability += j.probability;
    if (from + 1 < n)
      tables.transitions.push_back({.from = from, .to = from + 1, .probability = 1.0 - jump_probability});
    for (const Jump& j : jumps)
      if (j.from == from)
        tables.transitions.push_back({.from = j.from,
                                      .to = j.to,
                                      .probability = j.probability,
                                      .cost = 0.1,
                                      .future_cost = 0.2,
                                      .crossfade_frames = j.crossfade_frames});
  }
  tables.random_walk = {.start_frame = start_frame, .seed = seed};
  tables.report.graph.first_playable_frame = start_frame;
  return tables;
}


/// A sea-state library of two "baked" states written as a library run would leave them: states/dir0
/// (a 0.4 m, 5 s wave travelling east) and states/dir90 (a 0.7 m, 6 s wave travelling north), 16
/// frames 0.5 s apart over 24 x 20 cells of 5 m, and library.json indexing them on a direction axis.
inline const std::vector<PlaneWave> kLibraryFromWest = {{0.4, 2 * 3.141592653589793 / 30.0, 0.0, 2 * 3.141592653589793 / 5.0, 0.0}};
inline const std::vector<PlaneWave> kLibraryFromSouth = {{0.7, 0.0, 2 * 3.141592653589793 / 40.0, 2 * 3.141592653589793 / 6.0, 1.0}};
inline void write_two_state_library(const fs::path& folder) {
  const GridGeometry geometry = wave_geometry(24, 20, 5.0);
  write_wave_sequence(folder / "states" / "dir0", geometry, kLibraryFromWest, 16, 0.5);
  write_wave_sequence(folder / "states" / "dir90", geometry, kLibraryFromSouth, 16, 0.5);
  sequence::LibraryIndex index;
  index.title = "two directions";
  index.library_file = "test.toml";
  index.base_case = "test-case.toml";
  index.axes.push_back({sequence::SeaQuantity::kDirection, {0.0, 90.0}, {}});
  for (auto [id, direction] : {std::pair{"dir0", 0.0}, std::pair{"dir90", 90.0}}) {
    sequence::LibraryIndex::State state;
    state.id = id;
    state.conditions.direction_deg = direction;
    state.status = sequence::LibraryStateStatus::kBaked;
    state.sequence = std::string("states/") + id;
    state.case_file = std::string("cases/") + id + ".json";
    const std::string manifest = sequence::read_file_bytes(folder / state.sequence / "manifest.json");
    state.manifest_checksum = sequence::checksum_text(std::as_bytes(std::span(manifest.data(), manifest.size())));
    state.loops_checksum = "xxh64:0000000000000000";
    index.states.push_back(state);
  }
  sequence::write_library_index(folder, index);
}

}  // namespace nearshore::runtime::testing
