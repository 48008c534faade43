#include "nearshore/bathymetry/still_water_line.hpp"

#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <memory>

#include "nearshore/core/error.hpp"

namespace nearshore::bathymetry {

std::vector<PlaneLine> trace_still_water_line(const HarbourGrid& grid) {
  const GridGeometry& g = grid.geometry;
  constexpr double kNoData = -9999.0;
  auto fail = [](const std::string& what) {
    return Error("the harbour grid's still-water line", what + ": " + CPLGetLastErrorMsg(),
                 "check that GDAL was built with its MEM raster and Memory vector drivers");
  };
  GDALAllRegister();
  // 1. The depth as an in-memory raster, north row first, with the grid's georeference, so the
  //    contour's vertices come out in the grid's projected metres.
  GDALDriver* raster_driver = GetGDALDriverManager()->GetDriverByName("MEM");
  if (!raster_driver) throw fail("GDAL has no MEM driver");
  const std::unique_ptr<GDALDataset, void (*)(GDALDataset*)> raster(
      raster_driver->Create("", g.columns, g.rows, 1, GDT_Float32, nullptr), [](GDALDataset* d) { GDALClose(d); });
  if (!raster) throw fail("cannot create an in-memory raster");
  double geotransform[6] = {g.origin_x_m, g.spacing_x_m(), 0.0, g.origin_y_m + g.height_m(), 0.0, -g.spacing_y_m()};
  raster->SetGeoTransform(geotransform);
  std::vector<float> lines(g.cell_count());
  for (int row = 0; row < g.rows; ++row)
    for (int column = 0; column < g.columns; ++column) {
      const float depth_m = grid.still_water_depth_m(column, row);
      const bool no_data = grid.land(column, row) == kOutsideChartCell || !std::isfinite(depth_m);
      lines[static_cast<std::size_t>(g.rows - 1 - row) * g.columns + column] = no_data ? float(kNoData) : depth_m;
    }
  GDALRasterBand* band = raster->GetRasterBand(1);
  if (band->RasterIO(GF_Write, 0, 0, g.columns, g.rows, lines.data(), g.columns, g.rows, GDT_Float32, 0, 0) != CE_None)
    throw fail("cannot fill the in-memory raster");

  // 2. The one level, depth 0, into an in-memory line layer.
  GDALDriver* vector_driver = GetGDALDriverManager()->GetDriverByName("Memory");
  if (!vector_driver) throw fail("GDAL has no Memory driver");
  const std::unique_ptr<GDALDataset, void (*)(GDALDataset*)> vectors(
      vector_driver->Create("", 0, 0, 0, GDT_Unknown, nullptr), [](GDALDataset* d) { GDALClose(d); });
  if (!vectors) throw fail("cannot create an in-memory vector dataset");
  OGRLayer* layer = vectors->CreateLayer("still_water_line", nullptr, wkbLineString, nullptr);
  if (!layer) throw fail("cannot create the contour layer");
  double level_m = 0.0;
  if (GDALContourGenerate(band, 0.0, 0.0, 1, &level_m, TRUE, kNoData, layer, -1, -1, nullptr, nullptr) != CE_None)
    throw fail("GDALContourGenerate failed");

  // 3. The polylines, as the preview draws them.
  std::vector<PlaneLine> result;
  layer->ResetReading();
  for (const auto& feature : *layer) {
    const OGRGeometry* geometry = feature->GetGeometryRef();
    if (!geometry || wkbFlatten(geometry->getGeometryType()) != wkbLineString) continue;
    const OGRLineString* line = geometry->toLineString();
    PlaneLine points;
    points.reserve(line->getNumPoints());
    for (int i = 0; i < line->getNumPoints(); ++i) points.push_back({line->getX(i), line->getY(i)});
    if (points.size() >= 2) result.push_back(std::move(points));
  }
  return result;
}

}  // namespace nearshore::bathymetry
