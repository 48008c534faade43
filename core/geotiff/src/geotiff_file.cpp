#include "nearshore/core/geotiff_file.hpp"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cmath>

#include <fmt/core.h>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore {

void write_geotiff_file(const std::filesystem::path& path, const GridGeometry& g, const GeoTiffContent& content,
                        std::string_view what) {
  const auto fail = [&](const std::string& problem) {
    return Error(path.string(), problem + ": " + CPLGetLastErrorMsg(), "check that the output folder is writable and has space");
  };
  for (const GeoTiffBand& band : content.bands)
    if (!band.values || band.values->columns() != g.columns || band.values->rows() != g.rows)
      throw Error(path.string(), fmt::format("GeoTiffBand '{}' is not a {} x {} raster of the grid", band.description, g.columns, g.rows),
                  "give each band a raster of the grid's size");
  GDALAllRegister();
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    if (!driver) throw fail("GDAL has no GTiff driver");
    const char* options[] = {"COMPRESS=DEFLATE", "PREDICTOR=3", "INTERLEAVE=BAND", nullptr};
    GDALDataset* dataset = driver->Create(temporary.c_str(), g.columns, g.rows, static_cast<int>(content.bands.size()),
                                          GDT_Float32, const_cast<char**>(options));
    if (!dataset) throw fail("cannot create the GeoTIFF");
    // North-up; GDAL's pixel size per axis (rectangular cells write dx and -dy).
    double geotransform[6] = {g.origin_x_m, g.spacing_x_m(), 0.0, g.origin_y_m + g.height_m(), 0.0, -g.spacing_y_m()};
    dataset->SetGeoTransform(geotransform);
    if (!g.crs_wkt.empty()) {
      OGRSpatialReference crs;
      crs.importFromWkt(g.crs_wkt.c_str());
      dataset->SetSpatialRef(&crs);
    }
    for (const auto& [key, value] : content.metadata) dataset->SetMetadataItem(key.c_str(), value.c_str());
    std::vector<float> lines(g.cell_count());
    CPLErr written = CE_None;
    for (std::size_t b = 0; b < content.bands.size() && written == CE_None; ++b) {
      const Raster<float>& values = *content.bands[b].values;
      for (int row = 0; row < g.rows; ++row)  // GeoTIFF line 0 is the NORTHERN row
        for (int column = 0; column < g.columns; ++column) {
          const float value = values(column, row);
          lines[static_cast<std::size_t>(g.rows - 1 - row) * g.columns + column] = std::isnan(value) ? content.no_data_value : value;
        }
      GDALRasterBand* band = dataset->GetRasterBand(static_cast<int>(b) + 1);
      band->SetNoDataValue(content.no_data_value);
      band->SetDescription(content.bands[b].description.c_str());
      band->SetUnitType(content.bands[b].unit.c_str());
      written = band->RasterIO(GF_Write, 0, 0, g.columns, g.rows, lines.data(), g.columns, g.rows, GDT_Float32, 0, 0);
    }
    CPLErrorReset();
    GDALClose(dataset);  // void in GDAL 3.6: failures surface through CPLGetLastErrorType
    if (written != CE_None || CPLGetLastErrorType() >= CE_Failure) throw fail(fmt::format("writing {} failed", what));
  });
}

}  // namespace nearshore
