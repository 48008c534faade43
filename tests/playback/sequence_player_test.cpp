// SequencePlayer against a sequence written by the real SequenceWriter: frames follow the order,
// repeat forever, and are blended linearly between steps.
#include "nearshore/playback/sequence_player.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "nearshore/core/error.hpp"
#include "nearshore/sequence/sequence_writer.hpp"

namespace {
using namespace nearshore;
namespace fs = std::filesystem;

// Frame k holds eta = k / 8 m everywhere (exact in half precision), breaking = 0.
fs::path write_ramp_sequence(int frame_count) {
  const fs::path folder = fs::temp_directory_path() / "nearshore_player_test";
  fs::remove_all(folder);
  GridGeometry geometry;
  geometry.columns = 8;
  geometry.rows = 6;
  geometry.spacing_m = 2.0;
  const HarbourGrid harbour = HarbourGrid::open_water(geometry, 5.f);
  sequence::SequenceDescription description;
  description.frame_interval_s = 0.5;
  sequence::SequenceWriter writer(folder, harbour, description);
  Raster<float> zero(8, 6, 0.f);
  for (int k = 0; k < frame_count; ++k) {
    Raster<float> eta(8, 6, k / 8.f);
    writer.write_frame(k, {&eta, &zero, &zero, &zero});
  }
  writer.finish(frame_count);
  return folder;
}
}  // namespace

TEST(SequencePlayer, BlendsLinearlyAndWrapsAround) {
  const sequence::SequenceReader reader(write_ramp_sequence(4));
  playback::SequencePlayer player(reader);
  player.advance_to(0.25);  // half way from frame 0 to frame 1
  EXPECT_FLOAT_EQ(player.surface_elevation_m()(3, 2), 0.5f * (0.f + 1.f / 8));
  player.advance_to(1.5);  // exactly frame 3
  EXPECT_FLOAT_EQ(player.surface_elevation_m()(0, 0), 3.f / 8);
  player.advance_to(1.75);  // half way from frame 3 back to frame 0
  EXPECT_FLOAT_EQ(player.surface_elevation_m()(0, 0), 0.5f * 3.f / 8);
  player.advance_to(2.0 + 0.5);  // the order repeats: frame 1
  EXPECT_EQ(player.order_position(), 1);
  EXPECT_FLOAT_EQ(player.surface_elevation_m()(7, 5), 1.f / 8);
}

TEST(SequencePlayer, FollowsAGivenFrameOrder) {
  const sequence::SequenceReader reader(write_ramp_sequence(5));
  playback::SequencePlayer player(reader, {4, 2, 3});
  for (int step = 0; step < 7; ++step) {
    player.advance_to(step * 0.5);
    const int expected = std::vector<int>{4, 2, 3}[step % 3];
    EXPECT_FLOAT_EQ(player.surface_elevation_m()(1, 1), expected / 8.f) << "step " << step;
  }
  EXPECT_THROW(playback::SequencePlayer(reader, {0, 9}), nearshore::Error);
}
