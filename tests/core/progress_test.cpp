#include "nearshore/core/progress.hpp"

#include <gtest/gtest.h>

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
