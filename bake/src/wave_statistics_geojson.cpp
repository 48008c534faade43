// DIR/wave_statistics_runup.geojson: the bake's run-up line (band 4 of wave_statistics.tif) as
// lines a GIS opens directly (docs/formats/wave-statistics.md), written through GDAL's GeoJSON
// driver. The cells are chained in runup_line.cpp; this file only turns the chains into features.
#include <fmt/core.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <string>
#include <vector>

#include "nearshore/bake/runup_line.hpp"
#include "nearshore/bake/wave_statistics.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bake {

void write_runup_line_geojson(const std::filesystem::path& path, const WaveStatistics& statistics,
                              const GridGeometry& geometry, double first_time_s, double last_time_s) {
  const std::vector<RunupLine> lines =
      trace_runup_lines(statistics.runup_line_water_level_m(), statistics.maximum_surface_elevation_m());
  const auto fail = [&](const std::string& what) {
    return Error(path.string(), what + ": " + CPLGetLastErrorMsg(),
                 "check that the output folder is writable and has space");
  };

  // Where the coordinates are. GeoJSON (RFC 7946) knows only WGS 84 longitude and latitude; GDAL
  // still writes another CRS with an EPSG code as the 2008 specification's "crs" member
  // (urn:ogc:def:crs:EPSG::<code>), which GDAL and QGIS read. So:
  //   - a CRS with an EPSG code (a UTM harbour grid, `nearshore bathy`'s default): the coordinates
  //     stay in it, as in wave_statistics.tif, so the line lies on the raster and a modeller measures
  //     in the grid's metres;
  //   - a CRS without one (`local-tm`, a transverse Mercator about the harbour): GDAL would write no
  //     "crs" and every reader would take the metres for degrees, so GDAL reprojects the line to
  //     RFC 7946 longitude and latitude (z and the properties stay metres);
  //   - no CRS (a laboratory flume in local metres): none in the file either ("crs"-less, as GDAL
  //     writes it; readers then assume WGS 84), and the description says the numbers are local metres.
  OGRSpatialReference crs;
  std::string frame = "local metres of the harbour grid (no CRS)";
  bool longitude_latitude = false;
  if (!geometry.crs_wkt.empty()) {
    if (crs.importFromWkt(geometry.crs_wkt.c_str()) != OGRERR_NONE)
      throw Error(path.string(), "the harbour grid's CRS (GridGeometry::crs_wkt) is no WKT that GDAL reads",
                  "rebuild the harbour grid with `nearshore bathy`, which writes its CRS as WKT");
    crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x east, y north, whatever the CRS's axis order
    // A WKT that matches an EPSG CRS without naming it gets its code.
    if (!crs.GetAuthorityCode(nullptr)) crs.AutoIdentifyEPSG();
    const char* code = crs.GetAuthorityCode(nullptr);
    const char* authority = crs.GetAuthorityName(nullptr);
    longitude_latitude = !(code && authority && std::string(authority) == "EPSG");
    frame = longitude_latitude
                ? fmt::format(
                      "WGS 84 longitude and latitude, degrees (RFC 7946), reprojected from "
                      "the harbour grid's {}, which has no EPSG code",
                      crs.GetName())
                : fmt::format("metres of {} (EPSG:{}), the CRS of wave_statistics.tif", crs.GetName(), code);
  }
  const std::string description = fmt::format(
      "nearshore bake: the run-up line, the wet/dry front at its furthest reach over {} solver steps from "
      "t = {:g} s to {:g} s. One LineString per stretch of shore through the front cells' centres, never-wet "
      "ground on the left; x, y in {}; z = the highest water level reached at the cell, metres above still "
      "water",
      statistics.step_count(), first_time_s, last_time_s, frame);

  GDALAllRegister();
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GeoJSON");
    if (!driver) throw fail("GDAL has no GeoJSON driver");
    GDALDatasetUniquePtr dataset(driver->Create(temporary.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!dataset) throw fail("cannot create the GeoJSON file");
    // 15 significant figures: a UTM northing (7 digits before the point) keeps 0.1 um, and z, a float
    // widened to double, reads back as the same float (9 significant figures suffice). In degrees, 9
    // decimals: 0.1 mm on the ground (GDAL's RFC 7946 default of 7 is 1 cm).
    const std::string description_option = "DESCRIPTION=" + description;
    std::vector<const char*> layer_options = {description_option.c_str(), "SIGNIFICANT_FIGURES=15"};
    if (longitude_latitude) {
      layer_options.push_back("RFC7946=YES");
      layer_options.push_back("COORDINATE_PRECISION=9");
    }
    layer_options.push_back(nullptr);
    OGRLayer* layer = dataset->CreateLayer("runup_line", geometry.crs_wkt.empty() ? nullptr : &crs,
                                           wkbLineString25D, const_cast<char**>(layer_options.data()));
    if (!layer) throw fail("cannot create the run-up line layer");
    // The properties a modeller filters and labels by: the run-up range along the stretch, its size.
    OGRFieldDefn highest("water_level_max_m", OFTReal), lowest("water_level_min_m", OFTReal);
    OGRFieldDefn cells("cells", OFTInteger), length("length_m", OFTReal), closed("closed", OFTInteger);
    closed.SetSubType(OFSTBoolean);  // true/false in GeoJSON
    for (OGRFieldDefn* field : {&highest, &lowest, &cells, &length, &closed})
      if (layer->CreateField(field) != OGRERR_NONE)
        throw fail(fmt::format("cannot create the field {}", field->GetNameRef()));

    for (const RunupLine& line : lines) {
      OGRLineString polyline;
      for (const RunupVertex& vertex : line.vertices)
        polyline.addPoint(geometry.cell_centre_x_m(vertex.column), geometry.cell_centre_y_m(vertex.row),
                          vertex.water_level_m);
      // A ring repeats its first position at the end (OGC Simple Features: a LineString is closed
      // when its first and last points coincide; GIS tools test closure so). A line of one cell, a front of a single cell, repeats it too: a LineString has
      // two or more positions (RFC 7946 3.1.4); its length is 0.
      if (line.closed || line.vertices.size() == 1) {
        const RunupVertex& first = line.vertices.front();
        polyline.addPoint(geometry.cell_centre_x_m(first.column), geometry.cell_centre_y_m(first.row),
                          first.water_level_m);
      }
      OGRFeature feature(layer->GetLayerDefn());
      feature.SetField("water_level_max_m", static_cast<double>(line.highest_water_level_m()));
      feature.SetField("water_level_min_m", static_cast<double>(line.lowest_water_level_m()));
      feature.SetField("cells", line.cell_count());
      feature.SetField("length_m", line.length_m(geometry));
      feature.SetField("closed", line.closed ? 1 : 0);
      feature.SetGeometry(&polyline);
      if (layer->CreateFeature(&feature) != OGRERR_NONE) throw fail("writing a run-up line feature failed");
    }
    CPLErrorReset();
    dataset.reset();  // the driver writes the closing brackets here; failures surface through
                      // CPLGetLastErrorType
    if (CPLGetLastErrorType() >= CE_Failure) throw fail("closing the GeoJSON file failed");
  });
}

}  // namespace nearshore::bake
