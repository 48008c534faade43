#pragma once
// The demo harbour: a small but realistic harbour that nearshore GENERATES, in the same formats
// users bring (so the demo needs no data from outside the repository):
//   depth.tif        GeoTIFF, float32 depth in metres (positive down, negative = land elevation),
//                    in the UTM zone of the site (EPSG:326xx), nodata -9999;
//   coastline.geojson  the shoreline as LineStrings, WGS84 lon/lat (RFC 7946);
//   land.geojson       land as Polygons, WGS84;
//   structures.geojson two rubble-mound breakwater arms (10 m crest 3 m above the water, 1:1.5
//                    slopes) with a 140 m entrance between their toes, a detached rubble-mound
//                    breakwater 320 m long across the approach 160 m south of the entrance, and the
//                    vertical quay front, as LineStrings (properties: name, category, crest_width_m,
//                    crest_elevation_m), WGS84;
//   surroundings.tif GeoTIFF like depth.tif, coarser, over the site grown by surroundings_margin_m on
//                    every side: the same analytic ground (demo_harbour_depth_m) beyond the survey,
//                    which `nearshore bathy` grids into the harbour grid's surroundings (issue 41)
//                    when it comes after depth.tif in the inputs and the grid's box is the site's
//                    (DemoHarbourFiles::site_box_m).
// The site: an open coast facing south with a 15 m deep approach, an elliptic shoal east of the
// entrance (refraction), a dredged 8 m basin behind the breakwaters, reached only by waves bent
// round the detached breakwater's heads and through the gap (diffraction), and vertical quays on
// its north side (reflection).
#include <array>
#include <filesystem>

namespace nearshore::bathymetry {

struct DemoHarbourOptions {
  double centre_latitude_deg = 38.905;    ///< Dalian bay, where seed 003 baked its harbour
  double centre_longitude_deg = 121.695;
  double width_m = 1600.0;                ///< east-west extent of the depth grid
  double height_m = 1200.0;               ///< north-south extent
  double source_spacing_m = 8.0;          ///< cell size of the GeoTIFF written (the survey's resolution)
  /// How far surroundings.tif reaches beyond the site on every side, metres: the site's longer side,
  /// what `nearshore bathy` grids round a grid by default (BathyRequest::surroundings_margin_m).
  double surroundings_margin_m = 1600.0;
  double surroundings_spacing_m = 32.0;   ///< its cells: 4 of the survey's, as bathy's surroundings
};

struct DemoHarbourFiles {
  std::filesystem::path depth_geotiff;
  std::filesystem::path coastline_geojson;
  std::filesystem::path land_geojson;
  std::filesystem::path structures_geojson;
  std::filesystem::path surroundings_geotiff;
  /// The site (depth.tif's extent) in its UTM zone's metres, x0, y0, x1, y1: the harbour grid's box
  /// (BathyRequest::bbox_projected_m) when surroundings.tif is among the inputs.
  std::array<double, 4> site_box_m{};
};

/// Analytic still-water depth of the demo site at local (x, y) metres from the south-west corner
/// (positive down; negative is land elevation). Exposed so tests can check what GDAL reads back.
double demo_harbour_depth_m(const DemoHarbourOptions& options, double x_m, double y_m);

/// Writes the five files into `folder` (created if needed), each atomically. Throws nearshore::Error.
DemoHarbourFiles write_demo_harbour(const std::filesystem::path& folder, const DemoHarbourOptions& options = {});

}  // namespace nearshore::bathymetry
