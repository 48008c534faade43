#pragma once
// The sequence `nearshore bench play` measures when given none (bake side: loops/ writes it): a
// synthetic irregular linear sea (Tp 8 s, 24 components, Hs 1.5 m over 20 m, 2 m cells, a frame
// every 0.5 s) of size_cells x size_cells, written once into the work folder and kept for the next
// run. The measurement itself is runtime-side (play_bench.hpp, target nearshore_bench_runtime).
#include <filesystem>

namespace nearshore::bench {

struct PlayBenchSequenceOptions {
  std::filesystem::path work_folder = "nearshore-bench-play";  ///< kept for the next run
  int size_cells = 1024;
  int frames = 40;
};

/// The folder work_folder/sea_<size_cells>, written first (saying so on stderr) unless its manifest
/// is already there.
std::filesystem::path play_bench_sequence(const PlayBenchSequenceOptions& options);

}  // namespace nearshore::bench
