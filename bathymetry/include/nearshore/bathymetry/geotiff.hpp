#pragma once
// depth.tif: a single-band float32 GeoTIFF of still-water depth (metres, positive down, land
// negative), north-up, in the grid's projected CRS, with metadata NEARSHORE_VALUE=depth and
// NEARSHORE_DEPTH_SIGN=positive_down so `nearshore bathy` reads it back with the right sign.
// Used for `nearshore bathy` output and for the demo harbour's survey grid.
#include <filesystem>
#include <string>

#include "nearshore/core/raster.hpp"

namespace nearshore::bathymetry {

/// Writes atomically (DEFLATE, floating-point predictor). `depth_m` is a Raster (row 0 south);
/// the file stores row 0 north as GeoTIFF does. NaN cells are written as nodata -9999.
void write_depth_geotiff(const std::filesystem::path& path, const GridGeometry& geometry, const Raster<float>& depth_m,
                         const std::string& vertical_datum);

}  // namespace nearshore::bathymetry
