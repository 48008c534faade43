// Screen-space refraction on Mesa (docs/lighting.md step 5): what lies under the water (a hull's
// underwater part, a box on the seabed) seen through a calm surface, against the CPU twin
// (playback::shade_water with SurfacePoint::refracted_scene) and Snell's law.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "nearshore/playback/lighting.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/plot/plot.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"
#include "snapshot_fixtures.hpp"

namespace nearshore {
namespace {
using playback::Vector3;

// Still water over a flat seabed `depth_m` deep (the test site without land; no keyframes: calm).
runtime::SurfaceSnapshot calm_water(double depth_m) {
  test::SiteOptions options;
  options.land = false;
  auto site = test::make_site(options);
  for (int j = 0; j < options.rows; ++j)
    for (int i = 0; i < options.columns; ++i) site->harbour.still_water_depth_m(i, j) = float(depth_m);
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = site;
  return snapshot;
}

// An axis-aligned box from `low` to `high` (site frame) as a SolidMesh of one albedo.
struct Box {
  std::vector<float> vertices;
  std::vector<std::uint32_t> triangles = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                                          1, 5, 6, 1, 6, 2, 2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0};
  playback::SurfaceLayers layers;
  Box(const Vector3& low, const Vector3& high, const Rgb& albedo) {
    const float x0 = float(low[0]), y0 = float(low[1]), z0 = float(low[2]);
    const float x1 = float(high[0]), y1 = float(high[1]), z1 = float(high[2]);
    vertices = {x0, y0, z0, x1, y0, z0, x1, y1, z0, x0, y1, z0, x0, y0, z1, x1, y0, z1, x1, y1, z1, x0, y1, z1};
    playback::SolidMesh mesh;
    mesh.id = 41;
    mesh.vertices_m = vertices.data();
    mesh.vertex_count = vertices.size() / 3;
    mesh.triangles = triangles.data();
    mesh.triangle_count = triangles.size() / 3;
    mesh.albedo_above = mesh.albedo_below = albedo;
    layers.meshes.push_back(mesh);
  }
};

Image render(const runtime::SurfaceSnapshot& snapshot, const playback::Camera& camera, const playback::Lighting& lighting,
             int width, int height, const playback::SurfaceLayers* layers, bool refraction = true,
             bool local_reflections = true) {
  playback::RendererSettings settings;
  settings.refraction = refraction;
  settings.local_reflections = local_reflections;
  playback::WaterRenderer renderer(settings);
  renderer.render(snapshot, camera, lighting, width, height, {}, layers);
  return renderer.read_pixels();
}

// Lit as play lights it, in water of these constituents.
playback::Lighting in_water(double turbidity_ntu, double chlorophyll_mg_m3) {
  playback::Lighting lighting;
  lighting.water.turbidity_ntu = turbidity_ntu;
  lighting.water.chlorophyll_mg_m3 = chlorophyll_mg_m3;
  return lighting;
}

// 30 m up, 18 degrees from the vertical, the picture's axis through (128, 96, 0).
playback::Camera from_above() {
  playback::Camera camera;
  camera.eye_m = {128.0, 86.0, 30.0};
  camera.target_m = {128.0, 96.0, 0.0};
  camera.vertical_field_of_view_deg = 30.0;
  return camera;
}

double luminance(const Rgb& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

Vector3 normalized(const Vector3& v) {
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / length, v[1] / length, v[2] / length};
}

TEST(RefractionRender, ABoxOneMetreUnderClearWaterShowsWithTheAttenuationTheOpticsPredict) {
  // A grey box (albedo 0.8) whose top is 1 m under calm, clear water 10 m deep, seen from 30 m
  // up, 18 degrees from the vertical. The picture's centre pixel looks at the surface point
  // (128, 96, 0); its refracted view meets the box's top 1 m down. The CPU twin: shade_water with
  // the box's top as the refracted scene (lit in air: shade_lambertian facing up), 1 m below
  // the surface, its path 1 / cos(theta_w) along the refracted view.
  playback::GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = calm_water(10.0);
  const playback::Lighting lighting = in_water(0.0, 0.05);
  const Rgb grey = {0.8f, 0.8f, 0.8f};
  Box box({120.0, 88.0, -3.0}, {136.0, 104.0, -1.0}, grey);
  const playback::Camera camera = from_above();
  const int size = 81;  // odd: the centre pixel's ray is the view's axis, through the target
  const Image with = render(snapshot, camera, lighting, size, size, &box.layers);
  const Image without = render(snapshot, camera, lighting, size, size, nullptr);
  const Image opaque = render(snapshot, camera, lighting, size, size, &box.layers, false);
  write_png(with, std::filesystem::path(NEARSHORE_BINARY_DIR) / "playback_refraction_box_1m.png");

  const playback::LightingFrame frame = playback::prepare_lighting(lighting);
  playback::SurfacePoint point;
  point.to_eye = normalized({camera.eye_m[0] - 128.0, camera.eye_m[1] - 96.0, camera.eye_m[2]});
  point.water_depth_m = 10.0;
  const double sin_air = std::hypot(point.to_eye[0], point.to_eye[1]);
  const double cos_water = std::sqrt(1.0 - sin_air * sin_air / (1.333 * 1.333));
  point.refracted_scene = playback::shade_lambertian(frame, {0, 0, 1}, {grey[0], grey[1], grey[2]});
  point.refracted_scene_coverage = 1.0;
  point.refracted_depth_m = 1.0;
  point.refracted_path_m = 1.0 / cos_water;
  const playback::Radiance expected = playback::to_display(frame, playback::shade_water(frame, point));
  const Rgb pixel = with.get(size / 2, size / 2);
  std::printf("box 1 m down: GPU %.4f %.4f %.4f, CPU twin %.4f %.4f %.4f; without the box %.4f, opaque sea %.4f (luminance)\n",
              pixel[0], pixel[1], pixel[2], expected[0], expected[1], expected[2], luminance(without.get(size / 2, size / 2)),
              luminance(opaque.get(size / 2, size / 2)));
  // 3/255 as the other twin tests (8-bit output, float32 against double), which also covers the
  // 8-bit copy of the scene: its 1/2 step (1/510) reaches the pixel scaled by the share of the
  // water-leaving light in it (under 1) and the display curve's slopes' ratio (under 1.2 here).
  for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(pixel[c], expected[c], 3.0 / 255) << "channel " << c;
  // Visible: brighter than the sea without it by far more than that; and the opaque sea of
  // before (refraction off) does not show it.
  EXPECT_GT(luminance(pixel) - luminance(without.get(size / 2, size / 2)), 0.05);
  EXPECT_NEAR(luminance(opaque.get(size / 2, size / 2)), luminance(without.get(size / 2, size / 2)), 1.5 / 255);
}

TEST(RefractionRender, ABoxThirtyMetresUnderTurbidWaterIsNotSeen) {
  // The same box with its top 30 m under turbid coastal water (15 NTU, chlorophyll 3 mg/m3): the
  // optics keep exp(-K (30 / 0.8 + 30 / cos)) of its light, K 0.7-1.7 /m (printed): 2e-25 in the
  // green. Every pixel over it is the sea without it, to the last 8-bit step.
  playback::GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = calm_water(40.0);
  const playback::Lighting lighting = in_water(15.0, 3.0);
  const playback::LightingFrame frame = playback::prepare_lighting(lighting);
  std::printf("turbid K = %.3f %.3f %.3f /m, kept %.3g\n", frame.water.diffuse_attenuation_per_m[0],
              frame.water.diffuse_attenuation_per_m[1], frame.water.diffuse_attenuation_per_m[2],
              playback::submerged_transmittance(frame, 30.0, 30.0)[1]);
  Box box({110.0, 80.0, -34.0}, {146.0, 112.0, -30.0}, {0.8f, 0.8f, 0.8f});
  const playback::Camera camera = from_above();
  const int size = 81;
  const Image with = render(snapshot, camera, lighting, size, size, &box.layers);
  const Image without = render(snapshot, camera, lighting, size, size, nullptr);
  double largest = 0;
  for (int y = size / 4; y < 3 * size / 4; ++y)
    for (int x = size / 4; x < 3 * size / 4; ++x)
      for (std::size_t c = 0; c < 3; ++c) largest = std::max(largest, double(std::abs(with.get(x, y)[c] - without.get(x, y)[c])));
  EXPECT_LE(largest, 1.0 / 255) << "the box 30 m down shows through turbid water";
}

// The surface point (x_eye, y, 0) whose refracted view from `eye` reaches (y_target, -depth): Snell
// by bisection on y between the straight line's crossing and the target.
double snell_entry_y(const Vector3& eye, double y_target, double depth) {
  double low = eye[1], high = y_target;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double y = 0.5 * (low + high);
    const double sin_air = (y - eye[1]) / std::hypot(y - eye[1], eye[2]);
    const double sin_water = sin_air / 1.333;
    const double reach = y + depth * sin_water / std::sqrt(1.0 - sin_water * sin_water);
    (reach < y_target ? low : high) = y;
  }
  return 0.5 * (low + high);
}

TEST(RefractionRender, TheUnderwaterPartOfABoxHalfOutOfTheWaterIsShiftedBySnellsAngle) {
  // A dark red box 20 m wide standing from 4 m under the water to 2 m above it, its near face at
  // y = 95 m, over sand 8 m deep, seen from 6 m up at y = 60 m. Down the picture's middle column,
  // the lowest row that changes when the box is added is where its face's bottom edge (y = 95,
  // z = -4) shows through the surface: Snell puts it at the surface point whose refracted view
  // reaches that edge, well above (further away than) where the straight line from the eye
  // crosses the surface (60 + 35 x 6 / 10 = 81 m).
  playback::GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = calm_water(8.0);
  const playback::Lighting lighting = in_water(0.0, 0.05);
  Box box({118.0, 95.0, -4.0}, {138.0, 105.0, 2.0}, {0.6f, 0.1f, 0.1f});
  playback::Camera camera;
  camera.eye_m = {128.0, 60.0, 6.0};
  camera.target_m = {128.0, 100.0, -3.0};
  camera.vertical_field_of_view_deg = 40.0;
  const int width = 161, height = 161;
  // Without the local reflection: the box's mirror image would change the rows under the waterline too.
  const Image with = render(snapshot, camera, lighting, width, height, &box.layers, true, false);
  const Image without = render(snapshot, camera, lighting, width, height, nullptr, true, false);
  const Image opaque = render(snapshot, camera, lighting, width, height, &box.layers, false, false);
  write_png(with, std::filesystem::path(NEARSHORE_BINARY_DIR) / "playback_refraction_half_box.png");
  const playback::CameraView view = playback::camera_view(camera, width, height, 1.0, 1000.0);
  auto row_of = [&](double y_m) {  // picture row (0 at the top, continuous: pixel centres at k + 0.5)
    const auto clip = playback::transform(view.view_projection, {128.0, y_m, 0.0, 1.0});
    return (1.0 - (clip[1] / clip[3] * 0.5 + 0.5)) * height;
  };
  const double y_snell = snell_entry_y(camera.eye_m, 95.0, 4.0), y_straight = 60.0 + 35.0 * 6.0 / 10.0;
  const double row_snell = row_of(y_snell), row_straight = row_of(y_straight), row_waterline = row_of(95.0);
  auto lowest_changed_row = [&](const Image& picture) {
    for (int y = height - 1; y >= 0; --y)
      for (std::size_t c = 0; c < 3; ++c)  // the lit red face and the sea have nearly one luminance: by channel
        if (std::abs(picture.get(width / 2, y)[c] - without.get(width / 2, y)[c]) > 0.03) return y;
    return -1;
  };
  const int row_drawn = lowest_changed_row(with), row_opaque = lowest_changed_row(opaque);
  std::printf("bottom edge: Snell's entry y %.2f m (row %.2f), the straight line's %.2f m (row %.2f), waterline row %.2f; "
              "drawn: row %d (refraction off: row %d)\n",
              y_snell, row_snell, y_straight, row_straight, row_waterline, row_drawn, row_opaque);
  // The first changed pixel's centre lies past the edge's image: its row within 2 of the one
  // Snell's entry point projects to (the screen-space search converges to the refracted ray's
  // meeting with the face in three steps; a pixel's quantisation on top).
  EXPECT_NEAR(row_drawn + 0.5, row_snell, 2.0);
  EXPECT_GT(row_straight - row_snell, 6.0) << "the geometry must separate the two";
  // Without refraction nothing under the water shows: the first change is the waterline.
  EXPECT_NEAR(row_opaque + 0.5, row_waterline, 1.5);
}

}  // namespace
}  // namespace nearshore
