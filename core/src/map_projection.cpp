#include "nearshore/core/map_projection.hpp"

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/TransverseMercator.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include <cmath>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore {
namespace {

// Transverse Mercator with scale 1 on the central meridian (Karney 2011, 6th-order Krüger series).
const GeographicLib::TransverseMercator& unit_scale_transverse_mercator() {
  static const GeographicLib::TransverseMercator projection(GeographicLib::Constants::WGS84_a(),
                                                            GeographicLib::Constants::WGS84_f(), 1.0);
  return projection;
}

}  // namespace

MapProjection MapProjection::utm(int zone, bool north) {
  if (zone < GeographicLib::UTMUPS::MINUTMZONE || zone > GeographicLib::UTMUPS::MAXUTMZONE)
    throw Error("projection", fmt::format("UTM zone {} does not exist", zone), "give a zone from 1 to 60, e.g. 10N");
  MapProjection projection;
  projection.kind_ = Kind::kUtm;
  projection.zone_ = zone;
  projection.north_ = north;
  return projection;
}

MapProjection MapProjection::utm_for(LonLat centre) {
  const int zone = GeographicLib::UTMUPS::StandardZone(centre.latitude_deg, centre.longitude_deg);
  if (zone == GeographicLib::UTMUPS::UPS)
    throw Error("projection", fmt::format("latitude {:.4f} lies in a polar (UPS) region", centre.latitude_deg),
                "set BathyRequest::projection to local-tm (a transverse Mercator centred on the area)");
  return utm(zone, centre.latitude_deg >= 0.0);
}

MapProjection MapProjection::local_transverse_mercator(LonLat centre) {
  MapProjection projection;
  projection.kind_ = Kind::kTransverseMercator;
  projection.central_meridian_deg_ = centre.longitude_deg;
  projection.origin_latitude_deg_ = centre.latitude_deg;
  double x = 0, y = 0;
  unit_scale_transverse_mercator().Forward(centre.longitude_deg, centre.latitude_deg, centre.longitude_deg, x, y);
  projection.origin_northing_m_ = y;  // so that y = 0 at the centre, as OGR's SetTM(lat0, ...) defines it
  return projection;
}

MapProjection MapProjection::from_json(const nlohmann::json& json, const std::string& subject) {
  const std::string kind = json.is_object() ? json.value("kind", std::string{}) : std::string{};
  if (kind == "utm") return utm(json.value("zone", 0), json.value("north", true));
  if (kind == "transverse_mercator") {
    if (json.value("scale_factor", 1.0) != 1.0 || json.value("false_easting_m", 0.0) != 0.0 ||
        json.value("false_northing_m", 0.0) != 0.0)
      throw Error(subject, "transverse_mercator projection with scale or false origin other than 1/0/0",
                  "regrid it with BathyRequest::projection set to local-tm");
    return local_transverse_mercator({json.value("central_meridian_deg", 0.0), json.value("origin_latitude_deg", 0.0)});
  }
  throw Error(subject, "projection '" + json.dump() + "' is neither utm nor transverse_mercator",
              "regrid with nearshore bathy, which writes one of the two (docs/formats/harbour-grid.md)");
}

ProjectedPoint MapProjection::forward(LonLat p) const {
  ProjectedPoint out;
  if (kind_ == Kind::kUtm) {
    // Forced zone (setzone = zone_) so points just across a zone border stay in this frame.
    int zone = 0;
    bool north = true;
    try {
      GeographicLib::UTMUPS::Forward(p.latitude_deg, p.longitude_deg, zone, north, out.x_m, out.y_m, zone_);
    } catch (const GeographicLib::GeographicErr& error) {
      // A point far from the zone (lat 0, lon 0 for a grid in zone 10N): GeographicLib's own
      // message names neither the point's role nor a fix; callers add the entry (a gauge).
      throw Error(describe(),
                  fmt::format("cannot place lat {}, lon {}: it is {:.0f} degrees of longitude from the zone's central "
                              "meridian ({}), beyond what the projection covers ({})",
                              p.latitude_deg, p.longitude_deg,
                              std::abs(std::remainder(p.longitude_deg - (-183.0 + 6.0 * zone_), 360.0)), -183.0 + 6.0 * zone_,
                              error.what()),
                  "check the latitude and longitude (degrees, WGS 84; lat first) against the grid's area");
    }
    // Forward reports the hemisphere of the point; a grid straddling the equator keeps ours.
    if (north != north_) out.y_m += north_ ? -GeographicLib::UTMUPS::UTMShift() : GeographicLib::UTMUPS::UTMShift();
  } else {
    unit_scale_transverse_mercator().Forward(central_meridian_deg_, p.latitude_deg, p.longitude_deg, out.x_m, out.y_m);
    out.y_m -= origin_northing_m_;
  }
  return out;
}

LonLat MapProjection::reverse(ProjectedPoint p) const {
  LonLat out;
  if (kind_ == Kind::kUtm)
    GeographicLib::UTMUPS::Reverse(zone_, north_, p.x_m, p.y_m, out.latitude_deg, out.longitude_deg);
  else
    unit_scale_transverse_mercator().Reverse(central_meridian_deg_, p.x_m, p.y_m + origin_northing_m_,
                                             out.latitude_deg, out.longitude_deg);
  return out;
}

nlohmann::json MapProjection::to_json() const {
  if (kind_ == Kind::kUtm) return {{"kind", "utm"}, {"zone", zone_}, {"north", north_}, {"datum", "WGS84"}};
  return {{"kind", "transverse_mercator"}, {"central_meridian_deg", central_meridian_deg_},
          {"origin_latitude_deg", origin_latitude_deg_}, {"scale_factor", 1.0},
          {"false_easting_m", 0.0}, {"false_northing_m", 0.0}, {"datum", "WGS84"}};
}

std::string MapProjection::describe() const {
  if (kind_ == Kind::kUtm) return fmt::format("UTM zone {}{}", zone_, north_ ? 'N' : 'S');
  return fmt::format("local transverse Mercator at {:.4f}{} {:.4f}{}", std::abs(origin_latitude_deg_),
                     origin_latitude_deg_ >= 0 ? 'N' : 'S', std::abs(central_meridian_deg_),
                     central_meridian_deg_ >= 0 ? 'E' : 'W');
}

GridPosition grid_position_of(const GridGeometry& geometry, LonLat point) {
  const ProjectedPoint p = MapProjection::from_json(geometry.projection, "grid geometry").forward(point);
  return {(p.x_m - geometry.origin_x_m) / geometry.spacing_m - 0.5, (p.y_m - geometry.origin_y_m) / geometry.spacing_m - 0.5};
}

LonLat lon_lat_of(const GridGeometry& geometry, GridPosition position) {
  return MapProjection::from_json(geometry.projection, "grid geometry")
      .reverse({geometry.origin_x_m + (position.column + 0.5) * geometry.spacing_m,
                geometry.origin_y_m + (position.row + 0.5) * geometry.spacing_m});
}

}  // namespace nearshore
