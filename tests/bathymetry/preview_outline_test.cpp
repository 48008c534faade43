// Issue 19: a raster input brings no coastline, so the preview draws the gridded depth's still-water
// line in red (still_water_line.hpp). A conical island in a GeoTIFF survey: red around the island
// where depth crosses 0, none in open water and none on the island's top.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "nearshore/bathymetry/geotiff.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/bathymetry/projection.hpp"
#include "nearshore/bathymetry/still_water_line.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/plot/plot.hpp"
#include "test_folder.hpp"

namespace nb = nearshore::bathymetry;
using nearshore::GridGeometry;
using nearshore::Raster;

namespace {

// 100 x 100 cells of 10 m in UTM 51N; the island's centre in the middle; depth -5 m (5 m above
// water) at the centre rising to 0 at r = 100 m and 10 m at r = 300 m and beyond.
constexpr int kCells = 100;
constexpr double kSpacing_m = 10.0, kShoreRadius_m = 100.0;
double island_depth_m(double r_m) { return std::min(10.0, -5.0 + r_m * 5.0 / kShoreRadius_m); }

GridGeometry survey_geometry() {
  GridGeometry g;
  g.columns = kCells;
  g.rows = kCells;
  g.set_spacing(kSpacing_m, kSpacing_m);
  g.origin_x_m = 386000.0;
  g.origin_y_m = 4306000.0;
  g.projection = {{"kind", "utm"}, {"zone", 51}, {"north", true}, {"datum", "WGS84"}};
  g.crs_wkt = nb::crs_wkt(nearshore::MapProjection::utm(51, true));
  return g;
}

struct IslandRun {
  nb::BathyResult result;
  std::filesystem::path out;
  double centre_x_m = 0, centre_y_m = 0;
};

IslandRun bathy_of_island() {
  nearshore::ProgressBar::set_quiet(true);
  const std::filesystem::path folder = fresh_test_folder("");
  const GridGeometry g = survey_geometry();
  IslandRun run;
  run.centre_x_m = g.origin_x_m + g.width_m() / 2;
  run.centre_y_m = g.origin_y_m + g.height_m() / 2;
  Raster<float> depth_m(kCells, kCells);
  for (int row = 0; row < kCells; ++row)
    for (int column = 0; column < kCells; ++column)
      depth_m(column, row) = static_cast<float>(island_depth_m(
          std::hypot(g.cell_centre_x_m(column) - run.centre_x_m, g.cell_centre_y_m(row) - run.centre_y_m)));
  nb::write_depth_geotiff(folder / "island.tif", g, depth_m, "test datum");
  nb::BathyRequest request;
  request.inputs = {folder / "island.tif"};
  request.spacing_m = kSpacing_m;
  // The solver's minimum depth (0.5 m by default) would deepen the first water cells and pull the
  // depth-0 crossing up to half a cell landward; 1 cm keeps the gridded shore where the survey's is.
  request.minimum_depth_m = 0.01;
  run.result = nb::build_harbour_grid(request);
  run.out = folder / "out";
  nb::write_bathymetry_outputs(run.out, run.result);
  return run;
}

}  // namespace

// The traced line itself: every vertex lies on the shore circle. Depth is linear in r across the
// shore (0.5 m a cell), so the marching-squares crossing between two cell centres is exact along
// a grid line; the chord of the circle between crossings a cell apart strays under 0.2 m from it;
// bilinear resampling of the survey onto the grid is exact for a linear field but the cone's
// curvature across a cell (d'' ~ slope / r = 0.05 / 100 m) moves depth by under (10 m)^2 / 8 x
// 5e-4 = 6 mm, 0.12 m along r; the 1 cm minimum depth moves a crossing by under 0.2 m. 1.5 m
// leaves room for these.
TEST(BathyPreviewOutline, RasterIslandLineFollowsTheShoreCircle) {
  const IslandRun run = bathy_of_island();
  ASSERT_TRUE(run.result.coastline_from_depth);
  ASSERT_FALSE(run.result.coastline_m.empty());
  std::size_t vertices = 0;
  for (const auto& line : run.result.coastline_m)
    for (const auto& point : line) {
      ++vertices;
      EXPECT_NEAR(std::hypot(point.x_m - run.centre_x_m, point.y_m - run.centre_y_m), kShoreRadius_m, 1.5);
    }
  // A closed ring of about 2 pi r / 10 m = 63 cell crossings, two per cell the line passes.
  EXPECT_GT(vertices, 60u);
}

// preview.png decoded: red pixels all round the island's shore, none in open water or on land.
TEST(BathyPreviewOutline, RasterIslandPreviewShowsTheShoreInRed) {
  const IslandRun run = bathy_of_island();
  const nearshore::Image preview = nearshore::read_png(run.out / "preview.png");
  const GridGeometry& g = run.result.grid.geometry;
  nearshore::HeatMapStyle style;
  style.map_axes = nearshore::MapAxes{};
  const nearshore::HeatMapPlacement placement = nearshore::heat_map_placement(g.columns, g.rows, style);
  const double scale = placement.pixels_per_cell / g.spacing_m;  // pixels per metre
  const double centre_px = placement.left_px + (run.centre_x_m - g.origin_x_m) * scale;
  const double centre_py = placement.top_px + (g.origin_y_m + g.height_m() - run.centre_y_m) * scale;
  // The preview's coastline red (0.9, 0.1, 0.05); no colour of the depth map, land or furniture is
  // near it (the bathymetry map runs cyan to navy).
  auto is_red = [&](int x, int y) {
    const nearshore::Rgb c = preview.get(x, y);
    return c[0] > 0.8f && c[1] < 0.2f && c[2] < 0.2f;
  };
  // Along 36 rays from the centre, a red pixel within 2 cells of the shore radius.
  for (int ray = 0; ray < 36; ++ray) {
    const double angle = ray * std::numbers::pi / 18.0;
    bool found = false;
    // The line is one pixel wide and may run diagonally: a ray's sample looks at its 3 x 3
    // neighbourhood so it cannot slip between two of the line's pixels.
    for (double r_m = kShoreRadius_m - 20.0; r_m <= kShoreRadius_m + 20.0 && !found; r_m += 1.0) {
      const int x = static_cast<int>(std::lround(centre_px + r_m * scale * std::cos(angle)));
      const int y = static_cast<int>(std::lround(centre_py - r_m * scale * std::sin(angle)));
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) found = found || is_red(x + dx, y + dy);
    }
    EXPECT_TRUE(found) << "no red shore on the ray at " << ray * 10 << " degrees";
  }
  // No red on the field farther than 3 cells from the shore: open water and the island's top.
  int stray_red = 0;
  for (int py = static_cast<int>(placement.top_px); py < placement.top_px + placement.height_px; ++py)
    for (int px = static_cast<int>(placement.left_px); px < placement.left_px + placement.width_px; ++px) {
      const double r_m = std::hypot(px + 0.5 - centre_px, py + 0.5 - centre_py) / scale;
      if (std::abs(r_m - kShoreRadius_m) > 30.0) stray_red += is_red(px, py);
    }
  EXPECT_EQ(stray_red, 0);
}
