// The geotiff export: wave_statistics.tif, the wave climate of the exported frames as a four-band
// float32 GeoTIFF (surface_statistics.hpp), and its band 1 as a map to look at (wave_height_map.cpp),
// the shoreline's swash cells (wet part of the frames only) marked on it.
#include <array>
#include <optional>
#include <limits>

#include <fmt/core.h>

#include "export_input.hpp"
#include "nearshore/core/geotiff_file.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/export/surface_statistics.hpp"

namespace nearshore::exports {

void write_geotiff(const ExportInput& input, ExportSummary& summary) {
  const GridGeometry& g = input.harbour.geometry;
  const std::filesystem::path path = input.output_folder / "wave_statistics.tif";
  if (g.crs_wkt.empty())
    summary.notes.push_back("the grid has no CRS (a laboratory frame): the GeoTIFF's coordinates are metres from "
                            "its south-west corner, without a spatial reference");

  // 1. The statistics over the frames, one frame in memory at a time; the wet test with the bake's
  // own dry depth (an older sequence without it in its solver record: every cell counted wet).
  const std::optional<double> dry_depth_m = input.reader.manifest().recorded_dry_depth_m();
  if (!dry_depth_m)
    summary.notes.push_back("the sequence's solver record has no dry_depth_m: wet_fraction is 1 everywhere and the "
                            "Hs map marks no swash cells");
  SurfaceStatistics statistics = dry_depth_m ? SurfaceStatistics(input.harbour.still_water_depth_m, *dry_depth_m)
                                             : SurfaceStatistics(g.columns, g.rows);
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
  std::array<Raster<float>, 4> bands = {statistics.significant_wave_height_m(), statistics.mean_surface_elevation_m(),
                                       statistics.breaking_fraction(), statistics.wet_fraction()};
  for (Raster<float>& band : bands)  // land is no data
    for (std::size_t cell = 0; cell < band.values().size(); ++cell)
      if (input.is_land(cell)) band.values()[cell] = std::numeric_limits<float>::quiet_NaN();

  // 2. The file (core/geotiff: north-up, the grid's CRS, land as kNoDataValue).
  GeoTiffContent content;
  content.no_data_value = kNoDataValue;
  content.bands = {{&bands[0], "significant_wave_height (Hs = 4 standard deviations of eta, m)", "m"},
                   {&bands[1], "mean_surface_elevation (time mean of eta above still water, m)", "m"},
                   {&bands[2], "breaking_fraction (time mean of the breaking indicator, 0..1)", "1"},
                   {&bands[3], "wet_fraction (fraction of the frames the cell held water; below 1: swash, Hs not a wave height)", "1"}};
  content.metadata = {{"NEARSHORE_SEQUENCE", input.reader.folder().string()},
                      {"NEARSHORE_FRAMES", fmt::format("{}:{}", input.first_frame, input.end_frame)},
                      {"NEARSHORE_FRAME_INTERVAL_S", fmt::format("{}", input.reader.frame_interval_s())},
                      {"NEARSHORE_DURATION_S", fmt::format("{}", input.frame_count() * input.reader.frame_interval_s())}};
  write_geotiff_file(path, g, content, "the statistics bands");
  record_file(summary, path);
  write_wave_height_map(input, bands[0], bands[3], times, summary);
}

}  // namespace nearshore::exports
