// nearshore bathy on the demo harbour: the outputs read back (GDAL, EXR, OpenVDB, JSON) at the
// same place and with the same values, and the grid agrees with the demo's analytic site.
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "nearshore/bathymetry/coastline_level_set.hpp"
#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/bathymetry/projection.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/progress.hpp"
#include "test_folder.hpp"

namespace nb = nearshore::bathymetry;

namespace {

struct DemoRun {
  nb::DemoHarbourOptions site;
  nb::BathyResult result;
  nlohmann::json summary;
  std::filesystem::path out;
};

// The demo command's inputs at 20 m (2.5 source cells per grid cell keeps this test fast).
DemoRun run_demo(const std::filesystem::path& folder) {
  nearshore::ProgressBar::set_quiet(true);
  DemoRun run;
  const auto files = nb::write_demo_harbour(folder / "demo", run.site);
  nb::BathyRequest request;
  request.inputs = {files.depth_geotiff, files.coastline_geojson, files.land_geojson, files.structures_geojson};
  request.spacing_m = 20.0;
  run.result = nb::build_harbour_grid(request);
  run.out = folder / "out";
  run.summary = nb::write_bathymetry_outputs(run.out, run.result);
  return run;
}

// Local site coordinates (metres from the demo's south-west corner) of a grid cell centre.
std::pair<double, double> site_xy(const DemoRun& run, int column, int row) {
  const auto& g = run.result.grid.geometry;
  const auto centre = nearshore::MapProjection::utm(51, true).forward({run.site.centre_longitude_deg, run.site.centre_latitude_deg});
  return {g.cell_centre_x_m(column) - (centre.x_m - 0.5 * run.site.width_m),
          g.cell_centre_y_m(row) - (centre.y_m - 0.5 * run.site.height_m)};
}

}  // namespace

TEST(BathyOutputs, DemoGridMatchesTheSiteAndReadsBackEverywhere) {
  const DemoRun run = run_demo(fresh_test_folder(""));
  const nearshore::HarbourGrid& grid = run.result.grid;
  const auto& g = grid.geometry;
  // The survey raster is 1600 x 1200 m at 8 m; the grid lines up with it at 20 m.
  EXPECT_EQ(g.columns, 80);
  EXPECT_EQ(g.rows, 60);
  EXPECT_EQ(g.projection["zone"], 51);

  // Depth against the analytic site, and land where the site is above water.
  int land_disagreements = 0, water_cells = 0;
  std::vector<double> errors;
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c) {
      const auto [x, y] = site_xy(run, c, r);
      const double truth = nb::demo_harbour_depth_m(run.site, x, y);
      land_disagreements += (truth < 0) != (grid.land(c, r) != 0);
      if (truth > 0.5 && !grid.land(c, r)) {
        ++water_cells;
        errors.push_back(std::abs(grid.still_water_depth_m(c, r) - truth));
      }
    }
  std::sort(errors.begin(), errors.end());
  // Bilinear resampling of 8 m data: smooth parts are exact to O((8 m)^2 |d''|) ~ cm; only the
  // dredged basin's vertical edges (one cell wide) differ by metres, so the median is tight.
  EXPECT_LT(errors[errors.size() / 2], 0.05);
  // The shoreline crosses cells: a cell whose centre is on one side may be drawn on the other
  // by the land polygon's edge; one shoreline cell per column at most (80 of 4800).
  EXPECT_LE(land_disagreements, g.columns);
  EXPECT_GT(water_cells, 2000);

  // The west arm (rubble mound) at x = 420 m, y = 700 m: its impermeable core (porosity 0) where
  // the centre line runs, porous faces (the nominal 0.45 of a rubble mound until the bake fits them)
  // on either side; the grid carries the arm as a structure for the bake.
  const auto centre = nearshore::MapProjection::utm(51, true).forward({run.site.centre_longitude_deg, run.site.centre_latitude_deg});
  const int arm_column = static_cast<int>((centre.x_m - 800.0 + 420.0 - g.origin_x_m) / g.spacing_m);
  const int arm_row = static_cast<int>((centre.y_m - 600.0 + 700.0 - g.origin_y_m) / g.spacing_m);
  // The arm lies on the boundary between columns arm_column - 1 and arm_column, exactly half a cell
  // diagonal (the core's reach, 4 m) from both centres: GeoJSON's 1e-9 degree rounding (0.1 mm)
  // decides which one is core, and at least one is.
  EXPECT_FLOAT_EQ(std::min(grid.porosity(arm_column, arm_row), grid.porosity(arm_column - 1, arm_row)), 0.0f);
  EXPECT_FLOAT_EQ(grid.porosity(arm_column + 1, arm_row), 0.45f);
  EXPECT_FLOAT_EQ(grid.porosity(arm_column - 2, arm_row), 0.45f);
  ASSERT_EQ(grid.structures.size(), 4u);
  EXPECT_EQ(grid.structures[0].name, "west breakwater");
  EXPECT_EQ(grid.structures[0].kind, "rubble_mound_breakwater");
  EXPECT_LT(grid.structures[0].reflection_coefficient, 0.0);  // from the sea state, in the bake
  EXPECT_EQ(grid.structures[2].name, "detached breakwater");
  EXPECT_EQ(grid.structures[3].kind, "vertical_quay");
  EXPECT_DOUBLE_EQ(grid.structures[3].reflection_coefficient, 0.95);
  EXPECT_FLOAT_EQ(grid.porosity(5, 5), 1.0f);  // open sea in the south-west

  // depth.tif: same place (geotransform, EPSG:32651) and same values, read by GDAL.
  GDALAllRegister();
  std::unique_ptr<GDALDataset, void (*)(GDALDataset*)> tif(
      GDALDataset::Open((run.out / "depth.tif").c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY),
      [](GDALDataset* d) { GDALClose(d); });
  ASSERT_TRUE(tif);
  double gt[6];
  ASSERT_EQ(tif->GetGeoTransform(gt), CE_None);
  EXPECT_DOUBLE_EQ(gt[0], g.origin_x_m);
  EXPECT_DOUBLE_EQ(gt[3], g.origin_y_m + g.height_m());
  EXPECT_DOUBLE_EQ(gt[1], g.spacing_m);
  EXPECT_STREQ(tif->GetSpatialRef()->GetAuthorityCode(nullptr), "32651");
  float north_west = 0;  // GeoTIFF line 0 is the northern row
  ASSERT_EQ(tif->GetRasterBand(1)->RasterIO(GF_Read, 3, 0, 1, 1, &north_west, 1, 1, GDT_Float32, 0, 0), CE_None);
  EXPECT_EQ(north_west, grid.still_water_depth_m(3, g.rows - 1));

  // depth.exr through the core reader: identical channels and geometry.
  const nearshore::HarbourGrid again = nearshore::read_harbour_grid(run.out / "depth.exr");
  EXPECT_EQ(again.geometry.origin_x_m, g.origin_x_m);
  EXPECT_EQ(again.still_water_depth_m.values(), grid.still_water_depth_m.values());
  EXPECT_EQ(again.land.values(), grid.land.values());
  EXPECT_EQ(again.porosity.values(), grid.porosity.values());
  EXPECT_EQ(nlohmann::json(again.structures), nlohmann::json(grid.structures));

  // coastline.vdb: a level set whose voxel holds the coast distance of its cell.
  int coast_column = -1, coast_row = -1;
  for (int r = 0; r < g.rows && coast_column < 0; ++r)
    for (int c = 0; c < g.columns; ++c)
      if (std::abs(grid.coast_distance_m(c, r)) < 15.0) {
        coast_column = c, coast_row = r;
        break;
      }
  ASSERT_GE(coast_column, 0);
  double value = 0;
  const auto probe = nb::probe_coastline_level_set(run.out / "coastline.vdb", coast_column, coast_row, &value);
  EXPECT_FLOAT_EQ(static_cast<float>(value), grid.coast_distance_m(coast_column, coast_row));
  EXPECT_DOUBLE_EQ(probe.voxel_size_m, g.spacing_m);
  EXPECT_GT(probe.active_voxels, 100u);

  // summary.json is complete JSON with the grid's figures.
  std::ifstream summary_file(run.out / "summary.json");
  const auto summary = nlohmann::json::parse(summary_file);
  EXPECT_EQ(summary["columns"], 80);
  EXPECT_EQ(summary["cells"]["total"], 4800);
  EXPECT_EQ(summary["inputs"][0]["sign"].get<std::string>().rfind("positive_down", 0), 0u);
  EXPECT_TRUE(std::filesystem::exists(run.out / "preview.png"));
}

TEST(BathyOutputs, SlopeLimitAndMinimumDepthAreAppliedAndReported) {
  const auto folder = fresh_test_folder("");
  nearshore::ProgressBar::set_quiet(true);
  const auto files = nb::write_demo_harbour(folder / "demo");
  nb::BathyRequest request;
  request.inputs = {files.depth_geotiff, files.land_geojson};
  request.spacing_m = 20.0;
  request.minimum_depth_m = 2.0;
  request.maximum_slope = 0.05;
  const nb::BathyResult result = nb::build_harbour_grid(request);
  const auto& grid = result.grid;
  const auto& g = grid.geometry;
  EXPECT_GT(result.summary["conditioning"]["minimum_depth_clamp"]["cells"].get<int>(), 0);
  EXPECT_GT(result.summary["conditioning"]["slope_smoothing"]["cells"].get<int>(), 0);
  double steepest = 0;
  for (int r = 0; r + 1 < g.rows; ++r)
    for (int c = 0; c + 1 < g.columns; ++c) {
      if (grid.land(c, r)) continue;
      EXPECT_GE(grid.still_water_depth_m(c, r), 2.0f);
      if (!grid.land(c + 1, r))
        steepest = std::max(steepest, std::abs(double(grid.still_water_depth_m(c + 1, r)) - grid.still_water_depth_m(c, r)) / g.spacing_m);
    }
  // Relaxation stops when no step exceeds the limit, or after 200 sweeps (then within a little of it).
  EXPECT_LT(steepest, 0.05 * 1.5);
}

TEST(BathyOutputs, WaterLevelDeepensEveryCellAndFloodsLowLand) {
  const auto folder = fresh_test_folder("");
  nearshore::ProgressBar::set_quiet(true);
  const auto files = nb::write_demo_harbour(folder / "demo");
  nb::BathyRequest request;
  request.inputs = {files.depth_geotiff};
  request.spacing_m = 40.0;
  request.minimum_depth_m = 0.0;
  const nb::BathyResult datum = nb::build_harbour_grid(request);
  request.water_level_m = 1.5;
  const nb::BathyResult raised = nb::build_harbour_grid(request);
  const auto& a = datum.grid;
  const auto& b = raised.grid;
  int flooded = 0;
  for (std::size_t i = 0; i < a.still_water_depth_m.size(); ++i) {
    EXPECT_NEAR(b.still_water_depth_m.values()[i], a.still_water_depth_m.values()[i] + 1.5f, 1e-5);
    EXPECT_LE(b.land.values()[i], a.land.values()[i]);  // raising the water never makes land
    flooded += a.land.values()[i] && !b.land.values()[i];
  }
  EXPECT_GT(flooded, 0);  // the 1:15 beach above the shoreline goes under
  EXPECT_EQ(raised.summary["water_level_m"], 1.5);
}

// Issue 41: the surroundings. The demo's surroundings.tif (its analytic ground 1600 m beyond the
// site, 32 m cells) after depth.tif in the inputs, the grid over the site alone: the grid is as
// before (80 x 60 cells of 20 m) and its surroundings (80 m cells: 4 of the grid's, over the site
// grown by its longer side on every side) hold the analytic ground beyond it, water and land,
// with no cell without data; depth.exr carries them back exactly. Without surroundings.tif the
// cells beyond the survey are no data (NaN); with a margin of 0 there are none.
TEST(BathyOutputs, TheDemosSurroundingsAreItsAnalyticGroundBeyondTheGrid) {
  const auto folder = fresh_test_folder("");
  nearshore::ProgressBar::set_quiet(true);
  const nb::DemoHarbourOptions site;
  const auto files = nb::write_demo_harbour(folder / "demo", site);
  nb::BathyRequest request;
  request.inputs = {files.depth_geotiff, files.coastline_geojson, files.land_geojson, files.structures_geojson,
                    files.surroundings_geotiff};
  request.bbox_projected_m = files.site_box_m;
  request.spacing_m = 20.0;
  const nb::BathyResult result = nb::build_harbour_grid(request);
  const auto& g = result.grid.geometry;
  EXPECT_EQ(g.columns, 80);
  EXPECT_EQ(g.rows, 60);
  const nearshore::Surroundings& outer = result.grid.surroundings;
  ASSERT_FALSE(outer.empty());
  const auto& s = outer.geometry;
  EXPECT_DOUBLE_EQ(s.spacing_m, 80.0);
  EXPECT_EQ(s.columns, 60);  // (1600 + 2 x 1600) / 80
  EXPECT_EQ(s.rows, 55);     // (1200 + 2 x 1600) / 80
  EXPECT_EQ(s.crs_wkt, g.crs_wkt);
  EXPECT_NEAR(s.origin_x_m, g.origin_x_m - 1600.0, 1e-6);
  EXPECT_EQ(result.summary["surroundings"]["cells"]["no_data"], 0);
  std::vector<double> errors;
  int water = 0, land = 0, land_disagreements = 0;
  for (int r = 0; r < s.rows; ++r)
    for (int c = 0; c < s.columns; ++c) {
      const double x = s.cell_centre_x_m(c) - files.site_box_m[0], y = s.cell_centre_y_m(r) - files.site_box_m[1];
      const float depth = outer.still_water_depth_m(c, r);
      ASSERT_TRUE(std::isfinite(depth)) << c << ", " << r;
      if (x > 0 && x < site.width_m && y > 0 && y < site.height_m) continue;  // the grid's own box
      const double truth = nb::demo_harbour_depth_m(site, x, y);
      if (truth > 0.5) ++water, errors.push_back(std::abs(depth - truth));
      if (truth < -0.5) ++land, land_disagreements += !(depth < 0);
    }
  std::sort(errors.begin(), errors.end());
  EXPECT_GT(water, 1000);
  EXPECT_GT(land, 1000);
  EXPECT_LT(errors[errors.size() / 2], 0.05);  // bilinear of 32 m samples at 80 m cells
  EXPECT_LE(land_disagreements, s.columns);    // a shoreline cell per column at most
  // The terrace 12 m up in the far north.
  EXPECT_NEAR(outer.still_water_depth_m(30, s.rows - 1), -12.0, 0.01);
  const auto summary = nb::write_bathymetry_outputs(folder / "out", result);
  const nearshore::HarbourGrid again = nearshore::read_harbour_grid(folder / "out" / "depth.exr");
  EXPECT_EQ(again.still_water_depth_m.values(), result.grid.still_water_depth_m.values());
  EXPECT_EQ(again.surroundings.still_water_depth_m.values(), outer.still_water_depth_m.values());
  EXPECT_EQ(nlohmann::json(again.surroundings.geometry), nlohmann::json(s));

  // The survey alone: no data beyond it, and the grid's box fully covered.
  request.inputs = {files.depth_geotiff};
  const nb::BathyResult survey_only = nb::build_harbour_grid(request);
  const nearshore::Surroundings& bare = survey_only.grid.surroundings;
  ASSERT_FALSE(bare.empty());
  int no_data = 0;
  for (int r = 0; r < bare.geometry.rows; ++r)
    for (int c = 0; c < bare.geometry.columns; ++c) {
      const double x = bare.geometry.cell_centre_x_m(c) - files.site_box_m[0];
      const double y = bare.geometry.cell_centre_y_m(r) - files.site_box_m[1];
      const bool inside = x > 0 && x < site.width_m && y > 0 && y < site.height_m;
      no_data += std::isnan(bare.still_water_depth_m(c, r));
      if (inside) {
        EXPECT_TRUE(std::isfinite(bare.still_water_depth_m(c, r))) << c << ", " << r;
      }
    }
  EXPECT_GT(no_data, bare.geometry.columns * bare.geometry.rows * 8 / 10);  // the site is 1/9 of the box
  EXPECT_EQ(survey_only.summary["surroundings"]["cells"]["no_data"], no_data);
  request.surroundings_margin_m = 0.0;
  EXPECT_TRUE(nb::build_harbour_grid(request).grid.surroundings.empty());
}
