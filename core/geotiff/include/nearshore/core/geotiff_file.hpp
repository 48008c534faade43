#pragma once
// The project's one road to a GeoTIFF: float32 bands of a grid, north-up, in the grid's CRS, with a
// no-data value GIS tools honour, metadata, and a write that is checked and atomic. Used by `bathy`
// (depth.tif), the bake (wave_statistics.tif) and `export` (wave_statistics.tif of frames,
// agitation.tif), so every GeoTIFF of the project is georeferenced the same way. A library of its own
// (nearshore_core_geotiff, GDAL) so that core, and the playback runtime with it, never link GDAL.
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "nearshore/core/raster.hpp"

namespace nearshore {

/// One band: a raster of the grid (row 0 the southern row, as everywhere in the project; the
/// writer flips it, GeoTIFF's first line is the northern row). NaN cells are no data.
struct GeoTiffBand {
  const Raster<float>* values = nullptr;
  std::string description;  ///< what a GIS shows as the band's name, with its unit: "depth (m, positive down)"
  std::string unit;         ///< GDAL's unit type: "m", "1"
};

struct GeoTiffContent {
  std::vector<GeoTiffBand> bands;
  /// What NaN cells are written as and declared no data: -9999 (no water level or depth on Earth,
  /// and what many GIS tools handle better than NaN), or NaN itself.
  float no_data_value = -9999.0f;
  std::vector<std::pair<std::string, std::string>> metadata;  ///< NEARSHORE_* items of the file
};

/// Writes `content` over `geometry` (geotransform from the south-west corner and dx, dy; the CRS
/// from crs_wkt, none for a laboratory frame) to `path`, DEFLATE-compressed, band-interleaved,
/// atomically (a failed write or close leaves no file under `path`). `what` names the file in
/// messages ("the statistics bands"). Throws nearshore::Error naming the path.
void write_geotiff_file(const std::filesystem::path& path, const GridGeometry& geometry, const GeoTiffContent& content,
                        std::string_view what);

}  // namespace nearshore
