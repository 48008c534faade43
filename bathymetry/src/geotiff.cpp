#include "nearshore/bathymetry/geotiff.hpp"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <vector>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bathymetry {

void write_depth_geotiff(const std::filesystem::path& path, const GridGeometry& g, const Raster<float>& depth_m,
                         const std::string& vertical_datum) {
  constexpr double kNoData = -9999.0;
  const int columns = g.columns, rows = g.rows;
  std::vector<float> lines(static_cast<std::size_t>(columns) * rows);
  for (int row = 0; row < rows; ++row)  // GeoTIFF line 0 is the NORTHERN row
    for (int column = 0; column < columns; ++column) {
      const float d = depth_m(column, row);
      lines[static_cast<std::size_t>(rows - 1 - row) * columns + column] = std::isnan(d) ? float(kNoData) : d;
    }
  auto fail = [&](const std::string& what) {
    return Error(path.string(), what + ": " + CPLGetLastErrorMsg(), "check the output folder is writable and has space");
  };
  GDALAllRegister();
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    if (!driver) throw fail("GDAL has no GTiff driver");
    const char* options[] = {"COMPRESS=DEFLATE", "PREDICTOR=3", nullptr};
    GDALDataset* dataset = driver->Create(temporary.c_str(), columns, rows, 1, GDT_Float32, const_cast<char**>(options));
    if (!dataset) throw fail("cannot create GeoTIFF");
    // GDAL's pixel size per axis: rectangular cells (issue 15) write dx and -dy.
    double geotransform[6] = {g.origin_x_m, g.spacing_x_m(), 0.0, g.origin_y_m + rows * g.spacing_y_m(), 0.0, -g.spacing_y_m()};
    dataset->SetGeoTransform(geotransform);
    if (!g.crs_wkt.empty()) {
      OGRSpatialReference crs;
      crs.importFromWkt(g.crs_wkt.c_str());
      dataset->SetSpatialRef(&crs);
    }
    dataset->SetMetadataItem("NEARSHORE_VALUE", "depth");
    dataset->SetMetadataItem("NEARSHORE_DEPTH_SIGN", "positive_down");
    dataset->SetMetadataItem("NEARSHORE_VERTICAL_DATUM", vertical_datum.c_str());
    GDALRasterBand* band = dataset->GetRasterBand(1);
    band->SetNoDataValue(kNoData);
    band->SetDescription("depth (m, positive down)");
    band->SetUnitType("m");
    const CPLErr written = band->RasterIO(GF_Write, 0, 0, columns, rows, lines.data(), columns, rows, GDT_Float32, 0, 0);
    CPLErrorReset();
    GDALClose(dataset);  // void in GDAL 3.6: failures surface through CPLGetLastErrorType
    if (written != CE_None || CPLGetLastErrorType() >= CE_Failure) throw fail("writing the depth band failed");
  });
}

}  // namespace nearshore::bathymetry
