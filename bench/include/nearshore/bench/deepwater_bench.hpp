#pragma once
// `nearshore bench deepwater` (bake side: the tile set is the bake's, bake/deep_water_tiles.hpp):
// the FFT deep-water field (issue 5). For each grid size: the time to build the field (cell
// integrals of the spectrum), the synthesis time per frame of all cascades (the 8 runtime channels:
// height, displacement, slopes, Jacobian terms; median of `frames`), and what a baked tile set
// (sequence format, 4 channels) costs per minute of loop at `frame_rate_hz`.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace nearshore::bench {

struct DeepWaterBenchOptions {
  std::vector<int> grid_sizes = {256, 512};  ///< N of each measured N x N cascade lattice
  int cascades = 4;
  int frames = 20;  ///< frames timed per grid size (the median is reported)
  int beaufort = 6;  ///< Beaufort force of the preset sea (1-12)
  double shortest_wavelength_m = 0.1;  ///< resolved by the last cascade
  double loop_period_s = 120.0;
  double frame_rate_hz = 30.0;  ///< of the baked tile set
  int sample_frames = 8;        ///< tile-set frames written per cascade to measure bytes per frame
  std::string compression = "piz";  ///< the tile set's EXR compression (sequence::parse_compression)
  std::filesystem::path scratch_folder = "bench_deepwater_tiles";  ///< removed afterwards
};

struct DeepWaterBenchRun {
  int grid_size = 0, cascades = 0, threads = 0, beaufort = 0;
  std::vector<double> tile_lengths_m;
  double build_s = 0.0, synthesis_ms_per_frame = 0.0;
  double tile_set_bytes_per_frame = 0.0, tile_set_bytes_per_minute = 0.0;
  double tile_set_fps = 0.0;
  std::string tile_set_compression;
};

struct DeepWaterBenchResult {
  DeepWaterBenchOptions options;  ///< what was measured (the text's last line names it)
  std::vector<DeepWaterBenchRun> runs;  ///< one per grid size
};

/// Throws nearshore::Error naming DeepWaterBenchOptions' parameter at fault. Progress bars go to
/// stderr unless ProgressBar::set_quiet.
DeepWaterBenchResult run_deep_water_bench(const DeepWaterBenchOptions& options);

nlohmann::json deep_water_bench_json(const DeepWaterBenchResult& result);
std::string deep_water_bench_text(const DeepWaterBenchResult& result);

}  // namespace nearshore::bench
