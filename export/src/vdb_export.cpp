// The vdb export: per frame one .vdb holding height-field grids, the frames side by side in time
// (surface_NNNNNN.vdb), never stacked as a third axis. The only file of the export that includes
// OpenVDB (about 45 s to compile, toolchain.md).
#include <openvdb/io/Archive.h>
#include <openvdb/openvdb.h>

#include <vector>

#include <fmt/core.h>

#include "export_input.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/atomic_stream.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::exports {
namespace {

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

// Voxel (i, j, 0) is cell (column i, row j) with its centre at x = (i + 0.5) dx, y = (j + 0.5) dy:
// metres east and north of the grid's south-west corner, not UTM, which 32-bit floats would round
// to the metre. The georeference is file metadata. z has the smaller cell size, so the voxels are
// cubes for square cells (what Houdini and Blender expect of a volume).
openvdb::math::Transform::Ptr cell_transform(const GridGeometry& g) {
  openvdb::math::Mat4d matrix = openvdb::math::Mat4d::identity();
  matrix.preScale(openvdb::math::Vec3d(g.spacing_x_m(), g.spacing_y_m(), g.smaller_spacing_m()));
  matrix.postTranslate(openvdb::math::Vec3d(0.5 * g.spacing_x_m(), 0.5 * g.spacing_y_m(), 0.0));
  return openvdb::math::Transform::createLinearTransform(matrix);
}

}  // namespace

void write_vdb(const ExportInput& input, ExportSummary& summary) {
  openvdb::initialize();
  const GridGeometry& g = input.harbour.geometry;
  const openvdb::math::Transform::Ptr transform = cell_transform(g);
  ProgressBar progress("VDB export", input.frame_count(), "frames");
  sequence::Frame frame;
  for (int index = input.first_frame; index < input.end_frame; ++index) {
    input.reader.read_frame_into(index, frame, sequence::ChannelSelection::display());
    // 1. Two height fields of this frame: eta (m) and breaking (0..1); land stays inactive.
    openvdb::GridPtrVec grids;
    for (const auto& [name, field] : {std::pair{"surface_elevation", &frame.surface_elevation_m},
                                      std::pair{"breaking", &frame.breaking}}) {
      openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
      grid->setName(name);
      grid->setTransform(transform);
      grid->setGridClass(openvdb::GRID_UNKNOWN);
      openvdb::FloatGrid::Accessor accessor = grid->getAccessor();
      for (int row = 0; row < g.rows; ++row)
        for (int column = 0; column < g.columns; ++column) {
          const std::size_t cell = static_cast<std::size_t>(row) * g.columns + column;
          if (!input.is_land(cell)) accessor.setValue(openvdb::Coord(column, row, 0), field->values()[cell]);
        }
      grids.push_back(grid);
    }
    // 2. What a user needs to place and time it.
    openvdb::MetaMap metadata;
    metadata.insertMeta("nearshore_frame_index", openvdb::Int32Metadata(index));
    metadata.insertMeta("nearshore_time_s", openvdb::DoubleMetadata(input.reader.manifest().frame_time_s(index)));
    metadata.insertMeta("nearshore_frame_interval_s", openvdb::DoubleMetadata(input.reader.frame_interval_s()));
    metadata.insertMeta("nearshore_origin_x_m", openvdb::DoubleMetadata(g.origin_x_m));
    metadata.insertMeta("nearshore_origin_y_m", openvdb::DoubleMetadata(g.origin_y_m));
    metadata.insertMeta("nearshore_crs_wkt", openvdb::StringMetadata(g.crs_wkt));
    metadata.insertMeta("nearshore_layout",
                        openvdb::StringMetadata("height fields: voxel (i, j, 0) = cell (column i, row j); world x, y "
                                                "= metres east, north of the grid's south-west corner; values: "
                                                "surface_elevation in metres (z up), breaking 0..1; land inactive"));
    const std::filesystem::path path = input.frame_file("surface", index, "vdb");
    write_stream_atomically(
        path,
        [&](std::ostream& out) {
          try {
            CheckedVdbArchive().write_to(out, grids, metadata);
          } catch (const openvdb::Exception& e) {
            throw Error(path.string(), std::string("writing the VDB failed: ") + e.what(),
                        "check that the output folder is writable and has space");
          }
        },
        "the VDB frame");
    record_file(summary, path);
    progress.update(index - input.first_frame + 1.0);
  }
  progress.finish();
}

}  // namespace nearshore::exports
