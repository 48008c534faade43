#include "nearshore/core/vdb_file.hpp"

#include <mutex>
#include <string>

#include <openvdb/io/Archive.h>

#include "nearshore/core/atomic_stream.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore {
namespace {

// io::Archive::write is protected; io::File is what calls it, through its unchecked ofstream.
class CheckedVdbArchive : public openvdb::io::Archive {
 public:
  void write_to(std::ostream& out, const openvdb::GridPtrVec& grids, const openvdb::MetaMap& metadata) const {
    Archive::write(out, grids, /*seekable=*/true, metadata);
  }
};

}  // namespace

void initialise_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

openvdb::math::Transform::Ptr cell_centre_transform(const GridGeometry& geometry) {
  openvdb::math::Mat4d matrix = openvdb::math::Mat4d::identity();
  matrix.preScale(openvdb::math::Vec3d(geometry.spacing_x_m(), geometry.spacing_y_m(), geometry.smaller_spacing_m()));
  matrix.postTranslate(openvdb::math::Vec3d(0.5 * geometry.spacing_x_m(), 0.5 * geometry.spacing_y_m(), 0.0));
  return openvdb::math::Transform::createLinearTransform(matrix);
}

void add_georeference(openvdb::MetaMap& metadata, const GridGeometry& geometry) {
  metadata.insertMeta("nearshore_origin_x_m", openvdb::DoubleMetadata(geometry.origin_x_m));
  metadata.insertMeta("nearshore_origin_y_m", openvdb::DoubleMetadata(geometry.origin_y_m));
  metadata.insertMeta("nearshore_spacing_m", openvdb::DoubleMetadata(geometry.spacing_x_m()));
  metadata.insertMeta("nearshore_spacing_y_m", openvdb::DoubleMetadata(geometry.spacing_y_m()));
  metadata.insertMeta("nearshore_crs_wkt", openvdb::StringMetadata(geometry.crs_wkt));
}

void write_vdb_file(const std::filesystem::path& path, const openvdb::GridPtrVec& grids, const openvdb::MetaMap& metadata,
                    std::string_view what) {
  write_stream_atomically(
      path,
      [&](std::ostream& out) {
        try {
          CheckedVdbArchive().write_to(out, grids, metadata);
        } catch (const openvdb::Exception& e) {
          throw Error(path.string(), std::string("writing ") + std::string(what) + " failed: " + e.what(),
                      "check that the folder is writable and has space");
        }
      },
      what);
}

}  // namespace nearshore
