// The only translation unit that includes OpenVDB (see coastline_level_set.hpp).
#include "nearshore/bathymetry/coastline_level_set.hpp"

#include <openvdb/io/Archive.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <mutex>

#include <fmt/core.h>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/atomic_stream.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bathymetry {
namespace {

void initialise_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}


// OpenVDB's io::File::write writes through a std::ofstream whose state it never checks, so a full
// disk left a truncated .vdb that was then renamed into place (issue 44). The same archive (header,
// metadata, grids with their offsets: what io::File writes and reads) goes to the core's checked
// stream instead (write_stream_atomically), which refuses to rename a file whose write failed.
class CheckedVdbArchive : public openvdb::io::Archive {
 public:
  void write_to(std::ostream& out, const openvdb::GridPtrVec& grids, const openvdb::MetaMap& metadata) const {
    Archive::write(out, grids, /*seekable=*/true, metadata);
  }
};

}  // namespace

std::size_t write_coastline_level_set(const std::filesystem::path& vdb_path, const GridGeometry& geometry,
                                      const Raster<float>& coast_distance_m, double half_band_m) {
  initialise_openvdb();
  auto grid = openvdb::FloatGrid::create(static_cast<float>(half_band_m));
  grid->setName("coast_distance");
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  // Index (i, j, 0) -> world (origin + (i + 0.5) s, origin + (j + 0.5) s, 0): a cell-centred voxel.
  auto transform = openvdb::math::Transform::createLinearTransform(geometry.spacing_m);
  transform->postTranslate(openvdb::Vec3d(geometry.origin_x_m + 0.5 * geometry.spacing_m,
                                          geometry.origin_y_m + 0.5 * geometry.spacing_m, 0.0));
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
  write_stream_atomically(
      vdb_path,
      [&](std::ostream& out) {
        try {
          CheckedVdbArchive().write_to(out, openvdb::GridPtrVec{grid}, openvdb::MetaMap());
        } catch (const openvdb::Exception& e) {
          throw Error(vdb_path.string(), std::string("writing the OpenVDB level set failed: ") + e.what(),
                      "check the folder is writable and has space");
        }
      },
      "the OpenVDB level set");
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
