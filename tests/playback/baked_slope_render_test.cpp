// The baked field's slopes at distance on Mesa (issue 41): the shader's filtered slopes against
// the CPU twin (playback/slope_moments.hpp), and a far swell drawn at one sample a pixel against a
// supersampled reference of the same view.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <numbers>
#include <vector>

#include "nearshore/playback/lighting.hpp"
#include "nearshore/playback/slope_moments.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/plot/plot.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"
#include "snapshot_fixtures.hpp"

namespace nearshore {
namespace {
using playback::Vector3;

Vector3 normalized(const Vector3& v) {
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / length, v[1] / length, v[2] / length};
}
Vector3 pixel_ray(const playback::CameraView& view, int x, int y) {  // row 0 at the top
  const double ndc_x = (x + 0.5) / view.width_px * 2.0 - 1.0, ndc_y = 1.0 - (y + 0.5) / view.height_px * 2.0;
  const auto far = playback::transform(playback::inverse(view.view_projection), {ndc_x, ndc_y, 1.0, 1.0});
  return normalized({far[0] / far[3] - view.eye_m[0], far[1] / far[3] - view.eye_m[1], far[2] / far[3] - view.eye_m[2]});
}
double luminance(const std::array<float, 3>& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

// A harbour of 128 x 96 cells of 4 m, 40 m deep (the seabed out of sight: the water's colour does
// not depend on the drawn surface's height), no land, no deep water beyond, holding a swell of
// two trains, eta = A cos(k x) + B cos(k y), four cells a wavelength (16 m), A = 0.4 m, B =
// 0.25 m: slopes up to 0.16 and 0.1, a fraction of a cell to a few cells a pixel at 100-400 m.
constexpr double kCell = 4.0, kA = 0.4, kB = 0.25;
runtime::SurfaceSnapshot swell_snapshot() {
  test::SiteOptions options;
  options.columns = 128;
  options.rows = 96;
  options.spacing_m = kCell;
  options.land = false;
  auto site = test::make_site(options);
  for (int j = 0; j < options.rows; ++j)
    for (int i = 0; i < options.columns; ++i) site->harbour.still_water_depth_m(i, j) = 40.f;
  auto keyframe = std::make_shared<runtime::HarbourKeyframe>();
  keyframe->serial = 1;
  keyframe->surface_elevation_m = keyframe->breaking = keyframe->surface_elevation_rate_m_s = Raster<float>(options.columns, options.rows, 0.f);
  for (int j = 0; j < options.rows; ++j)
    for (int i = 0; i < options.columns; ++i)
      keyframe->surface_elevation_m(i, j) = float(kA * std::cos(std::numbers::pi / 2.0 * i) + kB * std::cos(std::numbers::pi / 2.0 * j));
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = site;
  snapshot.harbour_from = snapshot.harbour_to = keyframe;
  return snapshot;
}

// From a bridge 30 m up south of the harbour, looking north across it; the sun behind the camera
// (no glitter: its peak survives no 8-bit comparison), no shoreline waves.
playback::Camera bridge_camera() {
  playback::Camera camera;
  camera.eye_m = {256.0, -60.0, 30.0};
  camera.target_m = {256.0, 300.0, 0.0};
  camera.vertical_field_of_view_deg = 40.0;
  return camera;
}
playback::Lighting quiet_lighting(bool filter) {
  playback::Lighting lighting;
  lighting.sun_azimuth_deg = 170.0;
  lighting.sun_elevation_deg = 35.0;
  lighting.shore_wave_amplitude_m = 0.0;
  lighting.filter_baked_slopes = filter;
  return lighting;
}
Image render(const runtime::SurfaceSnapshot& snapshot, bool filter, int width, int height) {
  playback::RendererSettings settings;
  settings.refraction = false;  // the twin's procedural seabed (40 m down: out of sight anyway)
  settings.msaa_samples = 1;
  playback::WaterRenderer renderer(settings);
  renderer.render(snapshot, bridge_camera(), quiet_lighting(filter), width, height);
  return renderer.read_pixels();
}

TEST(BakedSlopeRender, FilteredSlopesMatchTheCpuTwin) {
  // Where a pixel covers four cells or more (lod >= 2) each level's texel holds whole
  // wavelengths of both trains: the mean slope is 0 and the variance per axis (A^2 + B^2) / 4 /
  // dx^2, whatever the point (the drawn surface's height moves the point the pixel sees by up to
  // 0.4 m / tan(grazing)). Each such pixel is the twin's shade_water with the twin's pyramid
  // sampled at baked_slope_lod of its footprint (from its 2 x 2 quad's neighbours, as dFdx /
  // dFdy) and filtered_baked_slope's variance added to the BRDF's.
  playback::GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = swell_snapshot();
  const int width = 160, height = 100;
  const Image image = render(snapshot, true, width, height);
  const playback::Camera camera = bridge_camera();
  const playback::CameraView view = playback::camera_view(camera, width, height, 1.0, 1000.0);
  const playback::LightingFrame frame = playback::prepare_lighting(quiet_lighting(true));
  const auto pyramid = playback::slope_moment_pyramid(snapshot.harbour_from->surface_elevation_m);
  const auto water_point = [&](int x, int y) {
    const Vector3 ray = pixel_ray(view, x, y);
    const double t = -camera.eye_m[2] / ray[2];
    return std::array<double, 2>{camera.eye_m[0] + t * ray[0], camera.eye_m[1] + t * ray[1]};
  };
  int compared = 0;
  double variance_seen = 0;
  for (int y = height - 1 - 2; y > 0; y -= 2)  // GL rows 2, 4, ...: the lower-left pixel of a quad
    for (int x = 2; x + 1 < width; x += 2) {
      if (pixel_ray(view, x, y - 1)[2] > -0.03) continue;
      const auto p = water_point(x, y), px = water_point(x + 1, y), py = water_point(x, y - 1);
      if (runtime::harbour_weight(*snapshot.site, p[0], p[1]) < 1.0) continue;
      const double footprint = std::max(std::hypot(px[0] - p[0], px[1] - p[1]), std::hypot(py[0] - p[0], py[1] - p[1]));
      const double lod = playback::baked_slope_lod(footprint, kCell);
      if (lod < 2.05) continue;
      const auto m = playback::sample_slope_moments(pyramid, p[0] / (128 * kCell), p[1] / (96 * kCell), lod);
      const auto filtered = playback::filtered_baked_slope(m, m, 0.0, kCell, kCell);
      // (within 10 %: the texels of the coarser levels near the grid's edges hold its edge cells,
      // whose slopes the clamped differences halve)
      EXPECT_NEAR(filtered.variance_per_axis, (kA * kA + kB * kB) / 4.0 / (kCell * kCell), 0.1 * (kA * kA + kB * kB) / 4.0 / (kCell * kCell));
      playback::SurfacePoint point;
      point.normal = normalized({-filtered.slope_x, -filtered.slope_y, 1.0});
      point.to_eye = normalized({camera.eye_m[0] - p[0], camera.eye_m[1] - p[1], camera.eye_m[2]});
      point.water_depth_m = 40.0;
      const auto bottom = playback::refracted_seabed_point(p[0], p[1], point.normal, point.to_eye, point.water_depth_m);
      point.seabed_albedo_scale = playback::seabed_texture(bottom[0], bottom[1]);
      point.extra_slope_variance_per_axis = filtered.variance_per_axis;
      const auto expected = playback::to_display(frame, playback::shade_water(frame, point));
      const auto pixel = image.get(x, y);
      ++compared;
      variance_seen = filtered.variance_per_axis;
      // 8-bit output, float32 against double, the hardware filter's 8-bit weights: 3/255 (as
      // LightingRender.ShaderMatchesTheCpuTwinOverATestPattern)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(pixel[std::size_t(c)], expected[std::size_t(c)], 3.0 / 255)
            << "pixel (" << x << ", " << y << ") channel " << c << ", footprint " << footprint << ", lod " << lod;
    }
  EXPECT_GT(compared, 150);
  // and the variance is a real share of the BRDF's: more than a tenth of the wind's sub-grid one
  EXPECT_GT(variance_seen, 0.1 * frame.slope_variance_per_axis);
}

TEST(BakedSlopeRender, AFarSwellShowsTheSupersampledMeanNotAliases) {
  // The same view at 160 x 100, one sample a pixel, against a reference drawn at 8 x 8 samples a
  // pixel (1280 x 800, box-averaged in linear light; a reference pixel covers a cell or less
  // there: the swell resolved), over the harbour where a 1x pixel covers a wavelength (4 cells) or
  // more: the swell cannot be drawn there, only its mean. Point-sampled slopes
  // (filter_baked_slopes off: the renderer before issue 41) pick a random phase of the swell in
  // each pixel: noise of the swell's contrast. Filtered, each pixel is the footprint's mean slope
  // with its variance in the BRDF: smooth, and as bright on average as the point samples are
  // (LEADR keeps the expectation). Both 1x pictures are brighter than the reference by the same
  // amount (measured 0.014): their grid does not draw the crests that hide the troughs at 2-5
  // degrees of grazing (the reference's does, and the faces turned to the eye reflect higher,
  // darker sky with less Fresnel), which no filtering of the normals gives back.
  playback::GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = swell_snapshot();
  const int width = 160, height = 100, factor = 8;
  const Image filtered = render(snapshot, true, width, height), point = render(snapshot, false, width, height);
  const Image fine = render(snapshot, true, width * factor, height * factor);
  const playback::Camera camera = bridge_camera();
  const playback::CameraView view = playback::camera_view(camera, width, height, 1.0, 1000.0);
  const playback::LightingFrame frame = playback::prepare_lighting(quiet_lighting(true));
  // A reference pixel: the mean radiance of its 64 samples, displayed (the box filter in linear
  // light; averaging the displayed values would darken it by the display curve's concavity).
  const auto reference_pixel = [&](int x, int y) {
    playback::Radiance sum{};
    for (int j = 0; j < factor; ++j)
      for (int i = 0; i < factor; ++i) {
        const auto c = fine.get(x * factor + i, y * factor + j);
        const auto radiance = playback::from_display(frame, {c[0], c[1], c[2]});
        for (std::size_t k = 0; k < 3; ++k) sum[k] += radiance[k] / (factor * factor);
      }
    const auto shown = playback::to_display(frame, sum);
    return Rgb{float(shown[0]), float(shown[1]), float(shown[2])};
  };
  std::vector<double> filtered_error, point_error;  // 1x minus reference, per pixel
  double filtered_mean = 0, point_mean = 0, reference_mean = 0;
  int count = 0;
  for (int y = 1; y + 1 < height; ++y)
    for (int x = 1; x + 1 < width; ++x) {
      const Vector3 ray = pixel_ray(view, x, y), next = pixel_ray(view, x, y + 1);
      if (ray[2] > -0.03) continue;
      const double t = -camera.eye_m[2] / ray[2], t_next = -camera.eye_m[2] / next[2];
      const double px = camera.eye_m[0] + t * ray[0], py = camera.eye_m[1] + t * ray[1];
      if (runtime::harbour_weight(*snapshot.site, px, py) < 1.0) continue;
      const double footprint = std::hypot(t * ray[0] - t_next * next[0], t * ray[1] - t_next * next[1]);
      if (footprint < 4.0 * kCell) continue;
      const double reference = luminance(reference_pixel(x, y));
      const double a = luminance(filtered.get(x, y)), b = luminance(point.get(x, y));
      filtered_error.push_back(a - reference);
      point_error.push_back(b - reference);
      filtered_mean += a;
      point_mean += b;
      reference_mean += reference;
      ++count;
    }
  // For docs/rendering.md: the three pictures.
  Image reference(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) reference.set(x, y, reference_pixel(x, y));
  const auto folder = std::filesystem::path(NEARSHORE_BINARY_DIR) / "playback-pictures";
  std::filesystem::create_directories(folder);
  write_png(point, folder / "baked_slope_point.png");
  write_png(filtered, folder / "baked_slope_filtered.png");
  write_png(reference, folder / "baked_slope_reference.png");
  ASSERT_GT(count, 800);
  // The aliasing: how much the error varies from pixel to pixel (its standard deviation; the mean
  // error is the masking above).
  const auto deviation = [](const std::vector<double>& e) {
    double mean = 0, square = 0;
    for (double v : e) mean += v / double(e.size());
    for (double v : e) square += (v - mean) * (v - mean) / double(e.size());
    return std::sqrt(square);
  };
  const double filtered_noise = deviation(filtered_error), point_noise = deviation(point_error);
  filtered_mean /= count;
  point_mean /= count;
  reference_mean /= count;
  std::printf("far swell, %d pixels: error against the 8x8 reference varies by %.4f filtered, %.4f point-sampled; "
              "mean %.4f filtered, %.4f point-sampled, %.4f reference\n",
              count, filtered_noise, point_noise, filtered_mean, point_mean, reference_mean);
  // Measured (llvmpipe, Mesa 22.3): 0.0048 filtered, 0.029 point-sampled. Bound 0.01: 2.5 levels
  // of 8 bits, twice the measured, where the 8-bit rounding of the three pictures alone gives 0.002.
  EXPECT_LT(filtered_noise, 0.01);
  EXPECT_GT(point_noise, 3.0 * filtered_noise);
  // the filtered mean brightness is the point samples' (LEADR's expectation; measured 0.0004 apart)
  EXPECT_NEAR(filtered_mean, point_mean, 0.004);
  // and within 0.025 (6 levels of 8 bits) of the reference: the masking the 1x grid cannot draw
  EXPECT_NEAR(filtered_mean, reference_mean, 0.025);
}

}  // namespace
}  // namespace nearshore
