#pragma once
// SequenceReader: random access to a baked sequence folder (docs/formats/sequence.md). Opening
// reads and validates manifest.json only; frame k is one file, so reading it costs the same for
// every k (O(1) random access). All methods are const and safe to call from several threads.
#include <cstddef>
#include <filesystem>
#include <span>
#include <string>

#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/raster.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "nearshore/sequence/sequence_format.hpp"

namespace nearshore::sequence {

/// Which channels to decode (the others stay empty rasters and cost nothing).
struct ChannelSelection {
  bool surface_elevation = true, flux_x = true, flux_y = true, breaking = true;
  static ChannelSelection all() { return {}; }
  /// eta, P, Q: what the distance matrix and crossfade analysis need.
  static ChannelSelection dynamics() { return {true, true, true, false}; }
  /// eta and breaking: what a renderer draws.
  static ChannelSelection display() { return {true, false, false, true}; }
};

/// One decoded frame. Rasters follow the core convention (row 0 = south).
struct Frame {
  int index = -1;
  double time_s = 0;
  Raster<float> surface_elevation_m;  ///< eta, m
  Raster<float> flux_x_m2_s;          ///< P, m^2/s
  Raster<float> flux_y_m2_s;          ///< Q, m^2/s
  Raster<float> breaking;             ///< 0..1
};

enum class Verify { kNo, kYes };

class SequenceReader {
 public:
  /// Reads and validates `folder`/manifest.json. Throws nearshore::Error if the folder has no
  /// manifest (an unfinished bake), or the manifest is malformed or of another version.
  explicit SequenceReader(const std::filesystem::path& folder);

  const std::filesystem::path& folder() const { return folder_; }
  const SequenceManifest& manifest() const { return manifest_; }
  const GridGeometry& geometry() const { return manifest_.geometry; }
  int frame_count() const { return manifest_.frame_count; }
  double frame_interval_s() const { return manifest_.frame_interval_s; }
  std::filesystem::path frame_path(int index) const;

  /// Decodes frame `index`. With Verify::kYes the file's XXH64 is checked against the manifest
  /// first. Throws nearshore::Error naming the frame file for a bad index, a missing, truncated
  /// or corrupt file, or a frame that does not match the manifest.
  Frame read_frame(int index, ChannelSelection channels = ChannelSelection::all(), Verify verify = Verify::kNo) const;
  /// The same into `frame`, reusing its rasters' memory (playback decodes into the same buffers).
  void read_frame_into(int index, Frame& frame, ChannelSelection channels = ChannelSelection::all(),
                       Verify verify = Verify::kNo) const;
  /// Decodes only raster rows [first_row, first_row + row_count) of frame `index` into rasters of
  /// `columns x row_count` (row 0 = first_row). For streaming passes over large grids; no checksum.
  void read_frame_rows(int index, int first_row, int row_count, Frame& frame,
                       ChannelSelection channels = ChannelSelection::dynamics()) const;

  /// The harbour grid stored beside the frames (depth.exr).
  HarbourGrid read_harbour_grid(Verify verify = Verify::kNo) const;

  /// Checks size and checksum of every file in the manifest; throws nearshore::Error naming the
  /// first bad file. Shows a ProgressBar unless quiet.
  void verify_checksums() const;

 private:
  void read_checked(const FileEntry& entry, Verify verify, FileBuffer& buffer) const;
  std::filesystem::path folder_;
  SequenceManifest manifest_;
};

/// Decodes one frame file held in memory and checks it against `manifest` (size, channels,
/// frame index). `source` names the file in error messages. Used by the reader and fuzzed.
void decode_frame(std::span<const std::byte> bytes, const std::string& source, const SequenceManifest& manifest,
                  int expected_index, ChannelSelection channels, Frame& frame);

}  // namespace nearshore::sequence

namespace nearshore::sequence {
/// OpenEXR's own worker threads for decoding (0: decode on the calling thread only). A player
/// decoding in a background thread wants 0; a batch tool may use more.
void set_exr_worker_threads(int threads);
}  // namespace nearshore::sequence
