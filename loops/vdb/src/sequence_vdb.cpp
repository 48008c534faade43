// The sequence as one volume, frames stacked as the third axis; voxels placed, georeferenced and
// written by core/vdb (vdb_file.hpp), as `export --to vdb` and `bathy`'s level set are.
#include "nearshore/loops/sequence_vdb.hpp"

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/core/vdb_file.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::loops {
void export_sequence_vdb(const std::filesystem::path& sequence_folder, const std::filesystem::path& vdb_path,
                         const VdbExportOptions& options) {
  const sequence::SequenceReader reader(sequence_folder);
  const GridGeometry& g = reader.geometry();
  const int last = options.frame_count < 0 ? reader.frame_count() : options.first_frame + options.frame_count;
  if (options.first_frame < 0 || last > reader.frame_count() || last <= options.first_frame || options.frame_stride < 1)
    throw Error(vdb_path.string(),
                fmt::format("frames {}..{} step {} requested but the sequence has frames 0..{}", options.first_frame,
                            last - 1, options.frame_stride, reader.frame_count() - 1),
                "choose a frame range inside the sequence and a stride >= 1");
  const HarbourGrid harbour = reader.read_harbour_grid();
  initialise_openvdb();
  // Cell (column, row) of frame f at voxel (column, row, (f - first) / stride), centred as every
  // VDB of the project (vdb_file.hpp); the frame axis has the smaller cell size.
  const openvdb::math::Transform::Ptr transform = cell_centre_transform(g);
  auto make = [&](const char* name) {
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    grid->setName(name);
    grid->setTransform(transform);
    grid->setGridClass(openvdb::GRID_UNKNOWN);
    return grid;
  };
  std::vector<openvdb::FloatGrid::Ptr> grids = {make("surface_elevation"), make("breaking")};
  if (options.fluxes) grids.push_back(make("flux_x")), grids.push_back(make("flux_y"));
  std::vector<openvdb::FloatGrid::Accessor> accessors;
  for (auto& grid : grids) accessors.push_back(grid->getAccessor());
  ProgressBar progress("VDB export", last - options.first_frame, "frames");
  sequence::Frame frame;
  sequence::ChannelSelection channels{true, options.fluxes, options.fluxes, true};
  for (int index = options.first_frame; index < last; index += options.frame_stride) {
    reader.read_frame_into(index, frame, channels);
    const int k = (index - options.first_frame) / options.frame_stride;
    const Raster<float>* fields[4] = {&frame.surface_elevation_m, &frame.breaking, &frame.flux_x_m2_s, &frame.flux_y_m2_s};
    for (int row = 0; row < g.rows; ++row)
      for (int column = 0; column < g.columns; ++column) {
        if (harbour.land(column, row)) continue;  // land stays inactive (background)
        const openvdb::Coord voxel(column, row, k);
        for (std::size_t c = 0; c < accessors.size(); ++c) accessors[c].setValue(voxel, (*fields[c])(column, row));
      }
    progress.update(index - options.first_frame + 1.0);
  }
  progress.finish();
  openvdb::GridPtrVec output(grids.begin(), grids.end());
  openvdb::MetaMap metadata;
  add_georeference(metadata, g);
  metadata.insertMeta("nearshore_frame_interval_s", openvdb::DoubleMetadata(reader.frame_interval_s()));
  metadata.insertMeta("nearshore_first_frame", openvdb::Int32Metadata(options.first_frame));
  metadata.insertMeta("nearshore_frame_stride", openvdb::Int32Metadata(options.frame_stride));
  metadata.insertMeta("nearshore_z_axis", openvdb::StringMetadata("voxel k = (frame - first_frame) / frame_stride"));
  write_vdb_file(vdb_path, output, metadata, "the VDB");
}

}  // namespace nearshore::loops
