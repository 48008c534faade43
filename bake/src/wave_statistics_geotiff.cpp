// DIR/wave_statistics.tif: the bake's wave statistics (wave_statistics.hpp) as a four-band float32
// GeoTIFF that QGIS and GDAL open (docs/formats/wave-statistics.md), written by core/geotiff as
// every GeoTIFF of the project is.
#include <fmt/core.h>

#include "nearshore/bake/wave_statistics.hpp"
#include "nearshore/core/geotiff_file.hpp"

namespace nearshore::bake {

void write_wave_statistics_geotiff(const std::filesystem::path& path, const WaveStatistics& statistics,
                                   const GridGeometry& geometry, double first_time_s, double last_time_s) {
  const Raster<float> envelope = statistics.maximum_surface_elevation_m(), hs = statistics.significant_wave_height_m(),
                      mean = statistics.mean_surface_elevation_m(), runup = statistics.runup_line_water_level_m();
  GeoTiffContent content;  // NaN (never wet, no run-up) is no data: -9999 m, no water level on Earth
  content.bands = {
      {&envelope, "maximum_surface_elevation (envelope of eta while wet over every step after spin-up, m above still water)", "m"},
      {&hs, "significant_wave_height (Hs = 4 standard deviations of eta, m)", "m"},
      {&mean, "mean_surface_elevation (time mean of eta above still water, m)", "m"},
      {&runup, "runup_line_water_level (highest water level on the wet/dry front at its furthest reach, m above still water)", "m"},
  };
  content.metadata = {{"NEARSHORE_STATISTICS", "bake: every solver step after spin-up"},
                      {"NEARSHORE_STEPS", fmt::format("{}", statistics.step_count())},
                      {"NEARSHORE_TIME_S", fmt::format("{}:{}", first_time_s, last_time_s)}};
  if (const auto highest = statistics.highest_runup()) {
    content.metadata.emplace_back("NEARSHORE_RUNUP_M", fmt::format("{}", highest->water_level_m));
    content.metadata.emplace_back("NEARSHORE_RUNUP_X_M", fmt::format("{}", highest->x_m));
    content.metadata.emplace_back("NEARSHORE_RUNUP_Y_M", fmt::format("{}", highest->y_m));
  }
  write_geotiff_file(path, geometry, content, "the statistics bands");
}

}  // namespace nearshore::bake
