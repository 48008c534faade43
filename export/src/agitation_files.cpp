// The agitation export's GDAL side: reading the Hs the bake wrote (wave_statistics.tif band 2,
// docs/formats/wave-statistics.md) and writing agitation.tif (through core/geotiff). The bake owns the statistics' writer
// (bake/src/wave_statistics_geotiff.cpp); export reads the file as any GIS does, through GDAL,
// because the sequence folder is its only input.
#include <gdal_priv.h>

#include <cmath>
#include <limits>
#include <vector>

#include <fmt/core.h>

#include "export_input.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/geotiff_file.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/export/agitation.hpp"
#include "nearshore/export/surface_statistics.hpp"

namespace nearshore::exports {
namespace {

constexpr const char* kBakeStatisticsFile = "wave_statistics.tif";
constexpr int kBakeHsBand = 2;  // docs/formats/wave-statistics.md: band 2 significant_wave_height

// Band 2 of the bake's wave_statistics.tif in the core's row order (row 0 south), NaN where the
// file has nodata or the grid has land; the number of steps it covers (NEARSHORE_STEPS).
Raster<float> read_bake_significant_wave_height(const std::filesystem::path& path, const HarbourGrid& harbour,
                                                std::string& steps) {
  const GridGeometry& g = harbour.geometry;
  GDALAllRegister();
  GDALDataset* dataset = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly));
  if (!dataset)
    throw Error(path.string(), std::string("cannot be read: ") + CPLGetLastErrorMsg(),
                "bake the sequence again (the bake writes it before its manifest), or export --frames to use the frames");
  struct Closer {
    GDALDataset* dataset;
    ~Closer() { GDALClose(dataset); }
  } closer{dataset};
  if (dataset->GetRasterXSize() != g.columns || dataset->GetRasterYSize() != g.rows || dataset->GetRasterCount() < kBakeHsBand)
    throw Error(path.string(),
                fmt::format("is {} x {} cells with {} bands, but the sequence's grid is {} x {} and the file has Hs in band {}",
                            dataset->GetRasterXSize(), dataset->GetRasterYSize(), dataset->GetRasterCount(), g.columns,
                            g.rows, kBakeHsBand),
                "it belongs to another bake: bake the sequence again");
  GDALRasterBand* band = dataset->GetRasterBand(kBakeHsBand);
  int has_no_data = 0;
  const double no_data = band->GetNoDataValue(&has_no_data);
  std::vector<float> lines(g.cell_count());
  if (band->RasterIO(GF_Read, 0, 0, g.columns, g.rows, lines.data(), g.columns, g.rows, GDT_Float32, 0, 0) != CE_None)
    throw Error(path.string(), std::string("band 2 cannot be read: ") + CPLGetLastErrorMsg(), "bake the sequence again");
  if (const char* value = dataset->GetMetadataItem("NEARSHORE_STEPS")) steps = value;
  Raster<float> hs(g.columns, g.rows, std::numeric_limits<float>::quiet_NaN());
  for (int row = 0; row < g.rows; ++row)
    for (int column = 0; column < g.columns; ++column) {
      // GeoTIFF stores the northern row first (core/raster.hpp: the readers and writers flip).
      const float value = lines[static_cast<std::size_t>(g.rows - 1 - row) * g.columns + column];
      const bool missing = !std::isfinite(value) || (has_no_data && value == static_cast<float>(no_data));
      if (!missing && harbour.land(column, row) == kWaterCell) hs(column, row) = value;
    }
  return hs;
}

}  // namespace

SignificantWaveHeight sequence_significant_wave_height(const sequence::SequenceReader& reader, const HarbourGrid& harbour,
                                                       int first_frame, int end_frame) {
  const GridGeometry& g = harbour.geometry;
  const std::filesystem::path bake_file = reader.folder() / kBakeStatisticsFile;
  SignificantWaveHeight result;
  if (first_frame == 0 && end_frame == reader.frame_count() && std::filesystem::is_regular_file(bake_file)) {
    std::string steps = "?";
    result.significant_wave_height_m = read_bake_significant_wave_height(bake_file, harbour, steps);
    result.source = fmt::format("the bake's statistics over every solver step after spin-up ({}, {} steps)",
                                kBakeStatisticsFile, steps);
    return result;
  }
  // The frames: 4 standard deviations of eta (surface_statistics.hpp), one frame in memory at a time.
  SurfaceStatistics statistics(g.columns, g.rows);
  ProgressBar progress("agitation statistics", end_frame - first_frame, "frames");
  sequence::Frame frame;
  for (int index = first_frame; index < end_frame; ++index) {
    reader.read_frame_into(index, frame, sequence::ChannelSelection::display());
    statistics.add_frame(frame.surface_elevation_m, frame.breaking);
    progress.update(index - first_frame + 1.0);
  }
  progress.finish();
  result.significant_wave_height_m = statistics.significant_wave_height_m();
  for (std::size_t cell = 0; cell < result.significant_wave_height_m.size(); ++cell)
    if (harbour.land.values()[cell] != kWaterCell)
      result.significant_wave_height_m.values()[cell] = std::numeric_limits<float>::quiet_NaN();
  result.source = fmt::format("4 standard deviations of eta over frames {}-{} ({} frames, {:.1f} s)", first_frame,
                              end_frame - 1, end_frame - first_frame, (end_frame - first_frame) * reader.frame_interval_s());
  return result;
}

void write_agitation_geotiff(const ExportInput& input, const Raster<float>& coefficient, const std::string& description,
                             const std::filesystem::path& path) {
  Raster<float> values = coefficient;  // land is no data (NaN), as in wave_statistics.tif and depth.tif
  for (std::size_t cell = 0; cell < values.values().size(); ++cell)
    if (input.is_land(cell)) values.values()[cell] = std::numeric_limits<float>::quiet_NaN();
  GeoTiffContent content;
  content.no_data_value = std::numeric_limits<float>::quiet_NaN();
  content.bands = {{&values, "agitation_coefficient (Hs / incident Hs, 1)", "1"}};
  content.metadata = {{"NEARSHORE_SEQUENCE", input.reader.folder().string()}, {"NEARSHORE_AGITATION", description}};
  write_geotiff_file(path, input.harbour.geometry, content, "the agitation band");
}

}  // namespace nearshore::exports
