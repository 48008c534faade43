#pragma once
// coastline.vdb: the signed coastline distance as a sparse OpenVDB level set (grid class
// "level set", float voxels, named "coast_distance"), for tools that want a narrow band around the
// shore only. One voxel per grid cell in the plane z = 0: voxel (i, j, 0) is cell (i, j), the
// transform puts its centre at the cell centre in projected metres. Negative on land (OpenVDB's
// "inside"), positive in water; voxels farther than `half_band_m` from the coast are not stored
// (background = half_band_m). OpenVDB is confined to coastline_level_set.cpp.
#include <filesystem>

#include "nearshore/core/raster.hpp"

namespace nearshore::bathymetry {

/// Writes atomically; returns the number of active voxels. Throws nearshore::Error on failure.
std::size_t write_coastline_level_set(const std::filesystem::path& vdb_path, const GridGeometry& geometry,
                                      const Raster<float>& coast_distance_m, double half_band_m);

/// Reads the level set back as (active voxel count, value at cell (column,row) or background).
struct CoastlineLevelSetProbe {
  std::size_t active_voxels = 0;
  double background_m = 0.0;
  double voxel_size_m = 0.0;
};
CoastlineLevelSetProbe probe_coastline_level_set(const std::filesystem::path& vdb_path, int column, int row,
                                                 double* value_m);

}  // namespace nearshore::bathymetry
