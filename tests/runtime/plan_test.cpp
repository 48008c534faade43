// Playback plans (runtime/playback_plan.hpp): the same seed gives the same steps, loops show what
// sequence/loop_playback.hpp's schedule says, the random walk takes only transitions of
// probability > 0 and crossfades every jump as planned, and a bad loops.json is a clear error.
#include "nearshore/runtime/playback_plan.hpp"

#include <fstream>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "nearshore/core/error.hpp"
#include "runtime_test_support.hpp"

namespace nearshore::runtime {
namespace {
using namespace testing;

// A 40-frame sequence of small 8 x 6 frames (the plans read only its manifest).
fs::path small_sequence(int frames = 40) {
  const fs::path folder = scratch_folder();
  write_wave_sequence(folder, wave_geometry(8, 6, 2.0), {{0.2, 0.3, 0.0, 1.7, 0.0}}, frames, 0.25);
  return folder;
}

const std::vector<Jump> kJumps = {{30, 5, 0.3, 4}, {37, 12, 0.5, 3}, {20, 2, 0.2, 2}, {38, 20, 1.0, 5},
                                  {10, 25, 0.0, 3}};  // probability 0: kept for loop planning, never walked

bool same(const sequence::BlendSource& a, const sequence::BlendSource& b) {
  return a.source_frame == b.source_frame && a.target_frame == b.target_frame && a.target_weight == b.target_weight;
}

TEST(PlaybackPlan, SameSeedGivesTheSameStepsAndRandomAccessReplays) {
  const fs::path folder = small_sequence();
  sequence::write_loops_file(folder, walk_tables_for(folder, kJumps, 0, 99));
  PlaybackPlan a(folder, PlanKind::kRandomWalk), b(folder, PlanKind::kRandomWalk);
  PlaybackPlan other(folder, PlanKind::kRandomWalk, 100);
  EXPECT_EQ(a.seed(), 99u);  // loops.json's random_walk.seed
  std::vector<PlanStep> steps;
  int differences = 0;
  for (long long k = 0; k < 3000; ++k) {
    const PlanStep s = a.step(k);
    const PlanStep t = b.step(k);
    ASSERT_EQ(s.frame, t.frame) << k;
    ASSERT_TRUE(same(s.shown, t.shown)) << k;
    ASSERT_EQ(s.transitions_taken, t.transitions_taken);
    differences += other.step(k).frame != s.frame;
    steps.push_back(s);
  }
  EXPECT_GT(differences, 100);  // another seed is another walk
  // Random access: a step behind the last one asked replays the walk from its start.
  for (long long k : {2999LL, 17LL, 1500LL, 0LL, 2998LL}) {
    const PlanStep s = a.step(k);
    EXPECT_EQ(s.frame, steps[static_cast<std::size_t>(k)].frame) << k;
    EXPECT_TRUE(same(s.shown, steps[static_cast<std::size_t>(k)].shown)) << k;
  }
  // A copy continues the same walk.
  PlaybackPlan copy = a;
  EXPECT_EQ(copy.step(2500).frame, steps[2500].frame);
}

TEST(PlaybackPlan, RandomWalkTakesOnlyTransitionsOfPositiveProbabilityAndCrossfadesEveryJump) {
  const fs::path folder = small_sequence();
  sequence::write_loops_file(folder, walk_tables_for(folder, kJumps, 3, 5));
  PlaybackPlan plan(folder, PlanKind::kRandomWalk);
  EXPECT_EQ(plan.max_crossfade_frames(), 5);
  std::map<std::pair<int, int>, int> allowed;  // (from, to) -> crossfade of rows with p > 0
  for (int from = 0; from + 1 < 40; ++from) allowed[{from, from + 1}] = -1;
  for (const Jump& j : kJumps)
    if (j.probability > 0) allowed[{j.from, j.to}] = j.crossfade_frames;
  allowed.erase({38, 39});  // 38 -> 20 has probability 1: the natural successor has 0
  constexpr long long kSteps = 20000;
  std::vector<PlanStep> steps;
  for (long long k = 0; k <= kSteps + 10; ++k) steps.push_back(plan.step(k));
  std::map<std::pair<int, int>, int> taken;
  long long jumps = 0;
  for (long long k = 0; k < kSteps; ++k) {
    const int from = steps[static_cast<std::size_t>(k)].frame, to = steps[static_cast<std::size_t>(k) + 1].frame;
    ASSERT_TRUE(allowed.count({from, to})) << "step " << k << ": " << from << " -> " << to << " has probability 0";
    ++taken[{from, to}];
    const int crossfade = allowed[{from, to}];
    EXPECT_EQ(steps[static_cast<std::size_t>(k)].jump_after_this_step, crossfade >= 0) << k;
    if (crossfade < 0) continue;
    ++jumps;
    EXPECT_EQ(steps[static_cast<std::size_t>(k) + 1].transitions_taken, jumps);
    // The c steps before the jump (those after the previous landing) are loop_playback.hpp's blends.
    for (int before = 1; before <= crossfade && k - before + 1 >= 0; ++before) {
      const PlanStep& s = steps[static_cast<std::size_t>(k - before + 1)];
      sequence::BlendSource expected;
      ASSERT_TRUE(sequence::crossfade_blend(from, to, crossfade, before, expected));
      EXPECT_TRUE(same(s.shown, expected)) << "step " << k - before + 1 << " before the jump " << from << " -> " << to;
      EXPECT_TRUE(s.in_crossfade);
      EXPECT_EQ(s.jump_from, from);
      EXPECT_EQ(s.jump_to, to);
      // Steps before the previous jump landed belong to that jump.
      if (k - before + 1 > 0 && steps[static_cast<std::size_t>(k - before)].jump_after_this_step) break;
    }
  }
  EXPECT_GT(jumps, 200);
  EXPECT_EQ(taken.count({10, 25}), 0u);  // probability 0 is never walked
  EXPECT_GT(taken[std::make_pair(38, 20)], 50);        // probability 1 always
  EXPECT_GT(taken[std::make_pair(30, 5)], 20);
  EXPECT_GT(taken[std::make_pair(37, 12)], 20);
  EXPECT_FALSE(steps[100].restarted_at_dead_end);
}

TEST(PlaybackPlan, LoopsShowWhatLoopPlaybackSchedules) {
  const fs::path folder = small_sequence();
  sequence::LoopsFile tables = tables_for(folder);
  sequence::LoopsFile::Loop period;
  period.kind = "period";
  period.start_frame = 5;
  period.length_frames = 30;
  period.length_s = 7.5;
  period.seams = {{.from = 34, .to = 5, .crossfade_frames = 4}};
  sequence::LoopsFile::Loop optimal;
  optimal.kind = "optimal";
  optimal.start_frame = 4;
  optimal.length_frames = 20;
  optimal.length_s = 5;
  optimal.worst_seam_ratio_after = 0.7;
  optimal.seams = {{.from = 12, .to = 20, .crossfade_frames = 3}, {.from = 30, .to = 4, .crossfade_frames = 4}};
  tables.report.period_loop = period;
  tables.report.best_loops_by_length = {optimal};
  sequence::write_loops_file(folder, tables);

  PlaybackPlan exact(folder, PlanKind::kExactPeriod);
  const sequence::LoopSchedule exact_schedule = sequence::schedule_of(period);
  ASSERT_EQ(exact.cycle_length_steps(), 30);
  for (long long k = 0; k < 3 * 30; ++k) {
    const PlanStep s = exact.step(k);
    EXPECT_TRUE(same(s.shown, exact_schedule.shown[static_cast<std::size_t>(k % 30)])) << k;
    EXPECT_EQ(s.transitions_taken, k / 30);
  }
  // kOptimalLoop plays read_loop_schedule's choice: the period loop when there is one.
  PlaybackPlan chosen(folder, PlanKind::kOptimalLoop);
  EXPECT_TRUE(same(chosen.step(29).shown, exact_schedule.shown[29]));
  // Without it, the optimal loop of two jumps.
  tables.report.period_loop.reset();
  sequence::write_loops_file(folder, tables);
  PlaybackPlan loop(folder, PlanKind::kOptimalLoop);
  const auto schedule = sequence::read_loop_schedule(folder);
  ASSERT_TRUE(schedule.has_value());
  for (long long k = 0; k < 4 * 20; ++k)
    EXPECT_TRUE(same(loop.step(k).shown, schedule->shown[static_cast<std::size_t>(k % 20)])) << k;
  EXPECT_EQ(loop.step(40).transitions_taken, 4);
  EXPECT_THROW(PlaybackPlan(folder, PlanKind::kExactPeriod), Error);  // not a periodic bake
}

std::string error_of(const fs::path& folder, PlanKind kind) {
  try {
    PlaybackPlan plan(folder, kind);
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error";
  return {};
}

TEST(PlaybackPlan, FrameOrderNeedsNoTablesAndBadTablesAreClearErrors) {
  const fs::path folder = small_sequence(12);
  PlaybackPlan order(folder, PlanKind::kFrameOrder);
  EXPECT_EQ(order.step(0).frame, 0);
  EXPECT_EQ(order.step(11).frame, 11);
  EXPECT_TRUE(order.step(11).jump_after_this_step);  // the hard cut back to 0
  EXPECT_EQ(order.step(12).frame, 0);
  EXPECT_EQ(order.step(25).transitions_taken, 2);
  EXPECT_FALSE(order.step(11).in_crossfade);

  // No loops.json: the message names the file and the fix.
  std::string message = error_of(folder, PlanKind::kRandomWalk);
  EXPECT_NE(message.find("loops.json"), std::string::npos) << message;
  EXPECT_NE(message.find("nearshore loops"), std::string::npos) << message;
  // Made for another bake (its manifest checksum differs).
  sequence::LoopsFile tables = walk_tables_for(folder, {}, 0, 1);
  tables.transitions.push_back({.from = 11, .to = 0, .probability = 1.0});
  tables.sequence_manifest_checksum = "xxh64:0123456789abcdef";
  sequence::write_loops_file(folder, tables);
  message = error_of(folder, PlanKind::kRandomWalk);
  EXPECT_NE(message.find("another bake"), std::string::npos) << message;
  // A newer version.
  nlohmann::json newer = sequence::loops_file_to_json(tables);
  newer["version"] = sequence::kLoopsFileVersion + 1;
  std::ofstream(folder / "loops.json") << newer.dump();
  message = error_of(folder, PlanKind::kOptimalLoop);
  EXPECT_NE(message.find("version"), std::string::npos) << message;
  // Malformed.
  std::ofstream(folder / "loops.json") << "{\"format\": \"nearshore loops\", \"version\": 1, \"transitions\": [";
  EXPECT_FALSE(error_of(folder, PlanKind::kRandomWalk).empty());
  EXPECT_EQ(parse_plan_kind("random walk"), PlanKind::kRandomWalk);
  EXPECT_EQ(parse_plan_kind("loop"), PlanKind::kOptimalLoop);
  EXPECT_FALSE(parse_plan_kind("shuffle").has_value());
}

}  // namespace
}  // namespace nearshore::runtime
