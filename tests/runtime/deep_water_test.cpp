// The deep water at runtime (runtime/deep_water_source.hpp): a field rebuilt from a bake's
// coefficient files is the bake's field; a weighted synthesis is the weighted sum of fields; the
// time mapping follows the plan; and in a real bake (a small flume whose wave maker is the field's
// own waves) the harbour frames and the deep water the engine shows beside them agree where the
// blending zone starts as the bake predicted (the manifest's predicted_relative_rms_start).
#include "nearshore/runtime/deep_water_source.hpp"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/runtime/surface_sampler.hpp"
#include "runtime_test_support.hpp"

namespace nearshore::runtime {
namespace {
using namespace testing;
using namespace std::chrono_literals;

// A 16 m x 0.6 m flume, 0.5 m deep, 10 cm cells; a JONSWAP sea (Hs 2 cm, Tp 1.5 s, as narrow as
// cos^2s goes) made by the deep_water wave maker from the west at x = 3 m, normal incidence only
// (the side walls would reflect oblique waves); sponges at both ends; frames every 0.1 s from 6 s
// to 14 s. One 14 m tile: its lattice step (0.45 rad/m) is 5 times the spread of the sea across
// the flume (k_p sigma_theta = 0.08 rad/m), so the waves off the k_y = 0 row, which the maker
// cannot make, hold almost nothing: the field is (nearly) all carried waves.
const char* const kFlumeCase = R"(title = "runtime coherence flume"
[bathymetry]
kind = "profile"
length_m = 16.0
width_m = 0.6
spacing_m = 0.1
profile = [[0.0, 0.5], [16.0, 0.5]]
[time]
duration_s = 14.0
spin_up_s = 6.0
output_interval_s = 0.1
courant_number = 0.5
[wave_maker]
kind = "deep_water"
facing = "west"
source_line_m = 3.0
loop_period_s = 32.0
ramp_time_s = 2.0
max_angle_from_normal_deg = 0.0
[deep_water]
spectrum = "jonswap"
significant_height_m = 0.02
peak_period_s = 1.5
spreading_s = 1000.0
grid_size = 64
tile_lengths_m = [14.0]
seed = 5
[[sponges]]
side = "west"
width_m = 2.0
[[sponges]]
side = "east"
width_m = 3.0
)";

struct Flume {
  fs::path sequence;
  std::unique_ptr<ocean::DeepWaterField> field;  // the bake's own, from its case
  std::vector<ocean::LatticeWave> uncarried;     // the field's waves its wave maker does not make
};

// Baked once per test program (a second or two), shared by the tests below.
const Flume& flume() {
  static const Flume baked = [] {
    ProgressBar::set_quiet(true);
    // One folder per test: ctest runs each test in its own process, in parallel, and every process
    // bakes the flume afresh (a shared folder was removed under a neighbour's reader: flaky at -j2).
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path folder = fs::path(NEARSHORE_BINARY_DIR) / "tests" / "runtime" / "scratch" /
                            (std::string("flume_") + (test ? test->test_suite_name() + std::string("_") + test->name() : "shared"));
    fs::remove_all(folder);
    fs::create_directories(folder);
    std::ofstream(folder / "case.toml") << kFlumeCase;
    const bake::BakeCase c = bake::read_bake_case(folder / "case.toml");
    bake::BakeOptions options;
    options.output_folder = folder / "sequence";
    bake::run_bake(c, options);
    auto field = std::make_unique<ocean::DeepWaterField>(*c.deep_water);
    std::vector<ocean::LatticeWave> uncarried;
    for (const ocean::LatticeWave& wave : field->lattice_waves()) {
      bool made = false;
      for (const ocean::LatticeWave& carried : c.deep_water_maker->carried)
        made = made || (carried.wavenumber_x_rad_m == wave.wavenumber_x_rad_m &&
                        carried.wavenumber_y_rad_m == wave.wavenumber_y_rad_m);
      if (!made) uncarried.push_back(wave);
    }
    return Flume{options.output_folder, std::move(field), std::move(uncarried)};
  }();
  return baked;
}

TEST(RuntimeDeepWater, AFieldRebuiltFromTheBakesCoefficientFilesIsTheBakesField) {
  const sequence::SequenceReader reader(flume().sequence);
  const std::optional<ocean::RecordedDeepWater> recorded = read_recorded_deep_water(reader, sequence::Verify::kYes);
  ASSERT_TRUE(recorded.has_value());
  ocean::DeepWaterField rebuilt(*recorded);
  const ocean::DeepWaterField& bakes = *flume().field;
  ASSERT_EQ(rebuilt.cascade_count(), bakes.cascade_count());
  EXPECT_NEAR(rebuilt.significant_wave_height_m(), bakes.significant_wave_height_m(), 1e-6 * bakes.significant_wave_height_m());
  const std::vector<ocean::LatticeWave> waves = bakes.lattice_waves();
  for (double t : {0.0, 7.3, 31.9}) {
    rebuilt.synthesise(t);
    const ocean::DeepWaterFrame& frame = rebuilt.frame(0);
    const int n = frame.grid_size;
    double largest = 0.0;
    for (int j = 0; j < n; j += 3)
      for (int i = 0; i < n; i += 5) {
        const double x = i * frame.tile_length_m / n, y = j * frame.tile_length_m / n;
        const double direct = ocean::surface_elevation_m(waves, x, y, t);
        largest = std::max(largest, std::abs(frame.surface_elevation_m[static_cast<std::size_t>(j * n + i)] - direct));
      }
    // Float tolerance: the file stores phases as float32 (6e-8 rad relative) and the FFT sums
    // N^2 float terms; 2e-4 of Hs is the ocean tests' bar for the FFT against the direct sum.
    EXPECT_LT(largest, 2e-4 * bakes.significant_wave_height_m()) << "t = " << t;
  }
  // A weighted synthesis is the weighted sum of the fields (one FFT set for both times).
  const std::array<ocean::TimedWeight, 2> times = {{{3.0, 0.3}, {11.5, 0.7}}};
  rebuilt.synthesise(times);
  const std::vector<float> mixed = rebuilt.frame(0).surface_elevation_m;
  rebuilt.synthesise(3.0);
  const std::vector<float> first = rebuilt.frame(0).surface_elevation_m;
  rebuilt.synthesise(11.5);
  const std::vector<float> second = rebuilt.frame(0).surface_elevation_m;
  double largest = 0.0;
  for (std::size_t i = 0; i < mixed.size(); ++i) largest = std::max(largest, std::abs(mixed[i] - (0.3 * first[i] + 0.7 * second[i])));
  EXPECT_LT(largest, 1e-5 * bakes.significant_wave_height_m());
}

TEST(RuntimeDeepWater, BakeTimesFollowTheTimelineAndCrossfadeAcrossJumps) {
  PlanStep now, next;
  now.shown = {10, 10, 0.0};
  next.shown = {11, 11, 0.0};
  // One timeline: one time, the bake time of frame 10 plus f dt.
  BakeTimes times = bake_times(now, next, 0.25, 0.5, 100.0);
  ASSERT_EQ(times.count, 1);
  EXPECT_NEAR(times.times[0].time_s, 100.0 + 10 * 0.5 + 0.125, 1e-12);
  EXPECT_NEAR(times.times[0].weight, 1.0, 1e-15);
  // In a crossfade (step k blends 10 and 3 at w = 0.4, step k + 1 blends 11 and 4 at w = 0.6):
  // two timelines, weights (1 - f)(1 - w_k) + f (1 - w_k+1) and the rest.
  now.shown = {10, 3, 0.4};
  next.shown = {11, 4, 0.6};
  times = bake_times(now, next, 0.25, 0.5, 100.0);
  ASSERT_EQ(times.count, 2);
  EXPECT_NEAR(times.times[0].time_s, 105.125, 1e-12);
  EXPECT_NEAR(times.times[0].weight, 0.75 * 0.6 + 0.25 * 0.4, 1e-12);
  EXPECT_NEAR(times.times[1].time_s, 100.0 + 3 * 0.5 + 0.125, 1e-12);
  EXPECT_NEAR(times.times[1].weight, 0.75 * 0.4 + 0.25 * 0.6, 1e-12);
  // Landing after a jump 11 -> 3: two different times, weights 1 - f and f.
  now.shown = {11, 11, 0.0};
  next.shown = {3, 3, 0.0};
  times = bake_times(now, next, 0.25, 0.5, 100.0);
  ASSERT_EQ(times.count, 2);
  EXPECT_NEAR(times.times[0].weight + times.times[1].weight, 1.0, 1e-15);
}

TEST(RuntimeDeepWater, HarbourAndDeepWaterAgreeWhereTheBlendStartsAsTheBakePredicted) {
  StreamingOptions options;
  options.plan = PlanKind::kFrameOrder;
  StreamingEngine engine(flume().sequence, options);
  ASSERT_TRUE(engine.deep_water_is_bakes());
  const sequence::DeepWaterSection& section = *engine.manifest().deep_water;
  ASSERT_TRUE(section.coupling && section.coupling->blending && section.coupling->wave_maker);
  const sequence::DeepWaterBlendingRecord& blending = *section.coupling->blending;
  const double carried = section.coupling->wave_maker->variance_fraction;
  const HarbourSite& site = *engine.site();
  EXPECT_EQ(site.source_axis, 0);
  EXPECT_EQ(site.inward_sign, 1.0);
  EXPECT_DOUBLE_EQ(site.blend_start_m, blending.start_m);
  // Where the cross-fade starts, at every frame from 2 s after the first (the waves have crossed
  // the 2 m from the line), across the flume. x on the FFT node nearest the zone's start: between
  // nodes (0.22 m apart here, 16 per peak wavelength) the bilinear sampling of the tile alone
  // differs from the field by up to (k dx)^2 / 8 = 2 % (what the renderer shows too, but not the
  // coherence this test measures); the sea is long-crested, so y between nodes costs nothing.
  const double node_m = section.cascades.front().tile_length_m / section.cascades.front().grid_size;
  const double x = std::round((blending.source_line_m + blending.start_m) / node_m) * node_m;
  const std::vector<ocean::LatticeWave> all = flume().field->lattice_waves();
  double engine_error2 = 0.0, field2 = 0.0, carried_error2 = 0.0, carried2 = 0.0, whole_error2 = 0.0;
  const double dt = engine.frame_interval_s();
  for (int k = 20; k + 1 < engine.manifest().frame_count; ++k) {
    const double t = (k + 1e-6) * dt;  // at frame k's own time (f = 1e-6)
    ASSERT_TRUE(engine.wait_until_ready(t, 20s));
    engine.advance_to(t);
    const SurfaceSampler sampler(engine.snapshot());
    const double bake_time_s = engine.manifest().frame_time_s(k);
    for (double y : {0.15, 0.3, 0.45}) {
      const double harbour = sampler.harbour_elevation_m(x, y), deep = sampler.deep_elevation_m(x, y);
      // 1. The engine's deep water is the bake's field at the bake time of the frame shown.
      const double field = ocean::surface_elevation_m(all, x, y, bake_time_s);
      engine_error2 += (deep - field) * (deep - field);
      field2 += field * field;
      // 2. Its carried part (the engine's field less the waves the maker does not make) is the
      //    harbour's waves to the bake's predicted eps.
      const double carried = deep - ocean::surface_elevation_m(flume().uncarried, x, y, bake_time_s);
      carried_error2 += (harbour - carried) * (harbour - carried);
      carried2 += carried * carried;
      whole_error2 += (harbour - deep) * (harbour - deep);
    }
  }
  const double engine_rms = std::sqrt(engine_error2 / field2), measured = std::sqrt(carried_error2 / carried2);
  const double eps = blending.predicted_relative_rms_start;
  std::printf("blend start %.2f m inland: engine's deep water vs the bake's field %.5f; harbour vs its carried waves %.4f "
              "(predicted eps %.4f); harbour vs the whole deep water %.4f (carried %.3f of the variance)\n",
              blending.start_m, engine_rms, measured, eps, std::sqrt(whole_error2 / field2), carried);
  // Float FFT at its nodes: 2e-4 of Hs (above); a deep water one frame off in time would be ~0.4.
  EXPECT_LT(engine_rms, 0.01);
  // The ocean coherence test's bar (docs/deep-water.md "Measured": within 0.03 of eps).
  EXPECT_LT(std::abs(measured - eps), 0.03);
}

}  // namespace
}  // namespace nearshore::runtime
