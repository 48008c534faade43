#include "nearshore/export/export_sequence.hpp"

#include <array>
#include <chrono>

#include <fmt/core.h>

#include "export_input.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/output_folder.hpp"
#include "nearshore/core/folder_lock.hpp"

namespace nearshore::exports {
namespace {

struct FormatEntry {
  ExportFormat format;
  std::string_view name;
  void (*write)(const ExportInput&, ExportSummary&);
};

// The one table from a format's name to its writer.
constexpr std::array<FormatEntry, 5> kFormats = {{
    {ExportFormat::kNetcdf, "netcdf", write_netcdf},
    {ExportFormat::kGeotiff, "geotiff", write_geotiff},
    {ExportFormat::kExrDisplacement, "exr-displacement", write_exr_displacement},
    {ExportFormat::kVdb, "vdb", write_vdb},
    {ExportFormat::kAgitation, "agitation", write_agitation},
}};

const FormatEntry& entry_of(ExportFormat format) {
  for (const FormatEntry& entry : kFormats)
    if (entry.format == format) return entry;
  throw Error("ExportRequest::format", "is not one of the export formats", "use netcdf, geotiff, exr-displacement, vdb or agitation");
}

}  // namespace

std::string_view export_format_name(ExportFormat format) { return entry_of(format).name; }

ExportFormat parse_export_format(std::string_view name) {
  for (const FormatEntry& entry : kFormats)
    if (entry.name == name) return entry.format;
  throw Error("ExportRequest::format", fmt::format("'{}' is not an export format", name),
              "use netcdf, geotiff, exr-displacement, vdb or agitation");
}

std::vector<ExportFormat> all_export_formats() {
  std::vector<ExportFormat> formats;
  for (const FormatEntry& entry : kFormats) formats.push_back(entry.format);
  return formats;
}

std::filesystem::path ExportInput::frame_file(const std::string& stem, int frame_index, const std::string& extension) const {
  return output_folder / fmt::format("{}_{:06d}.{}", stem, frame_index, extension);
}

void record_file(ExportSummary& summary, const std::filesystem::path& file) {
  summary.files.push_back({file, std::filesystem::file_size(file)});
}

std::uintmax_t ExportSummary::total_bytes() const {
  std::uintmax_t total = 0;
  for (const ExportedFile& file : files) total += file.bytes;
  return total;
}

nlohmann::json ExportSummary::to_json() const {
  nlohmann::json listed = nlohmann::json::array();
  for (const ExportedFile& file : files) listed.push_back({{"file", file.file.string()}, {"bytes", file.bytes}});
  nlohmann::json summary = {{"sequence", sequence_folder.string()},
          {"output", output_folder.string()},
          {"format", export_format_name(format)},
          {"frames", {{"first", first_frame}, {"end", end_frame}, {"count", end_frame - first_frame}}},
          {"frame_interval_s", frame_interval_s},
          {"files", listed},
          {"total_bytes", total_bytes()},
          {"seconds", seconds},
          {"horizontal_displacement", horizontal_displacement},
          {"notes", notes}};
  if (!agitation.is_null()) summary["agitation"] = agitation;
  return summary;
}

ExportSummary export_sequence(const ExportRequest& request) {
  const auto start = std::chrono::steady_clock::now();
  const sequence::SequenceReader reader(request.sequence_folder);
  const int frame_count = reader.frame_count();
  const int first = request.frames.first_frame;
  const int end = request.frames.end_frame < 0 ? frame_count : request.frames.end_frame;
  if (first < 0 || end > frame_count || end <= first)
    throw Error(request.sequence_folder.string(),
                fmt::format("ExportRequest::frames = [{}, {}) is not a range of frames of this sequence, which has "
                            "frames 0 .. {}",
                            first, end, frame_count - 1),
                fmt::format("choose 0 <= first < end <= {}", frame_count));
  const HarbourGrid harbour = reader.read_harbour_grid();

  // Never into the sequence itself (the GeoTIFF would replace the bake's own wave_statistics.tif,
  // statistics of every solver step that no frame can rebuild), nor into another command's outputs.
  check_output_folder(request.output_folder, OutputKind::kNone, false,
                      {{request.sequence_folder, "the sequence being exported (ExportRequest::sequence_folder)"}},
                      "ExportRequest::output_folder", "");
  create_output_folder(request.output_folder);
  const FolderLock lock(request.output_folder, "exporting " + request.sequence_folder.string());
  remove_stale_temporary_files(request.output_folder);

  ExportSummary summary;
  summary.sequence_folder = request.sequence_folder;
  summary.output_folder = request.output_folder;
  summary.format = request.format;
  summary.first_frame = first;
  summary.end_frame = end;
  summary.frame_interval_s = reader.frame_interval_s();
  const ExportInput input{reader, harbour, first, end, request.output_folder, request.agitation};
  entry_of(request.format).write(input, summary);
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace nearshore::exports
