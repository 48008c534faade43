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
  // One folder per test: ctest runs the tests of this executable in parallel.
  const fs::path folder =
      fs::temp_directory_path() / (std::string("nearshore_player_test_") +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
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
  EXPECT_THROW(playback::SequencePlayer(reader, std::vector<int>{0, 9}), nearshore::Error);
}

// A planned loop 4 .. 9 with the jump 9 -> 4 crossfaded over 2 frames: the last two steps before
// the jump show (2/3) f(8) + (1/3) f(2) and (1/3) f(9) + (2/3) f(3) (loop_playback.hpp), so eta
// steps 0.5, 0.625, 0.75, 0.875, 0.75, 0.625, then back to 0.5: no hard cut from 1.125 to 0.5.
TEST(SequencePlayer, PlaysTheCrossfadeBlendsOfALoopSchedule) {
  const sequence::SequenceReader reader(write_ramp_sequence(12));
  playback::SequencePlayer player(reader, sequence::schedule_loop(4, 6, {{9, 4, 2}}));
  const std::vector<float> expected = {0.5f, 0.625f, 0.75f, 0.875f, 0.75f, 0.625f, 0.5f};
  for (int step = 0; step < 7; ++step) {
    player.advance_to(step * 0.5);
    EXPECT_NEAR(player.surface_elevation_m()(2, 3), expected[static_cast<std::size_t>(step)], 1e-6)
        << "step " << step;
  }
  EXPECT_EQ(player.frame_order(), (std::vector<int>{4, 5, 6, 7, 8, 9}));
  EXPECT_THROW(playback::SequencePlayer(reader, sequence::schedule_loop(4, 6, {{9, 1, 3}})),
               nearshore::Error);
}
