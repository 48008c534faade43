#pragma once
// The project's one road to an OpenVDB file: where a grid cell lands in a VDB volume, the
// georeference a user needs to place it, and a write that never leaves a truncated file. Used by
// `bathy`'s coastline level set, `export --to vdb` (a file per frame) and `loops --vdb` (frames
// stacked as the third axis), so the same cell lands at the same place whichever command wrote it.
// A library of its own (nearshore_core_vdb) so that core, and the playback runtime with it, never
// link OpenVDB (about 45 s to compile a file that includes it: toolchain.md).
#include <filesystem>
#include <string_view>

#include <openvdb/openvdb.h>

#include "nearshore/core/raster.hpp"

namespace nearshore {

/// openvdb::initialize(), once per process (thread-safe).
void initialise_openvdb();

/// Index (i, j, k) -> world ((i + 0.5) dx, (j + 0.5) dy, k dz): voxel (i, j) is cell (column i,
/// row j) at its centre, in metres east and north of the grid's south-west corner, not in the
/// grid's CRS, which 32-bit floats would round to the metre (UTM northings are 10^6-10^7 m). dz is
/// the smaller cell size, so the voxels are cubes for square cells (what Houdini and Blender expect
/// of a volume). The georeference travels as metadata (add_georeference).
openvdb::math::Transform::Ptr cell_centre_transform(const GridGeometry& geometry);

/// Metadata that places the local frame of cell_centre_transform on the map:
/// nearshore_origin_x_m / _y_m (the south-west corner in the CRS), nearshore_spacing_m /
/// nearshore_spacing_y_m, nearshore_crs_wkt.
void add_georeference(openvdb::MetaMap& metadata, const GridGeometry& geometry);

/// Writes `grids` with `metadata` to `path` atomically. OpenVDB's io::File::write writes through a
/// std::ofstream whose state it never checks, so a full disk left a truncated .vdb that was then
/// renamed into place (issue 44); the same archive (header, metadata, grids with their offsets:
/// what io::File writes and reads) goes to the core's checked stream (write_stream_atomically),
/// which refuses to rename a file whose write failed. `what` names the file in messages
/// ("the VDB frame"). Throws nearshore::Error naming the path.
void write_vdb_file(const std::filesystem::path& path, const openvdb::GridPtrVec& grids, const openvdb::MetaMap& metadata,
                    std::string_view what);

}  // namespace nearshore
