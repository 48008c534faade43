// The agitation export's GDAL side: reading the Hs the bake wrote (wave_statistics.tif band 2,
// docs/formats/wave-statistics.md) and writing agitation.tif. The bake owns the statistics' writer
// (bake/src/wave_statistics_geotiff.cpp); export reads the file as any GIS does, through GDAL,
// because the sequence folder is its only input.
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <limits>
#include <vector>

#include <fmt/core.h>

#include "export_input.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
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
  const GridGeometry& g = input.harbour.geometry;
  const auto fail = [&](const std::string& what) {
    return Error(path.string(), what + ": " + CPLGetLastErrorMsg(), "check that the output folder is writable and has space");
  };
  GDALAllRegister();
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    if (!driver) throw fail("GDAL has no GTiff driver");
    const char* options[] = {"COMPRESS=DEFLATE", "PREDICTOR=3", nullptr};
    GDALDataset* dataset = driver->Create(temporary.c_str(), g.columns, g.rows, 1, GDT_Float32, const_cast<char**>(options));
    if (!dataset) throw fail("cannot create the GeoTIFF");
    // Georeferenced as wave_statistics.tif and depth.tif: north-up, the grid's CRS.
    double geotransform[6] = {g.origin_x_m, g.spacing_x_m(), 0.0, g.origin_y_m + g.height_m(), 0.0, -g.spacing_y_m()};
    dataset->SetGeoTransform(geotransform);
    if (!g.crs_wkt.empty()) {
      OGRSpatialReference crs;
      crs.importFromWkt(g.crs_wkt.c_str());
      dataset->SetSpatialRef(&crs);
    }
    dataset->SetMetadataItem("NEARSHORE_SEQUENCE", input.reader.folder().string().c_str());
    dataset->SetMetadataItem("NEARSHORE_AGITATION", description.c_str());
    std::vector<float> lines(g.cell_count());
    for (int row = 0; row < g.rows; ++row)
      for (int column = 0; column < g.columns; ++column)
        lines[static_cast<std::size_t>(g.rows - 1 - row) * g.columns + column] =
            input.is_land(static_cast<std::size_t>(row) * g.columns + column) ? std::numeric_limits<float>::quiet_NaN()
                                                                                : coefficient(column, row);
    GDALRasterBand* band = dataset->GetRasterBand(1);
    band->SetNoDataValue(std::numeric_limits<double>::quiet_NaN());
    band->SetDescription("agitation_coefficient (Hs / incident Hs, 1)");
    band->SetUnitType("1");
    const CPLErr written =
        band->RasterIO(GF_Write, 0, 0, g.columns, g.rows, lines.data(), g.columns, g.rows, GDT_Float32, 0, 0);
    CPLErrorReset();
    GDALClose(dataset);  // void in GDAL 3.6: failures surface through CPLGetLastErrorType
    if (written != CE_None || CPLGetLastErrorType() >= CE_Failure) throw fail("writing the agitation band failed");
  });
}

}  // namespace nearshore::exports
