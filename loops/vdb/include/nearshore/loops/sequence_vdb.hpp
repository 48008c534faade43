#pragma once
// OpenVDB export of a baked sequence for inspection in Houdini or Blender: x, y and frame as the
// third axis, land inactive. A separate library (nearshore_sequence_vdb) so that neither the
// sequence format nor the playback runtime ever link OpenVDB.
#include <filesystem>

namespace nearshore::loops {

struct VdbExportOptions {
  int first_frame = 0;
  int frame_count = -1;    ///< -1: to the end
  int frame_stride = 1;    ///< every n-th frame
  bool fluxes = false;     ///< also flux_x, flux_y grids (surface_elevation and breaking always)
};

/// Writes float grids "surface_elevation" (m), "breaking" (and "flux_x", "flux_y", m^2/s) with
/// voxel (i, j, k) = (column, row, (frame - first_frame) / stride); only water cells are active.
/// The transform is uniform with voxel size = the grid spacing in a LOCAL frame whose origin is
/// the grid's south-west corner (UTM coordinates would lose precision in 32-bit floats), so world
/// x, y are metres east/north of that corner and world z / spacing is the frame number. The
/// georeference, frame interval and stride are file metadata. Written atomically; shows progress.
void export_sequence_vdb(const std::filesystem::path& sequence_folder, const std::filesystem::path& vdb_path,
                         const VdbExportOptions& options = {});

}  // namespace nearshore::loops
