// Offscreen renders on Mesa llvmpipe: the rendered sea matches the CPU reference of its lighting,
// and a baked wave field shows up in the picture.
#include "nearshore/playback/water_renderer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "nearshore/playback/window.hpp"
#include "nearshore/plot/plot.hpp"

namespace {
using namespace nearshore;

// The harbour alone (no deep water), one keyframe of `eta` on screen: what the streaming engine
// hands the renderer for a sequence shown at one of its frames.
runtime::SurfaceSnapshot snapshot_of(const HarbourGrid& harbour, const Raster<float>& eta) {
  auto site = std::make_shared<runtime::HarbourSite>();
  site->harbour = harbour;
  site->width_m = harbour.geometry.width_m();
  site->height_m = harbour.geometry.height_m();
  auto keyframe = std::make_shared<runtime::HarbourKeyframe>();
  static std::uint64_t serial = 0;
  keyframe->serial = ++serial;  // a new keyframe: the renderer uploads each serial once
  keyframe->surface_elevation_m = eta;
  keyframe->breaking = Raster<float>(eta.columns(), eta.rows(), 0.f);
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = site;
  snapshot.harbour_from = snapshot.harbour_to = keyframe;
  return snapshot;
}

HarbourGrid sloping_harbour() {
  GridGeometry geometry;
  geometry.columns = 120;
  geometry.rows = 100;
  geometry.spacing_m = 5.0;
  HarbourGrid harbour = HarbourGrid::open_water(geometry, 10.f);
  for (int j = 0; j < geometry.rows; ++j)
    for (int i = 0; i < geometry.columns; ++i) {
      // 12 m deep in the south, rising to land (3 m high) in the north.
      harbour.still_water_depth_m(i, j) = 12.f - 15.f * j / (geometry.rows - 1);
      harbour.land(i, j) = harbour.still_water_depth_m(i, j) < 0 ? 1 : 0;
    }
  return harbour;
}
}  // namespace

TEST(WaterRenderer, FlatSeaSeenFromAboveMatchesTheCpuReference) {
  playback::GlWindow window(64, 64, "test", false);
  const HarbourGrid harbour = sloping_harbour();
  playback::WaterRenderer renderer;
  const runtime::SurfaceSnapshot snapshot = snapshot_of(harbour, Raster<float>(120, 100, 0.f));
  // Straight down (nearly: the look-at needs a horizontal component) onto a cell 4.4 m deep.
  playback::Camera camera;
  const int row = 50;  // depth 12 - 15 * 50 / 99 = 4.42 m
  const double x = 300.0, y = harbour.geometry.cell_centre_y_m(row);
  camera.eye_m = {x, y - 0.01, 200.0};
  camera.target_m = {x, y, 0.0};
  camera.vertical_field_of_view_deg = 2.0;  // the centre pixel sees only that cell
  playback::Lighting lighting;
  renderer.render(snapshot, camera, lighting, 33, 33);
  const Image image = renderer.read_pixels();
  const auto pixel = image.get(16, 16);
  const double depth = harbour.still_water_depth_m(60, row);
  const auto to_eye = playback::Vector3{0, -0.01 / std::hypot(0.01, 200.0), 200.0 / std::hypot(0.01, 200.0)};
  const playback::LightingFrame frame = playback::prepare_lighting(lighting);
  playback::SurfacePoint point;
  point.to_eye = to_eye;
  point.water_depth_m = depth;
  const auto bottom = playback::refracted_seabed_point(x, y, point.normal, to_eye, depth);  // the seabed's texture there
  point.seabed_albedo_scale = playback::seabed_texture(bottom[0], bottom[1]);
  const auto expected = playback::to_display(frame, playback::shade_water(frame, point));
  // 8-bit output: 2/255 for rounding plus llvmpipe's float32 vs the reference's double.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(pixel[c], expected[c], 2.5 / 255) << "channel " << c << " on " << window.gl_description();
}

TEST(WaterRenderer, WavesLandAndSkyAllAppearInTheOverview) {
  playback::GlWindow window(64, 64, "test", false);
  const HarbourGrid harbour = sloping_harbour();
  playback::WaterRenderer renderer;
  Raster<float> eta(120, 100);
  for (int j = 0; j < 100; ++j)
    for (int i = 0; i < 120; ++i) eta(i, j) = 0.8f * std::sin(2 * M_PI * j * 5.0 / 40.0);  // 40 m waves
  const playback::Camera camera = playback::Camera::overlooking_site(harbour.geometry.width_m(), harbour.geometry.height_m());
  // Muddy water (20 NTU) hides the seabed and its texture, so a flat sea's own variation is its
  // smooth gradients alone.
  playback::Lighting muddy;
  muddy.water.turbidity_ntu = 20.0;
  renderer.render(snapshot_of(harbour, eta), camera, muddy, 320, 200);
  const Image image = renderer.read_pixels();
  write_png(image, std::filesystem::path(NEARSHORE_BINARY_DIR) / "playback_overview_test.png");
  // The top rows are sky (bright, blue above red); somewhere below there is land (green above blue).
  const auto sky = image.get(160, 2);
  EXPECT_GT(sky[2], sky[0]);
  EXPECT_GT(sky[2], 0.5f);
  int land_pixels = 0;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 320; ++x) {
      const auto p = image.get(x, y);
      if (p[1] > p[2] + 0.05f && p[1] > p[0]) ++land_pixels;
    }
  EXPECT_GT(land_pixels, 100);
  // The waves modulate the shading of the water in the foreground: along a row and a column
  // there, the pixel-to-pixel variation is well above that of the same view of a flat sea (whose
  // own variation is the 8-bit steps of its smooth gradient: the view angle changing the Fresnel
  // reflectance, docs/lighting.md).
  const auto variation = [](const Image& picture) {
    double sum = 0;
    for (int x = 1; x < 320; ++x) sum += std::abs(picture.get(x, 190)[2] - picture.get(x - 1, 190)[2]);
    for (int y = 121; y < 200; ++y) sum += std::abs(picture.get(160, y)[2] - picture.get(160, y - 1)[2]);
    return sum;
  };
  renderer.render(snapshot_of(harbour, Raster<float>(120, 100, 0.f)), camera, muddy, 320, 200);
  const double flat = variation(renderer.read_pixels());
  EXPECT_GT(variation(image), 2.0 * flat + 0.1) << "flat sea: " << flat;
}

TEST(WaterRenderer, GeoreferencedGridRendersLikeTheSameGridAtTheOrigin) {
  // A UTM origin (~10^6 m) is beyond float32's metre resolution; the renderer works in the site
  // frame, so the picture cannot depend on where on Earth the grid lies.
  playback::GlWindow window(64, 64, "test", false);
  HarbourGrid harbour = sloping_harbour();
  Raster<float> eta(120, 100);
  for (int j = 0; j < 100; ++j)
    for (int i = 0; i < 120; ++i) eta(i, j) = 0.5f * std::sin(2 * M_PI * (i * 0.3 + j) * 5.0 / 60.0);
  auto render = [&](double origin_x_m, double origin_y_m) {
    harbour.geometry.origin_x_m = origin_x_m;
    harbour.geometry.origin_y_m = origin_y_m;
    playback::WaterRenderer renderer;
    renderer.render(snapshot_of(harbour, eta),
                    playback::Camera::overlooking_site(harbour.geometry.width_m(), harbour.geometry.height_m()),
                    playback::Lighting{}, 160, 100);
    return renderer.read_pixels();
  };
  const Image at_origin = render(0, 0);
  const Image in_utm = render(386128.0, 4306447.0);
  double largest_difference = 0;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 160; ++x)
      for (int c = 0; c < 3; ++c)
        largest_difference = std::max(largest_difference, double(std::abs(at_origin.get(x, y)[c] - in_utm.get(x, y)[c])));
  EXPECT_LT(largest_difference, 3.0 / 255) << "rasterisation may differ by rounding only";
}
