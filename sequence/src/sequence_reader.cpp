#include "nearshore/sequence/sequence_reader.hpp"

#include <fmt/core.h>

#include "exr_frame.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/sequence/checksum.hpp"

namespace nearshore::sequence {
namespace fs = std::filesystem;

SequenceReader::SequenceReader(const fs::path& folder) : folder_(folder) {
  std::error_code ec;
  const std::string fix = "give the folder a bake wrote, its BakeOptions::output_folder";
  if (!fs::exists(folder, ec)) throw Error(folder.string(), "does not exist", fix);
  if (!fs::is_directory(folder, ec)) throw Error(folder.string(), "is a file, not a sequence folder", fix);
  const fs::path manifest_path = folder / std::string(kManifestFile);
  if (!fs::exists(manifest_path, ec))
    throw Error(manifest_path.string(), "does not exist, so the bake never finished (the manifest is written last)",
                "finish the bake, or continue it with BakeOptions::resume");
  if (fs::is_directory(manifest_path, ec))
    throw Error(manifest_path.string(), "is a folder, not the manifest file a bake writes",
                "remove that folder, then bake the sequence again (or continue it with BakeOptions::resume)");
  const std::string text = read_file_bytes(manifest_path);
  manifest_ = parse_manifest(text, manifest_path.string());
}

fs::path SequenceReader::frame_path(int index) const {
  if (index < 0 || index >= manifest_.frame_count)
    throw Error(folder_.string(), fmt::format("frame {} requested but the sequence has frames 0..{}", index,
                                              manifest_.frame_count - 1),
                "ask for a frame inside the sequence");
  return folder_ / manifest_.frames[static_cast<std::size_t>(index)].file;
}

void SequenceReader::read_checked(const FileEntry& entry, Verify verify, FileBuffer& buffer) const {
  const fs::path path = folder_ / entry.file;
  read_file_into(path, buffer);
  if (verify == Verify::kYes) {
    if (buffer.size != entry.bytes)
      throw Error(path.string(), fmt::format("is {} bytes but the manifest says {} (truncated or replaced)",
                                             buffer.size, entry.bytes),
                  "re-bake the sequence or restore the file");
    const std::string checksum = checksum_text(buffer.bytes());
    if (checksum != entry.checksum)
      throw Error(path.string(), fmt::format("checksum {} does not match the manifest's {} (corrupt)", checksum,
                                             entry.checksum),
                  "re-bake the sequence or restore the file");
  }
}

Frame SequenceReader::read_frame(int index, ChannelSelection channels, Verify verify) const {
  Frame frame;
  read_frame_into(index, frame, channels, verify);
  return frame;
}

void SequenceReader::read_frame_into(int index, Frame& frame, ChannelSelection channels, Verify verify) const {
  const fs::path path = frame_path(index);
  thread_local FileBuffer buffer;  // one per decoding thread, reused frame after frame
  read_checked(manifest_.frames[static_cast<std::size_t>(index)], verify, buffer);
  decode_frame(buffer.bytes(), path.string(), manifest_, index, channels, frame);
}

void SequenceReader::read_frame_rows(int index, int first_row, int row_count, Frame& frame,
                                     ChannelSelection channels) const {
  detail::decode_frame_rows(frame_path(index), manifest_, index, first_row, row_count, channels, frame);
}

HarbourGrid SequenceReader::read_harbour_grid(Verify verify) const {
  const fs::path path = folder_ / manifest_.harbour_grid.file;
  if (verify == Verify::kYes) {
    FileBuffer buffer;
    read_checked(manifest_.harbour_grid, verify, buffer);
  }
  HarbourGrid grid = nearshore::read_harbour_grid(path);
  if (grid.geometry.columns != manifest_.geometry.columns || grid.geometry.rows != manifest_.geometry.rows)
    throw Error(path.string(), fmt::format("is {} x {} cells but the sequence is {} x {}", grid.geometry.columns,
                                           grid.geometry.rows, manifest_.geometry.columns, manifest_.geometry.rows),
                "the harbour grid was replaced; re-bake the sequence");
  return grid;
}

void SequenceReader::verify_checksums() const {
  ProgressBar progress("verifying checksums", manifest_.frame_count + 1.0, "files");
  FileBuffer buffer;
  read_checked(manifest_.harbour_grid, Verify::kYes, buffer);
  for (int index = 0; index < manifest_.frame_count; ++index) {
    read_checked(manifest_.frames[static_cast<std::size_t>(index)], Verify::kYes, buffer);
    progress.update(index + 2.0);
  }
  // The deep-water coefficient files the bake wrote beside the frames (manifest `deep_water`).
  if (manifest_.deep_water)
    for (const DeepWaterCascadeRecord& cascade : manifest_.deep_water->cascades)
      if (cascade.coefficients) read_checked(*cascade.coefficients, Verify::kYes, buffer);
  progress.finish();
}

}  // namespace nearshore::sequence
