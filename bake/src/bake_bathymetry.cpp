#include "nearshore/bake/bake_bathymetry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include <fmt/core.h>

#include "nearshore/bathymetry/distance_transform.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bake {
namespace {

GridGeometry flume_geometry(double length_m, double width_m, CellSize spacing, const std::string& subject) {
  if (!(spacing.x_m > 0.0) || !(spacing.y_m > 0.0) || !(length_m >= 2 * spacing.x_m) || !(width_m >= spacing.y_m))
    throw Error(subject,
                spacing.square() ? fmt::format("a flume of {} m x {} m with {} m cells is not a grid", length_m, width_m, spacing.x_m)
                                 : fmt::format("a flume of {} m x {} m with {} m x {} m cells is not a grid", length_m, width_m,
                                               spacing.x_m, spacing.y_m),
                "give length_m and width_m of at least two and one cells, and spacing_m > 0");
  GridGeometry geometry;
  geometry.columns = static_cast<int>(std::lround(length_m / spacing.x_m));
  geometry.rows = std::max(1, static_cast<int>(std::lround(width_m / spacing.y_m)));
  geometry.set_spacing(spacing.x_m, spacing.y_m);
  return geometry;
}

// Land is where the still water does not reach; the solver's moving shoreline wets it when waves run up.
void mark_land_from_depth(HarbourGrid& grid) {
  for (std::size_t i = 0; i < grid.land.size(); ++i) grid.land.values()[i] = grid.still_water_depth_m.values()[i] <= 0.f;
}

}  // namespace

void raise_still_water_level(HarbourGrid& grid, double level_m) {
  if (level_m == 0.0) return;
  for (float& depth_m : grid.still_water_depth_m.values()) depth_m += static_cast<float>(level_m);
  // The surroundings' depths are measured from the same still water (NaN, no data, stays NaN).
  for (float& depth_m : grid.surroundings.still_water_depth_m.values()) depth_m += static_cast<float>(level_m);
  mark_land_from_depth(grid);
}

std::size_t resolve_outside_chart(HarbourGrid& grid, const OutsideChartRule& rule, const std::string& subject) {
  std::size_t outside = 0;
  for (const std::uint8_t land : grid.land.values()) outside += land == kOutsideChartCell;
  if (outside == 0) return 0;
  if (rule.treatment == OutsideChartRule::Treatment::kLand) {
    // Today's behaviour, and what a reader that knows only land and water makes of such a cell.
    for (std::uint8_t& land : grid.land.values())
      if (land == kOutsideChartCell) land = kLandCell;
    return outside;
  }
  // Extended sea: the nearest charted water cell's depth (or the constant asked for). The seeds are
  // the water cells; the transform's spacing is the smaller cell size, exact for the square grids
  // `nearshore bathy` writes (this runs before any resampling to rectangular cells).
  Raster<std::uint8_t> water(grid.geometry.columns, grid.geometry.rows, 0);
  std::size_t water_cells = 0;
  for (std::size_t i = 0; i < water.size(); ++i) water_cells += water.values()[i] = grid.land.values()[i] == kWaterCell;
  if (water_cells == 0)
    throw Error(subject, "has no charted water cell whose depth the cells outside the chart could take",
                "set outside_chart = \"land\", or give outside_chart_depth_m");
  std::optional<bathymetry::NearestSeed> nearest;
  if (!(rule.depth_m > 0.0)) nearest = bathymetry::nearest_seed_transform(water, grid.geometry.smaller_spacing_m());
  for (int row = 0; row < grid.geometry.rows; ++row)
    for (int column = 0; column < grid.geometry.columns; ++column) {
      if (grid.land(column, row) != kOutsideChartCell) continue;
      grid.still_water_depth_m(column, row) =
          nearest ? grid.still_water_depth_m(nearest->nearest_column(column, row), nearest->nearest_row(column, row))
                  : static_cast<float>(rule.depth_m);
      grid.land(column, row) = kWaterCell;
      grid.porosity(column, row) = 1.0f;
    }
  grid.coast_distance_m = bathymetry::signed_coast_distance(grid.land, grid.geometry.smaller_spacing_m());
  return outside;
}

double profile_depth_m(const std::vector<std::pair<double, double>>& profile, double x_m) {
  if (x_m <= profile.front().first) return profile.front().second;
  if (x_m >= profile.back().first) return profile.back().second;
  const auto upper = std::upper_bound(profile.begin(), profile.end(), x_m,
                                      [](double x, const std::pair<double, double>& point) { return x < point.first; });
  const auto lower = upper - 1;
  const double t = (x_m - lower->first) / (upper->first - lower->first);
  return lower->second + t * (upper->second - lower->second);
}

HarbourGrid flume_from_profile(double length_m, double width_m, CellSize spacing,
                               const std::vector<std::pair<double, double>>& profile, const std::string& subject) {
  if (profile.empty())
    throw Error(subject, "the depth profile is empty", "give at least one [x_m, depth_m] point");
  for (std::size_t i = 1; i < profile.size(); ++i)
    if (!(profile[i].first > profile[i - 1].first))
      throw Error(subject, fmt::format("profile point {} (x = {} m) does not lie beyond point {} (x = {} m)", i + 1,
                                       profile[i].first, i, profile[i - 1].first),
                  "list the [x_m, depth_m] points with strictly increasing x");
  HarbourGrid grid = HarbourGrid::open_water(flume_geometry(length_m, width_m, spacing, subject), 0.f);
  for (int column = 0; column < grid.geometry.columns; ++column) {
    const float depth = static_cast<float>(profile_depth_m(profile, grid.geometry.cell_centre_x_m(column)));
    for (int row = 0; row < grid.geometry.rows; ++row) grid.still_water_depth_m(column, row) = depth;
  }
  mark_land_from_depth(grid);
  return grid;
}

double berkhoff_shoal_depth_m(const BerkhoffShoal& shoal, double x_m, double y_m) {
  // The paper's frame has x_p across the tank and y_p pointing up-wave; our waves travel along +x,
  // so x_p = (y - y_c) and y_p = -(x - x_c), then both are rotated by the contour angle.
  const double across = y_m - shoal.centre_y_m, upwave = -(x_m - shoal.centre_x_m);
  const double angle = shoal.rotation_deg * std::numbers::pi / 180.0;
  const double xr = across * std::cos(angle) - upwave * std::sin(angle);
  const double yr = across * std::sin(angle) + upwave * std::cos(angle);
  double depth = shoal.deep_depth_m;
  if (yr < shoal.slope_start_m)
    depth = std::max(shoal.minimum_depth_m, shoal.deep_depth_m - shoal.slope * (shoal.slope_start_m - yr));
  const double ellipse = (xr / 4.0) * (xr / 4.0) + (yr / 3.0) * (yr / 3.0);
  if (ellipse < 1.0)  // Berkhoff et al. (1982) eq. for the shoal, as in the README of the data
    depth += 0.3 - 0.5 * std::sqrt(1.0 - (xr / 5.0) * (xr / 5.0) - (yr / 3.75) * (yr / 3.75));
  return depth;
}

HarbourGrid berkhoff_shoal_grid(double length_m, double width_m, CellSize spacing, const BerkhoffShoal& shoal) {
  HarbourGrid grid = HarbourGrid::open_water(flume_geometry(length_m, width_m, spacing, "Berkhoff shoal"), 0.f);
  for (int row = 0; row < grid.geometry.rows; ++row)
    for (int column = 0; column < grid.geometry.columns; ++column)
      grid.still_water_depth_m(column, row) = static_cast<float>(
          berkhoff_shoal_depth_m(shoal, grid.geometry.cell_centre_x_m(column), grid.geometry.cell_centre_y_m(row)));
  mark_land_from_depth(grid);
  return grid;
}

HarbourGrid resample_harbour_grid(const HarbourGrid& grid, CellSize spacing) {
  const GridGeometry& from = grid.geometry;
  if (std::abs(spacing.x_m - from.spacing_x_m()) <= 1e-9 * from.spacing_x_m() &&
      std::abs(spacing.y_m - from.spacing_y_m()) <= 1e-9 * from.spacing_y_m())
    return grid;
  GridGeometry to = from;
  to.set_spacing(spacing.x_m, spacing.y_m);
  to.columns = std::max(2, static_cast<int>(std::lround(from.width_m() / spacing.x_m)));
  to.rows = std::max(1, static_cast<int>(std::lround(from.height_m() / spacing.y_m)));
  HarbourGrid out = HarbourGrid::open_water(to, 0.f);
  // Source cell coordinates (continuous, cell centres at integers) of a target cell centre, on the
  // source's own spacing along that axis.
  const auto source_index = [&](double position_m, double origin_m, double source_spacing_m, int count) {
    return std::clamp((position_m - origin_m) / source_spacing_m - 0.5, 0.0, static_cast<double>(count - 1));
  };
  const auto bilinear = [](const Raster<float>& field, double fi, double fj) {
    const int i0 = static_cast<int>(fi), j0 = static_cast<int>(fj);
    const int i1 = std::min(i0 + 1, field.columns() - 1), j1 = std::min(j0 + 1, field.rows() - 1);
    const double ti = fi - i0, tj = fj - j0;
    const double south = (1 - ti) * field(i0, j0) + ti * field(i1, j0);
    const double north = (1 - ti) * field(i0, j1) + ti * field(i1, j1);
    return static_cast<float>((1 - tj) * south + tj * north);
  };
  for (int row = 0; row < to.rows; ++row) {
    const double fj = source_index(to.cell_centre_y_m(row), from.origin_y_m, from.spacing_y_m(), from.rows);
    for (int column = 0; column < to.columns; ++column) {
      const double fi = source_index(to.cell_centre_x_m(column), from.origin_x_m, from.spacing_x_m(), from.columns);
      const int ni = static_cast<int>(std::lround(fi)), nj = static_cast<int>(std::lround(fj));
      out.still_water_depth_m(column, row) = bilinear(grid.still_water_depth_m, fi, fj);
      // Open-water grids hold +infinity as coast distance, which bilinear weights would turn into NaN.
      const float distance = bilinear(grid.coast_distance_m, fi, fj);
      out.coast_distance_m(column, row) = std::isfinite(distance) ? distance : grid.coast_distance_m(ni, nj);
      out.land(column, row) = grid.land(ni, nj);
      out.porosity(column, row) = grid.porosity(ni, nj);
      if (grid.porous_stone_diameter_m.size() > 0) {
        if (out.porous_stone_diameter_m.size() == 0) out.porous_stone_diameter_m = Raster<float>(to.columns, to.rows, 1.0f);
        out.porous_stone_diameter_m(column, row) = grid.porous_stone_diameter_m(ni, nj);
      }
    }
  }
  // The structures' geometry is in metres: the bake lays their footprints again at these cells
  // (structure_layers.hpp), so walls stay closed whatever the new cell size.
  out.structures = grid.structures;
  // The surroundings have their own cells, in projected metres: the same ground round the grid.
  out.surroundings = grid.surroundings;
  return out;
}

}  // namespace nearshore::bake
