#pragma once
// A grid in local metres with no map projection: a laboratory flume or basin, or a site survey in
// its own coordinates (issue 19, "the road for any laboratory or survey grid"). Read straight into a
// HarbourGrid whose x and y are the file's own metres, with no CRS and no projection invented for it:
//   - a raster GDAL reads (GeoTIFF, ESRI ASCII grid .asc, ...) with no CRS or a local engineering
//     CRS (LOCAL_CS), or a projected CRS in metres; its own cells are kept;
//   - "x y depth" text (.xyz, .csv, .txt): scattered soundings gridded by Sibson natural-neighbour
//     interpolation (natural_neighbour.hpp) at LocalGridRequest::spacing_m over their bounding box.
// Depth is positive down after the sign is applied; cells at or above still water (depth <= 0) are
// land holding minus their elevation, as everywhere in nearshore.
#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "nearshore/bathymetry/sources.hpp"
#include "nearshore/core/harbour_grid.hpp"

namespace nearshore::bathymetry {

struct LocalGridRequest {
  std::filesystem::path file;
  /// How the file's values are signed. kAuto: a raster's metadata decides, else (no metadata) the
  /// values are elevations; text soundings are depths.
  DepthSign sign = DepthSign::kAuto;
  /// {dx, dy} in metres of the cells laid over text soundings (required for them); a raster keeps
  /// its own cells (resample them downstream).
  std::optional<std::array<double, 2>> spacing_m;
  /// {dx, dy} in metres of a raster's pixels where the file has no georeference (a bare TIFF); its
  /// south-west corner is then at x = y = 0. Ignored for rasters that carry a geotransform.
  std::optional<std::array<double, 2>> pixel_size_m;
  /// Water shallower than this (metres) is deepened to it; 0 keeps every wet cell as given.
  double minimum_depth_m = 0.0;
};

struct LocalGrid {
  HarbourGrid grid;           ///< geometry in the file's metres (origin: its south-west corner), crs_wkt empty
  std::string format;         ///< "XYZ" or the GDAL driver's short name
  std::string sign_used;      ///< "positive_down (why)" or "positive_up (why)"
  std::size_t raised_cells = 0;  ///< water cells deepened to minimum_depth_m
  std::size_t filled_cells = 0;  ///< cells outside the soundings' hull or nodata, given the nearest depth
};

/// True for the text sounding files (.xyz, .csv, .txt) that need LocalGridRequest::spacing_m.
bool is_text_soundings(const std::filesystem::path& path);

/// Reads and grids `request.file`. Throws nearshore::Error naming the file, the problem and the fix:
/// what read_source refuses (missing file, undeclared NaN, implausible depths, bad text lines), a
/// raster in longitude/latitude (that belongs to BathyRequest), a rotated raster, a raster without
/// georeference and no pixel_size_m, text soundings without spacing_m or spanning less than two
/// cells, and a grid with no water.
LocalGrid read_local_grid(const LocalGridRequest& request);

}  // namespace nearshore::bathymetry
