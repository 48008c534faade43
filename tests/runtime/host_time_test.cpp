// The runtime as a simulator host's clock sees it (issue 40): the first frame is the planned one
// and the same on every run without waiting; in lockstep the fields at a display time do not
// depend on the time rate, pauses, steps or rewinds (bit for bit against keyframes the background
// workers made); a free-running underrun is reported by advance_to. The host's clock is paced
// with the wall clock at 0.25 x, 1 x and 8 x real time so the workers race it as they would.
#include <chrono>
#include <cstring>
#include <map>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/runtime/surface_sampler.hpp"
#include "runtime_test_support.hpp"

namespace nearshore::runtime {
namespace {
using namespace testing;
using namespace std::chrono_literals;

constexpr double kHostFrameInterval_s = 0.1;  // the baked frames of these tests
const std::vector<PlaneWave> kHostWaves = {{0.4, 0.2, 0.05, 1.4, 0.3}, {0.15, -0.05, 0.25, 1.9, 2.0}};

fs::path host_time_sequence() {
  const fs::path folder = scratch_folder();
  write_wave_sequence(folder, wave_geometry(48, 32, 2.0), kHostWaves, 30, kHostFrameInterval_s, 20.0);
  return folder;
}

// Frame order over the harbour, a small Beaufort 4 sea beyond it (3 cascades of 64^2: the deep
// water has its own keyframes and its own worker, so both rings race the clock).
StreamingOptions host_time_options(bool lockstep) {
  StreamingOptions options;
  options.plan = PlanKind::kFrameOrder;
  options.deep_water = DeepWaterChoice::kBeaufort;
  options.beaufort = {.force = 4, .grid_size = 64, .cascade_count = 3, .shortest_wavelength_m = 1.0};
  options.lockstep = lockstep;
  options.ring_capacity = 4;  // a short ring: at 8 x the clock outruns it every frame
  return options;
}

// The shown surface at points inside the harbour, in its edge fade and on the open sea
// (displaced queries: the choppy inversion), as raw doubles.
std::vector<double> host_time_fields(const SurfaceSnapshot& snapshot) {
  const SurfaceSampler sampler(snapshot);
  std::vector<double> values;
  for (double x = -30.0; x <= 126.0; x += 13.0)
    for (double y = -20.0; y <= 84.0; y += 11.0) {
      const SurfaceState s = sampler.state(x, y);
      values.insert(values.end(), {s.surface_elevation_m, s.velocity_x_m_s, s.slope_x, s.slope_y});
    }
  return values;
}

bool bit_identical(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// Display time of host tick n at 1/120 s units: the same double for the same n in every run.
double host_time_s(long long units) { return static_cast<double>(units) * (1.0 / 120.0); }

TEST(HostTime, TheFirstFrameIsThePlannedOneAndTheSameOnEveryRunWithoutWaiting) {
  const fs::path folder = host_time_sequence();
  std::vector<double> first[2];
  for (int run = 0; run < 2; ++run) {
    StreamingEngine engine(folder, host_time_options(false));  // free-running, no wait
    EXPECT_TRUE(engine.advance_to(0.0));
    const SurfaceSnapshot snapshot = engine.snapshot();
    ASSERT_TRUE(snapshot.harbour_from && snapshot.harbour_to) << "harbour";
    ASSERT_TRUE(snapshot.deep_from && snapshot.deep_to) << "deep " << bool(snapshot.deep_from);
    EXPECT_EQ(snapshot.harbour_from->plan_step, 0);
    EXPECT_EQ(snapshot.harbour_to->plan_step, 1);
    EXPECT_EQ(snapshot.deep_from->display_time_s, 0.0);
    EXPECT_EQ(engine.stats().underruns, 0);
    // The frame's own values at a cell centre, not a flat sea (half-float storage: 1.2e-4 m at 0.2 m).
    const SurfaceSampler sampler(snapshot);
    EXPECT_NEAR(sampler.harbour_elevation_m(49.0, 31.0), wave_elevation_m(kHostWaves, 49.0, 31.0, 20.0), 2e-4);
    first[run] = host_time_fields(snapshot);
  }
  EXPECT_TRUE(bit_identical(first[0], first[1]));
}

TEST(HostTime, LockstepGivesTheSameFieldsAtTheSameTimesAtAnyRatePauseStepOrRewind) {
  const fs::path folder = host_time_sequence();
  // Each run: a 30 Hz host clock at `rate` x real time, display time advancing 4 rate / 120 s a
  // tick, paced by the wall clock; the 1 x run also pauses (the same time three ticks running),
  // single-steps and rewinds.
  struct Run {
    double rate;
    std::vector<long long> ticks;  // display times in 1/120 s
  };
  std::vector<Run> runs = {{0.25, {}}, {1.0, {}}, {8.0, {}}};
  for (long long n = 0; n <= 40; ++n) runs[0].ticks.push_back(n);              // 0 .. 0.33 s
  for (long long n = 0; n <= 20; ++n) runs[1].ticks.push_back(4 * n);          // 0 .. 0.67 s
  runs[1].ticks.insert(runs[1].ticks.end(), {80, 80, 80, 81, 82, 12, 16, 20});  // pause, step, rewind
  for (long long n = 0; n <= 12; ++n) runs[2].ticks.push_back(32 * n);         // 0 .. 3.2 s
  std::map<long long, std::vector<double>> shown;  // every run's fields at every tick
  int compared = 0;
  for (const Run& run : runs) {
    StreamingEngine engine(folder, host_time_options(true));
    auto next_tick = std::chrono::steady_clock::now();
    for (long long units : run.ticks) {
      std::this_thread::sleep_until(next_tick);
      next_tick += std::chrono::microseconds(33333);
      EXPECT_TRUE(engine.advance_to(host_time_s(units))) << "rate " << run.rate << ", t = " << host_time_s(units);
      const std::vector<double> fields = host_time_fields(engine.snapshot());
      const auto [at, inserted] = shown.emplace(units, fields);
      if (!inserted) {
        EXPECT_TRUE(bit_identical(at->second, fields)) << "rate " << run.rate << ", t = " << host_time_s(units);
        ++compared;
      }
    }
    const StreamingStats stats = engine.stats();
    EXPECT_EQ(stats.underruns, 0) << "rate " << run.rate;
    if (run.rate == 8.0) {
      EXPECT_GT(stats.synchronous_keyframes, 0);  // the clock outran the ring
    }
  }
  EXPECT_GE(compared, 20);
  // Against keyframes only the background workers made (free-running, waited for): bit for bit.
  StreamingEngine reference(folder, host_time_options(false));
  reference.advance_to(0.0);
  for (const auto& [units, fields] : shown) {
    if (units == 0) continue;  // made synchronously by the first advance
    ASSERT_TRUE(reference.wait_until_ready(host_time_s(units), 20s));
    ASSERT_TRUE(reference.advance_to(host_time_s(units)));
    EXPECT_TRUE(bit_identical(fields, host_time_fields(reference.snapshot()))) << "t = " << host_time_s(units);
  }
}

TEST(HostTime, AFreeRunningUnderrunIsReportedByAdvance) {
  const fs::path folder = host_time_sequence();
  StreamingEngine engine(folder, host_time_options(false));
  EXPECT_TRUE(engine.advance_to(0.0));
  ASSERT_TRUE(engine.wait_until_ready(0.05, 20s));
  EXPECT_TRUE(engine.advance_to(0.05));
  // 100 s ahead: far beyond a 4-keyframe ring, so the workers restart there and nothing of that
  // time can be in the rings yet. The older keyframes are held, and said.
  EXPECT_FALSE(engine.advance_to(100.0));
  StreamingStats stats = engine.stats();
  EXPECT_FALSE(stats.last_advance_planned);
  EXPECT_EQ(stats.underruns, 1);
  EXPECT_EQ(stats.harbour_underruns, 1);
  EXPECT_EQ(stats.deep_underruns, 1);
  EXPECT_EQ(engine.snapshot().harbour_from->plan_step, 0);  // held, not a flat sea
  ASSERT_TRUE(engine.wait_until_ready(100.0, 20s));
  EXPECT_TRUE(engine.advance_to(100.0));
  EXPECT_TRUE(engine.stats().last_advance_planned);
}

}  // namespace
}  // namespace nearshore::runtime
