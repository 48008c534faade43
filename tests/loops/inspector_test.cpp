#include <gtest/gtest.h>

#include <fstream>

#include "loops_test_support.hpp"
#include "nearshore/loops/inspector.hpp"
#include "nearshore/loops/synthetic_sea.hpp"

namespace nearshore::loops {
namespace {
using namespace testing;

// End to end on a periodic sequence stored as half (the default encoding): the inspector finds
// the period with R <= 0.1 (the bar; half rounding alone gives ~1e-3), writes the tables,
// and a second run reuses the stored Gram matrices with identical results.
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
  const LoopsReport second = analyse_loops(folder, options);
  EXPECT_TRUE(second.gram_reused);
  EXPECT_EQ(second.to_json()["best_loops_by_length"], first.to_json()["best_loops_by_length"]);
  const nlohmann::json stored = nlohmann::json::parse(std::ifstream(folder / "loops.json"));
  EXPECT_EQ(stored["format"], "nearshore loops");
  EXPECT_DOUBLE_EQ(stored["parameters"]["sigma"].get<double>(), first.sigma);
  EXPECT_EQ(stored["parameters"]["filter_half_width_frames"], 2);
  write_loops_pictures(first, folder / "png");
  for (const char* name : {"distance_matrix.png", "seam_ratios.png", "worst_seam_gauge.png"})
    EXPECT_TRUE(std::filesystem::exists(folder / "png" / name)) << name;
}

}  // namespace
}  // namespace nearshore::loops
