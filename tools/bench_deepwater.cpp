// `nearshore bench deepwater`: the FFT deep-water field (issue 5). For each grid size: the time to
// build the field (cell integrals of the spectrum), the synthesis time per frame of all cascades
// (the 8 runtime channels: height, displacement, slopes, Jacobian terms; median of --frames), and
// what a baked tile set (sequence format, 4 channels) costs per minute of loop at --fps.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "command_support.hpp"
#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/bake/deep_water_tiles.hpp"
#include "nearshore/ocean/sea_state_beaufort.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::tools {

void add_bench_deepwater(CLI::App& bench) {
  struct Options {
    std::vector<int> grid_sizes = {256, 512};
    int cascades = 4;
    int frames = 20;
    int beaufort = 6;
    double shortest_wavelength_m = 0.1;
    double loop_period_s = 120.0;
    double frame_rate_hz = 30.0;
    int sample_frames = 8;
    std::string compression = "piz";
    std::string scratch = "bench_deepwater_tiles";
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = bench.add_subcommand(
      "deepwater", "Synthesis time per frame of the FFT deep-water cascades and bytes per minute of a baked tile set");
  command->add_option("--grid", options->grid_sizes, "Grid sizes N (N x N per cascade) to measure")
      ->delimiter(',')
      ->check(number_in(at_least(8), at_most(4096)));
  command->add_option("--cascades", options->cascades, "Number of cascades")
      ->check(number_in(at_least(1), at_most(16)));
  command->add_option("--frames", options->frames, "Frames timed per grid size (the median is reported)")
      ->check(number_in(at_least(1), at_most(100000)));
  command->add_option("--beaufort", options->beaufort, "Beaufort force of the preset sea (1-12)")
      ->check(number_in(at_least(1), at_most(12)));
  command->add_option("--shortest", options->shortest_wavelength_m, "Shortest wavelength resolved by the last cascade (m)")
      ->check(number_in(above(0), unbounded()));
  command->add_option("--loop", options->loop_period_s, "Loop period T_loop (s)")
      ->check(number_in(above(0), at_most(86400)));
  command->add_option("--fps", options->frame_rate_hz, "Frame rate of the baked tile set (frames per second of loop)")
      ->check(number_in(above(0), at_most(1000)));
  command->add_option("--sample-frames", options->sample_frames, "Tile-set frames written per cascade to measure bytes/frame")
      ->check(number_in(at_least(1), at_most(100000)));
  command->add_option("--compression", options->compression, "Tile-set EXR compression (none, zip, piz, b44, dwaa)")
      ->check(CLI::IsMember({"none", "zip", "piz", "b44", "dwaa"}));
  command->add_option("--scratch", options->scratch, "Folder for the sample tile sets (removed afterwards)");
  command->add_flag("--json", options->json, "Print the results as JSON");
  set_example(*command, "nearshore bench deepwater --grid 256,512 --cascades 4");
  command->callback([options]() {
    if (options->frames < 1 || options->cascades < 1 || options->sample_frames < 1 || !(options->frame_rate_hz > 0.0))
      throw Error("nearshore bench deepwater", "needs --frames, --cascades, --sample-frames >= 1 and --fps > 0",
                  "use the defaults");
    ProgressBar::set_quiet(options->json);
    const ocean::BeaufortPreset preset = ocean::beaufort_preset(options->beaufort);
    if (!preset.spectrum)
      throw Error("nearshore bench deepwater", "Beaufort 0 is a flat sea: there is nothing to synthesise",
                  "use --beaufort 1 to 12");
    sequence::FrameEncoding encoding;
    encoding.compression = sequence::parse_compression(options->compression);
    const int threads =
        static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    const int frames_per_loop = static_cast<int>(std::lround(options->loop_period_s * options->frame_rate_hz));

    nlohmann::json results = nlohmann::json::array();
    for (int grid_size : options->grid_sizes) {
      ocean::DeepWaterSpecification spec;
      spec.spectrum = preset.spectrum;
      spec.grid_size = grid_size;
      spec.tile_lengths_m =
          ocean::cascade_tile_lengths_for_m(*preset.spectrum, grid_size, options->cascades, options->shortest_wavelength_m);
      spec.loop_period_s = options->loop_period_s;
      const auto build_start = std::chrono::steady_clock::now();
      ocean::DeepWaterField field(spec);
      const double build_s = seconds_since(build_start);

      std::vector<double> frame_s;
      {
        ProgressBar progress(fmt::format("synthesising {0} x {0}", grid_size), options->frames, "frames");
        for (int frame = 0; frame < options->frames; ++frame) {
          const auto start = std::chrono::steady_clock::now();
          field.synthesise(frame / options->frame_rate_hz);
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
        const std::filesystem::path folder = std::filesystem::path(options->scratch) / fmt::format("n{}_c{}", grid_size, cascade);
        const bake::TileSetSummary summary =
            bake::write_deep_water_tile_set(field, cascade, frames_per_loop, folder, encoding, options->sample_frames);
        sample_bytes += summary.frame_bytes;
        sampled += summary.frame_count;
        std::filesystem::remove_all(folder);
      }
      const double bytes_per_frame_all_cascades = static_cast<double>(sample_bytes) / sampled * field.cascade_count();
      const double bytes_per_minute = bytes_per_frame_all_cascades * options->frame_rate_hz * 60.0;
      results.push_back({{"grid_size", grid_size},
                         {"cascades", field.cascade_count()},
                         {"threads", threads},
                         {"beaufort", options->beaufort},
                         {"tile_lengths_m", spec.tile_lengths_m},
                         {"build_s", build_s},
                         {"synthesis_ms_per_frame", 1e3 * median_frame_s},
                         {"tile_set_bytes_per_frame", bytes_per_frame_all_cascades},
                         {"tile_set_bytes_per_minute", bytes_per_minute},
                         {"tile_set_fps", options->frame_rate_hz},
                         {"tile_set_compression", options->compression}});
    }
    std::filesystem::remove_all(options->scratch);
    if (options->json) {
      std::printf("%s\n", results.dump(2).c_str());
      return;
    }
    std::printf("%s\n", fmt::format("{:>6}  {:>8}  {:>7}  {:>8}  {:>14}  {:>16}  {:>18}", "N", "cascades", "threads",
                                    "build s", "synthesis ms", "tile bytes/frame", "tile MB/min loop").c_str());
    for (const auto& r : results)
      std::printf("%s\n", fmt::format("{:>6}  {:>8}  {:>7}  {:>8.2f}  {:>14.2f}  {:>16.0f}  {:>18.1f}", r["grid_size"].get<int>(),
                                      r["cascades"].get<int>(), r["threads"].get<int>(), r["build_s"].get<double>(),
                                      r["synthesis_ms_per_frame"].get<double>(), r["tile_set_bytes_per_frame"].get<double>(),
                                      r["tile_set_bytes_per_minute"].get<double>() / 1e6).c_str());
    std::printf("%s\n", fmt::format("(Beaufort {}, tile set at {} fps, {} compression, half floats; synthesis = 8 channels "
                                    "x {} cascades, median of {} frames)",
                                    options->beaufort, options->frame_rate_hz, options->compression, options->cascades,
                                    options->frames).c_str());
  });
}

}  // namespace nearshore::tools
