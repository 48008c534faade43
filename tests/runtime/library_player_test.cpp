// LibraryPlayer (runtime/library_player.hpp): a sea-state library's states crossfade on request,
// and the snapshot shown mid-fade is (1 - w) one state + w the other with w the smoothstep of the
// fade's progress; the CPU queries sample that blend. Two sequences of different waves stand for
// two baked states; the index is written through sequence::write_library_index like a library run.
#include "nearshore/runtime/library_player.hpp"

#include <gtest/gtest.h>

#include <chrono>

#include "nearshore/core/error.hpp"
#include "nearshore/runtime/surface_sampler.hpp"
#include "runtime_test_support.hpp"

namespace nearshore::runtime {
namespace {
using namespace testing;
using namespace std::chrono_literals;

fs::path two_state_library() {
  const fs::path folder = scratch_folder();
  write_two_state_library(folder);
  return folder;
}

StreamingOptions calm() {
  StreamingOptions options;
  options.plan = PlanKind::kFrameOrder;
  options.deep_water = DeepWaterChoice::kNone;
  return options;
}

TEST(LibraryPlayer, CrossfadesBetweenStatesWithTheSmoothstepWeight) {
  const fs::path folder = two_state_library();
  sequence::SeaConditions west;
  west.direction_deg = 10.0;  // nearest: dir0
  LibraryPlayer player(folder, west, calm());
  EXPECT_EQ(player.state_id(), "dir0");
  sequence::SeaConditions south;
  south.direction_deg = 80.0;
  // The same state asked again changes nothing.
  EXPECT_EQ(player.request(west, 2.0), "dir0");
  ASSERT_TRUE(player.engine().wait_until_ready(1.0, 20s));
  player.advance_to(1.0);
  EXPECT_EQ(player.crossfade_weight(), 1.0);

  EXPECT_EQ(player.request(south, 2.0), "dir90");
  const std::vector<double> times = {1.0, 1.5, 2.0, 2.5, 3.0, 3.5};  // the fade starts at the first: 1.0 s
  for (double t : times) {
    // Both states' frames: the one fading out streams on its own and may lag the new one.
    ASSERT_TRUE(player.wait_until_ready(t, 20s)) << t;
    player.advance_to(t);
    const double u = (t - 1.0) / 2.0;
    const double w = u >= 1.0 ? 1.0 : u * u * (3.0 - 2.0 * u);
    EXPECT_NEAR(player.crossfade_weight(), w, 1e-12) << t;
    const SurfaceSampler sampler(player.snapshot());
    // At cell centres, at a frame's own time, each state's frames are its waves (half precision).
    for (double x : {32.5, 57.5, 82.5}) {
      const double y = 47.5;
      const double expected = (1.0 - w) * wave_elevation_m(kLibraryFromWest, x, y, t) + w * wave_elevation_m(kLibraryFromSouth, x, y, t);
      EXPECT_NEAR(sampler.elevation_m(x, y), expected, 2e-3) << "t = " << t << ", x = " << x;
    }
  }
  EXPECT_EQ(player.crossfade_weight(), 1.0);
  EXPECT_EQ(player.state_id(), "dir90");
}

TEST(LibraryPlayer, ALibraryWithNothingBakedIsRefusedByName) {
  const fs::path folder = two_state_library();
  sequence::LibraryIndex index = sequence::read_library_index(folder);
  for (auto& state : index.states) {
    state.status = sequence::LibraryStateStatus::kFailed;
    state.error = "unstable";
    state.manifest_checksum.clear();
    state.loops_checksum.clear();
  }
  sequence::write_library_index(folder, index);
  try {
    LibraryPlayer player(folder, {}, calm());
    FAIL() << "no error";
  } catch (const nearshore::Error& error) {
    EXPECT_NE(std::string(error.what()).find("library.json"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("no baked sea state"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace nearshore::runtime
