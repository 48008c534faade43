// The per-frame VDBs read back by OpenVDB: one file per frame, a height field on one voxel layer
// (never frames stacked as z), the frame's values, land inactive, placement and time as metadata;
// and the one placement every VDB of the project shares.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <gtest/gtest.h>

#include "export_test_support.hpp"
#include "nearshore/bathymetry/coastline_level_set.hpp"
#include "nearshore/export/export_sequence.hpp"
#include "nearshore/loops/sequence_vdb.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::exports {
namespace {
using testing::TestWave;
namespace fs = std::filesystem;

TEST(ExportVdb, EachFrameIsOneHeightFieldWithLandInactive) {
  const fs::path folder = testing::scratch_folder();
  TestWave::write(folder / "sequence");
  const ExportSummary summary = export_sequence({folder / "sequence", folder / "out", ExportFormat::kVdb, {4, 7}});
  ASSERT_EQ(summary.files.size(), 3u);
  openvdb::initialize();
  const sequence::SequenceReader reader(folder / "sequence");
  int water_cells = 0;
  for (int row = 0; row < TestWave::kRows; ++row)
    for (int column = 0; column < TestWave::kColumns; ++column) water_cells += !TestWave::is_land(column, row);
  for (int index = 4; index < 7; ++index) {
    openvdb::io::File file((folder / "out" / ("surface_00000" + std::to_string(index) + ".vdb")).string());
    file.open();
    const openvdb::MetaMap::Ptr metadata = file.getMetadata();
    EXPECT_EQ(metadata->metaValue<int32_t>("nearshore_frame_index"), index);
    EXPECT_DOUBLE_EQ(metadata->metaValue<double>("nearshore_time_s"), TestWave::frame_time_s(index));
    EXPECT_DOUBLE_EQ(metadata->metaValue<double>("nearshore_origin_x_m"), TestWave::kOriginX_m);
    auto eta = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("surface_elevation"));
    auto breaking = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("breaking"));
    file.close();
    ASSERT_TRUE(eta && breaking);
    EXPECT_EQ(eta->activeVoxelCount(), static_cast<openvdb::Index64>(water_cells));
    const openvdb::CoordBBox box = eta->evalActiveVoxelBoundingBox();
    EXPECT_EQ(box.min().z(), 0);
    EXPECT_EQ(box.max().z(), 0);  // one layer: time is the file, not the z axis
    const sequence::Frame frame = reader.read_frame(index);
    auto accessor = eta->getConstAccessor();
    for (int row = 0; row < TestWave::kRows; ++row)
      for (int column = 0; column < TestWave::kColumns; ++column) {
        const openvdb::Coord voxel(column, row, 0);
        EXPECT_EQ(accessor.isValueOn(voxel), !TestWave::is_land(column, row)) << column << ", " << row;
        if (!TestWave::is_land(column, row)) {
          EXPECT_EQ(accessor.getValue(voxel), frame.surface_elevation_m(column, row));
        }
      }
    EXPECT_EQ(breaking->getConstAccessor().getValue(openvdb::Coord(1, 4, 0)), TestWave::breaking(1, index) ? 1.0f : 0.0f);
    // Cell (3, 4) has its centre 35 m east and 45 m north of the grid's south-west corner.
    const openvdb::Vec3d centre = eta->transform().indexToWorld(openvdb::Coord(3, 4, 0));
    EXPECT_DOUBLE_EQ(centre.x(), 35.0);
    EXPECT_DOUBLE_EQ(centre.y(), 45.0);
  }
}

// The three VDB writers (export --to vdb, loops --vdb, bathy's coastline level set) put a cell at
// the same point: they all go through core/vdb (before, `loops --vdb` put it at its corner, half a
// cell from where `export --to vdb` put it), with rectangular cells too.
TEST(ExportVdb, EveryVdbOfTheProjectPlacesACellAtTheSamePoint) {
  const fs::path folder = testing::scratch_folder();
  const double spacing_y_m = 6.0;
  TestWave::write(folder / "sequence", spacing_y_m);
  export_sequence({folder / "sequence", folder / "out", ExportFormat::kVdb, {0, 1}});
  loops::export_sequence_vdb(folder / "sequence", folder / "stacked.vdb", {0, 1, 1, false});
  const GridGeometry geometry = TestWave::geometry(spacing_y_m);
  bathymetry::write_coastline_level_set(folder / "coast.vdb", geometry,
                                        Raster<float>(geometry.columns, geometry.rows, 1.0f), 5.0);
  openvdb::initialize();
  const std::vector<std::pair<fs::path, std::string>> files = {
      {folder / "out" / "surface_000000.vdb", "surface_elevation"},
      {folder / "stacked.vdb", "surface_elevation"},
      {folder / "coast.vdb", "coast_distance"}};
  for (const auto& [path, name] : files) {
    openvdb::io::File file(path.string());
    file.open();
    const openvdb::GridBase::Ptr grid = file.readGrid(name);
    const openvdb::MetaMap::Ptr metadata = file.getMetadata();
    file.close();
    const openvdb::Vec3d centre = grid->transform().indexToWorld(openvdb::Coord(3, 4, 0));
    EXPECT_DOUBLE_EQ(centre.x(), 3.5 * TestWave::kSpacing_m) << path;
    EXPECT_DOUBLE_EQ(centre.y(), 4.5 * spacing_y_m) << path;
    EXPECT_DOUBLE_EQ(metadata->metaValue<double>("nearshore_origin_y_m"), TestWave::kOriginY_m) << path;
    EXPECT_DOUBLE_EQ(metadata->metaValue<double>("nearshore_spacing_y_m"), spacing_y_m) << path;
  }
}

}  // namespace
}  // namespace nearshore::exports
