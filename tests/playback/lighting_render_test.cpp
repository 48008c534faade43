// The lighting shaders on Mesa: pixel against the CPU twin (playback/src/lighting.cpp and the
// models it uses), and whole scenes of the demo harbour at noon and at sunset.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/playback/lighting.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/plot/plot.hpp"
#include "snapshot_fixtures.hpp"

namespace nearshore {
namespace {
using playback::Camera;
using playback::Lighting;
using playback::Vector3;

constexpr double kPi = std::numbers::pi;

Vector3 normalized(const Vector3& v) {
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / length, v[1] / length, v[2] / length};
}

// The unit ray through the centre of pixel (x, y) (row 0 at the top), as the sky shader forms it.
Vector3 pixel_ray(const playback::CameraView& view, int x, int y) {
  const double ndc_x = (x + 0.5) / view.width_px * 2.0 - 1.0, ndc_y = 1.0 - (y + 0.5) / view.height_px * 2.0;
  const auto far = playback::transform(playback::inverse(view.view_projection), {ndc_x, ndc_y, 1.0, 1.0});
  return normalized({far[0] / far[3] - view.eye_m[0], far[1] / far[3] - view.eye_m[1], far[2] / far[3] - view.eye_m[2]});
}

double luminance(const std::array<float, 3>& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

TEST(LightingRender, ShaderMatchesTheCpuTwinOverATestPattern) {
  // A still harbour without land (depth 12 m in the south shoaling to 3 m in the north, linear in
  // y, so bilinear interpolation is exact) seen obliquely with the sky above the horizon: every
  // sampled pixel is either sky (sky_radiance of its ray) or water (shade_water at the ray's
  // meeting with z = 0), computed here on the CPU in double precision.
  playback::GlWindow window(64, 64, "test", false);
  test::SiteOptions options;
  options.land = false;
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = test::make_site(options);  // 256 m x 192 m, no keyframes: a flat harbour
  playback::Camera camera;
  camera.eye_m = {128.0, -40.0, 25.0};
  camera.target_m = {128.0, 120.0, 0.0};
  camera.vertical_field_of_view_deg = 60.0;
  const int width = 160, height = 100;
  int compared_sky = 0, compared_water = 0;
  for (const auto& [azimuth, elevation] : {std::pair{120.0, 40.0}, std::pair{300.0, 8.0}, std::pair{30.0, -3.0}}) {
    Lighting lighting;
    lighting.sun_azimuth_deg = azimuth;
    lighting.sun_elevation_deg = elevation;
    lighting.water.turbidity_ntu = 2.0;
    playback::WaterRenderer renderer;
    renderer.render(snapshot, camera, lighting, width, height);
    const Image image = renderer.read_pixels();
    const playback::CameraView view = playback::camera_view(camera, width, height, 1.0, 1000.0);
    const playback::LightingFrame frame = playback::prepare_lighting(lighting);
    for (int y = 2; y < height; y += 4)
      for (int x = 2; x < width; x += 4) {
        const Vector3 ray = pixel_ray(view, x, y);
        playback::Radiance expected{};
        if (ray[2] > 0.02) {
          expected = playback::to_display(frame, playback::sky_radiance(frame.sky, ray));
          ++compared_sky;
        } else if (ray[2] < -0.02) {
          const double t = -camera.eye_m[2] / ray[2];
          const double px = camera.eye_m[0] + t * ray[0], py = camera.eye_m[1] + t * ray[1];
          // away from the rectangle's edges (and its sea beyond), where the depth is bilinear
          if (px < 8 || px > 248 || py < 8 || py > 184) continue;
          playback::SurfacePoint point;
          point.to_eye = {-ray[0], -ray[1], -ray[2]};
          const double row = std::clamp(py / options.spacing_m - 0.5, 0.0, double(options.rows - 1));
          point.water_depth_m = 12.0 - 9.0 * row / (options.rows - 1);
          expected = playback::to_display(frame, playback::shade_water(frame, point));
          ++compared_water;
        } else {
          continue;  // the horizon's own pixels mix the two
        }
        const auto pixel = image.get(x, y);
        // 8-bit output (1/255), float32 in the shader against double here, and the 8-bit weights
        // of the hardware-filtered depth texture (a few mm of depth): 3/255.
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(pixel[std::size_t(c)], expected[std::size_t(c)], 3.0 / 255)
              << "pixel (" << x << ", " << y << ") channel " << c << ", sun " << azimuth << " / " << elevation;
      }
  }
  EXPECT_GT(compared_sky, 500);
  EXPECT_GT(compared_water, 500);
}

// The demo harbour (bathymetry/demo_harbour.hpp: Dalian bay, an open coast facing south, the
// breakwaters' basin) as a site, with Beaufort 4 deep water beyond it.
runtime::SurfaceSnapshot demo_scene() {
  bathymetry::DemoHarbourOptions demo;
  GridGeometry geometry;
  geometry.spacing_m = 8.0;
  geometry.columns = int(demo.width_m / geometry.spacing_m);
  geometry.rows = int(demo.height_m / geometry.spacing_m);
  auto site = std::make_shared<runtime::HarbourSite>();
  site->harbour = HarbourGrid::open_water(geometry, 10.f);
  for (int j = 0; j < geometry.rows; ++j)
    for (int i = 0; i < geometry.columns; ++i) {
      const double depth = bathymetry::demo_harbour_depth_m(demo, (i + 0.5) * geometry.spacing_m, (j + 0.5) * geometry.spacing_m);
      site->harbour.still_water_depth_m(i, j) = float(depth);
      site->harbour.land(i, j) = depth < 0.0 ? 1 : 0;
    }
  site->width_m = demo.width_m;
  site->height_m = demo.height_m;
  site->source_line_m = 0.0;
  site->blend_start_m = 16.0;
  site->blend_width_m = 80.0;
  site->edge_fade_m = 80.0;
  site->choppiness = 1.0;
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = site;
  snapshot.harbour_from = snapshot.harbour_to = test::make_harbour_keyframe(*site, 0, 1);
  const test::DeepPair deep = test::make_deep_pair(4, {180.0, 23.0}, 64, 0.0, 0.5, 10);
  snapshot.deep_from = deep.from;
  snapshot.deep_to = deep.to;
  snapshot.deep_fraction = 0.3;
  return snapshot;
}

// A camera on the harbour's seaward side, 20 m up, looking along compass bearing `azimuth_deg`.
Camera looking_towards(double azimuth_deg) {
  Camera camera;
  camera.eye_m = {800.0, 200.0, 20.0};
  const double a = azimuth_deg * kPi / 180.0;
  camera.target_m = {800.0 + 2000.0 * std::sin(a), 200.0 + 2000.0 * std::cos(a), -120.0};
  camera.vertical_field_of_view_deg = 50.0;
  return camera;
}

struct SceneStatistics {
  double red_over_blue = 0.0;      ///< mean R / mean B over the image
  int brightest_water_column = 0;  ///< of the lower half (the sea)
  int dark_pixels = 0;             ///< pure black (NaN lands there on Mesa)
};
SceneStatistics statistics_of(const Image& image) {
  SceneStatistics s;
  double red = 0, blue = 0, best = -1;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const auto p = image.get(x, y);
      red += p[0];
      blue += p[2];
      if (p[0] + p[1] + p[2] < 1.0 / 255) ++s.dark_pixels;
    }
  for (int x = 0; x < image.width(); ++x) {
    double column = 0;
    for (int y = image.height() / 2; y < image.height(); ++y) column += luminance(image.get(x, y));
    if (column > best) best = column, s.brightest_water_column = x;
  }
  s.red_over_blue = red / std::max(blue, 1e-9);
  return s;
}

TEST(LightingRender, SunsetAtTheDemoHarbourIsWarmerThanNoonAndItsGlitterLiesTowardsTheSun) {
  playback::GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = demo_scene();
  bathymetry::DemoHarbourOptions demo;
  Lighting noon, sunset;
  noon.set_sun_for(demo.centre_latitude_deg, demo.centre_longitude_deg, playback::UtcTime::parse("2026-06-21T04:10:00Z"));
  sunset.set_sun_for(demo.centre_latitude_deg, demo.centre_longitude_deg, playback::UtcTime::parse("2026-06-21T10:55:00Z"));
  ASSERT_GT(noon.sun_elevation_deg, 70.0);
  ASSERT_GT(sunset.sun_elevation_deg, 1.0);
  ASSERT_LT(sunset.sun_elevation_deg, 8.0);
  const int width = 192, height = 108;
  // Both seen looking 40 degrees to the left of the setting sun: its glitter lies right of centre.
  const Camera camera = looking_towards(sunset.sun_azimuth_deg - 40.0);
  playback::WaterRenderer renderer;
  renderer.render(snapshot, camera, noon, width, height);
  const SceneStatistics at_noon = statistics_of(renderer.read_pixels());
  renderer.render(snapshot, camera, sunset, width, height);
  const Image sunset_image = renderer.read_pixels();
  const SceneStatistics at_sunset = statistics_of(sunset_image);
  EXPECT_GT(at_sunset.red_over_blue, 1.3 * at_noon.red_over_blue);
  EXPECT_EQ(at_noon.dark_pixels, 0);
  EXPECT_EQ(at_sunset.dark_pixels, 0);
  // The column the sun's azimuth projects to (its direction at the horizon): the glitter path.
  const playback::CameraView view = playback::camera_view(camera, width, height, 1.0, 5000.0);
  const double a = sunset.sun_azimuth_deg * kPi / 180.0;
  const auto clip = playback::transform(view.view_projection, {camera.eye_m[0] + 1000.0 * std::sin(a),
                                                               camera.eye_m[1] + 1000.0 * std::cos(a), camera.eye_m[2], 1.0});
  const double sun_column = (clip[0] / clip[3] * 0.5 + 0.5) * width;
  EXPECT_NEAR(at_sunset.brightest_water_column, sun_column, width / 8.0)
      << "the sun projects to column " << sun_column;
  EXPECT_GT(sun_column, width / 2.0);
}

TEST(LightingRender, TwilightAndNightGiveFiniteImagesAndIdenticalInputsIdenticalImages) {
  playback::GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = demo_scene();
  const Camera camera = looking_towards(250.0);
  for (double elevation : {-3.0, -20.0}) {
    Lighting lighting;
    lighting.sun_azimuth_deg = 300.0;
    lighting.sun_elevation_deg = elevation;
    std::vector<float> first;
    for (int attempt = 0; attempt < 2; ++attempt) {
      playback::WaterRenderer renderer;
      renderer.render(snapshot, camera, lighting, 96, 54);
      const Image image = renderer.read_pixels();
      for (float v : image.pixels()) ASSERT_TRUE(std::isfinite(v));
      if (attempt == 0)
        first = image.pixels();
      else
        EXPECT_TRUE(image.pixels() == first) << "sun at " << elevation << " degrees: two renders differ";
    }
    if (elevation == -3.0) {  // civil twilight: the sky still shows
      playback::WaterRenderer renderer;
      renderer.render(snapshot, camera, lighting, 96, 54);
      EXPECT_GT(luminance(renderer.read_pixels().get(48, 2)), 0.05);
    }
  }
}

}  // namespace
}  // namespace nearshore

namespace nearshore {
namespace {

TEST(LightingRender, LandIsMirroredInTheWaterBelowIt) {
  // The test site's land block (north-east, 4-5 m high) seen from 3 m over the water: with the
  // local reflection on, the water just below the shoreline shows the dark land, not the bright
  // sky near the horizon, and the sky and land themselves are unchanged.
  playback::GlWindow window(64, 64, "test", false);
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = test::make_site();
  playback::Camera camera;
  camera.eye_m = {200.0, 60.0, 3.0};
  camera.target_m = {220.0, 180.0, 1.0};
  camera.vertical_field_of_view_deg = 20.0;
  const int width = 160, height = 120;
  Image with(width, height), without(width, height);
  for (bool reflections : {true, false}) {
    playback::RendererSettings settings;
    settings.local_reflections = reflections;
    playback::WaterRenderer renderer(settings);
    renderer.render(snapshot, camera, Lighting{}, width, height);
    (reflections ? with : without) = renderer.read_pixels();
  }
  write_png(with, std::filesystem::path(NEARSHORE_BINARY_DIR) / "playback_reflection_test.png");
  int darker = 0, changed_above = 0;
  for (int x = 0; x < width; ++x)
    for (int y = 0; y < height; ++y) {
      const double a = luminance(with.get(x, y)), b = luminance(without.get(x, y));
      if (y < height / 2 && std::abs(a - b) > 1e-6) ++changed_above;
      if (y > height / 2 && a < b - 0.05) ++darker;
    }
  EXPECT_GT(darker, 50) << "water pixels darkened by the land's reflection";
  EXPECT_EQ(changed_above, 0) << "the reflection changed pixels above the horizon";
}

}  // namespace
}  // namespace nearshore
