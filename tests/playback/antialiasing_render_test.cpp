// Multisample anti-aliasing (RendererSettings::msaa_samples) and the GPU time per pass
// (FrameStatistics::gpu), on Mesa llvmpipe: edge pixels take the coverage of their samples, the
// picture away from edges is the single-sample one, and the timer queries never fail a frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/plot/plot.hpp"
#include "snapshot_fixtures.hpp"

namespace {
using namespace nearshore;
using namespace nearshore::playback;

// A flat magenta disc on black: the radial grid (rings round the camera, out to outer_radius_m)
// seen straight down, no site, no keyframes, no sky. Its only edge is the grid's rim.
struct Disc {
  static constexpr int kSize = 128;
  static constexpr double kEyeHeightM = 1000.0, kRadiusM = 100.0;
  static constexpr double kHalfViewM = 160.0;  // the view's half height at the sea
  static double radius_px() { return kRadiusM / kHalfViewM * kSize / 2; }

  static Image render(int msaa_samples, FrameStatistics* statistics = nullptr) {
    RendererSettings settings;
    settings.grid = GridKind::radial;
    settings.radial.outer_radius_m = kRadiusM;
    settings.radial.inner_spacing_m = 2.0;
    settings.msaa_samples = msaa_samples;
    WaterRenderer renderer(settings);
    Camera camera;
    camera.eye_m = {0.0, -0.01, kEyeHeightM};  // straight down, nearly (the look needs a horizontal part)
    camera.target_m = {0.0, 0.0, 0.0};
    camera.vertical_field_of_view_deg = 2.0 * std::atan(kHalfViewM / kEyeHeightM) * 180.0 / std::numbers::pi;
    camera.far_m = 2.0 * kEyeHeightM;  // the default far plane is the grid's reach, 105 m
    DrawOptions options;
    options.colouring = SurfaceColouring::flat;
    options.flat_colour = {1.f, 0.f, 1.f};
    options.sky = false;
    options.background = {0.f, 0.f, 0.f};
    renderer.render(runtime::SurfaceSnapshot{}, camera, Lighting{}, kSize, kSize, options);
    if (statistics) *statistics = renderer.last_frame();
    return renderer.read_pixels();
  }
};

TEST(Antialiasing, DiscEdgePixelsTakeTheCoverageOfTheirSamples) {
  GlWindow window(64, 64, "test", false);
  FrameStatistics single_statistics, multi_statistics;
  const Image single = Disc::render(1, &single_statistics);
  const Image multi = Disc::render(4, &multi_statistics);
  EXPECT_EQ(single_statistics.msaa_samples, 1);
  // OpenGL 3.3 core requires GL_MAX_SAMPLES >= 4, so 4 is never clamped.
  EXPECT_EQ(multi_statistics.msaa_samples, 4) << window.gl_description();
  write_png(multi, std::filesystem::path(NEARSHORE_BINARY_DIR) / "playback_msaa_disc_test.png");
  // Red carries the coverage (magenta 1 on black 0); green must stay 0 in both (nothing else drawn).
  int single_between = 0, multi_between = 0;
  double single_area = 0, multi_area = 0;
  for (int y = 0; y < Disc::kSize; ++y)
    for (int x = 0; x < Disc::kSize; ++x) {
      const float a = single.get(x, y)[0], b = multi.get(x, y)[0];
      single_between += a > 0.5f / 255 && a < 254.5f / 255;
      multi_between += b > 0.5f / 255 && b < 254.5f / 255;
      single_area += a;
      multi_area += b;
      EXPECT_EQ(multi.get(x, y)[1], 0.f);
      EXPECT_NEAR(multi.get(x, y)[2], b, 0.5 / 255);  // blue = red: a blend of the two colours, nothing else
    }
  // One sample per pixel: every pixel is wholly one colour (8-bit exact).
  EXPECT_EQ(single_between, 0);
  // Four samples: the rim (a 256-gon of radius R = 40 px) passes through about 8R pixels (the
  // length of a circle's boundary in the L1 metric, 2 pi R x 4 / pi). A pixel it passes through
  // blends only if the rim also cuts the convex hull of the pixel's samples; by Cauchy-Crofton the
  // share of lines meeting a square that also meet a convex set inside it is the ratio of their
  // perimeters: 2.24 / 4 = 0.56 for the standard 4-sample pattern (a square of side 0.56 px
  // turned 27 degrees), so about 4.5R = 179 pixels blend (162 measured on llvmpipe). The bound asks
  // for 3R (2/3 of that: any 4-sample pattern of distinct offsets has a hull perimeter near it),
  // and at most every pixel the rim passes through (8R, plus 10 %).
  const double r = Disc::radius_px();
  EXPECT_GE(multi_between, int(3.0 * r)) << "R = " << r << " px";
  EXPECT_LE(multi_between, int(8.0 * r * 1.1));
  // The covered area is the disc's (pi R^2 = 5027 px): with four samples per pixel the estimate is
  // at least as close as with one. Bound: the rim pixels' quantisation, 8R x 1/2 px each at one
  // sample (errors of random sign: the sum is far under that), 8R x 1/8 at four (measured: 2.5 px
  // off at one sample, 1.1 px at four).
  const double area = std::numbers::pi * r * r;
  std::printf(
      "disc R = %.1f px: in between %d at 1 sample, %d at 4; area %.1f px at 1, %.1f at 4, pi R^2 = %.1f\n",
      r, single_between, multi_between, single_area, multi_area, area);
  EXPECT_NEAR(multi_area, area, 8.0 * r / 8.0);
  EXPECT_NEAR(single_area, area, 8.0 * r / 2.0);
  EXPECT_LE(std::abs(multi_area - area), std::abs(single_area - area) + 8.0 * r / 8.0);
}

double luminance_of(const std::array<float, 3>& p) {
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

TEST(Antialiasing, LitHarbourAgreesAwayFromEdgesAndBlendsAtThem) {
  // The test site's land block (north-east, 4-5 m high) and the horizon seen from 3 m over the
  // water, lit, with sky and the local reflection: every pass of a frame drawn.
  GlWindow window(64, 64, "test", false);
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = test::make_site();
  Camera camera;
  camera.eye_m = {200.0, 60.0, 3.0};
  camera.target_m = {235.0, 180.0, 1.0};  // the land's edges slant across the picture
  camera.vertical_field_of_view_deg = 20.0;
  const int width = 160, height = 120;
  Image images[2] = {Image(width, height), Image(width, height)};
  for (int k = 0; k < 2; ++k) {
    RendererSettings settings;
    settings.msaa_samples = k == 0 ? 1 : 4;
    settings.refraction = false;  // see below: the scene copy the refraction reads is resolved
    WaterRenderer renderer(settings);
    renderer.render(snapshot, camera, Lighting{}, width, height);
    images[k] = renderer.read_pixels();
  }
  write_png(images[1], std::filesystem::path(NEARSHORE_BINARY_DIR) / "playback_msaa_harbour_test.png");
  // Smooth: the single-sample picture's 3x3 neighbourhood spans at most 3/255 in every channel
  // (the lit sea's own gradient is 1-2/255 a pixel). There the fragment shader ran at the same
  // pixel centre in both pictures (a sample-shaded pixel wholly inside one triangle is shaded once),
  // so they differ only where a pixel straddles two of the water grid's triangles (each shades its
  // own samples, continuous across the edge): a few 1/255 at most.
  // Edge: the neighbourhood spans over 0.1 in luminance (land or sky against water). There, count
  // the pixels whose luminance lies strictly inside the neighbourhood's range (2/255 from either
  // end): at one sample a pixel on a hard edge is one side or the other; at four it blends them.
  int smooth = 0, smooth_off = 0, edges = 0;
  int between[2] = {0, 0};
  double largest_smooth_difference = 0;
  for (int y = 1; y + 1 < height; ++y)
    for (int x = 1; x + 1 < width; ++x) {
      float low[3] = {1, 1, 1}, high[3] = {0, 0, 0};
      double low_l = 1, high_l = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto p = images[0].get(x + dx, y + dy);
          for (int c = 0; c < 3; ++c) low[c] = std::min(low[c], p[c]), high[c] = std::max(high[c], p[c]);
          low_l = std::min(low_l, luminance_of(p)), high_l = std::max(high_l, luminance_of(p));
        }
      if (std::max({high[0] - low[0], high[1] - low[1], high[2] - low[2]}) <= 3.5f / 255) {
        ++smooth;
        double difference = 0;
        for (int c = 0; c < 3; ++c)
          difference =
              std::max(difference, double(std::abs(images[1].get(x, y)[c] - images[0].get(x, y)[c])));
        largest_smooth_difference = std::max(largest_smooth_difference, difference);
        smooth_off += difference > 3.5 / 255;
      } else if (high_l - low_l > 0.1) {
        ++edges;
        for (int k = 0; k < 2; ++k) {
          const double l = luminance_of(images[k].get(x, y));
          between[k] += l > low_l + 2.0 / 255 && l < high_l - 2.0 / 255;
        }
      }
    }
  EXPECT_GT(smooth, width * height / 2) << "the scene is mostly smooth sky and sea";
  EXPECT_EQ(smooth_off, 0) << "largest difference away from edges " << largest_smooth_difference * 255
                           << "/255";
  ASSERT_GT(edges, 100) << "the land and the horizon give edges";
  // A hard edge seen at one sample: its neighbourhood pixels are all one side or the other, so the
  // in-between ones (shading varying along the edge, the reflection's bilinear texture) are a few;
  // at four samples most pixels the edge passes through are blends. Bound: at least twice as many,
  // and at least a sixth of the edge neighbourhoods: each pixel an edge crosses is the centre of
  // one of them and lies in those of its neighbours across the edge (3 to 4 per crossed pixel,
  // more where the edge runs diagonally), and 3/4 of crossed pixels blend at four samples (the
  // disc test above): 3/16 to 1/4 of the neighbourhoods.
  EXPECT_GE(between[1], 2 * between[0] + 10) << "edges " << edges;
  EXPECT_GE(between[1], edges / 6) << "edges " << edges << ", in between at 1 sample " << between[0];
  std::printf(
      "lit harbour: %d smooth (largest difference %.2f/255), %d edge neighbourhoods, in between %d at 1 "
      "sample, %d at 4\n",
      smooth, largest_smooth_difference * 255, edges, between[0], between[1]);
}

TEST(GpuTiming, PassTimesArriveFramesLaterWithoutFailingAFrame) {
  GlWindow window(64, 64, "test", false);
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = test::make_site();
  const Camera camera = Camera::overlooking_site(snapshot.site->width_m, snapshot.site->height_m);
  for (int samples : {1, 4}) {
    RendererSettings settings;
    settings.msaa_samples = samples;
    WaterRenderer renderer(settings);
    renderer.render(snapshot, camera, Lighting{}, 96, 64);
    EXPECT_FALSE(renderer.last_frame().gpu.measured) << "no earlier frame: nothing to report";
    GpuPassTimes times;
    for (int frame = 0; frame < 6 && !times.measured; ++frame) {
      (void)renderer.read_pixels();  // the GPU has finished the frame: its queries are ready
      renderer.render(snapshot, camera, Lighting{}, 96, 64);
      times = renderer.last_frame().gpu;
    }
    // Mesa's llvmpipe has a timer (OpenGL 4.5 core); elsewhere a driver without one reports nothing.
    if (window.gl_description().find("llvmpipe") != std::string::npos) {
      ASSERT_TRUE(times.measured) << window.gl_description();
    }
    if (!times.measured) continue;
    EXPECT_GE(times.frames_behind, 1);
    std::printf("%d samples: GPU ms of a frame %d behind:", samples, times.frames_behind);
    for (int pass = 0; pass < kGpuPassCount; ++pass)
      std::printf(" %s %.3f", gpu_pass_name(GpuPass(pass)), times.ms[std::size_t(pass)]);
    std::printf("\n");
    double sum = 0;
    for (int pass = 0; pass < kGpuPassCount; ++pass) {
      EXPECT_GE(times.ms[std::size_t(pass)], 0.0) << gpu_pass_name(GpuPass(pass));
      sum += times.ms[std::size_t(pass)];
    }
    EXPECT_NEAR(times.total_ms, sum, 1e-9);
    EXPECT_GT(times.total_ms, 0.0);
    // Passes the frame did not draw take no time: no layers (decals, hulls), no resolve at 1 sample.
    EXPECT_EQ(times.ms_of(GpuPass::decal_foam), 0.0);
    EXPECT_EQ(times.ms_of(GpuPass::meshes), 0.0);
    if (samples == 1) {
      EXPECT_EQ(times.ms_of(GpuPass::resolve), 0.0);
    }
  }
  // Timing off: no queries, nothing measured.
  RendererSettings settings;
  settings.gpu_timing = false;
  WaterRenderer renderer(settings);
  for (int frame = 0; frame < 3; ++frame) {
    renderer.render(snapshot, camera, Lighting{}, 96, 64);
    (void)renderer.read_pixels();
  }
  EXPECT_FALSE(renderer.last_frame().gpu.measured);
  EXPECT_EQ(renderer.last_frame().gpu.total_ms, 0.0);
  EXPECT_STREQ(gpu_pass_name(GpuPass::water), "water");
  EXPECT_STREQ(gpu_pass_name(GpuPass::resolve), "resolve");
}

}  // namespace
