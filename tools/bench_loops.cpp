// `nearshore bench loops`: distance-matrix throughput (frame pairs x cells per second) and
// frames decoded per second; with --compression, the table of docs/formats/sequence.md (on a
// synthetic sea, or with --sequence on the frames of a real bake).
#include <cstdio>
#include <filesystem>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "command_support.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/loops/benchmarks.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::tools {

void add_bench_loops(CLI::App& bench) {
  struct Options {
    bool compression = false, json = false;
    int size = 1024, frames = 16, distance_size = 256, distance_frames = 300;
    std::string work = "nearshore-bench-loops";
    std::string sequence;  // --compression on this bake's frames instead of the synthetic sea
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = bench.add_subcommand("loops", "Distance-matrix throughput and frame decode speed");
  command->add_flag("--compression", options->compression,
                    "Measure size, error and decode speed of every frame codec (none, zip, piz, b44, dwaa, rle, zips, pxr24) instead");
  command->add_option("--size", options->size, "Grid side for the compression table (cells)")
      ->check(number_in(at_least(8), at_most(16384)));
  command->add_option("--frames", options->frames, "Frames for the compression table")
      ->check(number_in(at_least(1), at_most(100000)));
  command->add_option("--distance-size", options->distance_size, "Grid side for the distance benchmark (cells)")
      ->check(number_in(at_least(8), at_most(16384)));
  command->add_option("--distance-frames", options->distance_frames, "Frames for the distance benchmark")
      ->check(number_in(at_least(2), at_most(100000)));
  command->add_option("--sequence", options->sequence,
                      "With --compression: measure on the frames of this baked sequence folder (spread over the "
                      "bake; bake it with [output] frame_precision = \"float\" for exact error columns)")
      ->check(CLI::ExistingDirectory);
  command->add_option("--work", options->work, "Scratch folder (removed afterwards)");
  command->add_flag("--json", options->json, "Print the results as JSON on stdout instead of the table");
  set_example(*command, "nearshore bench loops --compression --size 1024 --frames 16");
  command->callback([options]() {
    ProgressBar::set_quiet(true);
    const std::filesystem::path work = options->work;
    if (options->compression) {
      nlohmann::json rows = nlohmann::json::array();
      // The player decodes one keyframe per frame interval of play (docs/runtime.md, "The engine"):
      // "x real time" is frames decoded per CPU-second times the interval.
      double frame_interval_s = 0.5;  // the synthetic sea's
      int grid_columns = options->size, grid_rows = options->size;
      std::string source = fmt::format("{} x {} cells of a synthetic irregular sea (Hs 1.5 m, Tp 8 s, 24 components)",
                                       options->size, options->size);
      if (!options->sequence.empty()) {
        const sequence::SequenceReader reader(options->sequence);
        frame_interval_s = reader.frame_interval_s();
        grid_columns = reader.manifest().geometry.columns;
        grid_rows = reader.manifest().geometry.rows;
        source = fmt::format("{} x {} cells of the bake {} ({} frames every {} s)", reader.manifest().geometry.columns,
                             reader.manifest().geometry.rows, options->sequence, reader.frame_count(), frame_interval_s);
      }
      if (!options->json) {
        std::printf("compression of %d frames, half channels: %s\n", options->frames, source.c_str());
        std::printf("| codec | bytes/cell/frame | max error eta (m) | RMS error eta (m) | max error P (m^2/s) | "
                    "decode frames per CPU-s (4 ch) | decode frames per CPU-s (eta+breaking) | M cells per CPU-s (4 ch) | "
                    "x real time at 1 frame per %g s (4 ch) | decode frames/s wall (4 ch) | encode frames/s |\n",
                    frame_interval_s);
        std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
      }
      for (sequence::Compression codec : sequence::all_compressions()) {
        const loops::CompressionMeasurement m =
            options->sequence.empty()
                ? loops::measure_compression(work / "compression", codec, options->size, options->size, options->frames)
                : loops::measure_compression_of_sequence(work / "compression", codec, options->sequence, options->frames);
        const double cells = static_cast<double>(m.columns) * m.rows;
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
                          {"decode_cells_per_cpu_s", m.decode_frames_per_cpu_s * cells},
                          {"real_time_factor", m.decode_frames_per_cpu_s * frame_interval_s},
                          {"encode_frames_per_s", m.encode_frames_per_s}});
          continue;
        }
        std::printf("| %s | %.3f | %.2e | %.2e | %.2e | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f |\n", name.c_str(),
                    m.bytes_per_cell_per_frame, m.max_error_m, m.rms_error_m, m.max_flux_error_m2_s,
                    m.decode_frames_per_cpu_s, m.decode_display_frames_per_cpu_s, m.decode_frames_per_cpu_s * cells / 1e6,
                    m.decode_frames_per_cpu_s * frame_interval_s, m.decode_frames_per_s, m.encode_frames_per_s);
        std::fflush(stdout);
      }
      if (options->json) {
        const nlohmann::json out = {{"benchmark", "compression"},
                                    {"source", source},
                                    {"grid_cells", {grid_columns, grid_rows}},
                                    {"frame_interval_s", frame_interval_s},
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
