// The C API's drawing functions through libnearshore.so, as a host with its own OpenGL context
// calls them (issue 12, issue 17): a renderer created in the host's context (GLFW here) draws the
// sea, reads the picture back, and takes its lighting from nearshore_renderer_set_lighting: a UTC
// time and a place put the sun where it stands (sunset warmer than noon), and a refused field keeps
// the previous lighting (the next picture is unchanged). Also nearshore_sun_position against a
// published ephemeris value. And a fleet drawn with the sea (nearshore_renderer_set_fleet, API
// version 3). Runs under Xvfb (tests/capi/CMakeLists.txt).
#include "nearshore.h"
#include "capi_test_support.hpp"

#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstddef>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace {
using namespace nearshore::capi_test;

// The NREL Solar Position Algorithm's worked example (Reda & Andreas 2004, NREL/TP-560-34302,
// table A5.1): Golden, Colorado, 2003-10-17 12:30:30 local time (UTC - 7): topocentric zenith
// 50.11162 deg (refraction included), azimuth 194.34024 deg. NOAA/Meeus is good to about 0.01 deg
// over 1800-2100 for the sun itself; 0.1 deg allows for the refraction models differing.
TEST(CApiLighting, SunPositionMatchesThePublishedEphemeris) {
  double azimuth_deg = 0, elevation_deg = 0;
  ASSERT_EQ(nearshore_sun_position(39.742476, -105.1786, "2003-10-17T19:30:30Z", &azimuth_deg, &elevation_deg),
            NEARSHORE_OK)
      << nearshore_last_error();
  EXPECT_NEAR(azimuth_deg, 194.34024, 0.1);
  EXPECT_NEAR(elevation_deg, 90.0 - 50.11162, 0.1);
  EXPECT_EQ(nearshore_sun_position(39.7, -105.2, "17 October 2003", &azimuth_deg, &elevation_deg),
            NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("utc_iso8601"), std::string::npos) << nearshore_last_error();
  EXPECT_EQ(nearshore_sun_position(95.0, 0.0, "2003-10-17T19:30:30Z", &azimuth_deg, &elevation_deg),
            NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("latitude_deg"), std::string::npos) << nearshore_last_error();
}

struct Window {
  GLFWwindow* window = nullptr;
  Window(int width, int height) {
    if (!glfwInit()) return;
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    window = glfwCreateWindow(width, height, "capi_render_test", nullptr, nullptr);
    if (window) glfwMakeContextCurrent(window);
  }
  ~Window() {
    if (window) glfwDestroyWindow(window);
    glfwTerminate();
  }
};

void* proc_address(const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); }

struct Picture {
  std::vector<std::uint8_t> rgba;
  double mean(int channel) const {
    double sum = 0;
    for (std::size_t i = channel; i < rgba.size(); i += 4) sum += rgba[i];
    return sum / (rgba.size() / 4);
  }
};

TEST(CApiLighting, TheRendererDrawsUnderTheSunOfAPlaceAndTimeAndKeepsItsLightingWhenAFieldIsRefused) {
  constexpr int kWidth = 160, kHeight = 90;
  Window host(kWidth, kHeight);
  ASSERT_NE(host.window, nullptr) << "no OpenGL 3.3 context (run under xvfb-run)";
  nearshore_sea* sea = open_calm(write_sequence("render"));
  ASSERT_NE(sea, nullptr);
  ASSERT_EQ(nearshore_sea_advance(sea, 1.0), NEARSHORE_OK) << nearshore_last_error();
  nearshore_renderer* renderer = nullptr;
  ASSERT_EQ(nearshore_renderer_create(sea, NEARSHORE_GRID_QUADTREE, proc_address, &renderer), NEARSHORE_OK)
      << nearshore_last_error();
  nearshore_camera camera;
  nearshore_camera_init(&camera);
  // From 30 m up at the basin's west edge, looking west-south-west out to sea and the horizon:
  // in the evening the sun stands there.
  camera.eye_m[0] = 0.0, camera.eye_m[1] = 60.0, camera.eye_m[2] = 30.0;
  camera.target_m[0] = -400.0, camera.target_m[1] = -100.0, camera.target_m[2] = 0.0;
  const auto draw = [&]() {
    Picture picture;
    picture.rgba.resize(std::size_t(kWidth) * kHeight * 4);
    EXPECT_EQ(nearshore_renderer_draw(renderer, &camera, kWidth, kHeight), NEARSHORE_OK) << nearshore_last_error();
    EXPECT_EQ(nearshore_renderer_read_pixels(renderer, kWidth, kHeight, picture.rgba.data()), NEARSHORE_OK)
        << nearshore_last_error();
    return picture;
  };
  // The basin lies in UTM 51N near 38.9 N 121.7 E (UTC + 8): local noon is about 04:00 UTC; on
  // 21 June the sun sets there at about 11:20 UTC in the west-north-west.
  nearshore_lighting lighting;
  nearshore_lighting_init(&lighting);
  std::strcpy(lighting.utc_iso8601, "2026-06-21T04:00:00Z");
  ASSERT_EQ(nearshore_renderer_set_lighting(renderer, &lighting), NEARSHORE_OK) << nearshore_last_error();
  const Picture noon = draw();
  std::strcpy(lighting.utc_iso8601, "2026-06-21T11:05:00Z");
  ASSERT_EQ(nearshore_renderer_set_lighting(renderer, &lighting), NEARSHORE_OK) << nearshore_last_error();
  const Picture sunset = draw();
  const double noon_warmth = noon.mean(0) / std::max(1.0, noon.mean(2));
  const double sunset_warmth = sunset.mean(0) / std::max(1.0, sunset.mean(2));
  EXPECT_GT(sunset_warmth, 1.2 * noon_warmth) << "red/blue at noon " << noon_warmth << ", at sunset " << sunset_warmth;

  // A refused field names itself and changes nothing: the next picture is the sunset again.
  lighting.chlorophyll_mg_m3 = -3.0;
  EXPECT_EQ(nearshore_renderer_set_lighting(renderer, &lighting), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("chlorophyll_mg_m3"), std::string::npos) << nearshore_last_error();
  lighting.chlorophyll_mg_m3 = 0.3;
  std::strcpy(lighting.utc_iso8601, "tomorrow at dawn");
  EXPECT_EQ(nearshore_renderer_set_lighting(renderer, &lighting), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("utc_iso8601"), std::string::npos) << nearshore_last_error();
  const Picture again = draw();
  EXPECT_EQ(again.rgba, sunset.rgba);

  // Without a UTC time the camera's sun holds again.
  nearshore_lighting_init(&lighting);
  ASSERT_EQ(nearshore_renderer_set_lighting(renderer, &lighting), NEARSHORE_OK) << nearshore_last_error();
  camera.sun_elevation_deg = 60.0;
  const Picture camera_sun = draw();
  EXPECT_NE(camera_sun.rgba, sunset.rgba);

  // API 7's weather: fog of 100 m visibility in a layer above the camera makes the picture nearly
  // one grey (the sea beyond 30 m keeps under 40 % of its contrast, Koschmieder); a struct of
  // version 6 (no weather fields) is taken, with clear air: the same picture as before.
  lighting.cloud_cover = 1.0;
  lighting.visibility_m = 100.0;
  lighting.fog_top_m = 200.0;
  ASSERT_EQ(nearshore_renderer_set_lighting(renderer, &lighting), NEARSHORE_OK) << nearshore_last_error();
  const Picture fog = draw();
  const auto spread = [](const Picture& p) {  // the standard deviation of the green channel
    double mean = p.mean(1), square = 0;
    for (std::size_t i = 1; i < p.rgba.size(); i += 4) square += (p.rgba[i] - mean) * (p.rgba[i] - mean);
    return std::sqrt(square / double(p.rgba.size() / 4));
  };
  EXPECT_LT(spread(fog), 0.5 * spread(camera_sun)) << "fog " << spread(fog) << ", clear " << spread(camera_sun);
  lighting.visibility_m = -5.0;
  EXPECT_EQ(nearshore_renderer_set_lighting(renderer, &lighting), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("visibility_m"), std::string::npos) << nearshore_last_error();
  lighting.struct_size = offsetof(nearshore_lighting, cloud_cover);
  ASSERT_EQ(nearshore_renderer_set_lighting(renderer, &lighting), NEARSHORE_OK) << nearshore_last_error();
  EXPECT_EQ(draw().rgba, camera_sun.rgba);
  nearshore_renderer_destroy(renderer);
  nearshore_sea_close(sea);
}

// The whitecaps a C host's renderer draws follow the wind it is given (nearshore_lighting.
// wind_speed_m_s): over a Beaufort 8 sea seen from 80 m, at that sea's own wind (19.2 m/s) Monahan &
// O'Muircheartaigh give 9 % of white water; in no wind the onset falls to the folded water alone.
// Compared pixel by pixel, the windy picture has white patches (brighter by > 0.25) on a share of
// the sea of at least a tenth of W (the fine cascades fade with distance at the picture's edges and
// foam's texture tears it: WhitecapRender.* measures the coverage itself).
TEST(CApiLighting, WhitecapsFollowTheWindGiven) {
  constexpr int kWidth = 160, kHeight = 90;
  Window host(kWidth, kHeight);
  ASSERT_NE(host.window, nullptr) << "no OpenGL 3.3 context (run under xvfb-run)";
  nearshore_sea* sea = open_in_frame_order(write_sequence("whitecaps"), 8);
  ASSERT_NE(sea, nullptr);
  ASSERT_EQ(nearshore_sea_advance(sea, 1.0), NEARSHORE_OK) << nearshore_last_error();
  nearshore_renderer* renderer = nullptr;
  ASSERT_EQ(nearshore_renderer_create(sea, NEARSHORE_GRID_QUADTREE, proc_address, &renderer), NEARSHORE_OK)
      << nearshore_last_error();
  nearshore_camera camera;
  nearshore_camera_init(&camera);
  camera.eye_m[0] = -300.0, camera.eye_m[1] = -300.0, camera.eye_m[2] = 80.0;  // over the open sea
  camera.target_m[0] = -300.0, camera.target_m[1] = -240.0, camera.target_m[2] = 0.0;
  camera.sun_elevation_deg = 50.0;
  const auto draw_at_wind = [&](double wind_m_s) {
    nearshore_lighting lighting;
    nearshore_lighting_init(&lighting);
    lighting.wind_speed_m_s = wind_m_s;
    EXPECT_EQ(nearshore_renderer_set_lighting(renderer, &lighting), NEARSHORE_OK) << nearshore_last_error();
    std::vector<std::uint8_t> rgba(std::size_t(kWidth) * kHeight * 4);
    EXPECT_EQ(nearshore_renderer_draw(renderer, &camera, kWidth, kHeight), NEARSHORE_OK) << nearshore_last_error();
    EXPECT_EQ(nearshore_renderer_read_pixels(renderer, kWidth, kHeight, rgba.data()), NEARSHORE_OK) << nearshore_last_error();
    return rgba;
  };
  const std::vector<std::uint8_t> calm = draw_at_wind(0.0), gale = draw_at_wind(19.2);
  int white = 0;
  for (std::size_t i = 0; i < calm.size(); i += 4) {
    const double brighter = ((gale[i] + gale[i + 1] + gale[i + 2]) - (calm[i] + calm[i + 1] + calm[i + 2])) / (3.0 * 255.0);
    if (brighter > 0.25) ++white;
  }
  const double share = double(white) / (kWidth * kHeight), monahan = 3.84e-6 * std::pow(19.2, 3.41);
  std::printf("white on %.2f %% of the picture at 19.2 m/s (Monahan %.2f %%)\n", 100 * share, 100 * monahan);
  EXPECT_GT(share, 0.1 * monahan) << "white on " << 100 * share << " % of the picture, Monahan " << 100 * monahan << " %";
  EXPECT_LT(share, 1.25 * monahan) << "white on " << 100 * share << " % of the picture, Monahan " << 100 * monahan << " %";
  nearshore_renderer_destroy(renderer);
  nearshore_sea_close(sea);
}

// A tug under way in the calm basin, drawn by the host's renderer once the fleet is bound
// (nearshore_renderer_set_fleet, ships::FleetLayers behind it): its hull, bow wave and wake change
// the picture; unbinding gives back the sea alone, pixel for pixel (the same snapshot drawn twice
// is the same picture, as the lighting test above relies on); a fleet of another sea is refused.
TEST(CApiFleetDrawing, TheRendererDrawsABoundFleetAndTheSeaAloneOnceUnbound) {
  constexpr int kWidth = 160, kHeight = 90;
  Window host(kWidth, kHeight);
  ASSERT_NE(host.window, nullptr) << "no OpenGL 3.3 context (run under xvfb-run)";
  nearshore_sea* sea = open_calm(write_sequence("render_fleet", 0.0));
  ASSERT_NE(sea, nullptr);
  nearshore_fleet* fleet = nullptr;
  ASSERT_EQ(nearshore_fleet_create(sea, &fleet), NEARSHORE_OK) << nearshore_last_error();
  nearshore_ship_options options;
  nearshore_ship_options_init(&options);
  options.name = "Tug";
  options.x_m = 50.0;
  options.y_m = 60.0;
  options.heading_deg = 90.0;  // east, along the basin
  options.order = NEARSHORE_ORDER_SPEED;
  options.speed_m_s = 3.0;
  options.initial_speed_m_s = 3.0;
  options.bow_wave_cells = 64;
  ASSERT_EQ(nearshore_fleet_add_ship(fleet, &options, nullptr), NEARSHORE_OK) << nearshore_last_error();
  for (int frame = 1; frame <= 60; ++frame) {  // 2 s under way: a bow wave and a few wake decals
    ASSERT_EQ(nearshore_sea_advance(sea, frame / 30.0), NEARSHORE_OK);
    ASSERT_EQ(nearshore_fleet_step(fleet, 1.0 / 30.0), NEARSHORE_OK) << nearshore_last_error();
  }
  nearshore_ship_pose pose;
  pose.struct_size = sizeof pose;
  ASSERT_EQ(nearshore_fleet_ship_pose(fleet, 0, &pose), NEARSHORE_OK) << nearshore_last_error();

  nearshore_renderer* renderer = nullptr;
  ASSERT_EQ(nearshore_renderer_create(sea, NEARSHORE_GRID_QUADTREE, proc_address, &renderer), NEARSHORE_OK)
      << nearshore_last_error();
  nearshore_camera camera;
  nearshore_camera_init(&camera);
  // From 40 m up, south of the tug, looking down at it.
  camera.eye_m[0] = pose.x_m, camera.eye_m[1] = pose.y_m - 45.0, camera.eye_m[2] = 40.0;
  camera.target_m[0] = pose.x_m, camera.target_m[1] = pose.y_m, camera.target_m[2] = 0.0;
  const auto draw = [&]() {
    Picture picture;
    picture.rgba.resize(std::size_t(kWidth) * kHeight * 4);
    EXPECT_EQ(nearshore_renderer_draw(renderer, &camera, kWidth, kHeight), NEARSHORE_OK) << nearshore_last_error();
    EXPECT_EQ(nearshore_renderer_read_pixels(renderer, kWidth, kHeight, picture.rgba.data()), NEARSHORE_OK)
        << nearshore_last_error();
    return picture;
  };
  const Picture sea_alone = draw();
  ASSERT_EQ(nearshore_renderer_set_fleet(renderer, fleet), NEARSHORE_OK) << nearshore_last_error();
  const Picture with_fleet = draw();
  ASSERT_EQ(nearshore_renderer_set_fleet(renderer, nullptr), NEARSHORE_OK) << nearshore_last_error();
  const Picture unbound = draw();

  // Pixels that changed by more than 8/255 in a channel: the hull (24 m x 9 m seen from about
  // 60 m fills several hundred of the 14400 pixels), its bow wave and its wake.
  int changed = 0;
  for (std::size_t i = 0; i < sea_alone.rgba.size(); i += 4)
    for (int c = 0; c < 3; ++c)
      if (std::abs(int(with_fleet.rgba[i + c]) - int(sea_alone.rgba[i + c])) > 8) {
        ++changed;
        break;
      }
  std::printf("fleet drawn: %d of %d pixels changed; tug at (%.1f, %.1f) m, %.2f m/s\n", changed, kWidth * kHeight,
              pose.x_m, pose.y_m, pose.speed_m_s);
  EXPECT_GT(changed, 300);
  EXPECT_EQ(unbound.rgba, sea_alone.rgba);

  // A fleet of another sea is refused, naming the call; the binding is unchanged.
  nearshore_sea* other_sea = open_calm(write_sequence("render_fleet_other", 0.0));
  ASSERT_NE(other_sea, nullptr);
  nearshore_fleet* other_fleet = nullptr;
  ASSERT_EQ(nearshore_fleet_create(other_sea, &other_fleet), NEARSHORE_OK) << nearshore_last_error();
  EXPECT_EQ(nearshore_renderer_set_fleet(renderer, other_fleet), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(std::string(nearshore_last_error()).find("nearshore_renderer_set_fleet"), std::string::npos)
      << nearshore_last_error();
  EXPECT_EQ(nearshore_renderer_set_fleet(nullptr, fleet), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_EQ(draw().rgba, sea_alone.rgba);
  nearshore_fleet_destroy(other_fleet);
  nearshore_sea_close(other_sea);
  nearshore_renderer_destroy(renderer);
  nearshore_fleet_destroy(fleet);
  nearshore_sea_close(sea);
}

}  // namespace
