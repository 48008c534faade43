#include "nearshore/bench/deepwater_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "nearshore/bake/deep_water_tiles.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/process_usage.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/ocean/sea_state_beaufort.hpp"

namespace nearshore::bench {

DeepWaterBenchResult run_deep_water_bench(const DeepWaterBenchOptions& options) {
  const auto at_least_one = [](const char* parameter, int value) {
    if (value < 1) throw Error(parameter, fmt::format("= {}: needs at least 1", value), "use the default");
  };
  at_least_one("DeepWaterBenchOptions::frames", options.frames);
  at_least_one("DeepWaterBenchOptions::cascades", options.cascades);
  at_least_one("DeepWaterBenchOptions::sample_frames", options.sample_frames);
  if (!(options.frame_rate_hz > 0.0))
    throw Error("DeepWaterBenchOptions::frame_rate_hz", fmt::format("= {}: must be positive", options.frame_rate_hz),
                "use the default, 30");
  const ocean::BeaufortPreset preset = ocean::beaufort_preset(options.beaufort);
  if (!preset.spectrum)
    throw Error("DeepWaterBenchOptions::beaufort", "Beaufort 0 is a flat sea: there is nothing to synthesise",
                "use Beaufort 1 to 12");
  sequence::FrameEncoding encoding;
  encoding.compression = sequence::parse_compression(options.compression);
  const int threads = static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  const int frames_per_loop = static_cast<int>(std::lround(options.loop_period_s * options.frame_rate_hz));

  DeepWaterBenchResult result;
  result.options = options;
  for (int grid_size : options.grid_sizes) {
    ocean::DeepWaterSpecification spec;
    spec.spectrum = preset.spectrum;
    spec.grid_size = grid_size;
    spec.tile_lengths_m =
        ocean::cascade_tile_lengths_for_m(*preset.spectrum, grid_size, options.cascades, options.shortest_wavelength_m);
    spec.loop_period_s = options.loop_period_s;
    const auto build_start = std::chrono::steady_clock::now();
    ocean::DeepWaterField field(spec);
    const double build_s = seconds_since(build_start);

    std::vector<double> frame_s;
    {
      ProgressBar progress(fmt::format("synthesising {0} x {0}", grid_size), options.frames, "frames");
      for (int frame = 0; frame < options.frames; ++frame) {
        const auto start = std::chrono::steady_clock::now();
        field.synthesise(frame / options.frame_rate_hz);
        frame_s.push_back(seconds_since(start));
        progress.update(frame + 1);
      }
    }
    std::nth_element(frame_s.begin(), frame_s.begin() + frame_s.size() / 2, frame_s.end());
    const double median_frame_s = frame_s[frame_s.size() / 2];

    // Bytes of the baked tile set: a sample of frames per cascade, scaled to a minute.
    std::uintmax_t sample_bytes = 0;
    int sampled = 0;
    for (int cascade = 0; cascade < field.cascade_count(); ++cascade) {
      const std::filesystem::path folder = options.scratch_folder / fmt::format("n{}_c{}", grid_size, cascade);
      const bake::TileSetSummary summary =
          bake::write_deep_water_tile_set(field, cascade, frames_per_loop, folder, encoding, options.sample_frames);
      sample_bytes += summary.frame_bytes;
      sampled += summary.frame_count;
      std::filesystem::remove_all(folder);
    }
    DeepWaterBenchRun run;
    run.grid_size = grid_size;
    run.cascades = field.cascade_count();
    run.threads = threads;
    run.beaufort = options.beaufort;
    run.tile_lengths_m = spec.tile_lengths_m;
    run.build_s = build_s;
    run.synthesis_ms_per_frame = 1e3 * median_frame_s;
    run.tile_set_bytes_per_frame = static_cast<double>(sample_bytes) / sampled * field.cascade_count();
    run.tile_set_bytes_per_minute = run.tile_set_bytes_per_frame * options.frame_rate_hz * 60.0;
    run.tile_set_fps = options.frame_rate_hz;
    run.tile_set_compression = options.compression;
    result.runs.push_back(run);
  }
  std::filesystem::remove_all(options.scratch_folder);
  return result;
}

nlohmann::json deep_water_bench_json(const DeepWaterBenchResult& result) {
  nlohmann::json runs = nlohmann::json::array();
  for (const DeepWaterBenchRun& r : result.runs)
    runs.push_back({{"grid_size", r.grid_size},
                    {"cascades", r.cascades},
                    {"threads", r.threads},
                    {"beaufort", r.beaufort},
                    {"tile_lengths_m", r.tile_lengths_m},
                    {"build_s", r.build_s},
                    {"synthesis_ms_per_frame", r.synthesis_ms_per_frame},
                    {"tile_set_bytes_per_frame", r.tile_set_bytes_per_frame},
                    {"tile_set_bytes_per_minute", r.tile_set_bytes_per_minute},
                    {"tile_set_fps", r.tile_set_fps},
                    {"tile_set_compression", r.tile_set_compression}});
  return runs;
}

std::string deep_water_bench_text(const DeepWaterBenchResult& result) {
  std::string text = fmt::format("{:>6}  {:>8}  {:>7}  {:>8}  {:>14}  {:>16}  {:>18}\n", "N", "cascades", "threads",
                                 "build s", "synthesis ms", "tile bytes/frame", "tile MB/min loop");
  for (const DeepWaterBenchRun& r : result.runs)
    text += fmt::format("{:>6}  {:>8}  {:>7}  {:>8.2f}  {:>14.2f}  {:>16.0f}  {:>18.1f}\n", r.grid_size, r.cascades,
                        r.threads, r.build_s, r.synthesis_ms_per_frame, r.tile_set_bytes_per_frame,
                        r.tile_set_bytes_per_minute / 1e6);
  const DeepWaterBenchOptions& o = result.options;
  text += fmt::format("(Beaufort {}, tile set at {} fps, {} compression, half floats; synthesis = 8 channels "
                      "x {} cascades, median of {} frames)\n",
                      o.beaufort, o.frame_rate_hz, o.compression, o.cascades, o.frames);
  return text;
}

}  // namespace nearshore::bench
