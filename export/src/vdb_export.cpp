// The vdb export: per frame one .vdb holding height-field grids, the frames side by side in time
// (surface_NNNNNN.vdb), never stacked as a third axis; voxels placed, georeferenced and written by
// core/vdb (vdb_file.hpp), as `loops --vdb` and `bathy`'s level set are.
#include <vector>

#include <fmt/core.h>

#include "export_input.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/core/vdb_file.hpp"

namespace nearshore::exports {
void write_vdb(const ExportInput& input, ExportSummary& summary) {
  initialise_openvdb();
  const GridGeometry& g = input.harbour.geometry;
  const openvdb::math::Transform::Ptr transform = cell_centre_transform(g);
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
    add_georeference(metadata, g);
    metadata.insertMeta("nearshore_layout",
                        openvdb::StringMetadata("height fields: voxel (i, j, 0) = cell (column i, row j); world x, y "
                                                "= metres east, north of the grid's south-west corner; values: "
                                                "surface_elevation in metres (z up), breaking 0..1; land inactive"));
    const std::filesystem::path path = input.frame_file("surface", index, "vdb");
    write_vdb_file(path, grids, metadata, "the VDB frame");
    record_file(summary, path);
    progress.update(index - input.first_frame + 1.0);
  }
  progress.finish();
}

}  // namespace nearshore::exports
