// `nearshore bench loops`: distance-matrix throughput (frame pairs x cells per second) and
// frames decoded per second; with --compression, the table of docs/formats/sequence.md.
#include <cstdio>
#include <filesystem>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "command_support.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/loops/benchmarks.hpp"

namespace nearshore::tools {

void add_bench_loops(CLI::App& bench) {
  struct Options {
    bool compression = false, json = false;
    int size = 1024, frames = 16, distance_size = 256, distance_frames = 300;
    std::string work = "nearshore-bench-loops";
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = bench.add_subcommand("loops", "Distance-matrix throughput and frame decode speed");
  command->add_flag("--compression", options->compression,
                    "Measure size, error and decode speed of none/zip/piz/b44/dwaa frames instead");
  command->add_option("--size", options->size, "Grid side for the compression table (cells)")
      ->check(number_in(at_least(8), at_most(16384)));
  command->add_option("--frames", options->frames, "Frames for the compression table")
      ->check(number_in(at_least(1), at_most(100000)));
  command->add_option("--distance-size", options->distance_size, "Grid side for the distance benchmark (cells)")
      ->check(number_in(at_least(8), at_most(16384)));
  command->add_option("--distance-frames", options->distance_frames, "Frames for the distance benchmark")
      ->check(number_in(at_least(2), at_most(100000)));
  command->add_option("--work", options->work, "Scratch folder (removed afterwards)");
  command->add_flag("--json", options->json, "Print the results as JSON on stdout instead of the table");
  set_example(*command, "nearshore bench loops --compression --size 1024 --frames 16");
  command->callback([options]() {
    ProgressBar::set_quiet(true);
    const std::filesystem::path work = options->work;
    if (options->compression) {
      nlohmann::json rows = nlohmann::json::array();
      if (!options->json) {
        std::printf("compression of %d x %d frames (irregular sea Hs 1.5 m, Tp 8 s, 24 components, half channels), %d frames\n",
                    options->size, options->size, options->frames);
        std::printf("| codec | bytes/cell/frame | max error eta (m) | RMS error eta (m) | max error P (m^2/s) | "
                    "decode frames per CPU-s (4 ch) | decode frames per CPU-s (eta+breaking) | x real time at 30 fps (4 ch) | "
                    "decode frames/s wall (4 ch) | encode frames/s |\n");
        std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
      }
      for (auto codec : {sequence::Compression::kNone, sequence::Compression::kZip, sequence::Compression::kPiz,
                         sequence::Compression::kB44, sequence::Compression::kDwaa}) {
        const loops::CompressionMeasurement m =
            loops::measure_compression(work / "compression", codec, options->size, options->size, options->frames);
        const std::string name(sequence::compression_name(codec));
        if (options->json) {
          rows.push_back({{"codec", name},
                          {"bytes_per_cell_per_frame", m.bytes_per_cell_per_frame},
                          {"max_error_m", m.max_error_m},
                          {"rms_error_m", m.rms_error_m},
                          {"max_flux_error_m2_s", m.max_flux_error_m2_s},
                          {"decode_frames_per_cpu_s", m.decode_frames_per_cpu_s},
                          {"decode_display_frames_per_cpu_s", m.decode_display_frames_per_cpu_s},
                          {"decode_frames_per_s", m.decode_frames_per_s},
                          {"encode_frames_per_s", m.encode_frames_per_s}});
          continue;
        }
        std::printf("| %s | %.3f | %.2e | %.2e | %.2e | %.1f | %.1f | %.2f | %.1f | %.1f |\n", name.c_str(),
                    m.bytes_per_cell_per_frame, m.max_error_m, m.rms_error_m, m.max_flux_error_m2_s,
                    m.decode_frames_per_cpu_s, m.decode_display_frames_per_cpu_s, m.decode_frames_per_cpu_s / 30.0,
                    m.decode_frames_per_s, m.encode_frames_per_s);
        std::fflush(stdout);
      }
      if (options->json) {
        const nlohmann::json out = {{"benchmark", "compression"},
                                    {"grid_cells", {options->size, options->size}},
                                    {"frames", options->frames},
                                    {"codecs", rows}};
        std::printf("%s\n", out.dump(2).c_str());
      }
      std::filesystem::remove_all(work);
      return;
    }
    if (!options->json)
      std::printf("distance matrix (streamed block Gram, eq. 8-10): %d frames of %d x %d cells\n",
                  options->distance_frames, options->distance_size, options->distance_size);
    nlohmann::json runs = nlohmann::json::array();
    for (int threads : {1, 2}) {
      const loops::DistanceThroughput t = loops::measure_distance_throughput(
          work / "distance", options->distance_size, options->distance_size, options->distance_frames, threads);
      if (options->json) {
        runs.push_back({{"threads", threads},
                        {"seconds", t.seconds},
                        {"pair_cells_per_s", t.pair_cells_per_s},
                        {"frames_decoded_per_s", t.frames_decoded_per_s}});
        continue;
      }
      std::printf("  %d thread%s: %.2f s, %.3g frame pairs x cells / s, %.1f frames/s decoded (eta, P, Q)\n", threads,
                  threads == 1 ? " " : "s", t.seconds, t.pair_cells_per_s, t.frames_decoded_per_s);
      std::fflush(stdout);
    }
    if (options->json) {
      const nlohmann::json out = {{"benchmark", "distance_matrix"},
                                  {"grid_cells", {options->distance_size, options->distance_size}},
                                  {"frames", options->distance_frames},
                                  {"runs", runs}};
      std::printf("%s\n", out.dump(2).c_str());
    }
    std::filesystem::remove_all(work);
  });
}

}  // namespace nearshore::tools
