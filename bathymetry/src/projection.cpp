#include "nearshore/bathymetry/projection.hpp"

#include <ogr_spatialref.h>

namespace nearshore::bathymetry {

std::string crs_wkt(const MapProjection& projection) {
  const nlohmann::json description = projection.to_json();
  OGRSpatialReference crs;
  if (description.at("kind") == "utm") {
    crs.importFromEPSG((description.at("north").get<bool>() ? 32600 : 32700) + description.at("zone").get<int>());
  } else {
    crs.SetWellKnownGeogCS("WGS84");
    crs.SetTM(description.at("origin_latitude_deg").get<double>(), description.at("central_meridian_deg").get<double>(),
              1.0, 0.0, 0.0);
    crs.SetProjCS("nearshore local transverse Mercator");
  }
  char* wkt = nullptr;
  crs.exportToWkt(&wkt);
  std::string text = wkt ? wkt : "";
  CPLFree(wkt);
  return text;
}

}  // namespace nearshore::bathymetry
