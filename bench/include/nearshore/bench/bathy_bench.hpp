#pragma once
// `nearshore bench bathy` (bake side): throughput of the gridding stage (issue 3): soundings
// triangulated per second (CGAL Delaunay, spatially sorted insertion) and cells interpolated per
// second (Sibson natural neighbours, rows in parallel with oneTBB) on a square grid, at one thread
// and at every thread oneTBB may use. docs/commands/bench.md ("bench bathy") shows the output.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace nearshore::bench {

struct BathyBenchOptions {
  int grid_cells = 2000;         ///< cells per side of the square grid (>= 2)
  std::size_t soundings = 200000;  ///< scattered soundings triangulated (>= 3; the square's 4 corners are added)
  double spacing_m = 10.0;       ///< cell size
};

/// One thread count's figures.
struct BathyBenchRun {
  int threads = 0;
  std::size_t soundings = 0;  ///< triangulated, corners included
  double triangulate_s = 0.0, soundings_per_s = 0.0;
  std::size_t cells = 0, cells_interpolated = 0;  ///< cells of the grid, and those given a finite depth
  double interpolate_s = 0.0, cells_per_s = 0.0;
};

struct BathyBenchResult {
  std::vector<BathyBenchRun> runs;  ///< one thread, then every thread (once where they are the same)
};

/// Progress bars go to stderr unless ProgressBar::set_quiet (core/progress.hpp).
BathyBenchResult run_bathy_bench(const BathyBenchOptions& options);

/// The array `nearshore bench bathy --json` prints.
nlohmann::json bathy_bench_json(const BathyBenchResult& result);
/// The table `nearshore bench bathy` prints, lines ending in '\n'.
std::string bathy_bench_text(const BathyBenchResult& result);

}  // namespace nearshore::bench
