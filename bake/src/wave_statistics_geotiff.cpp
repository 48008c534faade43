// DIR/wave_statistics.tif: the bake's wave statistics (wave_statistics.hpp) as a four-band float32
// GeoTIFF that QGIS and GDAL open (docs/formats/wave-statistics.md). With
// wave_statistics_geojson.cpp (the run-up line as lines), the only file of bake/ that includes GDAL.
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <array>
#include <cmath>
#include <vector>

#include <fmt/core.h>

#include "nearshore/bake/wave_statistics.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bake {

void write_wave_statistics_geotiff(const std::filesystem::path& path, const WaveStatistics& statistics,
                                   const GridGeometry& geometry, double first_time_s, double last_time_s) {
  // The value GIS tools take for "no value": NaN is legal in a float GeoTIFF but many tools (and
  // QGIS's statistics) handle an explicit nodata value better. -9999 m is no water level on Earth.
  constexpr float kNoData = -9999.0f;
  struct Band {
    Raster<float> values;
    const char* description;
  };
  const std::array<Band, 4> bands = {{
      {statistics.maximum_surface_elevation_m(),
       "maximum_surface_elevation (envelope of eta while wet over every step after spin-up, m above still water)"},
      {statistics.significant_wave_height_m(), "significant_wave_height (Hs = 4 standard deviations of eta, m)"},
      {statistics.mean_surface_elevation_m(), "mean_surface_elevation (time mean of eta above still water, m)"},
      {statistics.runup_line_water_level_m(),
       "runup_line_water_level (highest water level on the wet/dry front at its furthest reach, m above still water)"},
  }};
  const auto fail = [&](const std::string& what) {
    return Error(path.string(), what + ": " + CPLGetLastErrorMsg(), "check that the output folder is writable and has space");
  };
  GDALAllRegister();
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    if (!driver) throw fail("GDAL has no GTiff driver");
    const char* options[] = {"COMPRESS=DEFLATE", "PREDICTOR=3", "INTERLEAVE=BAND", nullptr};
    GDALDataset* dataset = driver->Create(temporary.c_str(), geometry.columns, geometry.rows, static_cast<int>(bands.size()),
                                          GDT_Float32, const_cast<char**>(options));
    if (!dataset) throw fail("cannot create the GeoTIFF");
    // North-up: the first line is the northern row (raster row rows - 1), as in depth.tif.
    double geotransform[6] = {geometry.origin_x_m, geometry.spacing_x_m(), 0.0,
                              geometry.origin_y_m + geometry.height_m(), 0.0, -geometry.spacing_y_m()};
    dataset->SetGeoTransform(geotransform);
    if (!geometry.crs_wkt.empty()) {
      OGRSpatialReference crs;
      crs.importFromWkt(geometry.crs_wkt.c_str());
      dataset->SetSpatialRef(&crs);
    }
    dataset->SetMetadataItem("NEARSHORE_STATISTICS", "bake: every solver step after spin-up");
    dataset->SetMetadataItem("NEARSHORE_STEPS", fmt::format("{}", statistics.step_count()).c_str());
    dataset->SetMetadataItem("NEARSHORE_TIME_S", fmt::format("{}:{}", first_time_s, last_time_s).c_str());
    if (const auto runup = statistics.highest_runup()) {
      dataset->SetMetadataItem("NEARSHORE_RUNUP_M", fmt::format("{}", runup->water_level_m).c_str());
      dataset->SetMetadataItem("NEARSHORE_RUNUP_X_M", fmt::format("{}", runup->x_m).c_str());
      dataset->SetMetadataItem("NEARSHORE_RUNUP_Y_M", fmt::format("{}", runup->y_m).c_str());
    }
    std::vector<float> lines(geometry.cell_count());
    CPLErr written = CE_None;
    for (std::size_t b = 0; b < bands.size() && written == CE_None; ++b) {
      for (int row = 0; row < geometry.rows; ++row)
        for (int column = 0; column < geometry.columns; ++column) {
          const float value = bands[b].values(column, row);
          lines[static_cast<std::size_t>(geometry.rows - 1 - row) * geometry.columns + column] =
              std::isnan(value) ? kNoData : value;
        }
      GDALRasterBand* band = dataset->GetRasterBand(static_cast<int>(b) + 1);
      band->SetNoDataValue(kNoData);
      band->SetDescription(bands[b].description);
      band->SetUnitType("m");
      written = band->RasterIO(GF_Write, 0, 0, geometry.columns, geometry.rows, lines.data(), geometry.columns,
                               geometry.rows, GDT_Float32, 0, 0);
    }
    CPLErrorReset();
    GDALClose(dataset);  // void in GDAL 3.6: failures surface through CPLGetLastErrorType
    if (written != CE_None || CPLGetLastErrorType() >= CE_Failure) throw fail("writing the statistics bands failed");
  });
}

}  // namespace nearshore::bake
