#pragma once
// `nearshore bench loops` (bake side): distance-matrix throughput (frame pairs x cells per second)
// and frames decoded per second; or, with `compression`, the table of docs/formats/sequence.md (on a
// synthetic sea, or on the frames of a real bake). The measurements are loops/'s
// (nearshore/loops/benchmarks.hpp); this file runs them as the command does and renders the figures.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nearshore/loops/benchmarks.hpp"

namespace nearshore::bench {

struct LoopsBenchOptions {
  bool compression = false;  ///< the codec table instead of the distance matrix
  int size_cells = 1024, frames = 16;  ///< grid side and frames of the codec table
  int distance_size_cells = 256, distance_frames = 300;
  std::filesystem::path work_folder = "nearshore-bench-loops";  ///< scratch, removed afterwards
  std::filesystem::path sequence;  ///< codec table on this bake's frames instead of the synthetic sea
};

struct LoopsCompressionRow {
  std::string codec;
  loops::CompressionMeasurement measurement;
};

struct LoopsBenchResult {
  bool compression = false;
  // The codec table.
  std::string source;  ///< what the frames were
  int grid_columns = 0, grid_rows = 0, frames = 0;
  /// The player decodes one keyframe per frame interval of play (docs/runtime.md, "The engine"):
  /// "x real time" is frames decoded per CPU-second times the interval.
  double frame_interval_s = 0.0;
  std::vector<LoopsCompressionRow> codecs;
  // The distance matrix.
  int distance_size_cells = 0, distance_frames = 0;
  std::vector<loops::DistanceThroughput> distance_runs;  ///< at 1 and 2 threads
};

/// Called once the result's header fields are known, then after each row (a codec, a thread count)
/// is added: the table is printed as it is measured.
using LoopsBenchProgress = std::function<void(const LoopsBenchResult& so_far)>;

LoopsBenchResult run_loops_bench(const LoopsBenchOptions& options, const LoopsBenchProgress& progress = {});

nlohmann::json loops_bench_json(const LoopsBenchResult& result);
/// The table's header lines (before any row).
std::string loops_bench_text_header(const LoopsBenchResult& result);
/// The line of the result's last row (codec or thread count).
std::string loops_bench_text_last_row(const LoopsBenchResult& result);

}  // namespace nearshore::bench
