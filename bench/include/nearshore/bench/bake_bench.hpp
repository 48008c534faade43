#pragma once
// `nearshore bench bake` (bake side): whole bakes as users run them (issue 15): real case files
// through run_bake() with their outputs (frames, gauges, checkpoints), each cut to a fixed number of
// time steps, at one thread and at every thread. Reports cell-updates/s per core from wall time and
// from CPU time, the load average seen, simulated seconds per wall second, the peak resident set and
// bytes per cell, and a roofline line: the bytes a step moves per cell (the bake's model of its
// solver, bake::streamed_bytes_per_cell_step) against this machine's memory bandwidth, measured here
// by a STREAM triad. Each case runs twice: with its own solver settings (for the shipped cases the
// defaults: the fully nonlinear equations, two ADI passes) and in the seed configuration (the seed
// papers' weakly nonlinear equations, one ADI pass; issue 43), the same steps, so the table gives
// what the defaults' physics costs per update and per cell. docs/commands/bench.md ("bench bake")
// shows the output.
#include <filesystem>
#include <limits>
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
  /// Leave out the seed configuration's bakes (they add about a third to the run).
  bool skip_seed = false;
};

/// Which solver settings a bake ran with.
enum class BakeConfiguration {
  kCase,  ///< the case's own (for berkhoff.toml, harbour.toml and the 1000 x 900 harbour: the defaults)
  /// The seed papers' equations: the case's own with SolverParameters::equations = kWeaklyNonlinear
  /// and adi_passes = 1, nothing else changed (docs/solver.md, "Speed").
  kSeed,
};

/// The STREAM triad a[i] = b[i] + s c[i] (McCalpin 1995) at `threads`.
struct TriadBandwidth {
  int threads = 0;
  double bytes_per_s = 0.0;  ///< STREAM's count: 24 bytes per element (2 reads, 1 write)
};

/// One timed bake.
struct BakeMeasurement {
  std::string name;
  BakeConfiguration configuration = BakeConfiguration::kCase;
  /// "defaults" where the case's equations and ADI passes are the solver's defaults, else "case";
  /// "seed" for the seed configuration.
  std::string configuration_name;
  /// The solver's parameters as the bake recorded them (bake::solver_record_of): "equations" (absent:
  /// weakly nonlinear), "adi_passes" and the rest.
  nlohmann::json solver_record;
  int threads = 0, columns = 0, rows = 0, steps = 0, frames = 0;
  double time_step_s = 0.0, wall_s = 0.0, cpu_s = 0.0, output_wall_s = 0.0, load_before = 0.0, load_after = 0.0;
  double updates_per_s_per_core = 0.0, updates_per_cpu_s = 0.0, simulated_s_per_wall_s = 0.0;
  double peak_resident_bytes = 0.0, bytes_per_cell = 0.0, streamed_bytes_per_cell_step = 0.0;
  /// What the solver's arrays hold per cell (BoussinesqSolver::memory_bytes() / cells: state, work,
  /// static coefficients, sponge lists, output rasters, sweep scratch), bytes.
  double solver_bytes_per_cell = 0.0;
  /// Seed rows: the wall time per cell-update of the same case in its own configuration at the same
  /// threads over this one's (the case's updates/s/core over the seed's); NaN on the case's own rows
  /// and where that bake was not run.
  double case_to_seed_time_per_update = std::numeric_limits<double>::quiet_NaN();
  /// The same from CPU time (less sensitive to other processes).
  double case_to_seed_cpu_time_per_update = std::numeric_limits<double>::quiet_NaN();
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
