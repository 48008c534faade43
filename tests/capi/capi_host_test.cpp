// The C API as a simulator host's clock sees it (issues 40 and 44): the open pre-fills, so the
// first frame is the planned one and the same on every open; lockstep gives the same samples at
// any rate, pause and rewind; a free-running underrun is NEARSHORE_UNDERRUN with counters, while a
// host built before version 5 keeps NEARSHORE_OK; every number of nearshore_sea_options and the
// times, counts and places of the sea calls are checked, named and never NEARSHORE_INTERNAL_ERROR.
#include "nearshore.h"
#include "capi_test_support.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <thread>
#include <vector>

namespace {
namespace fs = std::filesystem;
using namespace nearshore::capi_test;

// Points over the basin and 30 m of open sea round it, as x0, y0, x1, y1, ...
std::vector<double> host_points() {
  std::vector<double> xy;
  for (double x = -30.0; x <= 190.0; x += 17.0)
    for (double y = -30.0; y <= 150.0; y += 23.0) xy.insert(xy.end(), {x, y});
  return xy;
}

std::vector<nearshore_surface_sample> host_samples(const nearshore_sea* sea) {
  const std::vector<double> xy = host_points();
  std::vector<nearshore_surface_sample> samples(xy.size() / 2);
  EXPECT_EQ(nearshore_sea_query(sea, xy.data(), samples.size(), samples.data()), NEARSHORE_OK) << nearshore_last_error();
  return samples;
}

bool same_bits(const std::vector<nearshore_surface_sample>& a, const std::vector<nearshore_surface_sample>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(nearshore_surface_sample)) == 0;
}

nearshore_sea_options host_options(nearshore_time_mode mode) {
  nearshore_sea_options options;
  nearshore_sea_options_init(&options);
  options.plan = NEARSHORE_PLAN_FRAME_ORDER;
  options.beaufort_force = 4;  // a deep water of its own beyond the basin, with its own worker
  options.time_mode = mode;
  options.ring_keyframes = 3;
  return options;
}

TEST(CApiHost, TheOpenPrefillsAndTheFirstFrameIsThePlannedOneOnEveryOpen) {
  const fs::path folder = write_sequence("host_first");
  std::vector<nearshore_surface_sample> first[2];
  for (int run = 0; run < 2; ++run) {
    const nearshore_sea_options options = host_options(NEARSHORE_TIME_FREE_RUNNING);
    nearshore_sea* sea = nullptr;
    ASSERT_EQ(nearshore_sea_open(folder.c_str(), &options, &sea), NEARSHORE_OK) << nearshore_last_error();
    ASSERT_EQ(nearshore_sea_advance(sea, 0.0), NEARSHORE_OK) << nearshore_last_error();
    first[run] = host_samples(sea);
    // Frame 0 itself at a cell centre of the basin (float storage).
    const double point[2] = {(20 + 0.5) * kSpacingM, 62.0};
    nearshore_surface_sample sample;
    ASSERT_EQ(nearshore_sea_query(sea, point, 1, &sample), NEARSHORE_OK);
    EXPECT_NEAR(sample.elevation_m, analytic_eta(point[0], 0.0), 1e-5);
    nearshore_stats stats;
    stats.struct_size = sizeof stats;
    ASSERT_EQ(nearshore_sea_stats(sea, &stats), NEARSHORE_OK);
    EXPECT_EQ(stats.underruns, 0u);
    EXPECT_EQ(stats.last_advance_planned, 1);
    nearshore_sea_close(sea);
  }
  EXPECT_TRUE(same_bits(first[0], first[1]));
}

TEST(CApiHost, LockstepGivesTheSameSamplesAtAnyRatePauseAndRewind) {
  const fs::path folder = write_sequence("host_lockstep");
  // Display times in 1/120 s: 0.25 x, 1 x and 8 x real time on a 30 Hz clock paced by the wall
  // clock; the 1 x run pauses, steps and rewinds. Every advance must be NEARSHORE_OK.
  const std::vector<std::vector<long long>> runs = {
      {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 32},
      {0, 4, 8, 12, 16, 20, 24, 28, 32, 36, 40, 44, 48, 52, 56, 60, 64, 64, 64, 65, 66, 8, 12, 32},
      {0, 32, 64, 96, 128, 160, 192, 224, 256, 288, 320, 352, 384}};
  std::map<long long, std::vector<nearshore_surface_sample>> shown;
  int compared = 0;
  for (const std::vector<long long>& ticks : runs) {
    const nearshore_sea_options options = host_options(NEARSHORE_TIME_LOCKSTEP);
    nearshore_sea* sea = nullptr;
    ASSERT_EQ(nearshore_sea_open(folder.c_str(), &options, &sea), NEARSHORE_OK) << nearshore_last_error();
    auto next_tick = std::chrono::steady_clock::now();
    for (long long units : ticks) {
      std::this_thread::sleep_until(next_tick);
      next_tick += std::chrono::microseconds(33333);
      const double t = static_cast<double>(units) * (1.0 / 120.0);
      ASSERT_EQ(nearshore_sea_advance(sea, t), NEARSHORE_OK) << nearshore_last_error();
      const auto [at, inserted] = shown.emplace(units, host_samples(sea));
      if (!inserted) {
        EXPECT_TRUE(same_bits(at->second, host_samples(sea))) << "t = " << t;
        ++compared;
      }
      // nearshore_sea_query_at of the same time is the same sea.
      const std::vector<double> xy = host_points();
      std::vector<nearshore_surface_sample> at_time(xy.size() / 2);
      ASSERT_EQ(nearshore_sea_query_at(sea, t, xy.data(), at_time.size(), at_time.data()), NEARSHORE_OK);
      EXPECT_TRUE(same_bits(at->second, at_time)) << "t = " << t;
    }
    nearshore_stats stats;
    stats.struct_size = sizeof stats;
    ASSERT_EQ(nearshore_sea_stats(sea, &stats), NEARSHORE_OK);
    EXPECT_EQ(stats.underruns, 0u);
    EXPECT_EQ(stats.time_mode, NEARSHORE_TIME_LOCKSTEP);
    nearshore_sea_close(sea);
  }
  EXPECT_GE(compared, 15);
}

TEST(CApiHost, AFreeRunningUnderrunIsAStatusWithCountersAndOlderHostsKeepOk) {
  const fs::path folder = write_sequence("host_underrun");
  nearshore_sea_options options = host_options(NEARSHORE_TIME_FREE_RUNNING);
  nearshore_sea* sea = nullptr;
  ASSERT_EQ(nearshore_sea_open(folder.c_str(), &options, &sea), NEARSHORE_OK) << nearshore_last_error();
  ASSERT_EQ(nearshore_sea_advance(sea, 0.0), NEARSHORE_OK) << nearshore_last_error();
  // 100 s ahead, beyond a 3-keyframe ring: the decoder restarts there; nothing of it is ready.
  EXPECT_EQ(nearshore_sea_advance(sea, 100.0), NEARSHORE_UNDERRUN);
  EXPECT_NE(std::string(nearshore_last_error()).find("NEARSHORE_TIME_LOCKSTEP"), std::string::npos) << nearshore_last_error();
  nearshore_stats stats;
  stats.struct_size = sizeof stats;
  ASSERT_EQ(nearshore_sea_stats(sea, &stats), NEARSHORE_OK);
  EXPECT_EQ(stats.underruns, 1u);
  EXPECT_EQ(stats.harbour_underruns, 1u);
  EXPECT_EQ(stats.last_advance_planned, 0);
  EXPECT_STREQ(stats.plan_name, "frame order");  // the kind, whole (the description is longer than 31)
  // A wait of 0 s on a time the decoder has just been sent to is a timeout, said.
  EXPECT_EQ(nearshore_sea_wait_until_ready(sea, 200.0, 0.0), NEARSHORE_TIMEOUT);
  EXPECT_NE(std::string(nearshore_last_error()).find("200"), std::string::npos) << nearshore_last_error();
  ASSERT_EQ(nearshore_sea_wait_until_ready(sea, 100.0, 20.0), NEARSHORE_OK) << nearshore_last_error();
  EXPECT_EQ(nearshore_sea_advance(sea, 100.0), NEARSHORE_OK);
  // A rewind is a seek: allowed (an instructor's), an underrun until the decoder gets there.
  const nearshore_status back = nearshore_sea_advance(sea, 1.0);
  EXPECT_TRUE(back == NEARSHORE_OK || back == NEARSHORE_UNDERRUN) << nearshore_status_name(back);
  nearshore_sea_close(sea);

  // A host of version 4: its struct ends at verify_checksums; underruns stay NEARSHORE_OK for it,
  // and its shorter nearshore_stats is filled up to message.
  options.struct_size = static_cast<uint32_t>(offsetof(nearshore_sea_options, time_mode));
  options.time_mode = static_cast<nearshore_time_mode>(0x7f7f7f7f);  // its padding: never read
  ASSERT_EQ(nearshore_sea_open(folder.c_str(), &options, &sea), NEARSHORE_OK) << nearshore_last_error();
  EXPECT_EQ(nearshore_sea_advance(sea, 0.0), NEARSHORE_OK);
  EXPECT_EQ(nearshore_sea_advance(sea, 100.0), NEARSHORE_OK);
  nearshore_stats old{};
  old.struct_size = static_cast<uint32_t>(offsetof(nearshore_stats, harbour_underruns));
  old.harbour_underruns = 12345;
  ASSERT_EQ(nearshore_sea_stats(sea, &old), NEARSHORE_OK) << nearshore_last_error();
  EXPECT_EQ(old.underruns, 1u);
  EXPECT_EQ(old.harbour_underruns, 12345u);  // beyond the old struct: untouched
  nearshore_sea_close(sea);
}

TEST(CApiHost, EveryNumberOfTheSeaOptionsIsCheckedAndNamedNeverAnInternalError) {
  const fs::path folder = write_sequence("host_ranges");
  struct Probe {
    const char* field;
    std::function<void(nearshore_sea_options&)> set;
  };
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Probe> probes = {
      {"wind_direction_deg", [&](nearshore_sea_options& o) { o.wind_direction_deg = inf; }},
      {"wind_direction_deg", [&](nearshore_sea_options& o) { o.wind_direction_deg = nan; }},
      {"wind_direction_deg", [&](nearshore_sea_options& o) { o.beaufort_force = 5, o.wind_direction_deg = 1e6; }},
      {"deep_water_interval_s", [](nearshore_sea_options& o) { o.deep_water_interval_s = 1e-12; }},
      {"deep_water_interval_s", [](nearshore_sea_options& o) { o.deep_water_interval_s = -1.0; }},
      {"deep_water_interval_s", [](nearshore_sea_options& o) { o.deep_water_interval_s = 2.0; }},
      {"deep_water_interval_s", [&](nearshore_sea_options& o) { o.deep_water_interval_s = nan; }},
      {"ring_keyframes", [](nearshore_sea_options& o) { o.ring_keyframes = 1; }},
      {"ring_keyframes", [](nearshore_sea_options& o) { o.ring_keyframes = -3; }},
      {"ring_keyframes", [](nearshore_sea_options& o) { o.ring_keyframes = 5000; }},
      {"beaufort_force", [](nearshore_sea_options& o) { o.beaufort_force = -2; }},
      {"beaufort_force", [](nearshore_sea_options& o) { o.beaufort_force = 13; }},
      {"plan", [](nearshore_sea_options& o) { o.plan = static_cast<nearshore_plan>(99); }},
      {"time_mode", [](nearshore_sea_options& o) { o.time_mode = static_cast<nearshore_time_mode>(7); }},
      {"ready_timeout_s", [](nearshore_sea_options& o) { o.ready_timeout_s = -1.0; }},
      {"ready_timeout_s", [&](nearshore_sea_options& o) { o.ready_timeout_s = inf; }},
      {"ready_timeout_s", [](nearshore_sea_options& o) { o.ready_timeout_s = 1e9; }},
      {"struct_size", [](nearshore_sea_options& o) { o.struct_size = 1000; }},
  };
  for (const Probe& probe : probes) {
    nearshore_sea_options options;
    nearshore_sea_options_init(&options);
    probe.set(options);
    nearshore_sea* sea = reinterpret_cast<nearshore_sea*>(0x1);
    EXPECT_EQ(nearshore_sea_open(folder.c_str(), &options, &sea), NEARSHORE_INVALID_ARGUMENT) << probe.field;
    EXPECT_EQ(sea, nullptr);
    const std::string message = nearshore_last_error();
    EXPECT_NE(message.find(probe.field), std::string::npos) << message;
  }
  // The calls on an open sea: times, counts, places, struct sizes.
  nearshore_sea* sea = open_calm(folder);
  ASSERT_NE(sea, nullptr);
  for (double bad : {-1.0, nan, inf, 1e300}) {
    EXPECT_EQ(nearshore_sea_advance(sea, bad), NEARSHORE_INVALID_ARGUMENT) << bad;
    EXPECT_NE(std::string(nearshore_last_error()).find("time_s"), std::string::npos) << nearshore_last_error();
    EXPECT_EQ(nearshore_sea_wait_until_ready(sea, bad, 1.0), NEARSHORE_INVALID_ARGUMENT) << bad;
    EXPECT_EQ(nearshore_sea_wait_until_ready(sea, 0.0, bad), NEARSHORE_INVALID_ARGUMENT) << bad;
  }
  const double point[2] = {10.0, 10.0};
  nearshore_surface_sample sample;
  EXPECT_EQ(nearshore_sea_query(sea, point, std::numeric_limits<size_t>::max(), &sample), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("count"), std::string::npos) << nearshore_last_error();
  EXPECT_EQ(nearshore_sea_query_at(sea, 1.0, point, static_cast<size_t>(-4), &sample), NEARSHORE_INVALID_ARGUMENT);
  double x = 0, y = 0;
  // The basin is in UTM zone 51N; latitude 0, longitude 0 is 123 degrees of longitude away.
  EXPECT_EQ(nearshore_site_from_lat_lon(sea, 0.0, 0.0, &x, &y), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("latitude 0"), std::string::npos) << nearshore_last_error();
  nearshore_stats stats;
  stats.struct_size = 3;
  EXPECT_EQ(nearshore_sea_stats(sea, &stats), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_EQ(nearshore_sea_set_wind(sea, 3, inf), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_EQ(nearshore_sea_request_conditions(sea, "direction_deg=0", nan, nullptr), NEARSHORE_INVALID_ARGUMENT);
  nearshore_sea_close(sea);
}

}  // namespace
