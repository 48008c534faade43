#pragma once
// MapProjection: latitude/longitude (WGS 84) <-> the projected metric frame (x east, y north,
// metres) of a harbour grid. Two kinds, both computed with GeographicLib (Karney 2011, accurate to
// a few nanometres within the UTM belt):
//   utm                  Universal Transverse Mercator, zone chosen from the area or given;
//   transverse_mercator  a local transverse Mercator with scale 1 centred on the area (false
//                        easting and northing 0 at the centre), for areas that straddle zones.
// Here in core (GeographicLib only, no GDAL) because the bake and the runtime place things by
// latitude/longitude too; the OGC WKT of a projection (GDAL) is bathymetry/projection.hpp.
// The projection is stored with the grid (GridGeometry::projection, docs/formats/harbour-grid.md)
// so the runtime can place a camera by latitude/longitude:
//   {"kind":"utm","zone":10,"north":true,"datum":"WGS84"}
//   {"kind":"transverse_mercator","central_meridian_deg":-122.45,"origin_latitude_deg":47.28,
//    "scale_factor":1.0,"false_easting_m":0.0,"false_northing_m":0.0,"datum":"WGS84"}
#include <string>

#include <nlohmann/json.hpp>

#include "nearshore/core/raster.hpp"

namespace nearshore {

struct LonLat {
  double longitude_deg = 0.0;
  double latitude_deg = 0.0;
};

struct ProjectedPoint {
  double x_m = 0.0;  ///< easting, metres
  double y_m = 0.0;  ///< northing, metres
};

class MapProjection {
 public:
  /// UTM zone `zone` (1..60) of the northern (`north`) or southern hemisphere.
  static MapProjection utm(int zone, bool north);
  /// The standard UTM zone of a place (GeographicLib::UTMUPS::StandardZone).
  static MapProjection utm_for(LonLat centre);
  /// Local transverse Mercator, scale 1 on the central meridian, (0, 0) at `centre`.
  static MapProjection local_transverse_mercator(LonLat centre);
  /// From the JSON above; throws nearshore::Error naming `subject` if it is not one of the two kinds.
  static MapProjection from_json(const nlohmann::json& projection, const std::string& subject);

  ProjectedPoint forward(LonLat point) const;
  LonLat reverse(ProjectedPoint point) const;

  nlohmann::json to_json() const;
  /// "UTM zone 10N" or "local transverse Mercator at 47.2800N 122.4500W".
  std::string describe() const;

 private:
  enum class Kind { kUtm, kTransverseMercator };
  Kind kind_ = Kind::kUtm;
  int zone_ = 0;
  bool north_ = true;
  double central_meridian_deg_ = 0.0, origin_latitude_deg_ = 0.0, origin_northing_m_ = 0.0;
};

/// Fractional grid position of a place: column/row such that the centre of cell (i, j) is at
/// (i, j) exactly (so a place at column 3.5 lies on the boundary of cells 3 and 4).
struct GridPosition {
  double column = 0.0;
  double row = 0.0;
};

/// lat/lon -> grid and back, through the projection stored in `geometry.projection`.
GridPosition grid_position_of(const GridGeometry& geometry, LonLat point);
LonLat lon_lat_of(const GridGeometry& geometry, GridPosition position);

}  // namespace nearshore
