// [bathymetry] and [[porous_blocks]] of a case file (docs/commands/bake.md).
#include "nearshore/bake/bake_bathymetry.hpp"
#include "nearshore/bake/bake_estimate.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string_view>
#include <utility>

#include <fmt/core.h>

#include "nearshore/bathymetry/local_grid.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/geo_position.hpp"
#include "case_reader.hpp"

namespace nearshore::bake::detail {

using namespace nearshore::ocean;       // spectra, sea states, the deep-water field
using namespace nearshore::boussinesq;  // the solver and its parameters

namespace {

// The first cell whose still-water depth is not finite or deeper than kDeepestPlausibleDepth_m
// fails `key`: the solver would take such a grid's time step from that depth (a 6e28 m deep cell
// gave a 1e-14 s step and a bake that never ends).
void check_plausible_depths(TableReader& bathymetry, const std::string& key, const HarbourGrid& grid) {
  const GridGeometry& g = grid.geometry;
  for (int row = 0; row < g.rows; ++row)
    for (int column = 0; column < g.columns; ++column) {
      const float depth_m = grid.still_water_depth_m(column, row);
      if (depth_m <= kDeepestPlausibleDepth_m) continue;  // NaN fails too
      const std::string where = fmt::format("cell (column {}, row {}; {:.2f} m, {:.2f} m from the south-west corner)",
                                            column, row, (column + 0.5) * g.spacing_x_m(), (row + 0.5) * g.spacing_y_m());
      if (!std::isfinite(depth_m))
        bathymetry.fail(bathymetry.full(key), fmt::format("gives a depth of {} at {}", depth_m, where),
                        "fill the hole in the bathymetry (regrid the chart data with its holes filled or masked as land)");
      bathymetry.fail(bathymetry.full(key),
                      fmt::format("gives a depth of {} m at {}, deeper than {:.0f} m, the deepest water on Earth "
                                  "(the Challenger Deep, 10 935 m)",
                                  depth_m, where, kDeepestPlausibleDepth_m),
                      "such a depth is a fill value taken for a depth, a unit other than metres or a wrong sign: "
                      "correct the bathymetry (depths in metres, positive down)");
    }
}

// The bake's memory estimate (bake_estimate.hpp) for `grid` resampled to dx x dy, before the
// resampled grid is allocated: `spacing_m = 0.001` on a harbour grid ended in std::bad_alloc
// (issue 44); such a grid is now refused in a moment with the cells and the memory it needs, as a
// generated flume's is. The same limit of 20000 cells along a side holds for both.
void check_resampled_grid_fits(TableReader& bathymetry, const GridGeometry& source, double dx, double dy,
                               const CaseReadOptions& options) {
  const double columns = std::ceil(source.width_m() / dx), rows = std::ceil(source.height_m() / dy);
  const std::string key = bathymetry.full("spacing_m");
  if (columns > 20000 || rows > 20000)
    bathymetry.fail(key,
                    fmt::format("= {:.3g} x {:.3g} m resamples the {:.4g} x {:.4g} m grid to {:.3g} x {:.3g} cells, more than "
                                "20000 along a side",
                                dx, dy, source.width_m(), source.height_m(), columns, rows),
                    fmt::format("use a larger spacing_m (the grid's own cells are {:.3g} x {:.3g} m)", source.spacing_x_m(),
                                source.spacing_y_m()));
  const double cells = columns * rows;
  const double needed_bytes = cells * kBakeBytesPerCell + kBakeFixedBytes;
  const std::optional<double> available_bytes = available_memory_bytes();
  if (!options.allow_over_budget && available_bytes && needed_bytes > *available_bytes)
    bathymetry.fail(key,
                    fmt::format("resamples the grid to {:.0f} cells, whose bake needs about {} of memory ({:.0f} B per cell), "
                                "but the machine has {} available",
                                cells, format_bytes(needed_bytes), kBakeBytesPerCell, format_bytes(*available_bytes)),
                    "use a larger spacing_m; or, if the estimate is too pessimistic, set "
                    "CaseReadOptions::allow_over_budget and BakeOptions::allow_over_budget");
}

}  // namespace

// The grid the case names, with depths as its source gives them (below the datum).
static HarbourGrid read_grid_at_datum(TableReader& bathymetry, std::size_t kind, const fs::path& base,
                                      const CaseReadOptions& options);

HarbourGrid read_bathymetry(TableReader& bathymetry, const fs::path& base, const CaseReadOptions& options) {
  const std::size_t kind =
      bathymetry.choice("kind", std::nullopt, {"harbour_grid", "profile", "berkhoff_shoal", "local_grid"});
  // A tide (or surge) above the datum of the depths: bathymetry/ refuses water levels beyond the
  // same +-30 m (the largest tidal range on Earth, the Bay of Fundy, is 16 m).
  const double still_water_level_m =
      bathymetry.number("still_water_level_m", 0.0, -30.0, 30.0, false, "the still-water level above the depths' datum in metres");
  HarbourGrid grid = read_grid_at_datum(bathymetry, kind, base, options);
  raise_still_water_level(grid, still_water_level_m);
  return grid;
}

// kind = "local_grid": a raster or "x y depth" text in local metres with no CRS, a laboratory flume
// or basin (issue 19), read by bathymetry/local_grid.hpp with no projection invented for it. The
// sign is required: a wrong guess turns a whole basin into land, or land into water.
static HarbourGrid read_local_grid(TableReader& bathymetry, const fs::path& base, const CaseReadOptions& options) {
  nearshore::bathymetry::LocalGridRequest request;
  request.file = bathymetry.path("file", base);
  request.sign = bathymetry.choice("depth_sign", std::nullopt, {"positive_down", "positive_up"}) == 0
                     ? nearshore::bathymetry::DepthSign::kPositiveDown
                     : nearshore::bathymetry::DepthSign::kPositiveUp;
  request.minimum_depth_m = bathymetry.number("minimum_depth_m", 0.0, 0.0, kDeepestPlausibleDepth_m, false,
                                              "the depth shallower water is deepened to, metres (0 keeps the file's)");
  if (bathymetry.has("pixel_size_m")) {
    const auto [dx, dy] = bathymetry.cell_size("pixel_size_m");
    request.pixel_size_m = std::array<double, 2>{dx, dy};
  }
  // spacing_m: the cells laid over text soundings (required for them); for a raster, the cells it
  // is resampled to (default: its own).
  const bool soundings = nearshore::bathymetry::is_text_soundings(request.file);
  std::optional<CellSize> spacing;
  if (soundings || bathymetry.has("spacing_m")) {
    const auto [dx, dy] = bathymetry.cell_size("spacing_m");
    spacing = CellSize(dx, dy);
  }
  if (soundings) request.spacing_m = std::array<double, 2>{spacing->x_m, spacing->y_m};
  // The library names its own fields; the case file's user knows the keys of this table.
  const auto in_case_keys = [&](std::string text) {
    const std::pair<const char*, std::string> names[] = {
        {"LocalGridRequest::sign", bathymetry.full("depth_sign")},
        {"DepthSign::kPositiveDown", "\"positive_down\""},
        {"DepthSign::kPositiveUp", "\"positive_up\""},
        {"LocalGridRequest::spacing_m", bathymetry.full("spacing_m")},
        {"LocalGridRequest::pixel_size_m", bathymetry.full("pixel_size_m")},
        {"LocalGridRequest::minimum_depth_m", bathymetry.full("minimum_depth_m")}};
    for (const auto& [field, key] : names)
      for (auto at = text.find(field); at != std::string::npos; at = text.find(field, at + key.size()))
        text.replace(at, std::string_view(field).size(), key);
    return text;
  };
  HarbourGrid grid;
  try {
    grid = nearshore::bathymetry::read_local_grid(request).grid;
  } catch (const Error& error) {
    bathymetry.fail(bathymetry.full("file"),
                    "names a grid that cannot be used: " + in_case_keys(error.problem()) + " (" + error.subject() + ")",
                    in_case_keys(error.fix()));
  }
  check_plausible_depths(bathymetry, "file", grid);
  if (spacing && !soundings) {
    check_resampled_grid_fits(bathymetry, grid.geometry, spacing->x_m, spacing->y_m, options);
    grid = resample_harbour_grid(grid, *spacing);
  }
  return grid;
}

static HarbourGrid read_grid_at_datum(TableReader& bathymetry, std::size_t kind, const fs::path& base,
                                      const CaseReadOptions& options) {
  HarbourGrid grid;
  if (kind == 3) return read_local_grid(bathymetry, base, options);
  if (kind == 0) {
    const fs::path file = bathymetry.path("file", base);
    grid = bathymetry.reading_file("file", [&] { return read_harbour_grid(file); });
    // Cells outside the chart's coverage (issue 14 item 3): land (default, a reflecting wall as
    // before nodata existed) or extended sea, before any resampling so the rule sees the chart's
    // own cells (docs/commands/bake.md, "Outside the chart").
    OutsideChartRule outside_chart;
    if (bathymetry.choice("outside_chart", "land", {"land", "sea"}) == 1)
      outside_chart.treatment = OutsideChartRule::Treatment::kSea;
    if (bathymetry.has("outside_chart_depth_m")) {
      if (outside_chart.treatment != OutsideChartRule::Treatment::kSea)
        bathymetry.fail(bathymetry.full("outside_chart_depth_m"), "is given but outside_chart is not \"sea\"",
                        "set outside_chart = \"sea\", or remove outside_chart_depth_m");
      outside_chart.depth_m = bathymetry.number("outside_chart_depth_m", std::nullopt, 0.0, kDeepestPlausibleDepth_m, true,
                                                "the depth of the sea outside the chart, metres");
    }
    resolve_outside_chart(grid, outside_chart, bathymetry.subject() + ": key `" + bathymetry.full("outside_chart") + "`");
    check_plausible_depths(bathymetry, "file", grid);
    if (bathymetry.has("spacing_m")) {
      const auto [dx, dy] = bathymetry.cell_size("spacing_m");
      check_resampled_grid_fits(bathymetry, grid.geometry, dx, dy, options);
      grid = resample_harbour_grid(grid, CellSize(dx, dy));
    }
  } else {
    const double length_m = bathymetry.positive("length_m", std::nullopt, "flume length along x in metres");
    const double width_m = bathymetry.positive("width_m", std::nullopt, "flume width along y in metres");
    // spacing_m: one number (square cells) or [dx, dy] (rectangular cells, issue 15).
    const auto [spacing_x_m, spacing_y_m] = bathymetry.cell_size("spacing_m");
    const CellSize spacing(spacing_x_m, spacing_y_m);
    if (length_m / spacing_x_m > 20000 || width_m / spacing_y_m > 20000)
      bathymetry.fail(bathymetry.full("spacing_m"), "makes more than 20000 cells along a side",
                      "use a larger spacing_m (cells of at least 1/20000 of the flume)");
    // The bake's memory estimate (bake_estimate.hpp) before the grid is allocated: a grid the
    // machine cannot bake is refused in a moment, not after the case reader has built it.
    const double cells = std::ceil(length_m / spacing_x_m) * std::ceil(width_m / spacing_y_m);
    const double needed_bytes = cells * kBakeBytesPerCell + kBakeFixedBytes;
    const std::optional<double> available_bytes = available_memory_bytes();
    if (!options.allow_over_budget && available_bytes && needed_bytes > *available_bytes)
      bathymetry.fail(bathymetry.full("spacing_m"),
                      fmt::format("makes {:.0f} cells, whose bake needs about {} of memory ({:.0f} B per cell), "
                                  "but the machine has {} available",
                                  cells, format_bytes(needed_bytes), kBakeBytesPerCell, format_bytes(*available_bytes)),
                      "use a larger spacing_m or a smaller flume; or, if the estimate is too pessimistic, set "
                      "CaseReadOptions::allow_over_budget and BakeOptions::allow_over_budget");
    if (kind == 1) {
      grid = flume_from_profile(length_m, width_m, spacing,
                                bathymetry.pairs("profile", "[[x_m, depth_m], ...] with increasing x"),
                                bathymetry.subject() + ": key `" + bathymetry.full("profile") + "`");
      check_plausible_depths(bathymetry, "profile", grid);
      return grid;
    }
    BerkhoffShoal shoal;
    const std::vector<double> centre = bathymetry.numbers("centre_m", 2, "[x_m, y_m]");
    shoal.centre_x_m = centre[0];
    shoal.centre_y_m = centre[1];
    shoal.rotation_deg = bathymetry.number("rotation_deg", 20.0, -90.0, 90.0, false, "contour angle in degrees");
    shoal.deep_depth_m = bathymetry.positive("deep_depth_m", 0.45, "depth before the slope in metres");
    shoal.slope = bathymetry.non_negative("slope", 0.02, "bed slope (rise over run)");
    shoal.slope_start_m = bathymetry.number("slope_start_m", 5.84, -1e6, 1e6, false, "distance up-wave of the shoal centre where the slope starts, metres");
    shoal.minimum_depth_m = bathymetry.positive("minimum_depth_m", 0.07, "depth where the slope is clipped, metres");
    grid = berkhoff_shoal_grid(length_m, width_m, spacing, shoal);
    check_plausible_depths(bathymetry, "deep_depth_m", grid);
  }
  return grid;
}

ProjectedPoint read_case_position(TableReader& table, const HarbourGrid& grid, const std::string& entry,
                                  std::vector<std::string>& warnings) {
  // Every position key present, read as a number through the table (so it counts as known); the
  // pairing rules and the frames are core/geo_position.hpp's, the one parser of positions.
  // Metres from the south-west corner are bounded by the grid here, so such an error names the key
  // (`gauges[0].x_m` = 50 is out of range) as it always has; the other frames are bounded by
  // place_in_grid, which names the grid's extent in lat/lon.
  const GridGeometry& g = grid.geometry;
  std::map<std::string, double> keys;
  for (const auto& [first, second] : nearshore::geo_position_keys())
    for (const std::string& key : {first, second}) {
      if (!table.has(key)) continue;
      if (key == "x_m" || key == "y_m")
        keys[key] = table.number(key, std::nullopt, 0.0, key == "x_m" ? g.width_m() : g.height_m(), false,
                                 fmt::format("{} from the south-west corner, inside the grid, metres", key == "x_m" ? "x" : "y"));
      else
        keys[key] = table.number(key, std::nullopt, -std::numeric_limits<double>::infinity(),
                                 std::numeric_limits<double>::infinity(), false, "a coordinate (docs/commands/bake.md, \"Positions\")");
    }
  const nearshore::GeoPosition position =
      nearshore::geo_position_from_keys(keys, table.subject(), entry);
  ProjectedPoint point;
  try {
    point = nearshore::place_in_grid(position, grid.geometry, table.subject(), entry);
  } catch (const Error& error) {
    if (error.subject() == table.subject()) throw;  // already names the case file and the entry
    // The projection's own failure (lat 0, lon 0 for a grid in zone 10N): named by its entry.
    throw Error(table.subject(),
                fmt::format("{} lies where the grid's projection cannot reach: {} ({})", entry, error.problem(), error.subject()),
                "give a position inside the grid, which covers " + nearshore::describe_grid_extent(grid.geometry));
  }
  if (auto warning = nearshore::land_warning(grid, point, table.subject(), entry)) warnings.push_back(*warning);
  return point;
}

// Rectangles of porous structure (rubble mounds) or walls laid over any bathymetry.
void apply_porous_blocks(std::vector<TableReader> blocks, HarbourGrid& grid) {
  for (TableReader& block : blocks) {
    const std::vector<double> x_range = block.numbers("x_range_m", 2, "[x_min_m, x_max_m]");
    const std::vector<double> y_range = block.numbers("y_range_m", 2, "[y_min_m, y_max_m]");
    const double porosity = block.number("porosity", std::nullopt, 0.0, 1.0, false, "porosity n (0 wall .. 1 open water)");
    block.finish();
    if (!(x_range[1] > x_range[0]) || !(y_range[1] > y_range[0]))
      block.fail(block.full("x_range_m"), "or y_range_m is empty (max <= min)", "give [min, max] with max > min");
    int cells = 0;
    for (int row = 0; row < grid.geometry.rows; ++row)
      for (int column = 0; column < grid.geometry.columns; ++column) {
        const double x = grid.geometry.cell_centre_x_m(column) - grid.geometry.origin_x_m;  // local frame
        const double y = grid.geometry.cell_centre_y_m(row) - grid.geometry.origin_y_m;
        if (x >= x_range[0] && x <= x_range[1] && y >= y_range[0] && y <= y_range[1]) {
          grid.porosity(column, row) = static_cast<float>(porosity);
          ++cells;
        }
      }
    if (cells == 0)
      block.fail(block.full("x_range_m"), "and y_range_m contain no cell centre of the grid",
                 "widen the rectangle to at least one cell, inside the grid");
  }
}


}  // namespace nearshore::bake::detail
