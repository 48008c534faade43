#include "nearshore/bench/loops_bench.hpp"

#include <fmt/format.h>
#include <fmt/printf.h>

#include "nearshore/sequence/sequence_format.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::bench {

LoopsBenchResult run_loops_bench(const LoopsBenchOptions& options, const LoopsBenchProgress& progress) {
  const auto report = [&](const LoopsBenchResult& so_far) {
    if (progress) progress(so_far);
  };
  const std::filesystem::path& work = options.work_folder;
  LoopsBenchResult result;
  result.compression = options.compression;
  if (options.compression) {
    result.frames = options.frames;
    result.frame_interval_s = 0.5;  // the synthetic sea's
    result.grid_columns = result.grid_rows = options.size_cells;
    result.source = fmt::format("{} x {} cells of a synthetic irregular sea (Hs 1.5 m, Tp 8 s, 24 components)",
                                options.size_cells, options.size_cells);
    if (!options.sequence.empty()) {
      const sequence::SequenceReader reader(options.sequence);
      result.frame_interval_s = reader.frame_interval_s();
      result.grid_columns = reader.manifest().geometry.columns;
      result.grid_rows = reader.manifest().geometry.rows;
      result.source = fmt::format("{} x {} cells of the bake {} ({} frames every {} s)", result.grid_columns,
                                  result.grid_rows, options.sequence.string(), reader.frame_count(), result.frame_interval_s);
    }
    report(result);
    for (sequence::Compression codec : sequence::all_compressions()) {
      const loops::CompressionMeasurement m =
          options.sequence.empty()
              ? loops::measure_compression(work / "compression", codec, options.size_cells, options.size_cells, options.frames)
              : loops::measure_compression_of_sequence(work / "compression", codec, options.sequence, options.frames);
      result.codecs.push_back({std::string(sequence::compression_name(codec)), m});
      report(result);
    }
    std::filesystem::remove_all(work);
    return result;
  }
  result.distance_size_cells = options.distance_size_cells;
  result.distance_frames = options.distance_frames;
  report(result);
  for (int threads : {1, 2}) {
    result.distance_runs.push_back(loops::measure_distance_throughput(
        work / "distance", options.distance_size_cells, options.distance_size_cells, options.distance_frames, threads));
    report(result);
  }
  std::filesystem::remove_all(work);
  return result;
}

nlohmann::json loops_bench_json(const LoopsBenchResult& result) {
  if (result.compression) {
    nlohmann::json rows = nlohmann::json::array();
    for (const LoopsCompressionRow& row : result.codecs) {
      const loops::CompressionMeasurement& m = row.measurement;
      const double cells = static_cast<double>(m.columns) * m.rows;
      rows.push_back({{"codec", row.codec},
                      {"bytes_per_cell_per_frame", m.bytes_per_cell_per_frame},
                      {"max_error_m", m.max_error_m},
                      {"rms_error_m", m.rms_error_m},
                      {"max_flux_error_m2_s", m.max_flux_error_m2_s},
                      {"decode_frames_per_cpu_s", m.decode_frames_per_cpu_s},
                      {"decode_display_frames_per_cpu_s", m.decode_display_frames_per_cpu_s},
                      {"decode_frames_per_s", m.decode_frames_per_s},
                      {"decode_cells_per_cpu_s", m.decode_frames_per_cpu_s * cells},
                      {"real_time_factor", m.decode_frames_per_cpu_s * result.frame_interval_s},
                      {"encode_frames_per_s", m.encode_frames_per_s}});
    }
    return {{"benchmark", "compression"},
            {"source", result.source},
            {"grid_cells", {result.grid_columns, result.grid_rows}},
            {"frame_interval_s", result.frame_interval_s},
            {"frames", result.frames},
            {"codecs", rows}};
  }
  nlohmann::json runs = nlohmann::json::array();
  for (const loops::DistanceThroughput& t : result.distance_runs)
    runs.push_back({{"threads", t.threads},
                    {"seconds", t.seconds},
                    {"pair_cells_per_s", t.pair_cells_per_s},
                    {"frames_decoded_per_s", t.frames_decoded_per_s}});
  return {{"benchmark", "distance_matrix"},
          {"grid_cells", {result.distance_size_cells, result.distance_size_cells}},
          {"frames", result.distance_frames},
          {"runs", runs}};
}

std::string loops_bench_text_header(const LoopsBenchResult& result) {
  if (result.compression)
    return fmt::sprintf("compression of %d frames, half channels: %s\n", result.frames, result.source) +
           fmt::sprintf("| codec | bytes/cell/frame | max error eta (m) | RMS error eta (m) | max error P (m^2/s) | "
                        "decode frames per CPU-s (4 ch) | decode frames per CPU-s (eta+breaking) | M cells per CPU-s (4 ch) | "
                        "x real time at 1 frame per %g s (4 ch) | decode frames/s wall (4 ch) | encode frames/s |\n",
                        result.frame_interval_s) +
           "|---|---|---|---|---|---|---|---|---|---|---|\n";
  return fmt::sprintf("distance matrix (streamed block Gram, eq. 8-10): %d frames of %d x %d cells\n", result.distance_frames,
                      result.distance_size_cells, result.distance_size_cells);
}

std::string loops_bench_text_last_row(const LoopsBenchResult& result) {
  if (result.compression) {
    if (result.codecs.empty()) return {};
    const LoopsCompressionRow& row = result.codecs.back();
    const loops::CompressionMeasurement& m = row.measurement;
    const double cells = static_cast<double>(m.columns) * m.rows;
    return fmt::sprintf("| %s | %.3f | %.2e | %.2e | %.2e | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f |\n", row.codec,
                        m.bytes_per_cell_per_frame, m.max_error_m, m.rms_error_m, m.max_flux_error_m2_s,
                        m.decode_frames_per_cpu_s, m.decode_display_frames_per_cpu_s, m.decode_frames_per_cpu_s * cells / 1e6,
                        m.decode_frames_per_cpu_s * result.frame_interval_s, m.decode_frames_per_s, m.encode_frames_per_s);
  }
  if (result.distance_runs.empty()) return {};
  const loops::DistanceThroughput& t = result.distance_runs.back();
  return fmt::sprintf("  %d thread%s: %.2f s, %.3g frame pairs x cells / s, %.1f frames/s decoded (eta, P, Q)\n", t.threads,
                      t.threads == 1 ? " " : "s", t.seconds, t.pair_cells_per_s, t.frames_decoded_per_s);
}

}  // namespace nearshore::bench
