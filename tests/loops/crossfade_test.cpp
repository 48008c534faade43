#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "nearshore/loops/plans.hpp"
#include "nearshore/loops/transitions.hpp"
#include "nearshore/sequence/loop_playback.hpp"

namespace nearshore::loops {
namespace {
using sequence::blend_frames;
using sequence::BlendSource;
using sequence::crossfade_blend;
using sequence::crossfade_weight;

sequence::Frame constant_frame(float eta, float p, float q) {
  sequence::Frame frame;
  frame.surface_elevation_m = Raster<float>(7, 5, eta);
  frame.flux_x_m2_s = Raster<float>(7, 5, p);
  frame.flux_y_m2_s = Raster<float>(7, 5, q);
  return frame;
}

double volume(const sequence::Frame& frame) {
  const auto& v = frame.surface_elevation_m.values();
  return std::accumulate(v.begin(), v.end(), 0.0);
}

// The blend weights sum to 1, so the blended volume is the weighted volume exactly (mass kept),
// and the fluxes get the same weights as the elevation. Tolerance: float rounding of 35 cells.
TEST(Crossfade, BlendKeepsMassAndUsesOneWeightForAllChannels) {
  sequence::Frame a = constant_frame(0.3f, 1.0f, -2.0f), b = constant_frame(-0.1f, 3.0f, 0.5f), out;
  a.surface_elevation_m(2, 3) = 1.5f;
  for (int k = 1; k <= 4; ++k) {
    const double alpha = crossfade_weight(k, 4);
    EXPECT_DOUBLE_EQ(alpha, k / 5.0);
    blend_frames(a, b, alpha, out);
    EXPECT_NEAR(volume(out), (1 - alpha) * volume(a) + alpha * volume(b), 1e-5);
    EXPECT_NEAR(out.flux_x_m2_s(0, 0), (1 - alpha) * 1.0 + alpha * 3.0, 1e-6);
    EXPECT_NEAR(out.flux_y_m2_s(6, 4), (1 - alpha) * -2.0 + alpha * 0.5, 1e-6);
  }
  EXPECT_TRUE(out.breaking.empty());
}

TEST(Crossfade, BlendScheduleEndsJustBeforeTheJump) {
  BlendSource blend;
  ASSERT_TRUE(crossfade_blend(50, 20, 3, 1, blend));  // last frame before the jump 50 -> 20
  EXPECT_EQ(blend.source_frame, 50);
  EXPECT_EQ(blend.target_frame, 19);
  EXPECT_DOUBLE_EQ(blend.target_weight, 0.75);
  ASSERT_TRUE(crossfade_blend(50, 20, 3, 3, blend));  // first blend
  EXPECT_EQ(blend.source_frame, 48);
  EXPECT_EQ(blend.target_frame, 17);
  EXPECT_DOUBLE_EQ(blend.target_weight, 0.25);
  EXPECT_FALSE(crossfade_blend(50, 20, 3, 4, blend));
  EXPECT_FALSE(crossfade_blend(50, 20, 0, 1, blend));
}

// On a distance matrix where every cross-timeline distance is 3 median steps, a crossfade of c
// frames leaves R = 3 / (c + 1); the longest allowed wins, and the target must have c frames before it.
TEST(Crossfade, ChoiceSpreadsTheSeamOverTheBlend) {
  const int n = 40;
  Eigen::MatrixXd d(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) d(i, j) = std::abs(i - j) == 1 ? 1.0 : (i == j ? 0.0 : 3.0);
  const CrossfadeChoice five = choose_crossfade(d, 1.0, 30, 10, 5);
  EXPECT_EQ(five.frames, 5);
  EXPECT_DOUBLE_EQ(five.seam_ratio_after, 3.0 / 6);
  const CrossfadeChoice near_start = choose_crossfade(d, 1.0, 30, 2, 5);
  EXPECT_EQ(near_start.frames, 2);  // target frames 0, 1 exist, not more
  const CrossfadeChoice none = choose_crossfade(d, 1.0, 30, 10, 0);
  EXPECT_EQ(none.frames, 0);
  EXPECT_DOUBLE_EQ(none.seam_ratio_after, 3.0);
}

// A player's schedule of a planned loop: the frames of the plan, with the last c frames before each
// jump replaced by the blends crossfade_blend names (and nothing else blended).
TEST(Crossfade, LoopScheduleBlendsTheLastFramesBeforeEachJump) {
  LoopPlan plan;
  plan.kind = "optimal";
  plan.start_frame = 10;
  plan.length_frames = (30 - 10 + 1) + (50 - 20 + 1);  // 10..30, jump to 20, 20..50, jump to 10
  Transition first, second;
  first.from = 30;
  first.to = 20;
  first.crossfade_frames = 3;
  second.from = 50;
  second.to = 10;
  second.crossfade_frames = 2;
  plan.jumps = {first, second};
  const sequence::LoopSchedule schedule = plan.schedule();
  ASSERT_EQ(schedule.shown.size(), static_cast<std::size_t>(plan.length_frames));
  EXPECT_EQ(schedule.frames(), plan.frames());
  EXPECT_EQ(schedule.kind, "optimal");
  int blends = 0;
  for (std::size_t step = 0; step < schedule.shown.size(); ++step) {
    const BlendSource& shown = schedule.shown[step];
    if (shown.target_weight == 0) continue;
    ++blends;
    const Transition& jump = step < 21 ? first : second;
    BlendSource expected;
    ASSERT_TRUE(crossfade_blend(jump.from, jump.to, jump.crossfade_frames, jump.from - shown.source_frame + 1,
                                expected));
    EXPECT_EQ(shown.target_frame, expected.target_frame);
    EXPECT_DOUBLE_EQ(shown.target_weight, expected.target_weight);
  }
  EXPECT_EQ(blends, 3 + 2);
  // The last frame before the first jump is 3/4 the way to the target timeline: (1 - 3/4) f(30) + 3/4 f(19).
  EXPECT_EQ(schedule.shown[20].source_frame, 30);
  EXPECT_EQ(schedule.shown[20].target_frame, 19);
  EXPECT_DOUBLE_EQ(schedule.shown[20].target_weight, 0.75);
}

}  // namespace
}  // namespace nearshore::loops
