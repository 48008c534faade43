// The split drawn by the renderer (issue 14 item 1; docs/runtime.md "The split"): the deep
// water's components above the bake's band are drawn inside the harbour rectangle on top of the
// frames (water_vertex.glsl inside_elevation), as the CPU queries draw them (SurfaceSampler
// formula 3), and beyond the rectangle nothing changes (no variance counted twice there).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/plot/plot.hpp"
#include "nearshore/runtime/deep_water_source.hpp"
#include "nearshore/runtime/surface_sampler.hpp"
#include "snapshot_fixtures.hpp"

namespace {
using namespace nearshore;
using namespace nearshore::playback;

// The fixtures' site (64 x 48 cells of 4 m, no land) with its two analytic harbour keyframes, and
// a Beaufort 5 sea (tiles 97 m and 23 m, 64^2) split at 0.25 Hz (25 m deep-water waves): the
// layer is the 97 m tile's components above 0.25 Hz (it straddles the split, so it is
// synthesised again band-limited, runtime::split_deep_water) and the whole 23 m tile (wholly
// above it). Keyframes at 3 s and 3.5 s, shown 60 % of the way.
struct SplitScene {
  runtime::SurfaceSnapshot with_layer, without_layer;
  runtime::DeepWaterInsideLayer layer;
  ocean::RecordedDeepWater field;  // the whole field, as recorded
};

// The mean square the renderer's formulas give the layer at points spread uniformly over the
// tiles: each component a cos(k.x - w t + phi) keeps a^2/2 times
//  - g(k_x h) g(k_y h), g(theta) = (2 + cos theta) / 3: the bilinear interpolant between the nodes
//    (spacing h = L / N) of a unit wave, its square averaged over offset and phase (1-D: with
//    weights 1 - a, a, E[(1 - a)^2] = E[a^2] = 1/3, E[2 a (1 - a)] = 1/3; separable in 2-D);
//  - (1 - f)^2 + f^2 + 2 f (1 - f) cos(w dt): the two keyframes dt apart mixed with weight f.
double interpolated_mean_square_m2(const SplitScene& scene, double fraction, double dt_s) {
  double sum = 0.0;
  const auto add = [&](const ocean::RecordedCascade& c) {
    const double h = c.tile_length_m / c.grid_size, step = 2.0 * std::numbers::pi / c.tile_length_m;
    for (int row = 0; row < c.grid_size; ++row)
      for (int column = 0; column < c.grid_size; ++column) {
        const std::size_t i = std::size_t(row) * std::size_t(c.grid_size) + std::size_t(column);
        const double a = c.amplitude_m[i];
        if (a == 0.0) continue;
        const double kx = step * (column < c.grid_size / 2 ? column : column - c.grid_size);
        const double ky = step * (row < c.grid_size / 2 ? row : row - c.grid_size);
        const double g = (2.0 + std::cos(kx * h)) / 3.0 * (2.0 + std::cos(ky * h)) / 3.0;
        const double mix = (1 - fraction) * (1 - fraction) + fraction * fraction +
                           2 * fraction * (1 - fraction) * std::cos(c.angular_frequency_rad_s[i] * dt_s);
        sum += 0.5 * a * a * g * mix;
      }
  };
  for (std::size_t c = 0; c < scene.field.cascades.size(); ++c)
    if ((scene.layer.whole_cascade_mask >> c) & 1u) add(scene.field.cascades[c]);
  for (const ocean::RecordedCascade& c : scene.layer.straddling.cascades) add(c);
  return sum;
}

SplitScene split_scene() {
  SplitScene scene;
  test::SiteOptions options;
  options.land = false;
  runtime::SurfaceSnapshot& snapshot = scene.with_layer;
  snapshot.site = test::make_site(options);
  snapshot.harbour_from = test::make_harbour_keyframe(*snapshot.site, 0, 1);
  snapshot.harbour_to = test::make_harbour_keyframe(*snapshot.site, 1, 2);
  snapshot.harbour_fraction = 0.3;
  ocean::DeepWaterSpecification specification;
  specification.spectrum = ocean::beaufort_preset(5, 0.6).spectrum;
  specification.tile_lengths_m = {97.0, 23.0};
  specification.grid_size = 64;
  specification.seed = 7;
  ocean::DeepWaterField field(specification);
  scene.field = field.record();
  scene.layer = runtime::split_deep_water(scene.field, 2.0 * std::numbers::pi * 0.25);
  ocean::DeepWaterField inside(scene.layer.straddling);
  std::uint64_t serial = 10;
  for (double t : {3.0, 3.5}) {
    const ocean::TimedWeight at{t, 1.0};
    auto keyframe = std::make_shared<runtime::DeepWaterKeyframe>();
    keyframe->serial = serial++;
    keyframe->display_time_s = t;
    field.synthesise_into(std::span(&at, 1), keyframe->cascades);
    keyframe->inside_cascade_mask = scene.layer.whole_cascade_mask;
    inside.synthesise_into(std::span(&at, 1), keyframe->inside_cascades);
    (t == 3.0 ? snapshot.deep_from : snapshot.deep_to) = keyframe;
  }
  snapshot.deep_fraction = 0.6;
  scene.without_layer = snapshot;
  for (auto* keyframe : {&scene.without_layer.deep_from, &scene.without_layer.deep_to}) {
    auto bare = std::make_shared<runtime::DeepWaterKeyframe>(**keyframe);
    bare->serial += 100;
    bare->inside_cascade_mask = 0;
    bare->inside_cascades.clear();
    *keyframe = bare;
  }
  return scene;
}

TEST(SplitRender, TheHeightPassDrawsTheInsideLayerAsTheCpuDoesAndOnlyInsideTheRectangle) {
  GlWindow window(64, 64, "test", false);
  const SplitScene scene = split_scene();
  ASSERT_EQ(scene.layer.whole_cascade_mask, 2u) << "the 23 m tile lies wholly above 0.25 Hz";
  ASSERT_EQ(scene.layer.straddling.cascades.size(), 1u) << "the 97 m tile straddles 0.25 Hz";
  WaterRenderer renderer;
  // The site (256 x 192 m) and 40 m of deep water round it, at 2 m pixels.
  const SiteRectangle r{-40.0, -40.0, 296.0, 232.0};
  const int columns = 168, rows = 136;
  const Raster<float> with = renderer.render_height_map(scene.with_layer, r, columns, rows);
  const Raster<float> without = renderer.render_height_map(scene.without_layer, r, columns, rows);
  const runtime::SurfaceSampler sampler(scene.with_layer);
  ASSERT_TRUE(sampler.has_inside_layer());
  const runtime::HarbourSite& site = *scene.with_layer.site;
  const double dx = (r.x1_m - r.x0_m) / columns, dy = (r.y1_m - r.y0_m) / rows;
  double largest_m = 0.0, outside_change_m = 0.0, added_m2 = 0.0;
  int interior = 0, outside = 0;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      ASSERT_FALSE(std::isnan(with(i, j)) || std::isnan(without(i, j))) << "open water everywhere";
      const double x = r.x0_m + (i + 0.5) * dx, y = r.y0_m + (j + 0.5) * dy;
      // No choppy shift (the site's lambda is 0): every pixel centre is a lattice vertex, so the
      // pass returns the vertex shader's value, which differs from the sampler's double only by
      // float rounding (tests/playback/height_pass_test.cpp: 1e-5 m expected, 0.1 mm asserted).
      largest_m = std::max(largest_m, std::abs(double(with(i, j)) - sampler.elevation_m(x, y)));
      const double w = runtime::harbour_weight(site, x, y);
      if (w == 0.0) {
        outside_change_m = std::max(outside_change_m, std::abs(double(with(i, j)) - double(without(i, j))));
        ++outside;
      } else if (w == 1.0) {
        added_m2 += std::pow(double(with(i, j)) - double(without(i, j)), 2);
        ++interior;
      }
    }
  EXPECT_LT(largest_m, 1e-4) << "max |GPU - CPU| with the split's layer";
  // Beyond the rectangle the whole field is drawn, with or without the layer: the same to float
  // round-off (a ~1 m sum in float32 is good to ~1e-7 m; 1e-5 m is asserted, where the layer's
  // own waves, Hs 0.8 m, would change it by tenths of a metre).
  EXPECT_LT(outside_change_m, 1e-5) << outside << " pixels beyond the rectangle";
  // Inside it the layer adds the split-off waves. Their mean square over the full-weight box
  // (about 208 m x 120 m, some 40 x 25 of the layer's longest, 25 m, waves) estimates what the
  // formulas give the layer (interpolated_mean_square_m2: the variance sum a^2/2 less the
  // bilinear interpolation's and the keyframes' time blend's losses) with the sampling spread of a
  // few hundred independent wave patches: within 15 % (measured below).
  ASSERT_GT(interior, 3000);
  const double measured_m2 = added_m2 / interior;
  const double expected_m2 = interpolated_mean_square_m2(scene, 0.6, 0.5);
  std::printf("split render: layer Hs %.3f m (%d components), %.3f m as interpolated and blended in time; rendered "
              "inside the rectangle %.3f m over %d pixels; max |GPU - CPU| %.3g mm, beyond the rectangle %.3g mm\n",
              scene.layer.significant_wave_height_m(), scene.layer.component_count, 4.0 * std::sqrt(expected_m2),
              4.0 * std::sqrt(measured_m2), interior, 1e3 * largest_m, 1e3 * outside_change_m);
  EXPECT_NEAR(measured_m2, expected_m2, 0.15 * expected_m2);
}

// Not a check: the picture of docs/runtime.md "The split" (docs/images/split_inside_layer.png,
// written to build/.../playback-pictures/): the GPU height pass (the vertex shaders' surface) over
// the site and 40 m round it at 1 m pixels, without and with the split's layer; the rectangle
// outlined.
TEST(SplitRender, WritesTheDocumentationPicture) {
  GlWindow window(64, 64, "test", false);
  const SplitScene scene = split_scene();
  WaterRenderer renderer;
  const SiteRectangle r{-40.0, -40.0, 296.0, 232.0};
  const int columns = 336, rows = 272;
  Image panels[2] = {Image(1, 1), Image(1, 1)};
  HeatMapStyle style;
  style.map = ColourMap::kDiverging;
  style.low = -1.5;
  style.high = 1.5;
  style.value_label = "eta (m)";
  style.max_image_size_px = 2 * columns;
  MapAxes axes;
  axes.origin_x_m = r.x0_m;
  axes.origin_y_m = r.y0_m;
  axes.x_label = "x (m)";
  axes.y_label = "y (m)";
  axes.north_label = "+y";
  style.map_axes = axes;
  for (int k = 0; k < 2; ++k) {
    const runtime::SurfaceSnapshot& snapshot = k == 0 ? scene.without_layer : scene.with_layer;
    style.title = k == 0 ? "the bake's frames only inside the rectangle" : "with the split-off waves (above 0.25 Hz) on top";
    panels[k] = render_heat_map(renderer.render_height_map(snapshot, r, columns, rows), style);
    const HeatMapPlacement place = heat_map_placement(columns, rows, style);
    // The harbour rectangle (0..256 m, 0..192 m), north up.
    const double x0 = place.left_px + (0.0 - r.x0_m) * place.pixels_per_cell, x1 = place.left_px + (256.0 - r.x0_m) * place.pixels_per_cell;
    const double y0 = place.top_px + (r.y1_m - 192.0) * place.pixels_per_cell, y1 = place.top_px + (r.y1_m - 0.0) * place.pixels_per_cell;
    const Rgb black{0.f, 0.f, 0.f};
    draw_line(panels[k], x0, y0, x1, y0, black);
    draw_line(panels[k], x1, y0, x1, y1, black);
    draw_line(panels[k], x1, y1, x0, y1, black);
    draw_line(panels[k], x0, y1, x0, y0, black);
  }
  Image picture(panels[0].width() + panels[1].width(), std::max(panels[0].height(), panels[1].height()));
  for (int k = 0; k < 2; ++k)
    for (int y = 0; y < panels[k].height(); ++y)
      for (int x = 0; x < panels[k].width(); ++x) picture.set(x + k * panels[0].width(), y, panels[k].get(x, y));
  const auto folder = std::filesystem::path(NEARSHORE_BINARY_DIR) / "playback-pictures";
  std::filesystem::create_directories(folder);
  write_png(picture, folder / "split_inside_layer.png");
}

}  // namespace
