#include "nearshore/sequence/sequence_writer.hpp"

#include <cmath>
#include <map>
#include <mutex>
#include <string_view>

#include <fmt/core.h>

#include "exr_frame.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "nearshore/sequence/loops_file.hpp"

namespace nearshore::sequence {
namespace fs = std::filesystem;
namespace {

FileEntry entry_for(const std::string& name, std::span<const std::byte> bytes) {
  return FileEntry{name, bytes.size(), checksum_text(bytes)};
}

FileEntry entry_for_file(const fs::path& path) {
  const std::string bytes = read_file_bytes(path);
  return entry_for(path.filename().string(), std::as_bytes(std::span(bytes.data(), bytes.size())));
}

// Index of a frame file name ("frame_000123.exr" -> 123), or -1.
int frame_index_of(const std::string& name) {
  constexpr std::string_view prefix = "frame_", suffix = ".exr";
  if (name.size() < prefix.size() + 6 + suffix.size() || name.size() > prefix.size() + 9 + suffix.size() ||
      name.rfind(prefix, 0) != 0 || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return -1;
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::stoi(digits);
}

}  // namespace

struct SequenceWriter::Impl {
  fs::path folder;
  SequenceManifest manifest;  // everything but the frame list, filled at construction
  std::mutex mutex;
  std::map<int, FileEntry> written;  // frames written by this writer
  bool resume = false;
};

SequenceWriter::SequenceWriter(const fs::path& folder, const HarbourGrid& harbour, SequenceDescription description,
                               bool resume)
    : impl_(std::make_unique<Impl>()) {
  const GridGeometry& geometry = harbour.geometry;
  if (geometry.columns <= 0 || geometry.rows <= 0 || harbour.still_water_depth_m.columns() != geometry.columns ||
      harbour.still_water_depth_m.rows() != geometry.rows)
    throw Error(folder.string(), fmt::format("the harbour grid is {} x {} cells but its depth raster is {} x {}",
                                             geometry.columns, geometry.rows, harbour.still_water_depth_m.columns(),
                                             harbour.still_water_depth_m.rows()),
                "pass the grid read with read_harbour_grid()");
  if (!(description.frame_interval_s > 0) || !std::isfinite(description.frame_interval_s))
    throw Error(folder.string(), fmt::format("frame interval is {} s", description.frame_interval_s),
                "set SequenceDescription::frame_interval_s > 0 (the bake's output interval)");
  if (!(description.loop_period_s >= 0) || !std::isfinite(description.first_frame_time_s))
    throw Error(folder.string(), fmt::format("loop period {} s / first frame time {} s", description.loop_period_s,
                                             description.first_frame_time_s),
                "use loop_period_s = 0 for a non-periodic bake and a finite first frame time");
  create_output_folder(folder);
  Impl& impl = *impl_;
  impl.folder = folder;
  impl.resume = resume;
  // The sequence is being (re)written: it must not look complete, and old loop tables no longer
  // describe its frames. Without resume, frames of an earlier bake go too.
  std::error_code ignored;
  for (const std::string_view stale : {kManifestFile, std::string_view(kLoopsFileName), std::string_view(kLoopsGramFileName)})
    fs::remove(folder / stale, ignored);
  if (!resume)
    for (const auto& item : fs::directory_iterator(folder, ignored))
      if (frame_index_of(item.path().filename().string()) >= 0) fs::remove(item.path(), ignored);

  SequenceManifest& manifest = impl.manifest;
  manifest.geometry = geometry;
  manifest.frame_interval_s = description.frame_interval_s;
  manifest.first_frame_time_s = description.first_frame_time_s;
  manifest.loop_period_s = description.loop_period_s;
  manifest.seed = description.seed;
  manifest.encoding = description.encoding;
  manifest.wave_conditions = std::move(description.wave_conditions);
  manifest.deep_water = std::move(description.deep_water);
  manifest.solver = std::move(description.solver);
  const fs::path harbour_path = folder / std::string(kHarbourGridFile);
  write_harbour_grid(harbour_path, harbour);
  manifest.harbour_grid = entry_for_file(harbour_path);
}

SequenceWriter::~SequenceWriter() = default;

void SequenceWriter::write_frame(int index, const FrameFields& fields) {
  Impl& impl = *impl_;
  const GridGeometry& geometry = impl.manifest.geometry;
  const fs::path path = impl.folder / frame_file_name(index);
  if (index < 0 || index > 99'999'999)
    throw Error(path.string(), fmt::format("frame index {} is outside 0..99999999", index), "number frames from 0");
  const std::array<const Raster<float>*, 4> channels = {fields.surface_elevation_m, fields.flux_x_m2_s,
                                                        fields.flux_y_m2_s, fields.breaking};
  for (int c = 0; c < 4; ++c) {
    const Raster<float>* raster = channels[c];
    if (!raster) {
      if (c == 3) continue;  // no breaking indicator: stored as zeros
      throw Error(path.string(), fmt::format("frame {} has no {} field", index, kChannelNames[c]),
                  "pass surface elevation, flux x and flux y in FrameFields");
    }
    if (raster->columns() != geometry.columns || raster->rows() != geometry.rows)
      throw Error(path.string(), fmt::format("frame {}: {} is {} x {} but the harbour grid is {} x {}", index,
                                             kChannelNames[c], raster->columns(), raster->rows(), geometry.columns,
                                             geometry.rows),
                  "interpolate the fields to the grid's cell centres before writing");
    // A NaN here means the solver blew up: stop before it poisons the sequence.
    for (int row = 0; row < geometry.rows; ++row)
      for (int column = 0; column < geometry.columns; ++column)
        if (!std::isfinite((*raster)(column, row)))
          throw Error(path.string(),
                      fmt::format("frame {}: {} is {} at cell ({}, {}) (x={:.1f} m, y={:.1f} m)", index,
                                  kChannelNames[c], (*raster)(column, row), column, row,
                                  geometry.cell_centre_x_m(column), geometry.cell_centre_y_m(row)),
                      "the solver went unstable there: reduce the time step or check the depth");
  }
  const std::string bytes = detail::encode_frame(geometry, impl.manifest.encoding, index,
                                                 impl.manifest.frame_time_s(index), channels);
  const auto byte_span = std::as_bytes(std::span(bytes.data(), bytes.size()));
  write_bytes_atomically(path, byte_span);
  FileEntry entry = entry_for(path.filename().string(), byte_span);
  std::lock_guard lock(impl.mutex);
  impl.written[index] = std::move(entry);
}

void SequenceWriter::finish(int frame_count) {
  Impl& impl = *impl_;
  std::lock_guard lock(impl.mutex);
  const fs::path manifest_path = impl.folder / std::string(kManifestFile);
  if (frame_count < 1)
    throw Error(manifest_path.string(), fmt::format("finish() was given {} frames", frame_count),
                "write at least one frame before finishing");
  SequenceManifest manifest = impl.manifest;
  manifest.frame_count = frame_count;
  manifest.frames.reserve(static_cast<std::size_t>(frame_count));
  for (int index = 0; index < frame_count; ++index) {
    if (auto it = impl.written.find(index); it != impl.written.end()) {
      manifest.frames.push_back(it->second);
      continue;
    }
    const fs::path path = impl.folder / frame_file_name(index);
    std::error_code ec;
    if (!impl.resume || !fs::is_regular_file(path, ec))
      throw Error(path.string(), fmt::format("frame {} of {} was never written", index, frame_count),
                  impl.resume ? "resume the bake from an earlier checkpoint" : "write every frame before finish()");
    manifest.frames.push_back(entry_for_file(path));  // kept from the interrupted run
  }
  // Frames beyond the end (from a longer earlier run) are not part of this sequence.
  std::error_code ignored;
  for (const auto& item : fs::directory_iterator(impl.folder, ignored))
    if (frame_index_of(item.path().filename().string()) >= frame_count) fs::remove(item.path(), ignored);
  write_text_atomically(manifest_path, manifest_to_json(manifest).dump(1));
}

}  // namespace nearshore::sequence
