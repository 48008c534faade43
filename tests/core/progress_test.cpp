#include "nearshore/core/progress.hpp"

#include <gtest/gtest.h>

#include <cmath>

TEST(FormatDuration, ReadsLikeAPersonWouldSayIt) {
  EXPECT_EQ(nearshore::format_duration(12.34), "12.3 s");
  EXPECT_EQ(nearshore::format_duration(185), "3 min 05 s");
  EXPECT_EQ(nearshore::format_duration(3720), "1 h 02 min");
  EXPECT_EQ(nearshore::format_duration(-1), "?");
}

TEST(ProgressBar, UpdatesAndFinishesWithoutThrowing) {
  nearshore::ProgressBar bar("test", 10, "steps");
  for (int i = 0; i <= 10; ++i) bar.update(i, "detail");
  bar.finish();
  EXPECT_GE(bar.elapsed_seconds(), 0.0);
}

// A bake resumed at 46.4 % that has run 10 s to 50 %: 3.6 % in 10 s, so 50 % to go takes 139 s
// (not the 10 s a whole-fraction estimate, 10 x 0.5 / 0.5, would show).
TEST(RemainingSeconds, AResumedRunIsProjectedFromItsOwnProgress) {
  EXPECT_NEAR(nearshore::remaining_seconds(10.0, 0.5, 0.464), 10.0 * 0.5 / 0.036, 1e-9);
  EXPECT_DOUBLE_EQ(nearshore::remaining_seconds(10.0, 0.25), 30.0);
  EXPECT_TRUE(std::isnan(nearshore::remaining_seconds(10.0, 0.464, 0.464)));
  EXPECT_TRUE(std::isnan(nearshore::remaining_seconds(0.0, 0.0)));
}
