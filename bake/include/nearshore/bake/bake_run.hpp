#pragma once
// The bake run: a BakeCase through the Boussinesq solver into a sequence folder (seed 003 section
// 3: solve, keep every frame's height and flux fields). In the output folder:
//   the frame sequence (sequence::SequenceWriter: frames every output interval after spin-up, the
//   manifest written LAST by finish()), gauges.csv, gauge_fluxes.csv and gauge_statistics.csv
//   (bake_gauges.hpp), wave_statistics.tif (the
//   envelope, Hs, mean level and run-up line over every step after spin-up; wave_statistics.hpp)
//   with wave_statistics_runup.geojson (the run-up line as lines; runup_line.hpp), and
//   checkpoint.bin while the run is under way (removed when it completes).
// Checkpoints hold the solver state, the gauge records and a fingerprint of the case; a run
// resumed from one writes byte-identical frames and gauges to an uninterrupted run.
#include <cstdint>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "nearshore/bake/bake_case.hpp"

namespace nearshore::bake {

struct BakeOptions {
  std::filesystem::path output_folder;
  bool resume = false;  ///< continue from output_folder/checkpoint.bin (which must exist and match the case)
  /// Replace what output_folder holds: a complete sequence (manifest.json) or the checkpoint of an
  /// unfinished bake. Without it (and without resume) run_bake refuses such a folder untouched.
  bool overwrite = false;
  /// Bake even when the estimate (bake_estimate.hpp) exceeds the memory this machine has available
  /// or the free disk of output_folder.
  bool allow_over_budget = false;
};

struct BakeSummary {
  long long cells = 0;              ///< grid cells
  long total_steps = 0;             ///< steps of the whole bake
  long steps_this_run = 0;          ///< steps computed by this call (fewer when resumed)
  double time_step_s = 0.0;
  double wall_time_s = 0.0;         ///< of this call
  double cell_updates_per_s = 0.0;  ///< cells * steps_this_run / wall time of the run loop (outputs included)
  double output_wall_time_s = 0.0;  ///< of that, the wall time spent writing frames, gauges.csv and checkpoints
  int frames = 0;
  double first_frame_time_s = 0.0;
  double frame_interval_s = 0.0;
  double resumed_from_s = -1.0;     ///< simulated time of the checkpoint resumed from, -1 if not resumed
  std::uint64_t seed = 0;
  double loop_period_s = 0.0;
  std::filesystem::path output_folder, gauges_csv;
  /// gauge_statistics.csv (bake_gauges.hpp); empty when the case has no gauges or they hold fewer
  /// than 16 samples after the spin-up.
  std::filesystem::path gauge_statistics_csv;
  double estimated_memory_bytes = 0.0;  ///< what the bake expected to need (bake_estimate.hpp)
  double estimated_disk_bytes = 0.0;
  double peak_resident_bytes = 0.0;     ///< the whole process's peak resident set (getrusage), its code and libraries included
  /// What the solver's grid-sized arrays hold at the end of the run (BoussinesqSolver::memory_bytes():
  /// state, work, static coefficients, sponge lists, output rasters, per-thread sweep scratch), bytes.
  double solver_memory_bytes = 0.0;
  /// null unless the case has [deep_water]: cascades, grid size, Hs, coefficient bytes, and when the
  /// field drives the wave maker its component count, the variance fraction it carries, the carried
  /// Hs and the blending zone (deep_water_coupling.hpp); the tile set when baked.
  nlohmann::json deep_water;
  /// null unless [output] wave_statistics (the default): the GeoTIFF's path, the steps it maps and,
  /// when water went above the still-water shoreline, the run-up R (`runup`: water_level_m,
  /// ground_elevation_m, x_m, y_m; wave_statistics.hpp).
  nlohmann::json wave_statistics;
  nlohmann::json to_json() const;
};

/// Runs the bake. Shows a ProgressBar (simulated time, wall time, ETA) on stderr.
/// Before it allocates the solver or touches the folder it checks the whole plan and refuses (a
/// nearshore::Error naming the case file or the folder, the numbers and the fix):
///   - a step or frame count no bake can hold (a mistyped duration), or a plan with no frame;
///   - more memory or disk than the machine has (estimate_bake_resources), unless allow_over_budget;
///   - a folder another process writes into (it holds the folder's lock, folder_lock.hpp: named by
///     PID and command), held by run_bake until it returns;
///   - a folder holding a complete sequence or a checkpoint, unless overwrite (or resume).
/// It then removes the temporary files that killed writers left in the folder.
/// Throws nearshore::Error for bad output folders, a checkpoint that does not match the case, a
/// write that fails (naming the file and the reason, e.g. a full disk), and when the solver
/// becomes unstable (naming time, cell, depth and what to change; the last good checkpoint is kept).
BakeSummary run_bake(const BakeCase& bake_case, const BakeOptions& options);

/// Path of the checkpoint in an output folder.
std::filesystem::path checkpoint_path(const std::filesystem::path& output_folder);

}  // namespace nearshore::bake
