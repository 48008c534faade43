// Validation (label `validation`, not in CI): the bar for irregular seas on a synthetic
// stand-in until a real JONSWAP bake exists: a 5-minute irregular linear sea (24 components,
// Tp 8 s, Hs 1.5 m, incommensurate frequencies, so no exact repeat) at 10 frames/s must offer a
// loop of at least 60 s whose worst seam ratio after crossfade is <= 1.0. Writes the inspector's
// PNGs into the build folder.
#include <gtest/gtest.h>

#include <cstdio>

#include "loops_test_support.hpp"
#include "nearshore/loops/inspector.hpp"
#include "nearshore/loops/synthetic_sea.hpp"

namespace nearshore::loops {
namespace {
using namespace testing;

TEST(IrregularSeaValidation, FiveMinutesGiveASixtySecondLoopWithSeamRatioBelowOne) {
  const auto folder = fresh_folder("irregular_5min");
  write_sea_sequence(folder, irregular_sea(8.0, 24, 1.5, 12.0, 0.4, 2026), small_geometry(64, 64, 4.0), 3000, 0.1, 0);
  LoopsOptions options;
  options.report_lengths_s = {30, 60, 120};
  const LoopsReport report = analyse_loops(folder, options);
  write_loops_pictures(report, std::filesystem::path(NEARSHORE_BINARY_DIR) / "validation" / "loops_irregular");
  double best = 1e300;
  for (const LoopReport& loop : report.best_by_length) {
    std::printf("loop %.1f s: R %.2f before, %.2f after crossfade, %zu jumps\n", loop.length_s,
                loop.worst_seam_ratio_before, loop.worst_seam_ratio_after, loop.seams.size());
    if (loop.length_s >= 60) best = std::min(best, loop.worst_seam_ratio_after);
  }
  std::printf("distances %.1f s, tables and plans %.1f s\n", report.distance_seconds, report.table_seconds);
  EXPECT_LE(best, 1.0);
  EXPECT_TRUE(report.reachable_dead_ends.empty());
}

}  // namespace
}  // namespace nearshore::loops
