// The geotiff export: wave_statistics.tif, the wave climate of the exported frames as a three-band
// float32 GeoTIFF (surface_statistics.hpp), and its band 1 as a map to look at (wave_height_map.cpp).
// The only file of the export that includes GDAL.
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <array>
#include <vector>

#include <fmt/core.h>

#include "export_input.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/export/surface_statistics.hpp"

namespace nearshore::exports {

void write_geotiff(const ExportInput& input, ExportSummary& summary) {
  const GridGeometry& g = input.harbour.geometry;
  const std::filesystem::path path = input.output_folder / "wave_statistics.tif";
  if (g.crs_wkt.empty())
    summary.notes.push_back("the grid has no CRS (a laboratory frame): the GeoTIFF's coordinates are metres from "
                            "its south-west corner, without a spatial reference");

  // 1. The statistics over the frames, one frame in memory at a time.
  SurfaceStatistics statistics(g.columns, g.rows);
  ProgressBar progress("GeoTIFF statistics", input.frame_count(), "frames");
  sequence::Frame frame;
  FrameTimes times;
  for (int index = input.first_frame; index < input.end_frame; ++index) {
    input.reader.read_frame_into(index, frame, sequence::ChannelSelection::display());
    statistics.add_frame(frame.surface_elevation_m, frame.breaking);
    if (index == input.first_frame) times.first_s = frame.time_s;
    times.last_s = frame.time_s;
    progress.update(index - input.first_frame + 1.0);
  }
  progress.finish();
  const std::array<Raster<float>, 3> bands = {statistics.significant_wave_height_m(),
                                             statistics.mean_surface_elevation_m(), statistics.breaking_fraction()};
  struct BandText {
    const char* description;
    const char* unit;
  };
  constexpr std::array<BandText, 3> kBandTexts = {{
      {"significant_wave_height (Hs = 4 standard deviations of eta, m)", "m"},
      {"mean_surface_elevation (time mean of eta above still water, m)", "m"},
      {"breaking_fraction (time mean of the breaking indicator, 0..1)", "1"},
  }};

  // 2. The file: GeoTIFF stores the northern row first; land is nodata.
  auto fail = [&](const std::string& what) {
    return Error(path.string(), what + ": " + CPLGetLastErrorMsg(), "check that the output folder is writable and has space");
  };
  GDALAllRegister();
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    if (!driver) throw fail("GDAL has no GTiff driver");
    const char* options[] = {"COMPRESS=DEFLATE", "PREDICTOR=3", "INTERLEAVE=BAND", nullptr};
    GDALDataset* dataset = driver->Create(temporary.c_str(), g.columns, g.rows, static_cast<int>(bands.size()),
                                          GDT_Float32, const_cast<char**>(options));
    if (!dataset) throw fail("cannot create the GeoTIFF");
    double geotransform[6] = {g.origin_x_m, g.spacing_x_m(), 0.0, g.origin_y_m + g.height_m(), 0.0, -g.spacing_y_m()};
    dataset->SetGeoTransform(geotransform);
    if (!g.crs_wkt.empty()) {
      OGRSpatialReference crs;
      crs.importFromWkt(g.crs_wkt.c_str());
      dataset->SetSpatialRef(&crs);
    }
    dataset->SetMetadataItem("NEARSHORE_SEQUENCE", input.reader.folder().string().c_str());
    dataset->SetMetadataItem("NEARSHORE_FRAMES", fmt::format("{}:{}", input.first_frame, input.end_frame).c_str());
    dataset->SetMetadataItem("NEARSHORE_FRAME_INTERVAL_S", fmt::format("{}", input.reader.frame_interval_s()).c_str());
    dataset->SetMetadataItem("NEARSHORE_DURATION_S",
                             fmt::format("{}", input.frame_count() * input.reader.frame_interval_s()).c_str());
    std::vector<float> lines(g.cell_count());
    CPLErr written = CE_None;
    for (std::size_t b = 0; b < bands.size() && written == CE_None; ++b) {
      for (int row = 0; row < g.rows; ++row)
        for (int column = 0; column < g.columns; ++column) {
          const std::size_t cell = static_cast<std::size_t>(row) * g.columns + column;
          lines[static_cast<std::size_t>(g.rows - 1 - row) * g.columns + column] =
              input.is_land(cell) ? kNoDataValue : bands[b].values()[cell];
        }
      GDALRasterBand* band = dataset->GetRasterBand(static_cast<int>(b) + 1);
      band->SetNoDataValue(kNoDataValue);
      band->SetDescription(kBandTexts[b].description);
      band->SetUnitType(kBandTexts[b].unit);
      written = band->RasterIO(GF_Write, 0, 0, g.columns, g.rows, lines.data(), g.columns, g.rows, GDT_Float32, 0, 0);
    }
    CPLErrorReset();
    GDALClose(dataset);  // void in GDAL 3.6: failures surface through CPLGetLastErrorType
    if (written != CE_None || CPLGetLastErrorType() >= CE_Failure) throw fail("writing the statistics bands failed");
  });
  record_file(summary, path);
  write_wave_height_map(input, bands[0], times, summary);
}

}  // namespace nearshore::exports
