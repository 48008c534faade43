#pragma once
// The OGC WKT of a map projection (core/map_projection.hpp), from GDAL: what GeoTIFF and NetCDF
// outputs and GDAL's reprojection need. The projection itself is core's (GeographicLib only), so
// the bake and the runtime place things by latitude/longitude without linking GDAL.
#include <string>

#include "nearshore/core/map_projection.hpp"

namespace nearshore::bathymetry {

/// OGC WKT of the same CRS, from GDAL's OGRSpatialReference (EPSG:326zz / 327zz for UTM).
std::string crs_wkt(const MapProjection& projection);

}  // namespace nearshore::bathymetry
