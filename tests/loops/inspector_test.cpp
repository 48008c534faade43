#include "nearshore/loops/inspector.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "loops_test_support.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/loops/synthetic_sea.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "nearshore/sequence/loops_file.hpp"

namespace nearshore::loops {
namespace {
using namespace testing;

// End to end on a periodic sequence stored as half (the default encoding): the inspector finds
// the period with R <= 0.1 (the bar; half rounding alone gives ~1e-3), writes the tables,
// and a second run reuses the stored Gram matrices with identical results.
// Issue 14 item 4: `--loop-s 60` once returned a 12 s loop played five times. On a periodic sea
// every whole-period jump is free, so the cheapest closed walk of four periods may be the one-period
// loop four times over; the requested loop must instead show every frame once (the viewer would
// otherwise see the short repeat), at the requested length or the nearest one that does.
TEST(Inspector, RequestedLoopNeverReplaysAShorterLoop) {
  const auto folder = fresh_folder("requested");
  // A periodic sea plus a slow swell of 200 s period that does not repeat within the bake (the slow
  // part of a real harbour's flow): a jump back by d frames then costs about d^2, so four one-period
  // jumps (4 x 32^2) beat one four-period jump (128^2) and the cheapest walk is the short loop x 4.
  SyntheticSea sea = periodic_sea(8.0, 3, 1.5, 8.0, 5);
  ocean::LatticeWave slow;
  slow.wave.amplitude_m = 0.5;
  slow.wave.angular_frequency_rad_s = 2.0 * 3.141592653589793 / 200.0;
  slow.wavenumber_x_rad_m = 2.0 * 3.141592653589793 / 5000.0;
  sea.components.push_back(slow);
  write_sea_sequence(folder, sea, small_geometry(), 140, 0.25, 0.0);
  LoopsOptions options;
  options.report_lengths_s = {8};
  options.requested_loop_s = 32.0;  // 128 frames: four periods
  const LoopsReport report = analyse_loops(folder, options);
  ASSERT_TRUE(report.requested);
  EXPECT_TRUE(report.requested->plan.shows_each_frame_once());
  EXPECT_EQ(report.requested->plan.repetitions(), 1);
  EXPECT_GE(report.requested->plan.length_frames, 0.8 * 128);
  EXPECT_LE(report.requested->plan.length_frames, 1.25 * 128);
}

TEST(Inspector, PeriodicSequenceLoopsAtItsPeriodAndTablesAreReused) {
  const auto folder = fresh_folder("inspector");
  write_sea_sequence(folder, periodic_sea(8.0, 3, 1.5, 8.0, 5), small_geometry(), 90, 0.25, 8.0);
  LoopsOptions options;
  options.report_lengths_s = {5, 8, 16};
  const LoopsReport first = analyse_loops(folder, options);
  ASSERT_TRUE(first.period);
  EXPECT_EQ(first.period->plan.length_frames, 32);
  EXPECT_LE(first.period->worst_seam_ratio_before, 0.1);
  EXPECT_LE(first.worst_seam_ratio_after(), 0.1);
  EXPECT_FALSE(first.gram_reused);
  EXPECT_TRUE(std::filesystem::exists(folder / "loops.json"));
  EXPECT_TRUE(first.reachable_dead_ends.empty());
  // The only candidate jumps of a periodic sea are whole periods: the 5 s bucket (20-25 frames)
  // has no loop; the 8 s and 16 s buckets get 32 and 64 frames at zero cost.
  ASSERT_EQ(first.best_by_length.size(), 2u);
  EXPECT_EQ(first.best_by_length[0].plan.length_frames, 32);
  EXPECT_EQ(first.best_by_length[1].plan.length_frames, 64);
  EXPECT_LE(first.best_by_length[1].worst_seam_ratio_before, 0.1);
  // loops.json reads back through its type, and that type holds all of it: written again, the
  // same bytes.
  const sequence::LoopsFile stored = sequence::read_loops_file(folder);
  EXPECT_EQ(sequence::loops_file_to_json(stored).dump(1), sequence::read_file_bytes(folder / "loops.json"));
  EXPECT_DOUBLE_EQ(stored.report.parameters.sigma, first.sigma);
  EXPECT_EQ(stored.report.parameters.filter_half_width_frames, 2);
  EXPECT_EQ(stored.random_walk.start_frame, first.first_playable_frame);
  EXPECT_EQ(stored.transitions.size(), first.table.transitions.size());
  ASSERT_TRUE(stored.report.period_loop);
  EXPECT_EQ(stored.report.period_loop->length_frames, 32);
  const LoopsReport second = analyse_loops(folder, options);
  EXPECT_TRUE(second.gram_reused);
  const sequence::LoopsFile stored_again = sequence::read_loops_file(folder);
  EXPECT_TRUE(stored_again.report.gram_reused);
  EXPECT_EQ(stored_again.report.best_loops_by_length, stored.report.best_loops_by_length);
  EXPECT_EQ(stored_again.transitions, stored.transitions);
  EXPECT_EQ(second.to_json(), sequence::loops_report_to_json(stored_again.report));
  // A stored table that cannot be read (here: truncated) vouches for nothing: the Gram matrices are
  // computed again and a good table replaces it.
  std::ofstream(folder / "loops.json") << "{ \"format\": \"nearshore loops\", ";
  const LoopsReport third = analyse_loops(folder, options);
  EXPECT_FALSE(third.gram_reused);
  EXPECT_EQ(sequence::read_loops_file(folder).transitions.size(), stored.transitions.size());
  write_loops_pictures(first, folder / "png");
  for (const char* name : {"distance_matrix.png", "seam_ratios.png", "worst_seam_gauge.png"})
    EXPECT_TRUE(std::filesystem::exists(folder / "png" / name)) << name;
}

// Stored Gram matrices vouch for the frames as they were (issue 44): a frame removed or damaged
// since is found (the run exited 0 reusing them), and the temporary table a killed run left
// (loops_gram.bin.tmp-PID, megabytes) is removed by the next run, not kept.
TEST(Inspector, ReusedTablesDoNotHideAMissingOrDamagedFrameAndKilledRunsTemporariesGo) {
  const auto folder = fresh_folder("damaged");
  write_sea_sequence(folder, periodic_sea(8.0, 3, 1.5, 8.0, 5), small_geometry(), 40, 0.25, 8.0);
  LoopsOptions options;
  options.report_lengths_s = {5};
  analyse_loops(folder, options);
  std::ofstream(folder / "loops_gram.bin.tmp-2147483646") << std::string(4096, 'g');  // a killed run's
  EXPECT_TRUE(analyse_loops(folder, options).gram_reused);
  EXPECT_FALSE(std::filesystem::exists(folder / "loops_gram.bin.tmp-2147483646"));
  const std::filesystem::path frame = folder / "frame_000017.exr";
  const std::string bytes = sequence::read_file_bytes(frame);
  for (const bool removed : {true, false}) {
    if (removed) {
      std::filesystem::remove(frame);
    } else {
      std::string damaged = bytes;
      damaged[damaged.size() / 2] ^= 0x5a;
      std::ofstream(frame, std::ios::binary) << damaged;
    }
    try {
      analyse_loops(folder, options);
      ADD_FAILURE() << "loops ran on a sequence whose frame 17 is " << (removed ? "missing" : "damaged");
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("frame_000017.exr"), std::string::npos) << error.what();
    }
  }
}

}  // namespace
}  // namespace nearshore::loops
