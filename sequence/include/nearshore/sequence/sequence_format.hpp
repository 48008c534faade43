#pragma once
// The baked sequence folder, version 1 (docs/formats/sequence.md):
//   manifest.json          written LAST; its presence means "complete". Versioned JSON: grid,
//                          time step, units, channels, encoding, wave conditions, seed, loop period,
//                          deep-water description, and an XXH64 checksum for every file below.
//   depth.exr              the harbour grid (core/harbour_grid.hpp), so playback needs nothing else
//   frame_000000.exr ...   one scanline OpenEXR per frame, channels surface_elevation (m),
//                          flux_x, flux_y (m^2/s, cell centres) and breaking (0..1); EXR line 0 is
//                          the NORTHERN row, as in every nearshore EXR.
//   loops.json, loops_gram.bin   transition tables written later by `nearshore loops` (loops/).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "nearshore/core/raster.hpp"
#include "nearshore/sequence/deep_water_section.hpp"
#include "nearshore/sequence/file_entry.hpp"

namespace nearshore::sequence {

inline constexpr std::string_view kManifestFormat = "nearshore sequence";
inline constexpr int kManifestVersion = 1;
inline constexpr std::string_view kFrameFormat = "nearshore sequence frame 1";
inline constexpr std::string_view kManifestFile = "manifest.json";
inline constexpr std::string_view kHarbourGridFile = "depth.exr";

/// OpenEXR compression of the frames; the default comes from the measured table in
/// docs/formats/sequence.md (`nearshore bench loops --compression`). kRle (run lengths), kZips
/// (zlib on one line per block instead of 16) and kPxr24 (zlib after a byte predictor; lossless on
/// half channels, rounds float channels to 24 bits) are OpenEXR's own codecs, measured beside the
/// others on a real bake. New values go at the end: the enum's order is no file format (the
/// manifest stores the name), but callers initialise FrameEncoding by position.
enum class Compression { kNone, kZip, kPiz, kB44, kDwaa, kRle, kZips, kPxr24 };
/// Storage of one channel: half (16-bit, 11 significant bits) or float (32-bit).
enum class Precision { kHalf, kFloat };

/// How frames are encoded. Half keeps 3 significant decimal digits: 0.5 mm on a 1 m wave.
struct FrameEncoding {
  Compression compression = Compression::kNone;
  Precision surface_elevation = Precision::kHalf;
  Precision flux = Precision::kHalf;
  Precision breaking = Precision::kHalf;
};

/// The four channels, in file order.
inline constexpr const char* kChannelNames[4] = {"surface_elevation", "flux_x", "flux_y", "breaking"};

std::string_view compression_name(Compression compression);     ///< "none", "zip", "piz", "b44", "dwaa", "rle", "zips", "pxr24"
Compression parse_compression(std::string_view name);           ///< throws Error listing the names
/// Every codec nearshore writes, in the enum's order (for messages and the benchmark's table).
const std::vector<Compression>& all_compressions();
std::string_view precision_name(Precision precision);           ///< "half" or "float"
std::string frame_file_name(int index);                          ///< "frame_000123.exr"

/// manifest.json, parsed and validated.
struct SequenceManifest {
  int version = kManifestVersion;
  GridGeometry geometry;
  int frame_count = 0;
  double frame_interval_s = 0;
  double first_frame_time_s = 0;
  double loop_period_s = 0;  ///< > 0 for a time-periodic bake
  std::uint64_t seed = 0;
  FrameEncoding encoding;
  nlohmann::json wave_conditions, solver;
  std::optional<DeepWaterSection> deep_water;  ///< the FFT sea beyond the harbour, when the bake carries one
  FileEntry harbour_grid;
  std::vector<FileEntry> frames;  ///< frame_count entries, index order

  double frame_time_s(int index) const { return first_frame_time_s + index * frame_interval_s; }
  /// The bake's wet/dry threshold (m) from the solver record (`solver.dry_depth_m`): a cell whose
  /// total depth d + eta is at most this was dry. nullopt when the record has none (older bakes).
  std::optional<double> recorded_dry_depth_m() const {
    if (solver.is_object() && solver.contains("dry_depth_m") && solver["dry_depth_m"].is_number())
      return solver["dry_depth_m"].get<double>();
    return std::nullopt;
  }
};

nlohmann::json manifest_to_json(const SequenceManifest& manifest);
/// Parses and validates manifest text; every problem is a nearshore::Error naming `source` (the
/// file), the key and the fix. Never crashes on malformed input (fuzzed).
SequenceManifest parse_manifest(std::string_view text, const std::string& source);

}  // namespace nearshore::sequence
