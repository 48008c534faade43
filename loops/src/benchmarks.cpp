#include "nearshore/loops/benchmarks.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>

#include <tbb/global_control.h>

#include "nearshore/core/progress.hpp"
#include "nearshore/loops/distance.hpp"
#include "nearshore/loops/synthetic_sea.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::loops {
namespace fs = std::filesystem;
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// CPU time of the calling thread: what one core spends, whatever else the machine is running.
double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return now.tv_sec + 1e-9 * now.tv_nsec;
}

GridGeometry bench_geometry(int columns, int rows) {
  GridGeometry geometry;
  geometry.columns = columns;
  geometry.rows = rows;
  geometry.spacing_m = 2.0;
  return geometry;
}

SyntheticSea bench_sea() { return irregular_sea(8.0, 24, 1.5, 12.0, 0.4, 2026); }

}  // namespace

CompressionMeasurement measure_compression(const fs::path& work_folder, sequence::Compression compression, int columns,
                                           int rows, int frames) {
  CompressionMeasurement result;
  result.compression = compression;
  result.columns = columns;
  result.rows = rows;
  result.frames = frames;
  sequence::set_exr_worker_threads(0);
  const GridGeometry geometry = bench_geometry(columns, rows);
  const SyntheticSea sea = bench_sea();
  const double interval_s = 0.5;
  fs::remove_all(work_folder);
  {
    sequence::FrameEncoding encoding;
    encoding.compression = compression;
    sequence::SequenceDescription description;
    description.frame_interval_s = interval_s;
    description.encoding = encoding;
    sequence::SequenceWriter writer(work_folder, HarbourGrid::open_water(geometry, 12.0f), description);
    Raster<float> eta, p, q, breaking(columns, rows);
    double encode_s = 0;
    for (int k = 0; k < frames; ++k) {
      evaluate_sea(sea, geometry, k * interval_s, eta, p, q);
      // A foam indicator like a bake's: non-zero on the steepest crests only.
      for (std::size_t c = 0; c < eta.size(); ++c) breaking.values()[c] = std::clamp((eta.values()[c] - 0.8f) * 2.0f, 0.0f, 1.0f);
      const auto start = std::chrono::steady_clock::now();
      writer.write_frame(k, {&eta, &p, &q, &breaking});
      encode_s += seconds_since(start);
    }
    writer.finish(frames);
    result.encode_frames_per_s = frames / encode_s;
  }
  const sequence::SequenceReader reader(work_folder);
  double bytes = 0;
  for (const sequence::FileEntry& file : reader.manifest().frames) bytes += static_cast<double>(file.bytes);
  result.bytes_per_cell_per_frame = bytes / (static_cast<double>(geometry.cell_count()) * frames);
  // Errors against the exact float fields.
  double sum_squares = 0;
  Raster<float> eta, p, q;
  sequence::Frame frame;
  for (int k = 0; k < frames; ++k) {
    reader.read_frame_into(k, frame);
    evaluate_sea(sea, geometry, k * interval_s, eta, p, q);
    for (std::size_t c = 0; c < eta.size(); ++c) {
      const double error = frame.surface_elevation_m.values()[c] - eta.values()[c];
      result.max_error_m = std::max(result.max_error_m, std::abs(error));
      sum_squares += error * error;
      result.max_flux_error_m2_s =
          std::max(result.max_flux_error_m2_s, std::abs(double(frame.flux_x_m2_s.values()[c]) - p.values()[c]));
    }
  }
  result.rms_error_m = std::sqrt(sum_squares / (static_cast<double>(geometry.cell_count()) * frames));
  // Decode speed: files are in the page cache after the pass above, as in steady playback.
  const int passes = std::max(1, 48 / frames);
  auto start = std::chrono::steady_clock::now();
  double cpu = thread_cpu_seconds();
  for (int pass = 0; pass < passes; ++pass)
    for (int k = 0; k < frames; ++k) reader.read_frame_into(k, frame);
  result.decode_frames_per_s = passes * frames / seconds_since(start);
  result.decode_frames_per_cpu_s = passes * frames / (thread_cpu_seconds() - cpu);
  start = std::chrono::steady_clock::now();
  cpu = thread_cpu_seconds();
  for (int pass = 0; pass < passes; ++pass)
    for (int k = 0; k < frames; ++k) reader.read_frame_into(k, frame, sequence::ChannelSelection::display());
  result.decode_display_frames_per_s = passes * frames / seconds_since(start);
  result.decode_display_frames_per_cpu_s = passes * frames / (thread_cpu_seconds() - cpu);
  fs::remove_all(work_folder);
  return result;
}

DistanceThroughput measure_distance_throughput(const fs::path& work_folder, int columns, int rows, int frames,
                                               int threads) {
  DistanceThroughput result;
  result.columns = columns;
  result.rows = rows;
  result.frames = frames;
  result.threads = threads;
  sequence::set_exr_worker_threads(0);
  const GridGeometry geometry = bench_geometry(columns, rows);
  if (!fs::exists(work_folder / "manifest.json")) write_sea_sequence(work_folder, bench_sea(), geometry, frames, 0.5, 0);
  const sequence::SequenceReader reader(work_folder);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  GramOptions options;
  options.threads = threads;
  auto start = std::chrono::steady_clock::now();
  const GramMatrices gram = compute_gram_matrices(reader, options);
  result.seconds = seconds_since(start);
  result.pair_cells_per_s = 0.5 * frames * (frames + 1.0) * static_cast<double>(geometry.cell_count()) / result.seconds;
  sequence::Frame frame;
  start = std::chrono::steady_clock::now();
  for (int k = 0; k < frames; ++k) reader.read_frame_into(k, frame, sequence::ChannelSelection::dynamics());
  result.frames_decoded_per_s = frames / seconds_since(start);
  return result;
}

}  // namespace nearshore::loops
