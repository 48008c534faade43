// Issue 6's "done when" on real bakes of the demo harbour (not synthetic seas): the demo chart is
// gridded, the two example cases of data/cases/ are baked as documented, and the loop inspector
//   (a) finds the exact period of the time-periodic bake (harbour.toml) with seam ratio R <= 0.1,
//   (b) finds, in the 6-minute irregular JONSWAP bake (harbour_irregular.toml, not periodic), a
//       loop of at least 60 s that shows every frame once with R <= 1.0 after crossfade.
// The case files name their bathymetry "../../demo-out/harbour/depth.exr" relative to themselves,
// so the test lays out <root>/data/cases/<case>.toml and <root>/demo-out/harbour/ like the repository.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/loops/inspector.hpp"

namespace nearshore {
namespace {
namespace fs = std::filesystem;

class DemoHarbourLoops : public ::testing::Test {
 protected:
  // One root per test: ctest may run the two tests at the same time.
  void SetUp() override {
    ProgressBar::set_quiet(true);
    root_ = fs::path(NEARSHORE_BINARY_DIR) / "test-output" / "harbour" /
            ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(root_);
    const bathymetry::DemoHarbourFiles chart = bathymetry::write_demo_harbour(root_ / "demo-out" / "chart");
    bathymetry::BathyRequest request;
    request.inputs = {chart.depth_geotiff, chart.structures_geojson, chart.land_geojson,
                      chart.coastline_geojson};
    request.spacing_m = 8.0;
    bathymetry::write_bathymetry_outputs(root_ / "demo-out" / "harbour",
                                         bathymetry::build_harbour_grid(request));
    fs::create_directories(root_ / "data" / "cases");
  }
  // Bakes data/cases/<name>.toml into <root>/<name> and returns the sequence folder.
  fs::path bake_example(const std::string& name) const {
    const fs::path case_file = root_ / "data" / "cases" / (name + ".toml");
    fs::copy_file(fs::path(NEARSHORE_SOURCE_DIR) / "data" / "cases" / (name + ".toml"), case_file,
                  fs::copy_options::overwrite_existing);
    bake::BakeOptions options;
    options.output_folder = root_ / name;
    bake::run_bake(bake::read_bake_case(case_file), options);
    return options.output_folder;
  }
  fs::path root_;
};

TEST_F(DemoHarbourLoops, PeriodicBakeRepeatsWithSeamRatioBelowATenth) {
  const fs::path sequence = bake_example("harbour");
  const loops::LoopsReport report = loops::analyse_loops(sequence);
  // Found in the frames themselves, not only read from the manifest.
  EXPECT_TRUE(report.detected_period.found);
  EXPECT_DOUBLE_EQ(report.detected_period.lag_s, 600.0);
  ASSERT_TRUE(report.period.has_value()) << "the inspector did not find the period of a periodic bake";
  EXPECT_DOUBLE_EQ(report.period->length_s, 600.0);
  const loops::SeamReport& seam = report.period->seams.at(0);
  std::printf(
      "period seam: R %.3f before, %.3f after a %d-frame crossfade; volume jump %.0f m3 (median step %.0f "
      "m3)\n",
      seam.seam_ratio_before, seam.seam_ratio_after, seam.transition.crossfade_frames, seam.volume_jump_m3,
      report.median_volume_step_m3);
  EXPECT_LE(report.period->worst_seam_ratio_after, 0.1);
  // Without any crossfade the bake repeats to within one ordinary step: what is left is the slow,
  // chaotic part of the flow (eddies where waves break), not a phase error of the forcing.
  EXPECT_LE(seam.seam_ratio_before, 1.0);
}

TEST_F(DemoHarbourLoops, IrregularSixMinuteBakeOffersALoopOfAMinuteWithSeamRatioBelowOne) {
  const fs::path sequence = bake_example("harbour_irregular");
  loops::LoopsOptions options;
  options.report_lengths_s = {60, 120};
  const loops::LoopsReport report = loops::analyse_loops(sequence, options);
  EXPECT_FALSE(report.period.has_value());
  EXPECT_FALSE(report.detected_period.found)
      << "an irregular sea repeats after " << report.detected_period.lag_s << " s";
  EXPECT_GE(report.frame_count * report.frame_interval_s, 300.0);
  const loops::LoopReport* best = nullptr;
  for (const loops::LoopReport& loop : report.best_by_length) {
    std::printf("loop %.1f s, %zu jumps: R %.2f before, %.2f after crossfade\n", loop.length_s,
                loop.seams.size(), loop.worst_seam_ratio_before, loop.worst_seam_ratio_after);
    EXPECT_TRUE(loop.plan.shows_each_frame_once());
    if (loop.length_s >= 60 && (!best || loop.worst_seam_ratio_after < best->worst_seam_ratio_after))
      best = &loop;
  }
  ASSERT_NE(best, nullptr) << "no loop of 60 s or more";
  EXPECT_LE(best->worst_seam_ratio_after, 1.0);
  EXPECT_TRUE(report.reachable_dead_ends.empty());
}

}  // namespace
}  // namespace nearshore
