#include "nearshore/loops/benchmarks.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <cmath>

#include <tbb/global_control.h>

#include "nearshore/core/process_usage.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/loops/distance.hpp"
#include "nearshore/loops/synthetic_sea.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::loops {
namespace fs = std::filesystem;
namespace {

GridGeometry bench_geometry(int columns, int rows) {
  GridGeometry geometry;
  geometry.columns = columns;
  geometry.rows = rows;
  geometry.spacing_m = 2.0;
  return geometry;
}

SyntheticSea bench_sea() { return irregular_sea(8.0, 24, 1.5, 12.0, 0.4, 2026); }

}  // namespace

namespace {

// The exact fields of the frames a measurement encodes: frame k's eta, P, Q and breaking.
using ExactFrame = std::function<void(int k, Raster<float>& eta, Raster<float>& p, Raster<float>& q, Raster<float>& breaking)>;

CompressionMeasurement measure_frames(const fs::path& work_folder, sequence::Compression compression, const HarbourGrid& harbour,
                                      double interval_s, int frames, const ExactFrame& exact_frame) {
  CompressionMeasurement result;
  const GridGeometry& geometry = harbour.geometry;
  result.compression = compression;
  result.columns = geometry.columns;
  result.rows = geometry.rows;
  result.frames = frames;
  sequence::set_exr_worker_threads(0);
  fs::remove_all(work_folder);
  {
    sequence::FrameEncoding encoding;
    encoding.compression = compression;
    sequence::SequenceDescription description;
    description.frame_interval_s = interval_s;
    description.encoding = encoding;
    sequence::SequenceWriter writer(work_folder, harbour, description);
    Raster<float> eta, p, q, breaking;
    double encode_s = 0;
    for (int k = 0; k < frames; ++k) {
      exact_frame(k, eta, p, q, breaking);
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
  Raster<float> eta, p, q, breaking;
  sequence::Frame frame;
  for (int k = 0; k < frames; ++k) {
    reader.read_frame_into(k, frame);
    exact_frame(k, eta, p, q, breaking);
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
  double cpu = thread_cpu_s();
  for (int pass = 0; pass < passes; ++pass)
    for (int k = 0; k < frames; ++k) reader.read_frame_into(k, frame);
  result.decode_frames_per_s = passes * frames / seconds_since(start);
  result.decode_frames_per_cpu_s = passes * frames / (thread_cpu_s() - cpu);
  start = std::chrono::steady_clock::now();
  cpu = thread_cpu_s();
  for (int pass = 0; pass < passes; ++pass)
    for (int k = 0; k < frames; ++k) reader.read_frame_into(k, frame, sequence::ChannelSelection::display());
  result.decode_display_frames_per_s = passes * frames / seconds_since(start);
  result.decode_display_frames_per_cpu_s = passes * frames / (thread_cpu_s() - cpu);
  fs::remove_all(work_folder);
  return result;
}

}  // namespace

CompressionMeasurement measure_compression(const fs::path& work_folder, sequence::Compression compression, int columns,
                                           int rows, int frames) {
  const GridGeometry geometry = bench_geometry(columns, rows);
  const SyntheticSea sea = bench_sea();
  const double interval_s = 0.5;
  return measure_frames(work_folder, compression, HarbourGrid::open_water(geometry, 12.0f), interval_s, frames,
                        [&](int k, Raster<float>& eta, Raster<float>& p, Raster<float>& q, Raster<float>& breaking) {
                          evaluate_sea(sea, geometry, k * interval_s, eta, p, q);
                          // A foam indicator like a bake's: non-zero on the steepest crests only.
                          breaking = Raster<float>(columns, rows);
                          for (std::size_t c = 0; c < eta.size(); ++c)
                            breaking.values()[c] = std::clamp((eta.values()[c] - 0.8f) * 2.0f, 0.0f, 1.0f);
                        });
}

CompressionMeasurement measure_compression_of_sequence(const fs::path& work_folder, sequence::Compression compression,
                                                       const fs::path& source_folder, int frames) {
  const sequence::SequenceReader source(source_folder);
  frames = std::min(frames, source.frame_count());
  // Frames spread over the whole bake: calm starts and developed seas compress differently.
  const auto source_index = [&](int k) {
    return frames == 1 ? 0 : static_cast<int>(static_cast<long>(k) * (source.frame_count() - 1) / (frames - 1));
  };
  sequence::Frame frame;
  return measure_frames(work_folder, compression, source.read_harbour_grid(), source.frame_interval_s(), frames,
                        [&](int k, Raster<float>& eta, Raster<float>& p, Raster<float>& q, Raster<float>& breaking) {
                          source.read_frame_into(source_index(k), frame);
                          eta = frame.surface_elevation_m;
                          p = frame.flux_x_m2_s;
                          q = frame.flux_y_m2_s;
                          breaking = frame.breaking;
                        });
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
