#include "nearshore/bench/play_bench_sequence.hpp"

#include <cstdio>
#include <numbers>

#include <fmt/format.h>

#include "nearshore/core/raster.hpp"
#include "nearshore/loops/synthetic_sea.hpp"

namespace nearshore::bench {

std::filesystem::path play_bench_sequence(const PlayBenchSequenceOptions& options) {
  namespace fs = std::filesystem;
  const fs::path folder = options.work_folder / fmt::format("sea_{}", options.size_cells);
  if (fs::exists(folder / "manifest.json")) return folder;
  fs::remove_all(folder);
  GridGeometry geometry;
  geometry.columns = geometry.rows = options.size_cells;
  geometry.spacing_m = 2.0;
  std::fprintf(stderr, "writing a %d x %d synthetic sequence of %d frames to %s\n", options.size_cells, options.size_cells,
               options.frames, folder.c_str());
  loops::write_sea_sequence(folder, loops::irregular_sea(8.0, 24, 1.5, 20.0, 0.5 * std::numbers::pi, 3), geometry,
                            options.frames, 0.5, 0.0);
  return folder;
}

}  // namespace nearshore::bench
