// loops.json -> the schedule a player follows (sequence/loop_playback.hpp): which plan is chosen,
// its crossfades, and a loops table made for another bake refused.
#include "nearshore/sequence/loop_playback.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "nearshore/core/error.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "nearshore/sequence/loops_file.hpp"
#include "nearshore/sequence/sequence_format.hpp"
#include "test_sequence.hpp"

namespace nearshore::sequence {
namespace {
namespace fs = std::filesystem;
using namespace testing;

LoopsFile::Loop loop(const std::string& kind, int start, int length, double worst_after,
                     const std::vector<PlannedJump>& jumps) {
  LoopsFile::Loop planned;
  planned.kind = kind;
  planned.start_frame = start;
  planned.length_frames = length;
  planned.length_s = 0.5 * length;
  planned.worst_seam_ratio_after = worst_after;
  for (const PlannedJump& jump : jumps)
    planned.seams.push_back({.from = jump.from, .to = jump.to, .crossfade_frames = jump.crossfade_frames});
  return planned;
}

// A loops table without plans for the sequence in `folder` (its manifest checksum and frame count).
LoopsFile tables_for(const fs::path& folder) {
  const std::string manifest = read_file_bytes(folder / "manifest.json");
  LoopsFile tables;
  tables.sequence_manifest_checksum =
      checksum_text(std::as_bytes(std::span(manifest.data(), manifest.size())));
  tables.report.frame_count = parse_manifest(manifest, "manifest.json").frame_count;
  tables.report.frame_interval_s = 0.25;
  return tables;
}

TEST(LoopPlayback, ThePeriodLoopIsPlayedWhenThereIsOne) {
  const fs::path folder = fresh_folder("loop_schedule_period");
  write_test_sequence(folder, 20);
  EXPECT_FALSE(read_loop_schedule(folder).has_value());  // no loops.json yet
  LoopsFile tables = tables_for(folder);
  tables.report.best_loops_by_length.push_back(loop("optimal", 3, 10, 0.5, {{12, 3, 2}}));
  tables.report.period_loop = loop("period", 5, 13, 0.03, {{17, 5, 4}});
  write_loops_file(folder, tables);
  const auto schedule = read_loop_schedule(folder);
  ASSERT_TRUE(schedule.has_value());
  EXPECT_EQ(schedule->kind, "period");
  ASSERT_EQ(schedule->shown.size(), 13u);
  EXPECT_EQ(schedule->shown.front().source_frame, 5);
  EXPECT_EQ(schedule->shown.back().source_frame, 17);
  // The last frame before the jump 17 -> 5 is the 4th blend of 4: weight 4/5 on target frame 4.
  EXPECT_EQ(schedule->shown.back().target_frame, 4);
  EXPECT_DOUBLE_EQ(schedule->shown.back().target_weight, 0.8);
  EXPECT_EQ(schedule->shown[8].target_weight, 0.0);  // frame 13: before the crossfade
}

TEST(LoopPlayback, OtherwiseTheLongestLoopWhoseSeamsAreNoWorseThanAStep) {
  const fs::path folder = fresh_folder("loop_schedule_best");
  write_test_sequence(folder, 30);
  LoopsFile tables = tables_for(folder);
  tables.report.best_loops_by_length.push_back(loop("optimal", 3, 10, 0.5, {{12, 3, 2}}));
  // (A crossfade into frame `to` blends at most `to` frames: targets to - c .. to - 1 must exist.)
  tables.report.best_loops_by_length.push_back(loop("optimal", 1, 25, 0.9, {{25, 1, 1}}));
  // Longer, but its seam is too visible.
  tables.report.best_loops_by_length.push_back(loop("optimal", 0, 28, 1.7, {{27, 0, 0}}));
  write_loops_file(folder, tables);
  const auto schedule = read_loop_schedule(folder);
  ASSERT_TRUE(schedule.has_value());
  EXPECT_EQ(schedule->shown.size(), 25u);
  EXPECT_EQ(schedule->shown.front().source_frame, 1);
}

TEST(LoopPlayback, ALoopsTableOfAnotherBakeIsRefused) {
  const fs::path folder = fresh_folder("loop_schedule_stale");
  write_test_sequence(folder, 20);
  LoopsFile tables = tables_for(folder);
  tables.sequence_manifest_checksum = "xxh64:0000000000000000";
  tables.report.period_loop = loop("period", 5, 13, 0.03, {{17, 5, 4}});
  write_loops_file(folder, tables);
  try {
    read_loop_schedule(folder);
    FAIL() << "a stale loops.json was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("another bake"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nearshore loops"), std::string::npos) << e.what();
  }
  std::ofstream(folder / "loops.json") << "{ not json";
  EXPECT_THROW(read_loop_schedule(folder), Error);
}

// Same manifest but a table that counts more frames than the bake has: its plans could point past
// the last frame, so it is refused rather than played.
TEST(LoopPlayback, ALoopsTableCountingOtherFramesIsRefused) {
  const fs::path folder = fresh_folder("loop_schedule_frames");
  write_test_sequence(folder, 20);
  LoopsFile tables = tables_for(folder);
  tables.report.frame_count = 40;
  tables.report.period_loop = loop("period", 20, 13, 0.03, {{32, 20, 4}});
  write_loops_file(folder, tables);
  try {
    read_loop_schedule(folder);
    FAIL() << "a loops.json for 40 frames was played on a 20-frame bake";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("counts 40 frames"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace nearshore::sequence
