// Issue 41's "done when" on the real demo bake (data/cases/harbour.toml baked by the
// DemoHarbourLoops test, the ctest fixture demo_harbour_bake; or the folder named by
// NEARSHORE_DEMO_BAKE): the baked swell reaches the picture, and the sheltered basin looks calmer
// than the approach where the bake says it is. Rendered on Mesa from a bridge-height camera at the
// harbour entrance, once with the baked keyframes and once with them replaced by still water (the
// same deep water, the same site).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <vector>

#include "nearshore/ocean/sea_state_beaufort.hpp"
#include "nearshore/playback/lighting.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/runtime/streaming_engine.hpp"

namespace nearshore {
namespace {
namespace fs = std::filesystem;
using playback::Vector3;

fs::path demo_bake_folder() {
  if (const char* folder = std::getenv("NEARSHORE_DEMO_BAKE")) return folder;
  return NEARSHORE_DEMO_BAKE_DIR;  // tests/CMakeLists.txt: the fixture demo_harbour_bake's output
}

Vector3 unit(const Vector3& v) {
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / length, v[1] / length, v[2] / length};
}

double display_luminance(const std::array<float, 3>& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }
double display_luminance(const playback::Radiance& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

// A cell-centred raster read as the GPU's bilinear filter reads it (clamped at the edges).
double bilinear(const Raster<float>& field, double spacing_m, double x_m, double y_m) {
  const double u = std::clamp(x_m / spacing_m - 0.5, 0.0, double(field.columns() - 1));
  const double v = std::clamp(y_m / spacing_m - 0.5, 0.0, double(field.rows() - 1));
  const int i = std::min(int(u), field.columns() - 2), j = std::min(int(v), field.rows() - 2);
  const double a = u - i, b = v - j;
  return (1 - b) * ((1 - a) * field(i, j) + a * field(i + 1, j)) + b * ((1 - a) * field(i, j + 1) + a * field(i + 1, j + 1));
}

TEST(DemoHarbourOnScreen, TheBakedSwellChangesThePictureAndTheBasinLooksCalmerThanTheApproach) {
  const fs::path folder = demo_bake_folder();
  ASSERT_TRUE(fs::exists(folder / "manifest.json"))
      << folder << " holds no bake: ctest runs DemoHarbourLoops.PeriodicBakeRepeatsWithSeamRatioBelowATenth first "
      << "(fixture demo_harbour_bake), or set NEARSHORE_DEMO_BAKE to a demo bake";
  runtime::StreamingOptions options;
  options.lockstep = true;
  runtime::StreamingEngine engine(folder, options);
  engine.advance_to(120.0);
  const runtime::SurfaceSnapshot baked = engine.snapshot();
  ASSERT_TRUE(baked.site && baked.harbour_from && baked.deep_from);
  const runtime::HarbourSite& site = *baked.site;
  ASSERT_FALSE(site.relative_wave_height.empty()) << "the site's relative wave height";
  const GridGeometry& g = site.harbour.geometry;
  const double dx = g.spacing_m;

  // The same instant with still water in the harbour (the same deep water, site and sheltering).
  auto still = std::make_shared<runtime::HarbourKeyframe>();
  still->serial = 1u << 30;
  still->surface_elevation_m = still->breaking = still->surface_elevation_rate_m_s = Raster<float>(g.columns, g.rows, 0.f);
  runtime::SurfaceSnapshot calm = baked;
  calm.harbour_from = calm.harbour_to = still;

  // A ship's bridge (25 m) in the open approach east of the detached breakwater's lee, looking
  // north-west over the entrance (x 730-870 m at y = 640 m) and the arms into the basin; the
  // play command's lighting (sun 35 degrees high in the south-south-west).
  playback::Camera camera;
  camera.eye_m = {1100.0, 540.0, 25.0};
  camera.target_m = {720.0, 860.0, 0.0};
  camera.vertical_field_of_view_deg = 45.0;
  playback::Lighting lighting;
  lighting.wind_speed_m_s = ocean::beaufort_preset(3).wind_speed_10_m_s;
  if (engine.manifest().deep_water && engine.manifest().deep_water->unresolved_slope_variance > 0.0)
    lighting.sub_grid_slope_variance = engine.manifest().deep_water->unresolved_slope_variance;
  const int width = 640, height = 360;
  playback::GlWindow window(64, 64, "test", false);
  playback::WaterRenderer renderer;
  renderer.render(baked, camera, lighting, width, height);
  const Image baked_image = renderer.read_pixels();
  renderer.render(calm, camera, lighting, width, height);
  const Image calm_image = renderer.read_pixels();

  const playback::CameraView view = playback::camera_view(camera, width, height, 1.0, 1e4);
  const playback::LightingFrame frame = playback::prepare_lighting(lighting);
  const auto inverse = playback::inverse(view.view_projection);
  const auto is_water = [&](int i, int j) {
    return site.harbour.land(i, j) == 0 && site.harbour.porosity(i, j) >= 0.99f && site.harbour.still_water_depth_m(i, j) > 1.f;
  };
  const double f = baked.harbour_fraction;
  double measured = 0, predicted = 0, level = 0;
  int water_pixels = 0;
  struct Region {
    double texture = 0, change = 0;
    int count = 0;
  } approach, basin;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x + 1 < width; ++x) {
      const double ndc_x = (x + 0.5) / width * 2 - 1, ndc_y = 1 - (y + 0.5) / height * 2;
      const auto far = playback::transform(inverse, {ndc_x, ndc_y, 1.0, 1.0});
      const Vector3 ray = unit({far[0] / far[3] - camera.eye_m[0], far[1] / far[3] - camera.eye_m[1], far[2] / far[3] - camera.eye_m[2]});
      if (ray[2] > -0.02) continue;  // the sea only, away from the horizon
      const double t = -camera.eye_m[2] / ray[2];
      const double px = camera.eye_m[0] + t * ray[0], py = camera.eye_m[1] + t * ray[1];
      if (px < 2 * dx || py < 2 * dx || px > site.width_m - 2 * dx || py > site.height_m - 2 * dx) continue;
      const int i = int(px / dx), j = int(py / dx);
      bool water = true;  // this cell and its neighbours (no edge of a structure or the shore)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) water = water && is_water(i + di, j + dj);
      if (!water || runtime::harbour_weight(site, px, py) < 1.0) continue;
      // What the baked slopes predict through the BRDF (the twin), the normal the shader takes from
      // the keyframes (central differences one cell wide, blended by f), against a level sea.
      const auto slope = [&](double ox, double oy) {
        const auto at = [&](const Raster<float>& eta) {
          return (bilinear(eta, dx, px + ox, py + oy) - bilinear(eta, dx, px - ox, py - oy)) / (2 * dx);
        };
        return (1 - f) * at(baked.harbour_from->surface_elevation_m) + f * at(baked.harbour_to->surface_elevation_m);
      };
      playback::SurfacePoint point;
      point.to_eye = {-ray[0], -ray[1], -ray[2]};
      point.water_depth_m = bilinear(site.harbour.still_water_depth_m, dx, px, py);
      const double level_luminance = display_luminance(playback::to_display(frame, playback::shade_water(frame, point)));
      point.normal = unit({-slope(dx, 0), -slope(0, dx), 1.0});
      const double sloped_luminance = display_luminance(playback::to_display(frame, playback::shade_water(frame, point)));
      const double change = std::abs(display_luminance(baked_image.get(x, y)) - display_luminance(calm_image.get(x, y)));
      predicted += std::abs(sloped_luminance - level_luminance);
      measured += change;
      level += level_luminance;
      ++water_pixels;
      // Where the bake says the sea is open (K >= 0.8, south of the entrance) or sheltered (K <=
      // 0.5, in the basin north of it): the short waves' texture (neighbouring pixels' difference)
      // and what the baked field changes.
      const double k = site.relative_wave_height(i, j);
      Region* region = py < 630 && k >= 0.8 ? &approach : py > 680 && k <= 0.5 ? &basin : nullptr;
      if (!region) continue;
      region->texture += std::abs(display_luminance(baked_image.get(x, y)) - display_luminance(baked_image.get(x + 1, y)));
      region->change += change;
      ++region->count;
    }
  ASSERT_GT(water_pixels, 20000);
  ASSERT_GT(approach.count, 2000);
  ASSERT_GT(basin.count, 2000);
  measured /= water_pixels, predicted /= water_pixels, level /= water_pixels;
  std::printf("harbour water: %d pixels, mean display luminance %.3f; baked vs still: measured %.4f, the slopes predict %.4f\n",
              water_pixels, level, measured, predicted);
  std::printf("approach (K >= 0.8): %d pixels, texture %.4f, change %.4f; basin (K <= 0.5): %d pixels, texture %.4f, change %.4f\n",
              approach.count, approach.texture / approach.count, approach.change / approach.count, basin.count,
              basin.texture / basin.count, basin.change / basin.count);
  // The picture changes by at least half of what the baked slopes alone predict through the BRDF:
  // the rest of the renderer (the short waves' normals laid over them, the vertices moved by the
  // baked heights, 8-bit output) may blur it, never hide it. And the prediction is no rounding
  // noise: over 1 % of the water's luminance.
  EXPECT_GT(predicted, 0.01 * level);
  EXPECT_GE(measured, 0.5 * predicted);
  // Calmer where the bake is calmer: the basin's short-wave texture and its baked change are both
  // smaller than the approach's (K <= 0.5 against >= 0.8: at most 0.6 of the slopes).
  EXPECT_LT(basin.texture / basin.count, approach.texture / approach.count);
  EXPECT_LT(basin.change / basin.count, approach.change / approach.count);
}

TEST(DemoHarbourOnScreen, StructureFacesFoamWhereTheBakedRunUpPassesTheAirEntrainmentOnset) {
  // Foam at breakwaters and quays from the baked field (docs/lighting.md step 7): at every water
  // cell beside a structure, over 48 keyframes, the baked d eta / dt gives the speed of the water
  // along the face (|w| / 0.555 up and down a 1:1.5 rubble slope, w up a vertical wall) and
  // playback::structure_foam the white water from the onset of air entrainment (1 m/s). The
  // exposed rubble faces (the approach's swell, K >= 0.8) must foam at some waves, more often
  // than the sheltered faces (K <= 0.5); then the picture of the frame with the most face foam,
  // seen from a low bridge, must turn white next to the structures and nowhere else.
  const fs::path folder = demo_bake_folder();
  ASSERT_TRUE(fs::exists(folder / "manifest.json")) << folder << " holds no bake (fixture demo_harbour_bake)";
  runtime::StreamingOptions options;
  options.lockstep = true;
  runtime::StreamingEngine engine(folder, options);
  engine.advance_to(0.0);
  const auto site_pointer = engine.snapshot().site;
  ASSERT_TRUE(site_pointer);
  const runtime::HarbourSite& site = *site_pointer;
  const GridGeometry& g = site.harbour.geometry;
  const double dx = g.spacing_m, interval = site.frame_interval_s;
  ASSERT_GT(interval, 0.0);
  playback::Lighting lighting;
  const playback::LightingFrame frame = playback::prepare_lighting(lighting);
  const auto is_structure = [&](int i, int j) {
    return i >= 0 && j >= 0 && i < g.columns && j < g.rows && site.harbour.porosity(i, j) < 0.99f;
  };
  struct Face {
    int i, j;
    double sine, k;
  };
  std::vector<Face> faces;  // water cells with a structure among their eight neighbours
  int rubble = 0, vertical = 0;
  for (int j = 0; j < g.rows; ++j)
    for (int i = 0; i < g.columns; ++i) {
      if (is_structure(i, j) || site.harbour.land(i, j) != 0 || site.harbour.still_water_depth_m(i, j) <= 0.5f) continue;
      float porosity = 1.f;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
          if ((di == 0) != (dj == 0) && is_structure(i + di, j + dj)) porosity = std::min(porosity, site.harbour.porosity(i + di, j + dj));
      if (porosity >= 0.99f) continue;  // a face across a corner only: skipped (the shader takes those too)
      const double sine = porosity >= playback::kVerticalFacePorosity ? 1.0 : playback::kRubbleMoundFaceSine;
      (sine < 1.0 ? rubble : vertical) += 1;
      faces.push_back({i, j, sine, site.relative_wave_height.empty() ? 1.0 : double(site.relative_wave_height(i, j))});
    }
  ASSERT_GT(rubble, 50) << "rubble faces on the demo's breakwaters";
  // The keyframes one after another: at a keyframe's own time the shader's rate is its rate.
  struct Share {
    int samples = 0, foaming = 0;
    double peak_speed = 0;
  } exposed, sheltered, walls;
  double best_foam = -1, best_time = 0, best_cell_foam = -1;
  int best_i = 0, best_j = 0;
  for (int k = 0; k < 48; ++k) {
    const double t = 60.0 + k * interval;
    engine.advance_to(t);
    const runtime::SurfaceSnapshot snapshot = engine.snapshot();
    ASSERT_TRUE(snapshot.harbour_from);
    const runtime::HarbourKeyframe& key = snapshot.harbour_fraction < 0.5 ? *snapshot.harbour_from : *snapshot.harbour_to;
    ASSERT_FALSE(key.surface_elevation_rate_m_s.empty()) << "the bake's keyframes carry d eta / dt";
    double frame_foam = 0;
    for (const Face& face : faces) {
      const double rate = key.surface_elevation_rate_m_s(face.i, face.j);
      // the pixel at the cell's centre, half a cell from the face, band one cell
      const double foam = playback::structure_foam(frame, rate, face.sine, 0.5 * dx, dx);
      Share& share = face.sine >= 1.0 ? walls : face.k >= 0.8 ? exposed : face.k <= 0.5 ? sheltered : walls;
      if (face.sine < 1.0 && face.k > 0.5 && face.k < 0.8) continue;  // neither
      ++share.samples;
      share.foaming += foam > 0.0;
      share.peak_speed = std::max(share.peak_speed, std::abs(rate) / face.sine);
      if (face.sine < 1.0) frame_foam += foam;
      if (foam > best_cell_foam) best_cell_foam = foam, best_i = face.i, best_j = face.j;
    }
    if (frame_foam > best_foam) best_foam = frame_foam, best_time = t;
  }
  auto report = [](const char* name, const Share& s) {
    std::printf("%s: %d cell-frames, foaming %.1f %%, fastest along the face %.2f m/s\n", name, s.samples,
                s.samples ? 100.0 * s.foaming / s.samples : 0.0, s.peak_speed);
  };
  std::printf("faces: %d rubble, %d vertical (%.0f m cells), keyframes every %.2f s\n", rubble, vertical, dx, interval);
  report("exposed rubble faces (K >= 0.8)", exposed);
  report("sheltered rubble faces (K <= 0.5)", sheltered);
  report("vertical faces and the rest", walls);
  ASSERT_GT(exposed.samples, 0);
  ASSERT_GT(sheltered.samples, 0);
  const double exposed_share = double(exposed.foaming) / exposed.samples, sheltered_share = double(sheltered.foaming) / sheltered.samples;
  // What the physics says of the demo's sea (a 1.5 m, 12 s swell): on a 1:1.5 slope its Iribarren
  // number tan(alpha) / sqrt(H / L0) = 0.667 / sqrt(1.5 / 225) = 8.2 is far into surging (beyond
  // 3.3: Battjes 1974), the wave runs up and down the armour without breaking, so the faces whiten
  // only at the biggest waves where the exposed faces' flow passes the onset, and the sheltered
  // faces (at most half the wave) never; the vertical quay in the basin neither.
  EXPECT_GT(exposed.foaming, 0) << "no exposed face ever foams";
  EXPECT_LT(exposed_share, 0.1);
  EXPECT_LT(sheltered_share, exposed_share);
  EXPECT_EQ(walls.foaming, 0);

  // On screen: the frame with the most face foam, from a 15 m bridge 120 m south of the face that
  // foams most, looking at it, with the face foam and without it (onset infinite).
  engine.advance_to(best_time);
  const runtime::SurfaceSnapshot snapshot = engine.snapshot();
  playback::Camera camera;
  camera.target_m = {(best_i + 0.5) * dx, (best_j + 0.5) * dx, 0.0};
  camera.eye_m = {camera.target_m[0], camera.target_m[1] - 120.0, 15.0};
  std::printf("most foam: %.2f at the face cell (%.0f, %.0f) m at t = %.1f s\n", best_cell_foam, camera.target_m[0],
              camera.target_m[1], best_time);
  camera.vertical_field_of_view_deg = 45.0;
  const int width = 480, height = 270;
  playback::GlWindow window(64, 64, "test", false);
  playback::WaterRenderer renderer;
  renderer.render(snapshot, camera, lighting, width, height);
  const Image foamed = renderer.read_pixels();
  playback::Lighting without_face_foam = lighting;
  without_face_foam.structure_foam_onset_m_s = std::numeric_limits<double>::infinity();
  renderer.render(snapshot, camera, without_face_foam, width, height);
  const Image plain = renderer.read_pixels();
  const playback::CameraView view = playback::camera_view(camera, width, height, 1.0, 1e4);
  const auto inverse = playback::inverse(view.view_projection);
  int changed = 0, changed_near_structures = 0;
  double largest = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double difference = display_luminance(foamed.get(x, y)) - display_luminance(plain.get(x, y));
      largest = std::max(largest, std::abs(difference));
      if (std::abs(difference) <= 1.0 / 255) continue;
      ++changed;
      const double ndc_x = (x + 0.5) / width * 2 - 1, ndc_y = 1 - (y + 0.5) / height * 2;
      const auto far = playback::transform(inverse, {ndc_x, ndc_y, 1.0, 1.0});
      const Vector3 ray = unit({far[0] / far[3] - camera.eye_m[0], far[1] / far[3] - camera.eye_m[1], far[2] / far[3] - camera.eye_m[2]});
      if (ray[2] >= 0) continue;
      const double t = -camera.eye_m[2] / ray[2];
      const int i = int((camera.eye_m[0] + t * ray[0]) / dx), j = int((camera.eye_m[1] + t * ray[1]) / dx);
      bool near = false;  // a structure within two cells (the waves move the drawn point by up to a cell)
      for (int dj = -2; dj <= 2; ++dj)
        for (int di = -2; di <= 2; ++di) near = near || is_structure(i + di, j + dj);
      changed_near_structures += near;
    }
  std::printf("on screen: %d pixels changed by the face foam (%d of them within two cells of a structure), at most %.3f in luminance\n",
              changed, changed_near_structures, largest);
  // The face foam the bake asks for at that frame is thin (its largest is printed above): it
  // shows, and only beside the structures.
  EXPECT_GE(changed, 10) << "the face foam on screen";
  EXPECT_GE(changed_near_structures, 0.95 * changed) << "face foam away from the structures";
}

}  // namespace
}  // namespace nearshore
