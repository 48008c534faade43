#pragma once
// What every format's writer is given (private to nearshore_export): the open sequence, its
// harbour grid (the land mask), the frames to write and where, and the summary to add files to.
#include <filesystem>
#include <string>
#include <vector>

#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/export/agitation.hpp"
#include "nearshore/export/export_sequence.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::exports {

/// Land cells hold no water surface in any export: nodata in GIS files, inactive or zero in VFX
/// files. The frames hold the terrain height there, which is not a water level.
inline constexpr float kNoDataValue = -9999.0f;

struct ExportInput {
  const sequence::SequenceReader& reader;
  const HarbourGrid& harbour;
  int first_frame = 0, end_frame = 0;
  std::filesystem::path output_folder;
  AgitationOptions agitation;  ///< the agitation format's inputs (ExportRequest::agitation)

  int frame_count() const { return end_frame - first_frame; }
  bool is_land(std::size_t cell) const { return harbour.land.values()[cell] != 0; }
  /// "surface_000123.vdb": one file per frame, numbered by the frame's index in the sequence.
  std::filesystem::path frame_file(const std::string& stem, int frame_index, const std::string& extension) const;
};

/// Records `file` (written) with its size in `summary`.
void record_file(ExportSummary& summary, const std::filesystem::path& file);

void write_netcdf(const ExportInput& input, ExportSummary& summary);
void write_geotiff(const ExportInput& input, ExportSummary& summary);
void write_exr_displacement(const ExportInput& input, ExportSummary& summary);
void write_vdb(const ExportInput& input, ExportSummary& summary);
void write_agitation(const ExportInput& input, ExportSummary& summary);

/// agitation.tif: the coefficient as a one-band float32 GeoTIFF, NaN on land, georeferenced as
/// wave_statistics.tif (agitation_files.cpp, which includes GDAL).
void write_agitation_geotiff(const ExportInput& input, const Raster<float>& coefficient, const std::string& description,
                             const std::filesystem::path& path);
/// agitation.png: the coefficient as a map with the berths marked (agitation_map.cpp).
void write_agitation_map(const ExportInput& input, const Raster<float>& coefficient, const std::string& subtitle,
                         const std::vector<BerthValue>& berths, const std::filesystem::path& path);

/// The simulated times of the first and last exported frame, seconds (the bake's clock).
struct FrameTimes {
  double first_s = 0.0, last_s = 0.0;
};
/// wave_statistics_hs.png: `hs_m` (the GeoTIFF's band 1) as a map with axes, the water cells whose
/// `wet_fraction` (band 4) is below 1 drawn as swash (wave_height_map.cpp); the geotiff export writes
/// it beside the GeoTIFF.
void write_wave_height_map(const ExportInput& input, const Raster<float>& hs_m, const Raster<float>& wet_fraction,
                           const FrameTimes& times, ExportSummary& summary);

}  // namespace nearshore::exports
