// The top-down height pass against the CPU sampler (runtime::SurfaceSampler, the definition of
// the shown surface), and land and breakwaters kept dry, in the height pass and in a picture.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "nearshore/playback/site_terrain.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/runtime/surface_sampler.hpp"
#include "snapshot_fixtures.hpp"

namespace {
using namespace nearshore;
using namespace nearshore::playback;

// The site (64 x 48 cells of 4 m), harbour keyframes blended 30 %, two deep cascades blended 60 %.
runtime::SurfaceSnapshot scene(bool land, double choppiness) {
  test::SiteOptions options;
  options.land = land;
  options.choppiness = choppiness;
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = test::make_site(options);
  snapshot.harbour_from = test::make_harbour_keyframe(*snapshot.site, 0, 1);
  snapshot.harbour_to = test::make_harbour_keyframe(*snapshot.site, 1, 2);
  snapshot.harbour_fraction = 0.3;
  const test::DeepPair deep = test::make_deep_pair(5, {97.0, 23.0}, 64, 3.0, 3.5, 10);
  snapshot.deep_from = deep.from;
  snapshot.deep_to = deep.to;
  snapshot.deep_fraction = 0.6;
  return snapshot;
}

struct Comparison {
  double largest_difference_m = 0;
  int compared = 0, missing = 0;
};

Comparison compare_with_cpu(const runtime::SurfaceSnapshot& snapshot, const Raster<float>& heights, const SiteRectangle& r) {
  const runtime::SurfaceSampler sampler(snapshot);
  Comparison c;
  const double dx = (r.x1_m - r.x0_m) / heights.columns(), dy = (r.y1_m - r.y0_m) / heights.rows();
  for (int j = 0; j < heights.rows(); ++j)
    for (int i = 0; i < heights.columns(); ++i) {
      if (std::isnan(heights(i, j))) {
        ++c.missing;
        continue;
      }
      const double cpu = sampler.elevation_m(r.x0_m + (i + 0.5) * dx, r.y0_m + (j + 0.5) * dy);  // displaced point
      c.largest_difference_m = std::max(c.largest_difference_m, std::abs(double(heights(i, j)) - cpu));
      ++c.compared;
    }
  return c;
}
}  // namespace

TEST(HeightPass, AgreesWithTheCpuFormulasToATenthOfAMillimetre) {
  GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = scene(false, 0.0);
  WaterRenderer renderer;
  // The site (256 x 192 m) and 40 m of deep water round it: every part of the formula (harbour
  // pair joined by the Hermite in time, blend zone, edge fades, both cascades, wrap-around of the
  // tiles) at 2 m pixels.
  const SiteRectangle rectangle{-40.0, -40.0, 296.0, 232.0};
  const Raster<float> heights = renderer.render_height_map(snapshot, rectangle, 168, 136);
  const Comparison c = compare_with_cpu(snapshot, heights, rectangle);
  EXPECT_EQ(c.missing, 0) << "open water everywhere: no pixel may be empty";
  // Without the choppy shift every pixel centre is a lattice vertex, so the pass returns the
  // vertex shader's value itself. That differs from the sampler's double only by float32 rounding:
  // texel values are the same floats; the bilinear weights carry about 1e-5 of a texel (the texel
  // coordinate p / spacing, ~100, in float), i.e. 1e-5 of the ~1 m step between neighbouring
  // texels; w(p)'s sin in float is good to ~1e-6 of the ~2 m harbour-deep difference. So 1e-5 m
  // is the expected size, and 0.1 mm is asserted.
  EXPECT_LT(c.largest_difference_m, 1e-4) << c.compared << " pixels";
  std::printf("height pass, no choppy shift: max |GPU - CPU| = %.3g mm over %d pixels\n", 1e3 * c.largest_difference_m,
              c.compared);
}

TEST(HeightPass, AgreesWithTheCpuWhereTheChoppyShiftMovesTheVertices) {
  GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = scene(false, 1.0);
  WaterRenderer renderer;
  // South of the site, in the deep water (w = 0), 0.5 m pixels.
  const SiteRectangle rectangle{0.0, -60.0, 80.0, -10.0};
  const Raster<float> heights = renderer.render_height_map(snapshot, rectangle, 160, 100);
  const Comparison c = compare_with_cpu(snapshot, heights, rectangle);
  EXPECT_EQ(c.missing, 0);
  // With the shift the pixel centres fall inside the displaced lattice's triangles, and the
  // rasteriser interpolates linearly between vertices half a metre apart: an error of up to
  // h^2 / 8 times the surface's curvature. The curvature, measured by second differences of the
  // CPU's Eulerian elevation on the same 0.5 m lattice, bounds it (with a factor 2 for the
  // triangles' diagonals, the sheared lattice and float rounding).
  const runtime::SurfaceSampler sampler(snapshot);
  auto elevation = [&](double x, double y) { return sampler.elevation_m(x, y); };
  double curvature = 0;
  const double h = 0.5;
  for (int j = 1; j + 1 < 100; j += 3)
    for (int i = 1; i + 1 < 160; i += 3) {
      const double x = 0.25 + i * h, y = -59.75 + j * h;
      const double centre = elevation(x, y);
      curvature = std::max({curvature,
                            std::abs(elevation(x + h, y) - 2 * centre + elevation(x - h, y)) / (h * h),
                            std::abs(elevation(x, y + h) - 2 * centre + elevation(x, y - h)) / (h * h)});
    }
  const double bound = 2.0 * h * h / 8 * curvature + 1e-4;
  EXPECT_LT(c.largest_difference_m, bound);
  std::printf("height pass, choppy: max |GPU - CPU| = %.3g mm (interpolation bound %.3g mm) over %d pixels\n",
              1e3 * c.largest_difference_m, 1e3 * bound, c.compared);
}

TEST(HeightPass, LandAndBreakwaterCellsHoldNoWater) {
  GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = scene(true, 0.0);
  WaterRenderer renderer;
  const GridGeometry& g = snapshot.site->harbour.geometry;
  // One pixel per cell, at the cell centres.
  const Raster<float> heights =
      renderer.render_height_map(snapshot, {0.0, 0.0, g.width_m(), g.height_m()}, g.columns, g.rows);
  int land_cells = 0, structure_cells = 0;
  for (int j = 0; j < g.rows; ++j)
    for (int i = 0; i < g.columns; ++i) {
      const bool land = snapshot.site->harbour.land(i, j) != 0, structure = snapshot.site->harbour.porosity(i, j) < 0.99f;
      land_cells += land;
      structure_cells += structure;
      EXPECT_EQ(std::isnan(heights(i, j)), land || structure) << "cell (" << i << ", " << j << ")";
    }
  EXPECT_GT(land_cells, 100);
  EXPECT_GT(structure_cells, 10);
}

TEST(Render, LandAndBreakwatersShowNoWaterFromAbove) {
  GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = scene(true, 0.0);
  const HarbourGrid& harbour = snapshot.site->harbour;
  for (GridKind kind : {GridKind::radial, GridKind::quadtree}) {
    RendererSettings settings;
    settings.grid = kind;
    WaterRenderer renderer(settings);
    // Straight down (nearly: the look needs a horizontal component) from 3 km onto the site, a
    // 3.7 degree field of view: 1 m per pixel, parallax of the 2-5 m high land under 0.2 m.
    Camera camera;
    camera.eye_m = {128.0, 96.0 - 0.01, 3000.0};
    camera.target_m = {128.0, 96.0, 0.0};
    camera.vertical_field_of_view_deg = 2.0 * std::atan(96.0 / 3000.0) * 180 / M_PI;
    DrawOptions options;
    options.colouring = SurfaceColouring::flat;
    options.flat_colour = {1.f, 0.f, 1.f};
    const int width = 256, height = 192;
    renderer.render(snapshot, camera, Lighting{}, width, height, options);
    const Image image = renderer.read_pixels();
    const CameraView view = camera_view(camera, width, height, renderer.last_frame().near_m, renderer.last_frame().far_m);
    const Matrix4 unproject = inverse(view.view_projection);
    // Dry as the water's mask says (surface.glsl, is_dry): the bilinear depth well above the
    // waves (d < -1.5 m: the keyframes reach 1.2 m), or the porous cells' indicator, read
    // bilinearly, clearly over its half level (structure cells without geometry).
    auto structure_indicator = [&](double x, double y) {
      const double u = std::clamp(x / 4.0 - 0.5, 0.0, harbour.geometry.columns - 1.0);
      const double v = std::clamp(y / 4.0 - 0.5, 0.0, harbour.geometry.rows - 1.0);
      const int i0 = std::min(int(u), harbour.geometry.columns - 2), j0 = std::min(int(v), harbour.geometry.rows - 2);
      auto flag = [&](int i, int j) { return harbour.porosity(i, j) < 0.99f ? 1.0 : 0.0; };
      const double a = u - i0, b = v - j0;
      return (1 - b) * ((1 - a) * flag(i0, j0) + a * flag(i0 + 1, j0)) + b * ((1 - a) * flag(i0, j0 + 1) + a * flag(i0 + 1, j0 + 1));
    };
    int dry_checked = 0, structure_checked = 0, wet_pixels = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        // The still-water point under the pixel centre.
        const double ndc_x = (x + 0.5) / width * 2 - 1, ndc_y = 1 - (y + 0.5) / height * 2;
        auto a = transform(unproject, {ndc_x, ndc_y, -1, 1}), b = transform(unproject, {ndc_x, ndc_y, 1, 1});
        for (auto* p : {&a, &b})
          for (int k = 0; k < 3; ++k) (*p)[std::size_t(k)] /= (*p)[3];
        const double s = a[2] / (a[2] - b[2]);
        const double px = a[0] + s * (b[0] - a[0]), py = a[1] + s * (b[1] - a[1]);
        const int i = int(std::floor(px / 4.0)), j = int(std::floor(py / 4.0));
        const auto pixel = image.get(x, y);
        const bool water = pixel[0] > 0.9f && pixel[1] < 0.1f && pixel[2] > 0.9f;
        wet_pixels += water;
        // Where the land stands well above the waves, or a structure clearly stands (the mask's
        // level 0.6, 0.4 m inside its half level): clear of the parallax (0.2 m) and of the
        // waves' (eta / tan(87 deg), 5 cm).
        if (i < 0 || j < 0 || i >= harbour.geometry.columns || j >= harbour.geometry.rows) continue;
        const bool land = playback::ground_elevation_m(harbour, px, py) > 1.5;
        const bool structure = structure_indicator(px, py) > 0.6;
        if (!land && !structure) continue;
        ++dry_checked;
        structure_checked += structure;
        EXPECT_FALSE(water) << grid_kind_name(kind) << ": water drawn over dry ground at (" << px << ", " << py << ") m";
      }
    EXPECT_GT(dry_checked, 2000) << grid_kind_name(kind);
    EXPECT_GT(structure_checked, 100) << grid_kind_name(kind) << ": the breakwater's pixels";
    EXPECT_GT(wet_pixels, width * height / 2) << grid_kind_name(kind);
  }
}
