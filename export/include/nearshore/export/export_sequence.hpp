#pragma once
// export_sequence: a baked sequence (docs/formats/sequence.md) written as files that GIS, ocean and
// VFX tools open as they are (docs/commands/export.md). Four formats:
//   netcdf            sequence.nc: CF-1.8 NetCDF-4 with time, projected x/y, the grid mapping of the
//                     grid's CRS, 2-D lat/lon, surface elevation, fluxes, breaking, the still-water
//                     depth; land is _FillValue (QGIS, xarray, Panoply, GDAL).
//   geotiff           wave_statistics.tif: significant wave height, mean water level and breaking
//                     fraction over the frames as a georeferenced three-band GeoTIFF, land nodata;
//                     and wave_statistics_hs.png, Hs as a map to look at (axes in the grid's CRS,
//                     colour bar in metres, land and no data distinct, north arrow, scale bar).
//   exr-displacement  displacement_NNNNNN.exr per frame: RGB = x, y, z displacement in metres
//                     (x east, y north, z up), A = water; the horizontal part is the depth-averaged
//                     excursion integrated from the fluxes (horizontal_excursion.hpp).
//   vdb               surface_NNNNNN.vdb per frame: one height-field grid of the surface elevation
//                     (and one of breaking), land inactive.
//   agitation         agitation.tif: the disturbance coefficient Hs / Hs_incident (agitation.hpp) as a
//                     float32 GeoTIFF, NaN on land, and agitation.png (the map with axes, colour bar,
//                     land and structures); with berths, berths.csv (Hs and the coefficient at each).
// NNNNNN is the frame index in the sequence, so tools read the files as an image sequence. Every
// file is written atomically (temporary name, fsync, rename): an interrupted export leaves whole
// files of the frames it finished and never a damaged one. One writer per output folder (FolderLock).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace nearshore::exports {

enum class ExportFormat { kNetcdf, kGeotiff, kExrDisplacement, kVdb, kAgitation };

/// "netcdf", "geotiff", "exr-displacement", "vdb", "agitation".
std::string_view export_format_name(ExportFormat format);
/// The format of a name above; throws nearshore::Error listing the names for any other.
ExportFormat parse_export_format(std::string_view name);
/// Every format, in the order above.
std::vector<ExportFormat> all_export_formats();

/// Frames [first_frame, end_frame) of the sequence; end_frame = -1 means "to the last frame".
struct FrameRange {
  int first_frame = 0;
  int end_frame = -1;
};

/// What the agitation export takes besides the sequence (agitation.hpp).
struct AgitationOptions {
  /// Hs_incident of (1), metres (> 0); nullopt: the wave maker's, from the manifest.
  std::optional<double> incident_significant_wave_height_m;
  /// Berths to read the map at (read_berths: CSV or GeoJSON); empty: none.
  std::filesystem::path berths_file;
};

struct ExportRequest {
  std::filesystem::path sequence_folder;  ///< a complete baked sequence (its manifest.json exists)
  std::filesystem::path output_folder;    ///< created if missing; files of the same names are replaced
  ExportFormat format = ExportFormat::kNetcdf;
  FrameRange frames;                      ///< which frames to export
  AgitationOptions agitation{};           ///< the agitation format's inputs ({}: no aggregate warning where it is left out)
};

struct ExportedFile {
  std::filesystem::path file;
  std::uintmax_t bytes = 0;
};

struct ExportSummary {
  std::filesystem::path sequence_folder, output_folder;
  ExportFormat format = ExportFormat::kNetcdf;
  int first_frame = 0, end_frame = 0;  ///< the frames exported, [first, end)
  double frame_interval_s = 0.0;
  std::vector<ExportedFile> files;     ///< in the order written
  double seconds = 0.0;                ///< wall time of the export
  /// What the horizontal displacement of an exr-displacement export is ("depth-averaged excursion
  /// ..." or "zero: ..." with the reason); empty for the other formats.
  std::string horizontal_displacement;
  std::vector<std::string> notes;      ///< what a user should know about the output (e.g. no CRS)
  /// The agitation format's numbers: {"incident_significant_wave_height_m", "incident_source",
  /// "significant_wave_height_source", "berths": [berth_value_json...]}; null for the others.
  nlohmann::json agitation;

  std::uintmax_t total_bytes() const;
  /// {"sequence", "output", "format", "frames": {"first", "end", "count"}, "files": [{"file",
  /// "bytes"}], "total_bytes", "seconds", "horizontal_displacement", "notes"[, "agitation"]}.
  nlohmann::json to_json() const;
};

/// Writes the request's format. Shows a ProgressBar with ETA on stderr (ProgressBar::set_quiet
/// silences it). Throws nearshore::Error naming the sequence or the file at fault: an unfinished
/// sequence, a frame range outside the sequence (ExportRequest::frames), an output folder that is
/// not writable or locked by another writer, a failed write.
ExportSummary export_sequence(const ExportRequest& request);

}  // namespace nearshore::exports
