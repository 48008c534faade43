// The lighting shaders on Mesa: pixel against the CPU twin (playback/src/lighting.cpp and the
// models it uses), and whole scenes of the demo harbour at noon and at sunset.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/playback/lighting.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/plot/plot.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"
#include "snapshot_fixtures.hpp"

namespace nearshore {
namespace {
using playback::Camera;
using playback::Lighting;
using playback::Vector3;


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
  // The last two: weather presets (the CIE overcast sky, and fog whose layer the camera at 25 m
  // stands in: the sky dimmed by the 125 m above it, the water by its distance through the fog).
  const std::pair<double, double> suns[] = {{120.0, 40.0}, {300.0, 8.0}, {30.0, -3.0}, {200.0, 35.0}, {200.0, 35.0}};
  const char* weathers[] = {"clear", "clear", "clear", "overcast", "fog"};
  for (int run = 0; run < 5; ++run) {
    const auto [azimuth, elevation] = suns[run];
    Lighting lighting;
    playback::apply_weather(lighting, weathers[run]);
    if (run == 4) lighting.visibility_m = 300.0;  // the water 25-250 m away: transmittance 0.74-0.05
    lighting.sun_azimuth_deg = azimuth;
    lighting.sun_elevation_deg = elevation;
    lighting.water.turbidity_ntu = 2.0;
    // The twin is the optics' procedural seabed (shade_water); the screen-space refraction shows the
    // terrain pass's drawn seabed instead, which the twin does not model (RefractionRender.* and
    // Lighting.TheRefractedSceneIsTheFlatSeabedTermForTerm... test that road).
    playback::RendererSettings settings;
    settings.refraction = false;
    playback::WaterRenderer renderer(settings);
    renderer.render(snapshot, camera, lighting, width, height);
    const Image image = renderer.read_pixels();
    const playback::CameraView view = playback::camera_view(camera, width, height, 1.0, 1000.0);
    const playback::LightingFrame frame = playback::prepare_lighting(lighting);
    for (int y = 2; y < height; y += 4)
      for (int x = 2; x < width; x += 4) {
        const Vector3 ray = pixel_ray(view, x, y);
        playback::Radiance expected{};
        if (ray[2] > 0.02) {
          expected = playback::to_display(frame, playback::sky_seen(frame, camera.eye_m, ray));
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
          const auto bottom = playback::refracted_seabed_point(px, py, point.normal, point.to_eye, point.water_depth_m);
          point.seabed_albedo_scale = playback::seabed_texture(bottom[0], bottom[1]);
          expected = playback::to_display(frame, playback::through_air(frame, playback::shade_water(frame, point), camera.eye_m,
                                                                       {px, py, 0.0}));
          ++compared_water;
        } else {
          continue;  // the horizon's own pixels mix the two
        }
        const auto pixel = image.get(x, y);
        // 8-bit output (1/255), float32 in the shader against double here, and the 8-bit weights
        // of the hardware-filtered depth texture (a few mm of depth): 3/255.
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(pixel[std::size_t(c)], expected[std::size_t(c)], 3.0 / 255)
              << "pixel (" << x << ", " << y << ") channel " << c << ", sun " << azimuth << " / " << elevation << ", "
              << weathers[run];
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
  const double a = azimuth_deg * std::numbers::pi / 180.0;
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
  const double a = sunset.sun_azimuth_deg * std::numbers::pi / 180.0;
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
    settings.refraction = false;  // the reflection alone: refraction changes the same shore pixels
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

namespace nearshore {
namespace {

// Deep water whose cascades stand at constant heights (so the drawn sea is the plane z = sum of
// them, and every pixel's point is its ray's meeting with that plane, as on the CPU) but carry a
// smooth periodic slope pattern as their normal maps: a test pattern for the detail normals and
// their parallax (the heights and the slopes need not agree for that).
std::shared_ptr<runtime::DeepWaterKeyframe> relief_pattern_keyframe(const std::vector<double>& tile_lengths_m,
                                                                   const std::vector<double>& heights_m, int n) {
  auto keyframe = std::make_shared<runtime::DeepWaterKeyframe>();
  keyframe->serial = 900;
  for (std::size_t c = 0; c < tile_lengths_m.size(); ++c) {
    ocean::DeepWaterFrame frame;
    frame.grid_size = n;
    frame.tile_length_m = tile_lengths_m[c];
    const std::size_t count = std::size_t(n) * n;
    frame.surface_elevation_m.assign(count, float(heights_m[c]));
    for (auto* zero : {&frame.displacement_x_m, &frame.displacement_y_m, &frame.displacement_xx, &frame.displacement_yy,
                       &frame.displacement_xy})
      zero->assign(count, 0.f);
    frame.slope_x.resize(count);
    frame.slope_y.resize(count);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        frame.slope_x[std::size_t(j) * n + i] = float(0.15 * std::sin(2 * std::numbers::pi * (2 * i + j) / n + double(c)));
        frame.slope_y[std::size_t(j) * n + i] = float(0.10 * std::cos(2 * std::numbers::pi * (i - 3 * j) / n));
      }
    keyframe->cascades.push_back(std::move(frame));
  }
  return keyframe;
}

// A periodic tile read as the hardware's bilinear filter reads it (texel i at x = i L / N).
double periodic_bilinear(const std::vector<float>& field, int n, double tile_m, double x, double y) {
  const double u = x / tile_m * n, v = y / tile_m * n;
  const double fu = std::floor(u), fv = std::floor(v);
  const auto at = [&](double i, double j) {
    const int a = int(((long long)i % n + n) % n), b = int(((long long)j % n + n) % n);
    return double(field[std::size_t(b) * n + a]);
  };
  const double wu = u - fu, wv = v - fv;
  return (1 - wv) * ((1 - wu) * at(fu, fv) + wu * at(fu + 1, fv)) + wv * ((1 - wu) * at(fu, fv + 1) + wu * at(fu + 1, fv + 1));
}

TEST(LightingRender, DetailNormalsAndTheirParallaxMatchTheCpuTwin) {
  // Open sea only, two cascades (64 m and 16 m tiles of 64 samples: texels of 1 m and 0.25 m) at
  // 0.3 m and 0.2 m, seen from 6 m looking north so the rays meet the water at 8-25 degrees: the
  // near water keeps both normal maps and most of the fine cascade's relief is beyond the grid,
  // further out the fine one fades and the coarse one's relief is drawn by the grid. Each sampled
  // pixel is the twin's shade_water with the normal the shader reads: the cascades' slopes at the
  // point moved by eq. (5) (parallax_offset_m) for the relief weighted by detail_normal_weight x
  // unresolved_relief_weight, the footprint from the neighbouring pixels of its 2 x 2 quad (what
  // dFdx / dFdy give), and the faded slopes' variance added to sigma^2.
  playback::GlWindow window(64, 64, "test", false);
  const int n = 64;
  const std::vector<double> tiles = {64.0, 16.0}, heights = {0.3, 0.2};
  runtime::SurfaceSnapshot snapshot;
  snapshot.deep_from = snapshot.deep_to = relief_pattern_keyframe(tiles, heights, n);
  const double plane_z = heights[0] + heights[1];
  playback::Camera camera;
  camera.eye_m = {3.0, 1.0, 6.0};
  camera.target_m = {3.0, 40.0, 0.0};
  camera.vertical_field_of_view_deg = 40.0;
  const int width = 160, height = 100;  // even: 2 x 2 quads start at even GL rows
  const playback::CameraView view = playback::camera_view(camera, width, height, 1.0, 1000.0);
  std::vector<double> variance;  // per axis, as the renderer measures it on the first keyframe
  for (const auto& frame : snapshot.deep_from->cascades) {
    double sum = 0;
    for (std::size_t k = 0; k < frame.slope_x.size(); ++k)
      sum += double(frame.slope_x[k]) * frame.slope_x[k] + double(frame.slope_y[k]) * frame.slope_y[k];
    variance.push_back(0.5 * sum / double(frame.slope_x.size()));
  }
  const auto water_point = [&](int x, int y) {  // the ray through pixel (x, y) meets the plane
    const Vector3 ray = pixel_ray(view, x, y);
    const double t = (plane_z - camera.eye_m[2]) / ray[2];
    return std::array<double, 2>{camera.eye_m[0] + t * ray[0], camera.eye_m[1] + t * ray[1]};
  };
  Lighting lighting;  // the sun behind the camera: no glitter, whose peak no 8-bit comparison survives
  lighting.sun_azimuth_deg = 170.0;
  lighting.sun_elevation_deg = 35.0;
  Image images[2] = {Image(width, height), Image(width, height)};
  int compared = 0, offset_over_half_metre = 0;
  for (double parallax : {1.0, 0.0}) {
    lighting.detail_parallax = parallax;
    playback::WaterRenderer renderer;
    renderer.render(snapshot, camera, lighting, width, height);
    const Image image = renderer.read_pixels();
    images[parallax > 0 ? 0 : 1] = image;
    const playback::LightingFrame frame = playback::prepare_lighting(lighting);
    for (int y = height - 1 - 2; y > 0; y -= 4)  // GL rows 2, 6, ...: the lower-left pixel of a quad
      for (int x = 2; x + 1 < width; x += 4) {
        if (pixel_ray(view, x, y - 1)[2] > -0.05) continue;  // the sea only, away from the horizon
        const auto p = water_point(x, y), px = water_point(x + 1, y), py = water_point(x, y - 1);
        const double footprint = std::max(std::hypot(px[0] - p[0], px[1] - p[1]), std::hypot(py[0] - p[0], py[1] - p[1]));
        const Vector3 to_eye = normalized({camera.eye_m[0] - p[0], camera.eye_m[1] - p[1], camera.eye_m[2] - plane_z});
        double relief = 0;
        for (std::size_t c = 0; c < tiles.size(); ++c) {
          const double texel = tiles[c] / n;
          relief += playback::detail_normal_weight(texel, footprint) * playback::unresolved_relief_weight(texel, footprint) * heights[c];
        }
        const auto offset = playback::parallax_offset_m(to_eye, parallax * relief);
        if (std::hypot(offset[0], offset[1]) > 0.5) ++offset_over_half_metre;
        double slope_x = 0, slope_y = 0, extra_variance = 0;
        for (std::size_t c = 0; c < tiles.size(); ++c) {
          const auto& cascade = snapshot.deep_from->cascades[c];
          const double detail = playback::detail_normal_weight(tiles[c] / n, footprint);
          extra_variance += (1 - detail) * variance[c];
          slope_x += detail * periodic_bilinear(cascade.slope_x, n, tiles[c], p[0] + offset[0], p[1] + offset[1]);
          slope_y += detail * periodic_bilinear(cascade.slope_y, n, tiles[c], p[0] + offset[0], p[1] + offset[1]);
        }
        playback::SurfacePoint point;
        point.normal = normalized({-slope_x, -slope_y, 1.0});
        point.to_eye = to_eye;
        point.water_depth_m = 20.0 + plane_z;  // the renderer's open sea without a harbour
        const auto bottom = playback::refracted_seabed_point(p[0], p[1], point.normal, to_eye, point.water_depth_m);
        point.seabed_albedo_scale = playback::seabed_texture(bottom[0], bottom[1]);
        point.extra_slope_variance_per_axis = extra_variance;
        point.crest_thinness = std::clamp(plane_z / std::max(lighting.foam_onset_m, 0.1), 0.0, 1.0);
        const auto expected = playback::to_display(frame, playback::shade_water(frame, point));
        const auto pixel = image.get(x, y);
        ++compared;
        // as ShaderMatchesTheCpuTwinOverATestPattern: 8-bit output, float32 against double, and
        // the 8-bit weights of the hardware filter (here of the slope tiles)
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(pixel[std::size_t(c)], expected[std::size_t(c)], 3.0 / 255)
              << "pixel (" << x << ", " << y << ") channel " << c << ", parallax " << parallax << ", footprint " << footprint;
      }
  }
  EXPECT_GT(compared, 400);
  EXPECT_GT(offset_over_half_metre, 50) << "the pattern exercises the parallax";
  int changed = 0;  // and the parallax shows in the picture
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (std::abs(luminance(images[0].get(x, y)) - luminance(images[1].get(x, y))) > 4.0 / 255) ++changed;
  EXPECT_GT(changed, width * height / 20);
}

TEST(LightingRender, ShelteredShortWavesMatchTheCpuTwin) {
  // A still harbour (both keyframes zero) under deep water whose one cascade (64 m tiles of 64
  // samples, finer than 32 harbour cells of 4 m: drawn over the harbour) carries a slope pattern,
  // and a relative wave height K of 0 west of x = 98 m rising linearly to 1 at x = 162 m (a basin
  // sheltered towards the west). Where the harbour weight is 1 each sampled pixel is the
  // twin's shade_water with the cascade's slope scaled by cascade_share (K) and its faded
  // variance by cascade_variance_share (K^2); and the sheltering shows: the west half is calmer.
  playback::GlWindow window(64, 64, "test", false);
  test::SiteOptions options;
  options.land = false;
  auto site = test::make_site(options);  // 256 m x 192 m, 12 m deep in the south to 3 m in the north
  const GridGeometry& g = site->harbour.geometry;
  site->relative_wave_height = Raster<float>(g.columns, g.rows);
  for (int j = 0; j < g.rows; ++j)
    for (int i = 0; i < g.columns; ++i) site->relative_wave_height(i, j) = float(std::clamp((4.0 * i + 2.0 - 98.0) / 64.0, 0.0, 1.0));
  auto still = std::make_shared<runtime::HarbourKeyframe>();
  still->serial = 1;
  still->surface_elevation_m = still->breaking = still->surface_elevation_rate_m_s = Raster<float>(g.columns, g.rows, 0.f);
  const int n = 64;
  const double tile = 64.0;
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = site;
  snapshot.harbour_from = snapshot.harbour_to = still;
  snapshot.deep_from = snapshot.deep_to = relief_pattern_keyframe({tile}, {0.0}, n);
  const auto& cascade = snapshot.deep_from->cascades[0];
  double sum = 0;
  for (std::size_t k = 0; k < cascade.slope_x.size(); ++k)
    sum += double(cascade.slope_x[k]) * cascade.slope_x[k] + double(cascade.slope_y[k]) * cascade.slope_y[k];
  const double variance = 0.5 * sum / double(cascade.slope_x.size());
  playback::Camera camera;
  camera.eye_m = {128.0, 40.0, 14.0};
  camera.target_m = {128.0, 140.0, 0.0};
  camera.vertical_field_of_view_deg = 60.0;
  const int width = 160, height = 100;
  const playback::CameraView view = playback::camera_view(camera, width, height, 1.0, 1000.0);
  Lighting lighting;  // the sun behind the camera: no glitter
  lighting.sun_azimuth_deg = 170.0;
  lighting.sun_elevation_deg = 35.0;
  lighting.detail_parallax = 0.0;
  lighting.shore_wave_amplitude_m = 0.0;
  // The twin below takes the seabed flat at the point's depth (refracted_seabed_point); the
  // refraction of the drawn seabed meets this one's 1:21 slope where the waves' normals bend the
  // view by metres (up to 0.013 apart in the green): this test is about the sheltering, so the sea
  // shows its procedural seabed (RefractionRender.* test the refraction).
  playback::RendererSettings settings;
  settings.refraction = false;
  playback::WaterRenderer renderer(settings);
  renderer.render(snapshot, camera, lighting, width, height);
  const Image image = renderer.read_pixels();
  const playback::LightingFrame frame = playback::prepare_lighting(lighting);
  const auto water_point = [&](int x, int y) {
    const Vector3 ray = pixel_ray(view, x, y);
    const double t = -camera.eye_m[2] / ray[2];
    return std::array<double, 2>{camera.eye_m[0] + t * ray[0], camera.eye_m[1] + t * ray[1]};
  };
  int compared = 0;
  // How much neighbouring pixels (2 apart in a row) differ where K < 0.3 and where K > 0.7: the
  // short waves' texture, free of the picture's slow gradients (depth, view angle).
  std::vector<double> west, east;
  for (int y = height - 1 - 2; y > 0; y -= 2)  // the lower-left pixel of each 2 x 2 quad
    for (int x = 2; x + 1 < width; x += 2) {
      if (pixel_ray(view, x, y - 1)[2] > -0.05) continue;
      const auto p = water_point(x, y), px = water_point(x + 1, y), py = water_point(x, y - 1);
      if (runtime::harbour_weight(*site, p[0], p[1]) < 1.0 || p[0] < 8.0 || p[0] > 248.0) continue;
      const double footprint = std::max(std::hypot(px[0] - p[0], px[1] - p[1]), std::hypot(py[0] - p[0], py[1] - p[1]));
      const double k = std::clamp((p[0] - 98.0) / 64.0, 0.0, 1.0);  // its kinks at cell centres: bilinear is exact
      const double detail = playback::detail_normal_weight(tile / n, footprint);
      const double share = playback::cascade_share(true, 1.0, k);
      playback::SurfacePoint point;
      point.normal = normalized({-share * detail * periodic_bilinear(cascade.slope_x, n, tile, p[0], p[1]),
                                 -share * detail * periodic_bilinear(cascade.slope_y, n, tile, p[0], p[1]), 1.0});
      point.to_eye = normalized({camera.eye_m[0] - p[0], camera.eye_m[1] - p[1], camera.eye_m[2]});
      const double row = std::clamp(p[1] / options.spacing_m - 0.5, 0.0, double(options.rows - 1));
      point.water_depth_m = 12.0 - 9.0 * row / (options.rows - 1);
      const auto bottom = playback::refracted_seabed_point(p[0], p[1], point.normal, point.to_eye, point.water_depth_m);
      point.seabed_albedo_scale = playback::seabed_texture(bottom[0], bottom[1]);
      point.extra_slope_variance_per_axis = playback::cascade_variance_share(true, 1.0, k) * (1.0 - detail) * variance;
      const auto expected = playback::to_display(frame, playback::shade_water(frame, point));
      const auto pixel = image.get(x, y);
      ++compared;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(pixel[std::size_t(c)], expected[std::size_t(c)], 3.0 / 255)
            << "pixel (" << x << ", " << y << ") channel " << c << ", K " << k << ", footprint " << footprint;
      const double texture = std::abs(luminance(pixel) - luminance(image.get(x + 2 < width ? x + 2 : x - 2, y)));
      if (detail > 0.9 && k < 0.3) west.push_back(texture);  // where the pixel keeps the normal map
      if (detail > 0.9 && k > 0.7) east.push_back(texture);
    }
  EXPECT_GT(compared, 400);
  const auto spread = [](const std::vector<double>& values) {
    double mean = 0;
    for (double v : values) mean += v;
    return mean / double(values.size());
  };
  ASSERT_GT(west.size(), 50u);
  ASSERT_GT(east.size(), 50u);
  // The sheltered side's short waves have at most 0.3 of the open side's slopes (at least 0.7
  // there): its neighbouring pixels differ at most half as much.
  EXPECT_LT(spread(west), 0.5 * spread(east)) << "west " << spread(west) << ", east " << spread(east);
}

TEST(LightingRender, DeepWaterFoamFadesByOneOverEInItsDecayTime) {
  // Seed 000 eq. (3.46): foam from a Beaufort 8 sea's steepest crests (J < J_b) at t = 0, then the same
  // tiles with the folds gone (displacements zero: J = 1, no new foam): after one decay time each
  // texel holds 1/e of its foam, after three e^-3, exactly ocean::turbulent_foam's steps (the
  // twin); a second render at the same display time changes nothing.
  playback::GlWindow window(64, 64, "test", false);
  const test::DeepPair deep = test::make_deep_pair(8, {64.0, 16.0}, 64, 0.0, 0.5, 20);
  runtime::SurfaceSnapshot breaking;
  breaking.deep_from = breaking.deep_to = deep.from;
  auto calm_keyframe = std::make_shared<runtime::DeepWaterKeyframe>(*deep.from);
  calm_keyframe->serial = 40;
  for (auto& cascade : calm_keyframe->cascades)
    for (auto* field : {&cascade.displacement_x_m, &cascade.displacement_y_m}) std::fill(field->begin(), field->end(), 0.f);
  Lighting lighting;
  lighting.foam_decay_time_s = 2.5;
  // J_b raised from the Stokes limit (0.557, where this small tile's lowest J of 0.66 makes no
  // foam) so that many texels foam: the source only has to exist; the decay law is under test.
  lighting.jacobian_foam_onset = 0.9;
  playback::Camera camera;
  camera.eye_m = {0.0, -50.0, 30.0};
  camera.target_m = {0.0, 100.0, 0.0};
  playback::WaterRenderer renderer;
  renderer.render(breaking, camera, lighting, 64, 48);
  const Raster<float> first = renderer.deep_foam_map();
  ASSERT_EQ(first.columns(), 64);
  double total = 0, peak = 0;
  for (float v : first.values()) total += v, peak = std::max(peak, double(v));
  ASSERT_GT(peak, 0.2) << "the sea foams somewhere";
  runtime::SurfaceSnapshot calm;
  calm.deep_from = calm.deep_to = calm_keyframe;
  Raster<float> expected = first;
  double previous_time = 0.0;
  for (double time : {2.5, 2.5, 7.5}) {
    calm.display_time_s = time;
    renderer.render(calm, camera, lighting, 64, 48);
    const Raster<float> now = renderer.deep_foam_map();
    double sum = 0;
    for (std::size_t k = 0; k < now.values().size(); ++k) {
      expected.values()[k] = float(ocean::turbulent_foam(expected.values()[k], 0.0, time - previous_time, 2.5));
      ASSERT_NEAR(now.values()[k], expected.values()[k], 1e-5) << "texel " << k << " at " << time << " s";
      sum += now.values()[k];
    }
    // 1/e per decay time (float32's exp and products: 1e-5)
    EXPECT_NEAR(sum / total, std::exp(-time / 2.5), 1e-4) << "at " << time << " s";
    previous_time = time;
  }
}

}  // namespace
}  // namespace nearshore

namespace nearshore {
namespace {

TEST(LightingRender, HullsStandMirroredInTheWater) {
  // A white box hull (40 m x 10 m, 6 m high, 3 m of it under water) in a harbour without land,
  // seen from 2 m over the water 60 m away: with the local reflection on, the water below its
  // waterline shows the hull's image (the only thing standing there to mirror), so those pixels
  // change; nothing above the waterline changes (the hull and the sky are drawn as before).
  playback::GlWindow window(64, 64, "test", false);
  test::SiteOptions options;
  options.land = false;
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = test::make_site(options);
  const std::vector<float> vertices = {-20, -5, 0, 20, -5, 0, 20, 5, 0, -20, 5, 0,   // keel
                                       -20, -5, 6, 20, -5, 6, 20, 5, 6, -20, 5, 6};  // deck
  const std::vector<std::uint32_t> triangles = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                                                1, 5, 6, 1, 6, 2, 2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0};
  playback::SurfaceLayers layers;
  playback::SolidMesh hull;
  hull.id = 7;
  hull.vertices_m = vertices.data();
  hull.vertex_count = vertices.size() / 3;
  hull.triangles = triangles.data();
  hull.triangle_count = triangles.size() / 3;
  hull.position_m = {128.0, 120.0, -3.0};
  hull.albedo_above = hull.albedo_below = {0.9f, 0.9f, 0.9f};
  layers.meshes.push_back(hull);
  playback::Camera camera;
  camera.eye_m = {128.0, 60.0, 2.0};
  camera.target_m = {128.0, 120.0, 0.0};
  camera.vertical_field_of_view_deg = 30.0;
  const int width = 160, height = 120;
  Image with(width, height), without(width, height);
  for (bool reflections : {true, false}) {
    playback::RendererSettings settings;
    settings.local_reflections = reflections;
    settings.refraction = false;  // the reflection alone: refraction changes the same shore pixels
    playback::WaterRenderer renderer(settings);
    renderer.render(snapshot, camera, Lighting{}, width, height, {}, &layers);
    (reflections ? with : without) = renderer.read_pixels();
  }
  write_png(with, std::filesystem::path(NEARSHORE_BINARY_DIR) / "playback_hull_reflection_test.png");
  // The waterline's row at the hull's near side (y = 115 m): where z = 0 projects.
  const playback::CameraView view = playback::camera_view(camera, width, height, 1.0, 1000.0);
  const auto clip = playback::transform(view.view_projection, {128.0, 115.0, 0.0, 1.0});
  const int waterline_row = int((1.0 - (clip[1] / clip[3] * 0.5 + 0.5)) * height);
  int changed_below = 0, changed_above = 0;
  for (int x = 0; x < width; ++x)
    for (int y = 0; y < height; ++y) {
      const bool changed = std::abs(luminance(with.get(x, y)) - luminance(without.get(x, y))) > 2.0 / 255;
      if (y < waterline_row - 1 && changed) ++changed_above;
      if (y > waterline_row + 1 && changed) ++changed_below;
    }
  EXPECT_GT(changed_below, 100) << "the hull's image in the water below row " << waterline_row;
  EXPECT_EQ(changed_above, 0) << "the reflection changed pixels above the waterline";
}

}  // namespace
}  // namespace nearshore
