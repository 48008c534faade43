// The C API (capi/include/nearshore.h) through the shared library a host links: status codes and
// messages for bad input, queries that return the baked field, a bad frame that is held while
// the sea plays on, latitude/longitude through the grid's projection, and queries from other
// threads while the render thread advances. The sequences are written here with the C++ API that
// libnearshore.so exports too (sequence::SequenceWriter).
#include "nearshore.h"
#include "capi_test_support.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/sequence/sequence_writer.hpp"
#include "../runtime/runtime_test_support.hpp"

namespace {
namespace fs = std::filesystem;
using namespace nearshore::capi_test;

TEST(CApi, BadInputReturnsAStatusAndAMessageNamingTheFix) {
  EXPECT_EQ(nearshore_api_version(), NEARSHORE_API_VERSION);
  EXPECT_STREQ(nearshore_status_name(NEARSHORE_IO_ERROR), "NEARSHORE_IO_ERROR");
  nearshore_sea* sea = reinterpret_cast<nearshore_sea*>(0x1);
  EXPECT_EQ(nearshore_sea_open("/nonexistent/bake", nullptr, &sea), NEARSHORE_IO_ERROR);
  EXPECT_EQ(sea, nullptr);
  EXPECT_NE(std::string(nearshore_last_error()).find("/nonexistent/bake"), std::string::npos) << nearshore_last_error();
  EXPECT_EQ(nearshore_sea_open(nullptr, nullptr, &sea), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("sequence_folder"), std::string::npos);
  EXPECT_EQ(nearshore_sea_advance(nullptr, 0.0), NEARSHORE_INVALID_ARGUMENT);

  // A manifest of a newer version is refused by name, not misread.
  const fs::path newer = write_sequence("newer");
  std::ifstream in(newer / "manifest.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const std::size_t at = text.find("\"version\": 1");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 12, "\"version\": 99");
  std::ofstream(newer / "manifest.json") << text;
  EXPECT_EQ(nearshore_sea_open(newer.c_str(), nullptr, &sea), NEARSHORE_FORMAT_ERROR);
  EXPECT_NE(std::string(nearshore_last_error()).find("version"), std::string::npos) << nearshore_last_error();

  // Out-of-range options are named.
  nearshore_sea_options options;
  nearshore_sea_options_init(&options);
  options.beaufort_force = 13;
  EXPECT_EQ(nearshore_sea_open(write_sequence("options").c_str(), &options, &sea), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("beaufort_force"), std::string::npos) << nearshore_last_error();
}

TEST(CApi, QueriesGiveTheBakedSurfaceAndItsCurrent) {
  nearshore_sea* sea = open_calm(write_sequence("query"));
  ASSERT_NE(sea, nullptr);
  nearshore_site_info site;
  site.struct_size = sizeof site;
  ASSERT_EQ(nearshore_site_info_get(sea, &site), NEARSHORE_OK);
  EXPECT_EQ(site.columns, kColumns);
  EXPECT_DOUBLE_EQ(site.width_m, kColumns * kSpacingM);
  // At cell centres well inside the rectangle, at a frame's own time, the shown surface is that
  // frame's value (float storage: 1e-6 m) and the current is P / (d + eta).
  const double time_s = 3 * kFrameIntervalS;
  std::vector<double> xy;
  for (int column = 12; column < 28; column += 3) xy.insert(xy.end(), {(column + 0.5) * kSpacingM, 60.0 + 2.0});
  std::vector<nearshore_surface_sample> samples(xy.size() / 2);
  ASSERT_EQ(nearshore_sea_query_at(sea, time_s, xy.data(), samples.size(), samples.data()), NEARSHORE_OK)
      << nearshore_last_error();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double eta = analytic_eta(xy[2 * i], time_s);
    EXPECT_NEAR(samples[i].elevation_m, eta, 1e-5) << "x = " << xy[2 * i];
    EXPECT_NEAR(samples[i].velocity_x_m_s, kWavelengthM / kPeriodS * eta / (10.0 + eta), 1e-4);
    EXPECT_EQ(samples[i].dry, 0);
    EXPECT_NEAR(std::hypot(samples[i].normal[0], samples[i].normal[1], samples[i].normal[2]), 1.0, 1e-5);
  }
  // The displayed snapshot after an advance gives the same numbers.
  ASSERT_EQ(nearshore_sea_advance(sea, time_s), NEARSHORE_OK);
  std::vector<nearshore_surface_sample> shown(samples.size());
  ASSERT_EQ(nearshore_sea_query(sea, xy.data(), shown.size(), shown.data()), NEARSHORE_OK);
  nearshore_stats stats;
  stats.struct_size = sizeof stats;
  ASSERT_EQ(nearshore_sea_stats(sea, &stats), NEARSHORE_OK);
  if (stats.underruns == 0) {
    for (std::size_t i = 0; i < shown.size(); ++i) EXPECT_NEAR(shown[i].elevation_m, samples[i].elevation_m, 1e-6);
  }
  EXPECT_EQ(nearshore_sea_query(sea, nullptr, 1, shown.data()), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("xy_m"), std::string::npos);
  nearshore_sea_close(sea);
}

TEST(CApi, TheVerticalVelocityIsTheTimeDerivativeOfTheShownHeights) {
  nearshore_sea* sea = open_calm(write_sequence("vertical"));
  ASSERT_NE(sea, nullptr);
  std::vector<double> xy;
  // Cell centres (bilinear interpolation in space would add its own error at 10 cells a wavelength).
  for (int column = 12; column < 28; column += 3) xy.insert(xy.end(), {(column + 0.5) * kSpacingM, 62.0});
  const std::size_t count = xy.size() / 2;
  const double t = 2.2, dt = 1e-3;  // between keyframes 4 and 5 (0.5 s apart)
  auto heights_at = [&](double time_s) {
    std::vector<nearshore_surface_sample> samples(count);
    EXPECT_EQ(nearshore_sea_advance(sea, time_s), NEARSHORE_OK) << nearshore_last_error();
    EXPECT_EQ(nearshore_sea_query(sea, xy.data(), count, samples.data()), NEARSHORE_OK);
    return samples;
  };
  const auto before = heights_at(t - dt);
  const auto after = heights_at(t + dt);
  heights_at(t);
  std::vector<float> rate(count);
  ASSERT_EQ(nearshore_sea_query_vertical_velocity(sea, xy.data(), count, rate.data()), NEARSHORE_OK) << nearshore_last_error();
  const double amplitude_omega = kAmplitudeM * 2.0 * std::numbers::pi / kPeriodS;
  for (std::size_t i = 0; i < count; ++i) {
    // The derivative of what is shown (centred difference: (w dt)^2 / 6 ~ 2e-7 of it; float heights).
    EXPECT_NEAR(rate[i], (after[i].elevation_m - before[i].elevation_m) / (2.0 * dt), 0.005 * amplitude_omega);
    // The wave's own, a w sin(k x - w t): the rates are the mass equation of fluxes given at cell
    // centres at 10 cells a wavelength, where the divergence's response is sin(k dx)/(k dx) times
    // 1 + (1 - cos k dx) / 2 = 1.025 (surface_snapshot.hpp): within 4 %.
    const double phase = 2.0 * std::numbers::pi * (xy[2 * i] / kWavelengthM - t / kPeriodS);
    EXPECT_NEAR(rate[i], amplitude_omega * std::sin(phase), 0.04 * amplitude_omega) << "x = " << xy[2 * i];
  }
  EXPECT_EQ(nearshore_sea_query_vertical_velocity(sea, xy.data(), count, nullptr), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("vertical_velocity_m_s"), std::string::npos);
  nearshore_sea_close(sea);
}

TEST(CApi, LatitudeLongitudeGoThroughTheGridsProjection) {
  nearshore_sea* sea = open_calm(write_sequence("latlon"));
  ASSERT_NE(sea, nullptr);
  nearshore_site_info site;
  site.struct_size = sizeof site;
  ASSERT_EQ(nearshore_site_info_get(sea, &site), NEARSHORE_OK);
  ASSERT_TRUE(std::isfinite(site.origin_latitude_deg));
  double x = 1, y = 1;
  ASSERT_EQ(nearshore_site_from_lat_lon(sea, site.origin_latitude_deg, site.origin_longitude_deg, &x, &y), NEARSHORE_OK);
  EXPECT_NEAR(x, 0.0, 1e-3);  // GeographicLib round trip: nanometres; the corner is the site origin
  EXPECT_NEAR(y, 0.0, 1e-3);
  EXPECT_EQ(nearshore_site_from_lat_lon(sea, 91.0, 0.0, &x, &y), NEARSHORE_INVALID_ARGUMENT);
  nearshore_sea_close(sea);
}

TEST(CApi, ABadFrameIsHeldAndSaidWhileTheSeaPlaysOn) {
  const fs::path folder = write_sequence("bad_frame");
  fs::resize_file(folder / "frame_000004.exr", 100);  // truncated
  nearshore_sea* sea = open_calm(folder);
  ASSERT_NE(sea, nullptr);
  nearshore_stats stats;
  stats.struct_size = sizeof stats;
  nearshore_surface_sample sample;
  const double point[2] = {80.0, 60.0};
  for (int frame = 0; frame < 180; ++frame) {  // 6 s of display at 30 fps: past frame 4, twice round
    ASSERT_EQ(nearshore_sea_advance(sea, frame / 30.0), NEARSHORE_OK) << nearshore_last_error();
    ASSERT_EQ(nearshore_sea_query(sea, point, 1, &sample), NEARSHORE_OK);
    ASSERT_TRUE(std::isfinite(sample.elevation_m));
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_EQ(nearshore_sea_stats(sea, &stats), NEARSHORE_OK);
  EXPECT_GE(stats.bad_frames_held, 1u);
  EXPECT_NE(std::string(stats.message).find("frame_000004.exr"), std::string::npos) << stats.message;
  nearshore_sea_close(sea);
}

TEST(CApi, QueriesFromOtherThreadsWhileTheRenderThreadAdvances) {
  nearshore_sea* sea = open_calm(write_sequence("threads"));
  ASSERT_NE(sea, nullptr);
  std::atomic<bool> stop{false};
  std::atomic<long> answered{0}, failed{0};
  std::vector<std::thread> ships;
  for (int ship = 0; ship < 2; ++ship)
    ships.emplace_back([&, ship] {
      const double point[2] = {40.0 + 30.0 * ship, 50.0};
      nearshore_surface_sample sample;
      while (!stop) {
        if (nearshore_sea_query(sea, point, 1, &sample) != NEARSHORE_OK || !std::isfinite(sample.elevation_m)) ++failed;
        ++answered;
      }
    });
  for (int frame = 0; frame < 120; ++frame) {
    EXPECT_EQ(nearshore_sea_advance(sea, frame / 30.0), NEARSHORE_OK);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  stop = true;
  for (std::thread& ship : ships) ship.join();
  EXPECT_GT(answered.load(), 0);
  EXPECT_EQ(failed.load(), 0);
  nearshore_sea_close(sea);
}

// A sea-state library through the C API: opened at the state nearest the conditions, switched
// with a crossfade whose midpoint shows both states' waves, bad conditions named.
TEST(CApi, ALibrarySwitchesSeaStateWithACrossfade) {
  const fs::path folder = scratch_folder() / "capi_library";
  fs::remove_all(folder);
  nearshore::runtime::testing::write_two_state_library(folder);
  nearshore_sea_options options;
  nearshore_sea_options_init(&options);
  options.plan = NEARSHORE_PLAN_FRAME_ORDER;
  options.beaufort_force = 0;
  options.time_mode = NEARSHORE_TIME_LOCKSTEP;  // both states' engines show exactly t
  nearshore_sea* sea = nullptr;
  EXPECT_EQ(nearshore_sea_open_library(folder.c_str(), "speed=3", &options, &sea), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("speed=3"), std::string::npos) << nearshore_last_error();
  ASSERT_EQ(nearshore_sea_open_library(folder.c_str(), "direction_deg=10", &options, &sea), NEARSHORE_OK)
      << nearshore_last_error();
  char state[64] = "";
  ASSERT_EQ(nearshore_sea_request_conditions(sea, "direction_deg=85", 2.0, state), NEARSHORE_OK) << nearshore_last_error();
  EXPECT_STREQ(state, "dir90");
  // Fade from t = 1 s over 2 s: at 2 s the smoothstep weight is 1/2.
  const double point[2] = {57.5, 47.5};
  nearshore_surface_sample sample;
  for (double t : {1.0, 2.0}) {
    for (int tries = 0; tries < 2000; ++tries) {  // let the decoders reach t (start-up), then advance
      ASSERT_EQ(nearshore_sea_advance(sea, t), NEARSHORE_OK);
      nearshore_stats stats;
      stats.struct_size = sizeof stats;
      ASSERT_EQ(nearshore_sea_stats(sea, &stats), NEARSHORE_OK);
      ASSERT_EQ(nearshore_sea_query(sea, point, 1, &sample), NEARSHORE_OK);
      const double expected = t == 1.0 ? nearshore::runtime::testing::wave_elevation_m(
                                             nearshore::runtime::testing::kLibraryFromWest, point[0], point[1], t)
                                       : 0.5 * nearshore::runtime::testing::wave_elevation_m(
                                                   nearshore::runtime::testing::kLibraryFromWest, point[0], point[1], t) +
                                             0.5 * nearshore::runtime::testing::wave_elevation_m(
                                                       nearshore::runtime::testing::kLibraryFromSouth, point[0], point[1], t);
      if (std::abs(sample.elevation_m - expected) < 2e-3) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      if (tries == 1999) ADD_FAILURE() << "t = " << t << ": " << sample.elevation_m << " != " << expected;
    }
  }
  nearshore_sea_close(sea);
  nearshore_sea* single = open_calm(write_sequence("not_a_library"));
  EXPECT_EQ(nearshore_sea_request_conditions(single, "direction_deg=0", 1.0, nullptr), NEARSHORE_INVALID_ARGUMENT);
  nearshore_sea_close(single);
}

}  // namespace
