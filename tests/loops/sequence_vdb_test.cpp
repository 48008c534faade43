#include <gtest/gtest.h>

#include <openvdb/openvdb.h>
#include <openvdb/io/File.h>

#include "loops_test_support.hpp"
#include "nearshore/loops/sequence_vdb.hpp"
#include "nearshore/loops/synthetic_sea.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::loops {
namespace {
using namespace testing;

// Frames land on the third axis, values are the frames' own (float storage: exact), land inactive.
TEST(SequenceVdb, FramesBecomeTheThirdAxisWithLandInactive) {
  const auto folder = fresh_folder("vdb");
  const GridGeometry geometry = small_geometry(12, 8);
  HarbourGrid harbour = HarbourGrid::open_water(geometry, 5.0f);
  for (int column = 0; column < 12; ++column) harbour.land(column, 7) = 1;  // northern row is land
  sequence::SequenceDescription description;
  description.frame_interval_s = 0.5;
  description.encoding = {sequence::Compression::kNone, sequence::Precision::kFloat, sequence::Precision::kFloat,
                          sequence::Precision::kFloat};
  {
    sequence::SequenceWriter writer(folder, harbour, description);
    Raster<float> eta, p, q;
    for (int k = 0; k < 4; ++k) {
      evaluate_sea(periodic_sea(4.0, 2, 1.0, 5.0, 1), geometry, 0.5 * k, eta, p, q);
      writer.write_frame(k, {&eta, &p, &q, nullptr});
    }
    writer.finish(4);
  }
  export_sequence_vdb(folder, folder / "sea.vdb", {1, 3, 2, true});  // frames 1 and 3
  openvdb::initialize();
  openvdb::io::File file((folder / "sea.vdb").string());
  file.open();
  auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("surface_elevation"));
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->activeVoxelCount(), 2u * 12u * 7u);
  const sequence::Frame frame3 = sequence::SequenceReader(folder).read_frame(3);
  auto accessor = grid->getConstAccessor();
  EXPECT_EQ(accessor.getValue(openvdb::Coord(5, 2, 1)), frame3.surface_elevation_m(5, 2));
  EXPECT_FALSE(accessor.isValueOn(openvdb::Coord(5, 7, 1)));  // land
  EXPECT_TRUE(file.readGrid("flux_y"));
  EXPECT_DOUBLE_EQ(grid->voxelSize()[0], geometry.spacing_m);
  // Voxel (5, 2, 1) is cell (5, 2) at its centre, metres from the south-west corner (vdb_file.hpp).
  const openvdb::Vec3d centre = grid->transform().indexToWorld(openvdb::Coord(5, 2, 1));
  EXPECT_DOUBLE_EQ(centre.x(), 5.5 * geometry.spacing_m);
  EXPECT_DOUBLE_EQ(centre.y(), 2.5 * geometry.spacing_m);
  file.close();
}

}  // namespace
}  // namespace nearshore::loops
