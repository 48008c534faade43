#pragma once
// `nearshore bench library` (bake side): sea states baked per hour by `nearshore library` alone and
// under `mpirun -np 1` and `-np 2`, and the efficiency of each against the serial run
// (docs/library.md, "Scaling"). The workload is a small library of the generated demo harbour
// (coarse cells, a short regular swell): 8 states, 2 directions x 2 heights x 2 tides. Each run is a
// separate process of the command, which only its caller knows how to start: LibraryBenchLauncher.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace nearshore::bench {

struct LibraryBenchOptions {
  std::filesystem::path work_folder = "nearshore-bench-library";  ///< emptied first; removed afterwards unless keep_work_folder
  double spacing_m = 12.0;   ///< cell size of the demo harbour's grid
  double duration_s = 90.0;  ///< simulated time of each state's bake
  bool keep_work_folder = false;
  bool with_mpi = false;  ///< also the runs under MPI with 1 and 2 ranks
};

/// One run of the library: `library_file` into `output_folder` by `ranks` MPI ranks (0: one process
/// without MPI). Returns the JSON summary the library command prints (states_per_hour, wall_time_s,
/// actions.baked); throws nearshore::Error when the run fails.
using LibraryBenchLauncher = std::function<nlohmann::json(const std::filesystem::path& library_file,
                                                          const std::filesystem::path& output_folder, int ranks)>;

struct LibraryBenchRun {
  std::string label;  ///< "serial", "mpi1", "mpi2"
  int ranks = 0;
  int states_baked = 0;
  double wall_time_s = 0.0, states_per_hour = 0.0;
};

struct LibraryBenchResult {
  int states = 8;
  int grid_columns = 0, grid_rows = 0;
  double spacing_m = 0.0, duration_s = 0.0;
  bool with_mpi = false;
  std::vector<LibraryBenchRun> runs;  ///< serial first
  std::string load_average;           ///< /proc/loadavg at the end of the runs
  unsigned cores = 0;
  double efficiency_vs_serial(const LibraryBenchRun& run) const;
  double efficiency_per_rank(const LibraryBenchRun& run) const;
};

LibraryBenchResult run_library_bench(const LibraryBenchOptions& options, const LibraryBenchLauncher& launch);

nlohmann::json library_bench_json(const LibraryBenchResult& result);
std::string library_bench_text(const LibraryBenchResult& result);

}  // namespace nearshore::bench
