// Rendered pictures of the three grids on Mesa llvmpipe: the quadtree has no gap pixels across its
// level boundaries, the radial and projected grids put the horizon where the camera geometry says,
// identical inputs give identical images, and keyframes stream within the upload budget.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>

#include "nearshore/playback/slope_moments.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/plot/plot.hpp"
#include "flat_sea_probes.hpp"
#include "snapshot_fixtures.hpp"

namespace {
using namespace nearshore;
using namespace nearshore::playback;

using test::first_water_rows;
using test::flat_options;
using test::is_water;

// Row (from the top, continuous: the edge between rows y-1 and y is y) of a normalised device y.
double row_of(double ndc_y, int height) { return 0.5 * (1.0 - ndc_y) * height; }

// Deep water alone (no site: choppiness 1), two cascades, blended 40 % of the way.
runtime::SurfaceSnapshot open_sea(int force) {
  runtime::SurfaceSnapshot snapshot;
  const test::DeepPair deep = test::make_deep_pair(force, {61.0, 13.0}, 64, 2.0, 2.5, 100);
  snapshot.deep_from = deep.from;
  snapshot.deep_to = deep.to;
  snapshot.deep_fraction = 0.4;
  return snapshot;
}

runtime::SurfaceSnapshot harbour_scene(double choppiness) {
  test::SiteOptions options;
  options.choppiness = choppiness;
  runtime::SurfaceSnapshot snapshot = open_sea(5);
  snapshot.site = test::make_site(options);
  snapshot.harbour_from = test::make_harbour_keyframe(*snapshot.site, 0, 1);
  snapshot.harbour_to = test::make_harbour_keyframe(*snapshot.site, 1, 2);
  snapshot.harbour_fraction = 0.3;
  return snapshot;
}

std::filesystem::path picture_folder() {
  const auto folder = std::filesystem::path(NEARSHORE_BINARY_DIR) / "playback-pictures";
  std::filesystem::create_directories(folder);
  return folder;
}
}  // namespace

TEST(QuadtreeRender, NoGapPixelsAcrossLevelBoundaries) {
  GlWindow window(64, 64, "test", false);
  RendererSettings settings;
  settings.grid = GridKind::quadtree;
  settings.quadtree.finest_spacing_m = 0.25;
  settings.quadtree.patch_quads = 8;
  settings.quadtree.screen_error_px = 3.0;
  WaterRenderer renderer(settings);
  // A choppy deep sea (every vertex displaced, horizontally too), seen from 25 m looking down
  // 15 degrees: the screen below the horizon crosses many level boundaries.
  const runtime::SurfaceSnapshot snapshot = open_sea(6);
  Camera camera;
  camera.eye_m = {10.3, -5.7, 25.0};
  const double pitch = 15.0 * std::numbers::pi / 180;
  camera.target_m = {10.3 + 100 * std::sin(0.3) * std::cos(pitch), -5.7 + 100 * std::cos(0.3) * std::cos(pitch),
                     25.0 - 100 * std::sin(pitch)};
  const int width = 256, height = 192;
  renderer.render(snapshot, camera, Lighting{}, width, height, flat_options());
  const Image image = renderer.read_pixels();
  // Several levels are on screen, and the join between them is where cracks would open.
  const CameraView view = camera_view(camera, width, height, renderer.last_frame().near_m, renderer.last_frame().far_m);
  const QuadtreeSelection selection = select_quadtree(settings.quadtree, view);
  std::set<int> levels;
  for (const QuadtreePatch& patch : selection.patches) levels.insert(patch.level);
  EXPECT_GE(levels.size(), 5u);
  EXPECT_EQ(renderer.last_frame().quadtree_patches, int(selection.patches.size()));
  // Below the horizon (flat: tan(pitch) above the centre; the waves and the 100 km reach move
  // it by well under a pixel) plus 3 rows, every pixel is water.
  const double horizon_row = row_of(std::tan(pitch) / std::tan(22.5 * std::numbers::pi / 180), height);
  int gaps = 0, water = 0;
  for (int y = std::max(0, int(std::ceil(horizon_row)) + 3); y < height; ++y)
    for (int x = 0; x < width; ++x) (is_water(image.get(x, y)) ? water : gaps) += 1;
  if (gaps) write_png(image, picture_folder() / "quadtree_gaps.png");
  EXPECT_EQ(gaps, 0) << "of " << water + gaps << " pixels below the horizon; see playback-pictures/quadtree_gaps.png";
  // The LOD-coloured view with the grid's edges, for the eye.
  DrawOptions lod;
  lod.colouring = SurfaceColouring::level_of_detail;
  lod.wireframe = true;
  renderer.render(snapshot, camera, Lighting{}, width, height, lod);
  write_png(renderer.read_pixels(), picture_folder() / "quadtree_lod_test.png");
}

TEST(FlatGridsRender, HorizonIsWhereTheCameraSays) {
  GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = open_sea(3);
  for (GridKind kind : {GridKind::radial, GridKind::quadtree}) {
    RendererSettings settings;
    settings.grid = kind;
    WaterRenderer renderer(settings);
    // 20 m up, looking 6 degrees down: the flat horizon lies tan(6 deg) / tan(22.5 deg) of the
    // half-height above the centre row; the grid's end at 100 km dips it by atan(20 / 1e5),
    // 0.011 degree (0.03 pixel).
    Camera camera;
    camera.eye_m = {120.0, 80.0, 20.0};
    const double pitch = 6.0 * std::numbers::pi / 180;
    camera.target_m = {120.0 + 100 * std::cos(pitch), 80.0, 20.0 - 100 * std::sin(pitch)};
    const int width = 160, height = 240;
    renderer.render(snapshot, camera, Lighting{}, width, height, flat_options());
    const double expected = row_of(std::tan(pitch) / std::tan(22.5 * std::numbers::pi / 180), height);
    const std::vector<int> rows = first_water_rows(renderer.read_pixels());
    for (int x = 0; x < width; ++x)
      ASSERT_NEAR(rows[std::size_t(x)], expected, 1.5) << grid_kind_name(kind) << " column " << x;
    EXPECT_GT(renderer.last_frame().vertices_drawn, 1000);
  }
}

TEST(ProjectedRender, HorizonDipsAsTheSphereSaysFromTenKilometres) {
  GlWindow window(64, 64, "test", false);
  RendererSettings settings;
  settings.grid = GridKind::projected;
  WaterRenderer renderer(settings);
  const runtime::SurfaceSnapshot snapshot = open_sea(4);
  // 10 km up, looking horizontally: the sphere's horizon is acos(R / (R + h)) = 3.2 degrees down.
  // Through screen column ndc_x a ray dips by that angle at ndc_y = -tan(dip) sqrt(1 + (ndc_x t
  // a)^2) / t (t = tan(fov / 2), a = aspect): a conic, lowest at the edges.
  const double h = 10000.0;
  Camera camera;
  camera.eye_m = {0.0, 0.0, h};
  camera.target_m = {0.0, 1000.0, h};
  const int width = 200, height = 240;
  renderer.render(snapshot, camera, Lighting{}, width, height, flat_options());
  const double dip = horizon_dip_rad(h, kEarthRadiusM);
  EXPECT_NEAR(dip * 180 / std::numbers::pi, 3.2, 0.01);
  const double t = std::tan(22.5 * std::numbers::pi / 180), aspect = double(width) / height;
  const std::vector<int> rows = first_water_rows(renderer.read_pixels());
  for (int x = 0; x < width; ++x) {
    const double ndc_x = (x + 0.5) / width * 2 - 1;
    const double expected = row_of(-std::tan(dip) * std::sqrt(1 + std::pow(ndc_x * t * aspect, 2)) / t, height);
    ASSERT_NEAR(rows[std::size_t(x)], expected, 1.5) << "column " << x;
  }
  // A flat sea would reach the horizontal (the centre row): the dip is 0.056 / 0.414 of the half
  // height, 16 rows here.
  EXPECT_GT(rows[100], row_of(0.0, height) + 14);
  EXPECT_GT(renderer.last_frame().vertices_drawn, 1000);
}

TEST(Render, IdenticalInputsGiveIdenticalImages) {
  GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = harbour_scene(1.0);
  const Camera camera = Camera::overlooking_site(snapshot.site->width_m, snapshot.site->height_m);
  for (GridKind kind : {GridKind::radial, GridKind::quadtree, GridKind::projected}) {
    RendererSettings settings;
    settings.grid = kind;
    std::vector<float> first;
    for (int attempt = 0; attempt < 2; ++attempt) {
      WaterRenderer renderer(settings);
      renderer.render(snapshot, camera, Lighting{}, 128, 80);
      renderer.render(snapshot, camera, Lighting{}, 128, 80);  // a second draw of the same renderer, too
      const Image image = renderer.read_pixels();
      if (attempt == 0)
        first = image.pixels();
      else
        EXPECT_TRUE(image.pixels() == first) << grid_kind_name(kind) << ": two renders of one snapshot differ";
    }
  }
}

TEST(Render, StagedKeyframesUploadWithinTheBudget) {
  GlWindow window(64, 64, "test", false);
  test::SiteOptions options;
  options.columns = 256;
  options.rows = 128;
  options.spacing_m = 1.0;
  runtime::SurfaceSnapshot snapshot;
  snapshot.site = test::make_site(options);
  snapshot.harbour_from = snapshot.harbour_to = test::make_harbour_keyframe(*snapshot.site, 0, 1);
  RendererSettings settings;
  settings.grid = GridKind::radial;
  settings.upload_budget_bytes_per_frame = 32 * 1024;
  WaterRenderer renderer(settings);
  const Camera camera = Camera::overlooking_site(256, 128);
  renderer.render(snapshot, camera, Lighting{}, 32, 24);
  // The first frame needs its keyframe whole: forced (eta, breaking and d eta / dt, 256 x 128 x 4
  // bytes each, and the slope moments' mip levels, 16 bytes a texel: slope_moments.hpp).
  std::size_t moment_bytes = 0;
  for (const auto& level : playback::slope_moment_pyramid(snapshot.harbour_from->surface_elevation_m))
    moment_bytes += level.texels.size() * sizeof(float);
  const std::size_t keyframe_bytes = 3 * 256 * 128 * 4 + moment_bytes;
  EXPECT_EQ(renderer.last_frame().forced_upload_bytes, keyframe_bytes);
  // The next keyframe, staged, goes up in row chunks of at most the budget...
  const auto next = test::make_harbour_keyframe(*snapshot.site, 1, 2);
  EXPECT_TRUE(renderer.stage(next));
  EXPECT_FALSE(renderer.stage(next)) << "queued once";
  std::size_t sent = 0;
  int frames = 0;
  for (; sent < keyframe_bytes && frames < 100; ++frames) {
    renderer.render(snapshot, camera, Lighting{}, 32, 24);
    EXPECT_LE(renderer.last_frame().upload_bytes, settings.upload_budget_bytes_per_frame);
    EXPECT_EQ(renderer.last_frame().forced_upload_bytes, 0u);
    sent += renderer.last_frame().upload_bytes;
  }
  EXPECT_EQ(sent, keyframe_bytes);
  // every frame full but the last (the rows of each field and level divide the budget)
  EXPECT_EQ(frames, int((keyframe_bytes + settings.upload_budget_bytes_per_frame - 1) / settings.upload_budget_bytes_per_frame));
  // ...so when a snapshot shows it, nothing more is sent, and nothing at all once both are up.
  snapshot.harbour_to = next;
  snapshot.harbour_fraction = 0.5;
  renderer.render(snapshot, camera, Lighting{}, 32, 24);
  EXPECT_EQ(renderer.last_frame().upload_bytes, 0u);
  EXPECT_FALSE(renderer.stage(next)) << "already on the GPU";
}

// Not a check: the pictures of docs/rendering.md (build/.../playback-pictures/grid_*.png).
TEST(GridPictures, WritesTheDocumentationPictures) {
  GlWindow window(64, 64, "test", false);
  const runtime::SurfaceSnapshot snapshot = harbour_scene(1.0);
  Camera low;
  low.eye_m = {-60.0, -90.0, 70.0};
  low.target_m = {150.0, 120.0, 0.0};
  DrawOptions lod;
  lod.colouring = SurfaceColouring::level_of_detail;
  lod.wireframe = true;
  const int width = 480, height = 270;
  for (GridKind kind : {GridKind::radial, GridKind::quadtree}) {
    RendererSettings settings;
    settings.grid = kind;
    settings.radial.segment_count = 96;  // coarse enough to see in a small picture
    settings.radial.inner_spacing_m = 2.0;
    settings.quadtree.screen_error_px = 12.0;
    settings.quadtree.patch_quads = 8;
    WaterRenderer renderer(settings);
    renderer.render(snapshot, low, Lighting{}, width, height);
    write_png(renderer.read_pixels(), picture_folder() / ("grid_" + std::string(grid_kind_name(kind)) + "_lit.png"));
    renderer.render(snapshot, low, Lighting{}, width, height, lod);
    write_png(renderer.read_pixels(), picture_folder() / ("grid_" + std::string(grid_kind_name(kind)) + "_wire.png"));
  }
  RendererSettings settings;
  settings.grid = GridKind::projected;
  settings.projected.vertex_spacing_px = 8.0;
  WaterRenderer renderer(settings);
  Camera high;
  high.eye_m = {100.0, -3000.0, 8000.0};
  high.target_m = {100.0, 60000.0, 0.0};
  renderer.render(snapshot, high, Lighting{}, width, height);
  write_png(renderer.read_pixels(), picture_folder() / "grid_projected_lit.png");
  renderer.render(snapshot, high, Lighting{}, width, height, lod);
  write_png(renderer.read_pixels(), picture_folder() / "grid_projected_wire.png");
}
