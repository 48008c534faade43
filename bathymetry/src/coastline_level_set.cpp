// The only translation unit that includes OpenVDB (see coastline_level_set.hpp).
#include "nearshore/bathymetry/coastline_level_set.hpp"

#include <cmath>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "nearshore/core/vdb_file.hpp"

namespace nearshore::bathymetry {
std::size_t write_coastline_level_set(const std::filesystem::path& vdb_path, const GridGeometry& geometry,
                                      const Raster<float>& coast_distance_m, double half_band_m) {
  initialise_openvdb();
  auto grid = openvdb::FloatGrid::create(static_cast<float>(half_band_m));
  grid->setName("coast_distance");
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  // Voxel (i, j, 0) is cell (column i, row j) at its centre, in metres from the grid's south-west
  // corner, the georeference as metadata: as every VDB of the project (vdb_file.hpp).
  const openvdb::math::Transform::Ptr transform = cell_centre_transform(geometry);
  grid->setTransform(transform);
  grid->insertMeta("crs_wkt", openvdb::StringMetadata(geometry.crs_wkt));
  grid->insertMeta("units", openvdb::StringMetadata("metres, negative on land"));
  auto accessor = grid->getAccessor();
  for (int row = 0; row < coast_distance_m.rows(); ++row)
    for (int column = 0; column < coast_distance_m.columns(); ++column) {
      const float d = coast_distance_m(column, row);
      if (std::isfinite(d) && std::abs(d) < half_band_m) accessor.setValue(openvdb::Coord(column, row, 0), d);
    }
  grid->pruneGrid();
  const std::size_t active = grid->activeVoxelCount();
  openvdb::MetaMap metadata;
  add_georeference(metadata, geometry);
  write_vdb_file(vdb_path, openvdb::GridPtrVec{grid}, metadata, "the OpenVDB level set");
  return active;
}

CoastlineLevelSetProbe probe_coastline_level_set(const std::filesystem::path& vdb_path, int column, int row,
                                                 double* value_m) {
  initialise_openvdb();
  try {
    openvdb::io::File file(vdb_path.string());
    file.open();
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("coast_distance"));
    file.close();
    if (!grid) throw Error(vdb_path.string(), "has no float grid named coast_distance", "rewrite it with nearshore bathy");
    if (value_m) *value_m = grid->getConstAccessor().getValue(openvdb::Coord(column, row, 0));
    return {grid->activeVoxelCount(), grid->background(), grid->voxelSize()[0]};
  } catch (const openvdb::Exception& e) {
    throw Error(vdb_path.string(), std::string("cannot read OpenVDB file: ") + e.what(), "rewrite it with nearshore bathy");
  }
}

}  // namespace nearshore::bathymetry
