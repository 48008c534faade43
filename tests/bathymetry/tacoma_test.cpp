// The real chart: NOAA ENC US5WA22M (Tacoma Harbor) at 10 m, as `nearshore bathy` grids it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/bathymetry/rasterise.hpp"
#include "nearshore/bathymetry/sources.hpp"
#include "nearshore/core/progress.hpp"
#include "test_folder.hpp"

namespace nb = nearshore::bathymetry;
namespace fs = std::filesystem;

TEST(Tacoma, TenMetreGridAgreesWithTheChartsSoundingsAndAreas) {
  nearshore::ProgressBar::set_quiet(true);
  const fs::path chart = fs::path(NEARSHORE_SHARED_DIR) / "charts/tacoma_us5wa22m/US5WA22M.000";
  nb::BathyRequest request;
  request.inputs = {chart};
  request.spacing_m = 10.0;
  request.leave_one_out = true;
  const nb::BathyResult result = nb::build_harbour_grid(request);
  const auto& grid = result.grid;
  const auto& g = grid.geometry;
  nb::write_bathymetry_outputs(fresh_test_folder("") / "out", result);  // preview.png to look at

  // 1. Leave-one-out at the chart's soundings. The chart keeps ~980 soundings for 60 km^2 of
  //    water (one per ~250 m) and its relief reaches 177 m, so a sounding's neighbours can be tens
  //    of metres of depth away; cartographers also select soundings that mark shoals and holes,
  //    the points least predictable from their neighbours. We measured a median |error| of
  //    1.78 m (90th percentile 9.7 m); the bound 2.5 m leaves 40 % for platform differences.
  //    A second bound compares with the soundings alone (same triangulation, no contours, depth
  //    areas or coastline, measured 1.79 m): the chart's other features must not pull the grid
  //    away from its own soundings (5 % slack for the bound each area applies).
  const auto& loo = result.summary["leave_one_out"];
  const double median_error_m = loo["median_absolute_error_m"];
  RecordProperty("loo_median_absolute_error_m", std::to_string(median_error_m));
  RecordProperty("loo_p90_absolute_error_m", std::to_string(loo["p90_absolute_error_m"].get<double>()));
  EXPECT_GT(loo["soundings"].get<int>(), 900);
  EXPECT_LT(median_error_m, 2.5);
  nb::ReadOptions options;
  const nb::SourceData source = nb::read_source(chart, options);
  {
    const fs::path xyz = fresh_test_folder("-soundings-only") / "soundings.xyz";
    std::ofstream out(xyz);
    out.precision(10);
    for (const auto& s : source.soundings) out << s.place.longitude_deg << ' ' << s.place.latitude_deg << ' ' << s.depth_m << '\n';
    out.close();
    nb::BathyRequest soundings_only = request;
    soundings_only.inputs = {xyz};
    const double baseline_m = nb::build_harbour_grid(soundings_only).summary["leave_one_out"]["median_absolute_error_m"];
    RecordProperty("loo_median_absolute_error_soundings_only_m", std::to_string(baseline_m));
    EXPECT_LT(median_error_m, 1.05 * baseline_m);
  }

  // 2. Land/water against the chart's own areas: LNDARE cells must be land, cells of depth areas
  //    that never dry (DRVAL1 >= 0) water. Drying areas (DRVAL1 < 0) are land or water with the
  //    tide and are not counted, nor are cells in no area (outside the chart's coverage).
  const nearshore::MapProjection projection = nearshore::MapProjection::from_json(g.projection, "test");
  nearshore::Raster<std::uint8_t> expected(g.columns, g.rows, 0);  // 1 land, 2 water
  auto burn = [&](const nb::GeoPolygon& polygon, std::uint8_t value) {
    std::vector<nb::PlaneLine> rings;
    for (const auto& ring : polygon.rings) {
      nb::PlaneLine line;
      for (const auto& p : ring) line.push_back(projection.forward(p));
      rings.push_back(std::move(line));
    }
    nb::for_each_cell_in_polygon(g, rings, [&](int c, int r) { expected(c, r) = value; });
  };
  for (const auto& area : source.depth_areas)
    if (area.shallowest_m >= 0) burn(area.polygon, 2);
  for (const auto& land : source.land) burn(land, 1);
  std::size_t compared = 0, agreeing = 0;
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c) {
      if (!expected(c, r)) continue;
      ++compared;
      agreeing += (expected(c, r) == 1) == (grid.land(c, r) != 0);
    }
  const double agreement = static_cast<double>(agreeing) / compared;
  RecordProperty("land_water_agreement", std::to_string(agreement));
  EXPECT_GT(compared, 500000u);
  EXPECT_GT(agreement, 0.99);  // the bound

  // 3. Sanity of the harbour as a whole: Commencement Bay is deep (DEPARE reaches 182.8 m).
  EXPECT_GT(result.summary["water_depth_m"]["max"].get<double>(), 150.0);
  EXPECT_LT(result.summary["water_depth_m"]["max"].get<double>(), 183.0);
}
