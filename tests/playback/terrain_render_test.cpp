// The terrain on Mesa: the shore drawn where the bilinear depth crosses still water (not the
// cells' staircase), a breakwater's crest drawn at its crest elevation, and the land continuing
// past the grid's edge (no cut-off slab with the open sea beyond). The sea is drawn in a flat
// magenta, the terrain lit, no sky (black), so each pixel says what it shows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "nearshore/playback/site_terrain.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"
#include "surroundings_fixture.hpp"

namespace nearshore {
namespace {
using playback::Camera;

constexpr double kOriginX = 386128.0, kOriginY = 4306447.0;  // projected: the site frame must not care

// A still harbour (no keyframes, no deep water: flat still water) on `harbour`.
runtime::SurfaceSnapshot still_site(const HarbourGrid& harbour) {
  auto site = std::make_shared<runtime::HarbourSite>();
  site->harbour = harbour;
  site->width_m = harbour.geometry.width_m();
  site->height_m = harbour.geometry.height_m();
  site->source_axis = 1;
  site->inward_sign = 1.0;
  site->blend_width_m = 20.0;
  site->edge_fade_m = 20.0;
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = site;
  return snapshot;
}

HarbourGrid grid(int columns, int rows, double spacing_m) {
  GridGeometry g;
  g.columns = columns;
  g.rows = rows;
  g.spacing_m = spacing_m;
  g.origin_x_m = kOriginX;
  g.origin_y_m = kOriginY;
  return HarbourGrid::open_water(g, 8.f);
}

struct Picture {
  Image image;
  playback::CameraView view;
};

// `harbour` still, seen from `eye` towards `target`: the sea flat magenta, no sky (black).
Picture look(const HarbourGrid& harbour, const playback::Vector3& eye, const playback::Vector3& target,
             double field_of_view_deg, int width, int height) {
  const runtime::SurfaceSnapshot snapshot = still_site(harbour);
  Camera camera;
  camera.eye_m = eye;
  camera.target_m = target;
  camera.vertical_field_of_view_deg = field_of_view_deg;
  playback::WaterRenderer renderer;
  playback::DrawOptions options;
  options.colouring = playback::SurfaceColouring::flat;
  options.flat_colour = {1.f, 0.f, 1.f};
  options.sky = false;
  renderer.render(snapshot, camera, playback::Lighting{}, width, height, options);
  const auto& frame = renderer.last_frame();
  return {renderer.read_pixels(), playback::camera_view(camera, width, height, frame.near_m, frame.far_m)};
}

bool is_sea(const Rgb& c) { return c[0] > 0.9f && c[1] < 0.1f && c[2] > 0.9f; }
bool is_background(const Rgb& c) { return c[0] + c[1] + c[2] < 0.01f; }

// Where the ray through the normalised device point (ndc_x, ndc_y) reaches `value` on site axis
// `axis` (0 x, 1 y, 2 z).
std::array<double, 3> ray_at(const playback::CameraView& view, double ndc_x, double ndc_y, int axis, double value) {
  const playback::Matrix4 unproject = playback::inverse(view.view_projection);
  auto a = playback::transform(unproject, {ndc_x, ndc_y, -1, 1}), b = playback::transform(unproject, {ndc_x, ndc_y, 1, 1});
  for (auto* p : {&a, &b})
    for (int k = 0; k < 3; ++k) (*p)[std::size_t(k)] /= (*p)[3];
  const auto k = std::size_t(axis);
  const double s = (value - a[k]) / (b[k] - a[k]);
  return {a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])};
}

// Where the ray through pixel (x + 0.5, y + 0.5) (row 0 at the top) meets the plane z = z_m.
std::array<double, 3> on_plane(const playback::CameraView& view, double x, double y, double z_m) {
  return ray_at(view, (x + 0.5) / view.width_px * 2 - 1, 1 - (y + 0.5) / view.height_px * 2, 2, z_m);
}

// The pixel (column, row from the top) a site point projects to.
std::array<double, 2> pixel_of(const playback::CameraView& view, double x, double y, double z) {
  const auto clip = playback::transform(view.view_projection, {x, y, z, 1.0});
  return {(clip[0] / clip[3] + 1) / 2 * view.width_px - 0.5, (1 - clip[1] / clip[3]) / 2 * view.height_px - 0.5};
}

}  // namespace

// A coast along the diagonal x + y = 258 m of a grid of 4 m cells, off the cells' diagonals (so a
// mask cell by cell would show its teeth): the depth is linear across it (0.05 (258 - x - y),
// land beyond), so the bilinear depth's zero contour is that straight line. Seen from straight
// above at 0.5 m a pixel, the drawn water's edge (the last magenta pixel of each row) lies on a
// straight line within 0.6 m (0.15 cell); with the land masked per cell as before, 0.80 m.
TEST(TerrainRender, ADiagonalShoreIsDrawnStraightNotAsTheCellsStaircase) {
  playback::GlWindow window(64, 64, "test", false);
  HarbourGrid h = grid(64, 64, 4.0);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const double x = (i + 0.5) * 4.0, y = (j + 0.5) * 4.0;
      const float depth = float(0.05 * (258.0 - x - y));
      h.still_water_depth_m(i, j) = depth;
      h.land(i, j) = depth < 0 ? kLandCell : kWaterCell;
      h.coast_distance_m(i, j) = float((258.0 - x - y) / std::sqrt(2.0));
    }
  const int size = 256;  // 128 m across: 0.5 m a pixel
  const Picture picture = look(h, {128.0, 128.0 - 0.01, 3000.0}, {128.0, 128.0, 0.0},
                               2.0 * std::atan(64.0 / 3000.0) * 180 / M_PI, size, size);
  std::vector<double> offsets_m;
  for (int y = 8; y < size - 8; ++y) {
    int last_sea = -1;
    for (int x = 0; x < size; ++x)
      if (is_sea(picture.image.get(x, y))) last_sea = x;
    ASSERT_GT(last_sea, 0) << "row " << y;
    ASSERT_LT(last_sea, size - 1) << "row " << y << ": no land";
    for (int x = last_sea + 1; x < size; ++x)
      ASSERT_FALSE(is_sea(picture.image.get(x, y)) || is_background(picture.image.get(x, y)))
          << "row " << y << ", column " << x << ": sea or nothing inside the land";
    const auto p = on_plane(picture.view, last_sea + 0.5, y, 0.0);  // the edge between the two pixels
    offsets_m.push_back((p[0] + p[1] - 258.0) / std::sqrt(2.0));
  }
  double mean = 0;
  for (double d : offsets_m) mean += d / double(offsets_m.size());
  double largest = 0;
  for (double d : offsets_m) largest = std::max(largest, std::abs(d - mean));
  EXPECT_LT(std::abs(mean), 1.0) << "the shore's mean offset from the zero contour, m";
  EXPECT_LT(largest, 0.6) << "the drawn shore's largest departure from a straight line, m (a cell is 4 m)";
  std::printf("diagonal shore: mean offset %.3f m, largest departure %.3f m over %zu rows\n", mean, largest,
              offsets_m.size());
}

// A rubble breakwater from the chart (a centre line, crest 3.2 m above still water, 8 m wide,
// faces 1:1.5) in 8 m of water, seen side-on from 1 m above the water 76 m from its near crest
// edge: the top of its silhouette is the crest's near edge at 3.2 m, within 3 cm (2 pixels).
TEST(TerrainRender, ABreakwatersCrestIsDrawnAtItsCrestElevation) {
  playback::GlWindow window(64, 64, "test", false);
  HarbourGrid h = grid(64, 48, 4.0);
  CoastalStructure breakwater;
  breakwater.name = "test breakwater";
  breakwater.kind = "rubble_mound_breakwater";
  breakwater.lines = {{{kOriginX + 40.0, kOriginY + 100.0}, {kOriginX + 216.0, kOriginY + 100.0}}};
  breakwater.crest_width_m = 8.0;
  breakwater.crest_elevation_m = 3.2;
  breakwater.side_slope = 1.5;
  h.structures = {breakwater};
  for (int i = 10; i < 54; ++i) h.porosity(i, 25) = 0.4f;  // what the bake burns (not drawn from)
  const int width = 320, height = 480;
  const Picture picture = look(h, {128.0, 20.0, 1.0}, {128.0, 100.0, 1.0}, 6.0, width, height);
  const int x = width / 2;
  int top = -1;
  for (int y = 0; y < height && top < 0; ++y)
    if (!is_background(picture.image.get(x, y))) top = y;
  ASSERT_GE(top, 0);
  EXPECT_FALSE(is_sea(picture.image.get(x, top))) << "the silhouette's top is the structure, not the sea";
  const double expected_row = pixel_of(picture.view, 128.0, 96.0, 3.2)[1];
  // The crest's elevation the top row shows: where the ray through the row's upper edge meets
  // the plane of the near crest edge (y = 96 m).
  const double crest_seen_m = ray_at(picture.view, 0.0, 1 - double(top) / height * 2, 1, 96.0)[2];
  EXPECT_NEAR(crest_seen_m, 3.2, 0.03) << "rows: top " << top << ", the crest's " << expected_row;
  std::printf("breakwater crest drawn at %.3f m (3.2 m charted), silhouette row %d, expected %.1f\n", crest_seen_m,
              top, expected_row);
}

// Land along the grid's whole north edge (2.5 m up, a sloping beach south of it), seen from 8 m
// inside the harbour looking north past the edge: the ground 10, 50, 200 and 800 m beyond the
// edge is drawn as land (lit terrain), neither the open sea nor nothing.
TEST(TerrainRender, TheLandContinuesPastTheGridsEdge) {
  playback::GlWindow window(64, 64, "test", false);
  HarbourGrid h = grid(64, 48, 4.0);
  for (int j = 0; j < 48; ++j)
    for (int i = 0; i < 64; ++i) {
      const double y = (j + 0.5) * 4.0;
      const float depth = float(std::clamp(0.08 * (150.0 - y), -2.5, 6.0));
      h.still_water_depth_m(i, j) = depth;
      h.land(i, j) = depth < 0 ? kLandCell : kWaterCell;
      h.coast_distance_m(i, j) = float(150.0 - y);
    }
  const int width = 640, height = 360;
  const Picture picture = look(h, {128.0, 40.0, 8.0}, {128.0, 400.0, 0.0}, 30.0, width, height);
  // out to the horizon: 3, 10 and 40 km beyond, where the skirt's land used to sink under a grey
  // band of sea (docs/images/terrain-tacoma-after.png); the sea is not drawn over it (surface.glsl
  // on_skirt_land)
  for (double beyond_m : {10.0, 50.0, 200.0, 800.0, 3000.0, 10000.0, 40000.0})
    for (double x_m : {60.0, 128.0, 200.0}) {
      const auto pixel = pixel_of(picture.view, x_m, 192.0 + beyond_m, 2.5);
      const int px = int(std::lround(pixel[0])), py = int(std::lround(pixel[1]));
      ASSERT_TRUE(px >= 0 && px < width && py >= 0 && py < height) << beyond_m << " m beyond";
      const Rgb c = picture.image.get(px, py);
      EXPECT_FALSE(is_sea(c)) << x_m << " m east, " << beyond_m << " m beyond the north edge: the open sea";
      EXPECT_FALSE(is_background(c)) << x_m << " m east, " << beyond_m << " m beyond the north edge: nothing";
    }
}

// Issue 41: the surroundings on Mesa. An all-water grid (8 m) inside surroundings of 10 m cells
// holding an island 3 m high (a disc of 50 m radius) 150 m south of it, two reefs one cell wide
// (3 m up) across them, and no data east of x = 450 m. Seen from straight above (about 1.1 m a
// pixel), each pixel shows land where the CPU twin (playback::skirt_ground_m with the same
// SurroundingGround) puts the ground above still water and the sea where it puts it below (pixels
// within 0.3 m of still water are not judged), on at least 99.9 % of the pixels (measured: 13
// of 129 482 differ). The reefs are narrower than the skirt's mesh resolves, so along them the
// mesh stays under water where the twin stands above it: only the shader's own twin (surface.glsl
// skirt_ground_m, on_skirt_land: no sea drawn on the skirt's land) shows them; with its
// surroundings term removed, 850 pixels differ. Without the surroundings the view is all sea.
TEST(TerrainRender, AnIslandInTheSurroundingsIsDrawnWhereTheTwinPutsIt) {
  playback::GlWindow window(64, 64, "test", false);
  HarbourGrid h = grid(64, 48, 4.0);
  h.surroundings = test::surroundings_round(h.geometry, 10.0, 300.0, [](double x, double y) {
    const int i = int(std::floor((x + 300.0) / 10.0)), j = int(std::floor((y + 300.0) / 10.0));
    if (i == 40 || j == 5) return -3.0;  // two reefs one cell wide
    return x > 450.0 ? NAN : std::clamp(0.2 * (std::hypot(x - 128.0, y + 150.0) - 50.0), -3.0, 8.0);
  });
  const playback::SurroundingGround ground = playback::surrounding_ground(h);
  const double open_sea_depth_m = 8.0;  // SiteTextures: the deepest edge depth, at least 5 m
  const int width = 512, height = 256;
  const playback::Vector3 eye{250.0, -150.0 - 0.01, 3000.0}, target{250.0, -150.0, 0.0};
  const double field_of_view_deg = 2.0 * std::atan(140.0 / 3000.0) * 180 / M_PI;
  const Picture picture = look(h, eye, target, field_of_view_deg, width, height);
  int judged = 0, disagree = 0, land = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const auto p = on_plane(picture.view, x, y, 0.0);
      const double twin = playback::skirt_ground_m(h, ground, open_sea_depth_m, p[0], p[1]);
      if (std::abs(twin) < 0.3 || (p[0] >= 0 && p[0] <= 256 && p[1] >= 0 && p[1] <= 192)) continue;
      const Rgb c = picture.image.get(x, y);
      ASSERT_FALSE(is_background(c)) << "nothing drawn at (" << p[0] << ", " << p[1] << ")";
      ++judged;
      land += twin > 0;
      disagree += is_sea(c) != (twin < 0);
    }
  // The island's disc above 0.3 m (radius 48.5 m, 7400 m^2, about 6000 pixels of 1.1 m) and the reefs.
  EXPECT_GT(land, 6000);
  EXPECT_GT(judged, width * height / 2);
  EXPECT_LE(disagree, judged / 1000) << disagree << " of " << judged << " pixels disagree with the twin";
  std::printf("surroundings island: %d land pixels, %d of %d judged pixels disagree with the CPU twin\n", land, disagree,
              judged);
  HarbourGrid without = h;
  without.surroundings = Surroundings{};
  const Picture before = look(without, eye, target, field_of_view_deg, width, height);
  int not_sea = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) not_sea += !is_sea(before.image.get(x, y));
  EXPECT_EQ(not_sea, 0) << "without surroundings the edge's rule makes open water here";
}

// Far off: the skirt's mesh keeps the surroundings' cells as its steps out to their box's edge, so
// a low island 2.5 m high and 6 km across, 17 to 23 km north of an all-water grid, seen from 100 m
// through a 2 degree lens, is drawn as land (its near half: the far half is hidden by the Earth's
// curvature).
TEST(TerrainRender, AFarLowIslandInTheSurroundingsIsDrawn) {
  playback::GlWindow window(64, 64, "test", false);
  HarbourGrid h = grid(64, 48, 4.0);
  h.surroundings = test::surroundings_round(h.geometry, 200.0, 25872.0, [](double x, double y) {
    return std::clamp(0.01 * (std::hypot(x - 128.0, y - 20000.0) - 3000.0), -2.5, 8.0);
  });
  const int width = 640, height = 360;
  const Picture picture = look(h, {128.0, 40.0, 100.0}, {128.0, 20000.0, 0.0}, 2.0, width, height);
  int land = 0, samples = 0;
  for (double y_m : {17500.0, 18500.0, 19500.0})
    for (double x_m : {-300.0, 128.0, 500.0}) {
      const auto pixel = pixel_of(picture.view, x_m, y_m, 2.5);
      const int px = int(std::lround(pixel[0])), py = int(std::lround(pixel[1]));
      ASSERT_TRUE(px >= 0 && px < width && py >= 0 && py < height) << x_m << ", " << y_m;
      ++samples;
      const Rgb c = picture.image.get(px, py);
      land += !is_sea(c) && !is_background(c);
    }
  EXPECT_EQ(land, samples) << "points of the island drawn as land";
}

}  // namespace nearshore
