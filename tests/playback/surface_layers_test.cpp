// SurfaceLayers drawn by the renderer against their CPU definitions: the bow waves of a real
// ships::ShipFleet added by the height pass as ShipFleet::shown_elevation_m adds them; wake foam
// decals whitening the sea where they lie; a hull mesh showing above the water and hidden below it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/runtime/surface_sampler.hpp"
#include "nearshore/ships/generic_hulls.hpp"
#include "nearshore/ships/ship_fleet.hpp"
#include "snapshot_fixtures.hpp"

namespace {
using namespace nearshore;
using namespace nearshore::playback;

// The fixtures' site (256 x 192 m, 12 m deep in the south shoaling to 3 m), harbour keyframes
// blended 30 %, no deep water's choppy shift (so every pixel centre is a lattice vertex).
runtime::SurfaceSnapshot harbour_scene() {
  test::SiteOptions options;
  options.land = false;
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = test::make_site(options);
  snapshot.harbour_from = test::make_harbour_keyframe(*snapshot.site, 0, 1);
  snapshot.harbour_to = test::make_harbour_keyframe(*snapshot.site, 1, 2);
  snapshot.harbour_fraction = 0.3;
  return snapshot;
}

ships::ShipDefinition tug(const char* name, double x_m, double y_m, double heading_deg) {
  ships::ShipDefinition d;
  d.name = name;
  d.hull = ships::harbour_tug();
  d.loading.draft_m = 3.0;
  d.hull_points = 800;
  d.x_m = x_m, d.y_m = y_m;
  d.heading_deg = heading_deg;
  d.initial_speed_m_s = 3.0;
  d.orders.speed_m_s = 3.0;
  return d;
}

SurfaceLayers patches_of(const ships::ShipFleet& fleet) {
  SurfaceLayers layers;
  for (const ships::BowWaveField& f : fleet.bow_wave_fields())
    layers.height_patches.push_back({f.origin_x_m, f.origin_y_m, f.spacing_m, f.columns, f.rows, f.heights_m->data(), f.serial});
  return layers;
}
}  // namespace

TEST(SurfaceLayers, HeightPatchesAddTheFleetsBowWavesAsItsCpuQueryDoes) {
  GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = harbour_scene();
  // Two tugs under way on crossing tracks, their bow-wave windows (96 m each) overlapping.
  ships::ShipFleet fleet;
  fleet.set_site(snapshot.site);
  fleet.add_ship(tug("east", 100.0, 60.0, 90.0));
  fleet.add_ship(tug("west", 160.0, 80.0, 270.0));
  for (int frame = 0; frame < 60; ++frame) fleet.step(snapshot, 1.0 / 30.0);
  const SurfaceLayers layers = patches_of(fleet);
  ASSERT_EQ(layers.height_patches.size(), 2u);

  WaterRenderer renderer;
  const SiteRectangle r{60.0, 20.0, 200.0, 120.0};  // both windows, 0.5 m pixels
  const Raster<float> heights = renderer.render_height_map(snapshot, r, 280, 200, &layers);
  const runtime::SurfaceSampler sampler(snapshot);
  double largest_difference = 0, largest_bow = 0;
  int compared = 0;
  for (int j = 0; j < heights.rows(); ++j)
    for (int i = 0; i < heights.columns(); ++i) {
      if (std::isnan(heights(i, j))) continue;  // dry under a hull's depression in shallow water
      const double x = r.x0_m + (i + 0.5) * 0.5, y = r.y0_m + (j + 0.5) * 0.5;
      largest_difference = std::max(largest_difference, std::abs(double(heights(i, j)) - fleet.shown_elevation_m(sampler, x, y)));
      largest_bow = std::max(largest_bow, std::abs(fleet.bow_wave_elevation_m(x, y)));
      ++compared;
    }
  EXPECT_GT(compared, 280 * 200 * 9 / 10);
  // Not vacuous: the hulls' depressions (their draft, 3 m) and bow waves are added.
  EXPECT_GT(largest_bow, 0.05);
  // The patch texels are the fleet's own floats; the shader's bilinear weights carry float32
  // rounding of (p - origin) / spacing, about 1e-5 of a 0.75 m cell at 200 m, times the largest
  // step between neighbouring texels (under 1 m at the hull's side): 1e-5 m. The harbour part
  // agrees to 1e-5 m (height_pass_test). 0.1 mm is asserted, as for the sea alone.
  EXPECT_LT(largest_difference, 1e-4) << compared << " pixels";
  std::printf("height pass with two bow waves: max |GPU - CPU| = %.3g mm over %d pixels (largest bow-wave height %.3f m)\n",
              1e3 * largest_difference, compared, largest_bow);
  // Without the layers the same pass is the sea alone: the patches are what made the difference.
  const Raster<float> sea = renderer.render_height_map(snapshot, r, 280, 200);
  double largest_change = 0;
  for (int j = 0; j < sea.rows(); ++j)
    for (int i = 0; i < sea.columns(); ++i)
      if (!std::isnan(sea(i, j)) && !std::isnan(heights(i, j)))
        largest_change = std::max(largest_change, std::abs(double(heights(i, j) - sea(i, j))));
  EXPECT_NEAR(largest_change, largest_bow, 0.05 * largest_bow);
}

TEST(SurfaceLayers, FoamDecalsWhitenTheSeaWhereTheyLie) {
  GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = harbour_scene();
  WaterRenderer renderer;
  Camera camera;
  camera.eye_m = {128.0, 96.0, 150.0};
  camera.target_m = {128.0, 96.5, 0.0};  // straight down (a hair off so "up" is defined)
  const Lighting lighting;
  renderer.render(snapshot, camera, lighting, 128, 128, {});
  const Image plain = renderer.read_pixels();
  SurfaceLayers layers;
  layers.foam_decals.push_back({128.0, 96.0, 0.3, 30.0, 12.0, 1.0, 0});
  renderer.render(snapshot, camera, lighting, 128, 128, {}, &layers);
  const Image foamed = renderer.read_pixels();
  EXPECT_EQ(renderer.last_frame().foam_decals, 1);
  auto brightness = [](const Image& image, int x, int y) {
    const Rgb c = image.get(x, y);
    return (c[0] + c[1] + c[2]) / 3.f;
  };
  // The middle of the decal is much brighter; a corner of the picture (60 m away) is unchanged.
  EXPECT_GT(brightness(foamed, 64, 64), brightness(plain, 64, 64) + 0.15f);
  EXPECT_EQ(brightness(foamed, 4, 4), brightness(plain, 4, 4));
}

TEST(SurfaceLayers, AHullShowsAboveTheWaterlineAndIsHiddenBelowIt) {
  GlWindow window(64, 64, "test", false);
  runtime::SurfaceSnapshot snapshot = harbour_scene();
  snapshot.harbour_from = snapshot.harbour_to = nullptr;  // still water: the waterline at z = 0
  WaterRenderer renderer;
  // A box 40 m long, 10 m wide, keel 3 m under still water and deck 3 m above it, seen from its
  // beam at the water's level, the sea drawn flat magenta and the hull one colour.
  const ships::HullMesh box = ships::box_barge(40.0, 10.0, 6.0);
  std::vector<float> vertices;
  std::vector<std::uint32_t> triangles;
  for (const auto& v : box.vertices_m) vertices.insert(vertices.end(), {float(v.x()), float(v.y()), float(v.z())});
  for (const auto& t : box.triangles) triangles.insert(triangles.end(), {std::uint32_t(t[0]), std::uint32_t(t[1]), std::uint32_t(t[2])});
  SurfaceLayers layers;
  SolidMesh hull;
  hull.id = 1;
  hull.vertices_m = vertices.data();
  hull.vertex_count = vertices.size() / 3;
  hull.triangles = triangles.data();
  hull.triangle_count = triangles.size() / 3;
  hull.position_m = {128.0, 96.0, -3.0};  // the body origin on the keel
  hull.albedo_above = hull.albedo_below = {0.9f, 0.9f, 0.1f};
  layers.meshes.push_back(hull);
  Camera camera;
  camera.eye_m = {128.0, 46.0, 0.5};
  camera.target_m = {128.0, 96.0, 0.5};
  DrawOptions flat;
  flat.colouring = SurfaceColouring::flat;
  flat.sky = false;
  renderer.render(snapshot, camera, Lighting{}, 200, 200, flat, &layers);
  const Image picture = renderer.read_pixels();
  auto is_sea = [&](int y) { const Rgb c = picture.get(100, y); return c[0] > 0.9f && c[1] < 0.1f && c[2] > 0.9f; };
  auto is_hull = [&](int y) { const Rgb c = picture.get(100, y); return c[0] > 0.5f && c[1] > 0.5f && c[2] < 0.5f; };  // yellow, lit
  // Down the picture's middle column: hull above the horizon line of the water, sea below; the
  // boundary is the waterline.
  int first_sea = -1;
  for (int y = 0; y < 200 && first_sea < 0; ++y)
    if (is_sea(y)) first_sea = y;
  ASSERT_GT(first_sea, 0);
  EXPECT_TRUE(is_hull(first_sea - 3)) << "the hull shows just above the waterline";
  for (int y = first_sea; y < 200; ++y) EXPECT_FALSE(is_hull(y)) << "row " << y << ": the hull shows through the water";
  EXPECT_EQ(renderer.last_frame().meshes, 1);
  std::printf("waterline at picture row %d of 200\n", first_sea);
}
