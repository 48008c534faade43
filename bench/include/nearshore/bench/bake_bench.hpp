#pragma once
// `nearshore bench bake` (bake side): whole bakes as users run them (issue 15): real case files
// through run_bake() with their outputs (frames, gauges, checkpoints), each cut to a fixed number of
// time steps, at one thread and at every thread. Reports cell-updates/s per core from wall time and
// from CPU time, the load average seen, simulated seconds per wall second, the peak resident set and
// bytes per cell, and a roofline line: the bytes a step moves per cell (the bake's model of its
// solver, bake::streamed_bytes_per_cell_step) against this machine's memory bandwidth, measured here
// by a STREAM triad. docs/commands/bench.md ("bench bake") shows the output.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace nearshore::bench {

struct BakeBenchOptions {
  int steps = 200;          ///< time steps of the Berkhoff and demo harbour bakes
  int harbour_steps = 10;   ///< time steps of the 1000 x 900 harbour bake
  int triad_repeats = 10;   ///< passes of the STREAM triad; the fastest is reported
  std::filesystem::path cases_folder = "data/cases";  ///< holds berkhoff.toml and harbour.toml
  /// Generated grids and baked outputs; empty: a new folder in the system's temporary folder.
  std::filesystem::path scratch_folder;
  bool keep_scratch = false;
  bool skip_demo = false, skip_large = false;
  bool one_thread_only = false;  ///< not also at every thread
};

/// The STREAM triad a[i] = b[i] + s c[i] (McCalpin 1995) at `threads`.
struct TriadBandwidth {
  int threads = 0;
  double bytes_per_s = 0.0;  ///< STREAM's count: 24 bytes per element (2 reads, 1 write)
};

/// One timed bake.
struct BakeMeasurement {
  std::string name;
  int threads = 0, columns = 0, rows = 0, steps = 0, frames = 0;
  double time_step_s = 0.0, wall_s = 0.0, cpu_s = 0.0, output_wall_s = 0.0, load_before = 0.0, load_after = 0.0;
  double updates_per_s_per_core = 0.0, updates_per_cpu_s = 0.0, simulated_s_per_wall_s = 0.0;
  double peak_resident_bytes = 0.0, bytes_per_cell = 0.0, streamed_bytes_per_cell_step = 0.0;
  /// What the model says the bake streamed per second: bytes per cell and step x updates per second.
  double streamed_bytes_per_s() const { return streamed_bytes_per_cell_step * updates_per_s_per_core * threads; }
};

struct BakeBenchResult {
  std::string date;  ///< "2026-11-30 13:01 UTC"
  int hardware_threads = 0;
  std::vector<TriadBandwidth> bandwidth;  ///< one thread, then every thread
  std::vector<BakeMeasurement> bakes;
  /// The triad's bandwidth at `threads` (the one-thread figure where it was not measured there).
  double triad_bytes_per_s(int threads) const;
};

BakeBenchResult run_bake_bench(const BakeBenchOptions& options);

nlohmann::json bake_bench_json(const BakeBenchResult& result);
std::string bake_bench_text(const BakeBenchResult& result);

}  // namespace nearshore::bench
