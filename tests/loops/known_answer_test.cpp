#include <gtest/gtest.h>

#include <cmath>

#include "loops_test_support.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/loops/plans.hpp"
#include "nearshore/loops/synthetic_sea.hpp"

namespace nearshore::loops {
namespace {
using namespace testing;

const sequence::FrameEncoding kExact{sequence::Compression::kZip, sequence::Precision::kFloat,
                                     sequence::Precision::kFloat, sequence::Precision::kFloat};

// A sum of sines whose frequencies are all harmonics of 1/T with T = 24 frames (6 s at 0.25 s):
// f(k + 24) = f(k) up to float rounding of the same values, and no shorter shift repeats.
struct PeriodicCase {
  static constexpr int kPeriodFrames = 24;
  static constexpr int kFrames = 100;
  static constexpr double kInterval = 0.25;
  std::filesystem::path folder = fresh_folder("periodic");
  DistanceMatrices distances;
  TransitionTable table;
  PeriodicCase() {
    write_sea_sequence(folder, periodic_sea(kPeriodFrames * kInterval, 4, 1.0, 6.0, 11), small_geometry(),
                       kFrames, kInterval, kPeriodFrames * kInterval, kExact);
    distances = distances_from_gram(compute_gram_matrices(sequence::SequenceReader(folder)), 1.0);
    table = build_transition_table(distances, TransitionOptions{});
  }
};

// "Zero" below is float rounding of identical fields: |f_i - f_j| / max <= 1e-5.
constexpr double kZero = 1e-5;

TEST(KnownAnswer, SumOfSinesRepeatsExactlyAtItsPeriodOnly) {
  const PeriodicCase c;
  const Eigen::MatrixXd& d = c.distances.combined;
  for (int i = 0; i + PeriodicCase::kPeriodFrames < PeriodicCase::kFrames; ++i) {
    EXPECT_LT(d(i, i + PeriodicCase::kPeriodFrames), kZero) << i;
    for (int shift = 1; shift < PeriodicCase::kPeriodFrames; ++shift)
      ASSERT_GT(d(i, i + shift), 0.05) << i << " +" << shift;
  }
}

// The table: every transition a random walk may take either is the natural successor or lands
// exactly a whole number of periods away, at zero cost, and then is as likely as the natural one
// (or, where the natural successor leads into the dead end at the sequence's end, as likely as
// the other zero-cost jumps: the future cost gives that natural successor probability 0).
TEST(KnownAnswer, SumOfSinesTableHasOnlyWholePeriodJumps) {
  const PeriodicCase c;
  int jumps = 0;
  for (int i = 0; i < PeriodicCase::kFrames; ++i) {
    const auto row = c.table.from(i);
    double natural = -1;
    for (const Transition& t : row)
      if (t.natural()) natural = t.probability;
    if (natural == 0)
      for (const Transition& t : row)
        if (t.probability > 0) natural = t.probability;  // any taken one: they must all be equal
    for (const Transition& t : row) {
      if (t.natural() || t.probability == 0) continue;
      ++jumps;
      EXPECT_EQ((t.to - (t.from + 1)) % PeriodicCase::kPeriodFrames, 0) << t.from << " -> " << t.to;
      EXPECT_LT(t.cost, kZero);
      EXPECT_NEAR(t.probability, natural, 1e-6) << t.from << " -> " << t.to;
    }
  }
  EXPECT_GT(jumps, 50);
  EXPECT_TRUE(c.table.reachable_dead_ends(c.table.first_playable_frame()).empty());
}

// Optimal loops: exactly the multiples of the period cost nothing; every other length costs more.
TEST(KnownAnswer, SumOfSinesBestLoopsAreWholePeriods) {
  const PeriodicCase c;
  const auto best = best_loops_by_length(c.table, 80);
  for (int length = 10; length <= 80; ++length) {
    const bool whole = length % PeriodicCase::kPeriodFrames == 0;
    ASSERT_TRUE(best[length].has_value() || !whole) << length;
    if (!best[length]) continue;
    if (whole)
      EXPECT_LT(best[length]->cost, kZero * kZero) << length;
    else
      EXPECT_GT(best[length]->cost, 1e-4) << length;
  }
  const auto loop = optimal_loop(c.table, 48);
  ASSERT_TRUE(loop);
  EXPECT_EQ(loop->length_frames, 48);
  // A played cycle repeats the field: after the last frame comes the first again, seamlessly.
  const std::vector<int> frames = loop->frames();
  ASSERT_EQ(frames.size(), 48u);
  for (std::size_t k = 0; k + 1 < frames.size(); ++k)
    EXPECT_LT(c.distances.combined(frames[k] + 1, frames[k + 1]), kZero) << k;
}

TEST(KnownAnswer, SumOfSinesPeriodPlanIsTheLastPeriod) {
  const PeriodicCase c;
  const LoopPlan plan = period_loop(c.table, c.distances.combined, 6.0, 0.25);
  EXPECT_EQ(plan.length_frames, 24);
  EXPECT_EQ(plan.start_frame, 100 - 1 - 24);
  ASSERT_EQ(plan.jumps.size(), 1u);
  EXPECT_EQ(plan.jumps[0].from, 98);
  EXPECT_LT(plan.jumps[0].seam_ratio, 1e-3);
  const std::vector<int> frames = plan.frames();
  EXPECT_EQ(frames.front(), 75);
  EXPECT_EQ(frames.back(), 98);
  EXPECT_THROW(period_loop(c.table, c.distances.combined, 6.1, 0.25), Error);  // 24.4 frames
}

// A random walk of fields with frames 30..69 copied to 110..149: the only zero distances are
// D(30 + k, 110 + k); the best loop is the jump back from 110 + k - 1 to 30 + k (80 frames).
TEST(KnownAnswer, PlantedRepeatIsFoundExactly) {
  const auto folder = fresh_folder("planted");
  constexpr int kSource = 30, kCopy = 110, kLength = 40, kFrames = 180;
  write_planted_repeat_sequence(folder, small_geometry(16, 12), kFrames, kSource, kCopy, kLength, 0.05, 3);
  const DistanceMatrices d =
      distances_from_gram(compute_gram_matrices(sequence::SequenceReader(folder)), 1.0);
  for (int i = 0; i < kFrames; ++i)
    for (int j = i + 1; j < kFrames; ++j) {
      const bool planted = j - i == kCopy - kSource && i >= kSource && i < kSource + kLength;
      if (planted)
        EXPECT_LT(d.combined(i, j), 1e-6) << i << ", " << j;
      else
        ASSERT_GT(d.combined(i, j), 1e-3) << i << ", " << j;
    }
  const TransitionTable table = build_transition_table(d, TransitionOptions{});
  // Rows whose next frame lies inside the copy (with the filter's full support) jump back.
  const int m = table.options.filter_half_width;
  for (int k = m; k <= kLength - m; ++k) {
    const int from = kCopy + k - 1, to = kSource + k;
    bool found = false;
    for (const Transition& t : table.from(from))
      if (t.to == to) {
        found = true;
        EXPECT_LT(t.cost, 1e-6);
        EXPECT_GT(t.probability, 0.0);
      }
    EXPECT_TRUE(found) << from << " -> " << to;
  }
  const auto best = best_loops_by_length(table, 150);
  ASSERT_TRUE(best[kCopy - kSource]);
  EXPECT_LT(best[kCopy - kSource]->cost, 1e-10);
  ASSERT_EQ(best[kCopy - kSource]->jumps.size(), 1u);
  EXPECT_EQ(best[kCopy - kSource]->jumps[0].to - best[kCopy - kSource]->jumps[0].from, kSource - kCopy + 1);
  for (int length = 20; length <= 150; ++length)
    if (length != kCopy - kSource && best[length]) {
      EXPECT_GT(best[length]->cost, 1e-8) << length;
    }
  // A long random walk by T never runs into a dead end (the future cost steers it away).
  const std::vector<int> walk = random_walk(table, table.first_playable_frame(), 20000, 99);
  EXPECT_EQ(walk.size(), 20000u);
  EXPECT_TRUE(table.reachable_dead_ends(table.first_playable_frame()).empty());
}

// The compound loop the dynamic programme found on the demo's irregular bake: a 24 s loop
// (23 .. 70, jump 70 -> 23) three times over is no 72 s loop; a loop of two different jumps that
// revisits frames is not simple either; a single backward jump is.
TEST(LoopPlanShape, RepeatedAndReplayingLoopsAreRecognised) {
  LoopPlan thrice;
  thrice.start_frame = 23;
  thrice.length_frames = 3 * 48;
  Transition back;
  back.from = 70;
  back.to = 23;
  thrice.jumps = {back, back, back};
  EXPECT_EQ(thrice.repetitions(), 3);
  EXPECT_FALSE(thrice.shows_each_frame_once());

  LoopPlan replaying;  // the 71 s "loop" found there: 33 .. 79 shown twice
  replaying.start_frame = 23;
  Transition first, second;
  first.from = 79;
  first.to = 33;
  second.from = 70;
  second.to = 23;
  replaying.jumps = {first, first, second};
  replaying.length_frames = 57 + 47 + 38;  // 23..79, 33..79, 33..70
  EXPECT_EQ(replaying.repetitions(), 1);
  EXPECT_FALSE(replaying.shows_each_frame_once());

  LoopPlan simple;
  simple.start_frame = 32;
  simple.length_frames = 250;
  Transition jump;
  jump.from = 281;
  jump.to = 32;
  simple.jumps = {jump};
  EXPECT_EQ(simple.repetitions(), 1);
  EXPECT_TRUE(simple.shows_each_frame_once());
  EXPECT_EQ(simple.frames().front(), 32);
  EXPECT_EQ(simple.frames().back(), 281);
}

}  // namespace
}  // namespace nearshore::loops
