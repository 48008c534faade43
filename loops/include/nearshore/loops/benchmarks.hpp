#pragma once
// Measurements behind `nearshore bench loops` and the compression table of
// docs/formats/sequence.md. They time real work on synthetic seas (synthetic_sea.hpp) written as
// real sequence folders; nothing here is asserted, only reported.
#include <filesystem>
#include <string>

#include "nearshore/sequence/sequence_format.hpp"

namespace nearshore::loops {

struct CompressionMeasurement {
  sequence::Compression compression{};
  int columns = 0, rows = 0, frames = 0;
  double bytes_per_cell_per_frame = 0;  ///< file size / (cells * frames), all 4 channels
  double max_error_m = 0, rms_error_m = 0;  ///< surface elevation against the float field
  double max_flux_error_m2_s = 0;           ///< flux x against the float field
  double decode_frames_per_s = 0;           ///< all four channels, one core (no OpenEXR threads)
  double decode_display_frames_per_s = 0;   ///< surface elevation + breaking only (what a renderer reads)
  double decode_frames_per_cpu_s = 0;       ///< the same per second of this thread's CPU time (load-independent)
  double decode_display_frames_per_cpu_s = 0;
  double encode_frames_per_s = 0;
};

/// Writes `frames` frames of an irregular sea (Hs 1.5 m, Tp 8 s, 12 m deep, 2 m cells) of
/// columns x rows with `compression` (half channels) into `work_folder`, then reads them back.
CompressionMeasurement measure_compression(const std::filesystem::path& work_folder, sequence::Compression compression,
                                           int columns, int rows, int frames);
/// The same on the frames of a real bake: `frames` frames spread evenly over the sequence in
/// `source_folder` (its harbour grid included) are written again with `compression` (half channels)
/// and read back; errors are against the source's values (exact when it was baked with
/// `[output] frame_precision = "float"`, docs/commands/bake.md).
CompressionMeasurement measure_compression_of_sequence(const std::filesystem::path& work_folder,
                                                       sequence::Compression compression,
                                                       const std::filesystem::path& source_folder, int frames);

struct DistanceThroughput {
  int columns = 0, rows = 0, frames = 0, threads = 0;
  double seconds = 0;
  double pair_cells_per_s = 0;  ///< frame pairs (N (N + 1) / 2) x cells per second
  double frames_decoded_per_s = 0;
};

/// Times compute_gram_matrices on a `frames`-frame sequence of columns x rows (written first).
DistanceThroughput measure_distance_throughput(const std::filesystem::path& work_folder, int columns, int rows,
                                               int frames, int threads);

}  // namespace nearshore::loops
