// The run-up line's cells chained along the shore by crack following (runup_line.hpp explains why).
#include "nearshore/bake/runup_line.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "nearshore/core/error.hpp"

namespace nearshore::bake {
namespace {

// The four directions, anticlockwise from east (east, north, west, south: row numbers grow
// northward), so that (d + 3) % 4 turns right and (d + 2) % 4 turns back.
constexpr std::array<int, 4> kStepColumn = {1, 0, -1, 0};
constexpr std::array<int, 4> kStepRow = {0, 1, 0, -1};
constexpr int turn_right(int direction) {
  return (direction + 3) % 4;
}
constexpr int turn_back(int direction) {
  return (direction + 2) % 4;
}

// A crack: the side of an ever-wet cell that faces a never-wet 4-neighbour, named by the wet cell
// and the direction of that neighbour (`dry_side`). Walking it with the dry side on the left means
// heading turn_right(dry_side): dry to the east is walked southward, dry to the north eastward.
class CrackGrid {
 public:
  explicit CrackGrid(const Raster<float>& maximum_surface_elevation_m)
      : envelope_(maximum_surface_elevation_m), columns_(envelope_.columns()), rows_(envelope_.rows()) {}

  std::size_t crack_count() const { return envelope_.size() * 4; }
  static std::size_t crack(std::size_t cell, int dry_side) {
    return cell * 4 + static_cast<std::size_t>(dry_side);
  }
  int column_of(std::size_t crack) const {
    return static_cast<int>(crack / 4 % static_cast<std::size_t>(columns_));
  }
  int row_of(std::size_t crack) const {
    return static_cast<int>(crack / 4 / static_cast<std::size_t>(columns_));
  }
  static int dry_side_of(std::size_t crack) { return static_cast<int>(crack % 4); }

  bool inside(int column, int row) const {
    return column >= 0 && column < columns_ && row >= 0 && row < rows_;
  }
  bool wet(int column, int row) const { return !std::isnan(envelope_(column, row)); }
  /// Never wet and on the grid: outside the grid is no land (WaveStatistics: the water goes on).
  bool dry(int column, int row) const { return inside(column, row) && !wet(column, row); }

  bool is_crack(std::size_t crack) const {
    const int column = column_of(crack), row = row_of(crack), side = dry_side_of(crack);
    return wet(column, row) && dry(column + kStepColumn[side], row + kStepRow[side]);
  }

  /// The crack that continues `crack` at the cell corner it walks into, or nullopt at the grid's edge.
  /// With heading t, wet cell W on the right and dry cell D on the left, the cells ahead are
  /// D + t (ahead-left) and W + t (ahead-right):
  ///   ahead-left wet             turn left round D      (also where W and ahead-left touch only at
  ///                                                      this corner: the water passes through it)
  ///   ahead-left dry, right wet  straight on            between ahead-left and ahead-right
  ///   both ahead dry             turn right round W
  /// At every corner this pairs each arriving crack with one leaving crack, so the walks never merge.
  std::optional<std::size_t> next(std::size_t crack) const {
    const int column = column_of(crack), row = row_of(crack), dry_side = dry_side_of(crack);
    const int heading = turn_right(dry_side);
    const int ahead_right_column = column + kStepColumn[heading], ahead_right_row = row + kStepRow[heading];
    if (!inside(ahead_right_column, ahead_right_row))
      return std::nullopt;  // the crack ends on the grid's edge
    const int ahead_left_column = ahead_right_column + kStepColumn[dry_side];
    const int ahead_left_row = ahead_right_row + kStepRow[dry_side];
    const auto cell = [&](int c, int r) { return static_cast<std::size_t>(r) * columns_ + c; };
    // The dry cell D of this crack is on the grid, and ahead-left lies beside ahead-right across the
    // same line as D beside W, so ahead-left is on the grid too.
    if (wet(ahead_left_column, ahead_left_row))
      return CrackGrid::crack(cell(ahead_left_column, ahead_left_row),
                              turn_back(heading));  // D lies behind it
    if (wet(ahead_right_column, ahead_right_row))
      return CrackGrid::crack(cell(ahead_right_column, ahead_right_row), dry_side);
    return CrackGrid::crack(cell(column, row), heading);  // ahead-right is the dry cell now
  }

 private:
  const Raster<float>& envelope_;
  int columns_, rows_;
};

}  // namespace

float RunupLine::highest_water_level_m() const {
  assert(!vertices.empty());
  return std::max_element(
             vertices.begin(), vertices.end(),
             [](const RunupVertex& a, const RunupVertex& b) { return a.water_level_m < b.water_level_m; })
      ->water_level_m;
}

float RunupLine::lowest_water_level_m() const {
  assert(!vertices.empty());
  return std::min_element(
             vertices.begin(), vertices.end(),
             [](const RunupVertex& a, const RunupVertex& b) { return a.water_level_m < b.water_level_m; })
      ->water_level_m;
}

int RunupLine::cell_count() const {
  std::set<std::pair<int, int>> cells;
  for (const RunupVertex& vertex : vertices) cells.emplace(vertex.column, vertex.row);
  return static_cast<int>(cells.size());
}

double RunupLine::length_m(const GridGeometry& geometry) const {
  const auto segment_m = [&](const RunupVertex& a, const RunupVertex& b) {
    return std::hypot((b.column - a.column) * geometry.spacing_x_m(),
                      (b.row - a.row) * geometry.spacing_y_m());
  };
  double length = 0.0;
  for (std::size_t k = 1; k < vertices.size(); ++k) length += segment_m(vertices[k - 1], vertices[k]);
  if (closed && vertices.size() > 1) length += segment_m(vertices.back(), vertices.front());
  return length;
}

std::vector<RunupLine> trace_runup_lines(const Raster<float>& runup_line_water_level_m,
                                         const Raster<float>& maximum_surface_elevation_m) {
  const Raster<float>& front = runup_line_water_level_m;
  const std::string subject = "the run-up line raster (runup_line_water_level_m)";
  const std::string fix =
      "pass the run-up line and the envelope of one WaveStatistics "
      "(runup_line_water_level_m() and maximum_surface_elevation_m())";
  if (front.columns() != maximum_surface_elevation_m.columns() ||
      front.rows() != maximum_surface_elevation_m.rows())
    throw Error(subject,
                fmt::format("is {} x {} cells but the envelope (maximum_surface_elevation_m) is {} x {}",
                            front.columns(), front.rows(), maximum_surface_elevation_m.columns(),
                            maximum_surface_elevation_m.rows()),
                fix);
  const CrackGrid grid(maximum_surface_elevation_m);

  // 1. Which cracks exist, and which have a crack walking into them: those without one start at
  //    the grid's edge. One byte of flags per crack, 4 B per cell: less than the GeoTIFF writer holds
  //    before it (the bake's memory estimate counts 20 B per cell for the writing of the statistics).
  enum : std::uint8_t { kExists = 1, kHasPredecessor = 2, kWalked = 4 };
  std::vector<std::uint8_t> flags(grid.crack_count(), 0);
  for (std::size_t crack = 0; crack < grid.crack_count(); ++crack)
    if (grid.is_crack(crack)) flags[crack] = kExists;
  for (std::size_t crack = 0; crack < grid.crack_count(); ++crack)
    if (flags[crack] & kExists)
      if (const auto following = grid.next(crack)) {
        assert((flags[*following] & kExists) && !(flags[*following] & kHasPredecessor));
        flags[*following] |= kHasPredecessor;
      }

  // 2. Walk: the wet cell of each crack in turn is the line, a cell that keeps several cracks in a
  //    row (a wet cell jutting into dry ground) one vertex.
  std::vector<RunupLine> lines;
  const auto walk = [&](std::size_t first, bool closed) {
    RunupLine line;
    line.closed = closed;
    std::optional<std::size_t> crack = first;
    while (crack && !(flags[*crack] & kWalked)) {
      flags[*crack] |= kWalked;
      const int column = grid.column_of(*crack), row = grid.row_of(*crack);
      if (line.vertices.empty() || line.vertices.back().column != column || line.vertices.back().row != row) {
        const float level = front(column, row);
        if (std::isnan(level))
          throw Error(
              subject,
              fmt::format(
                  "has no value at cell (column {}, row {}), which the envelope shows ever wet beside a "
                  "never-wet cell, on the front",
                  column, row),
              fix);
        line.vertices.push_back({column, row, level});
      }
      crack = grid.next(*crack);
    }
    // A ring that starts and ends in one cell (cracks on two sides of its first cell) holds it once.
    if (closed && line.vertices.size() > 1 && line.vertices.front().column == line.vertices.back().column &&
        line.vertices.front().row == line.vertices.back().row)
      line.vertices.pop_back();
    lines.push_back(std::move(line));
  };
  for (std::size_t crack = 0; crack < grid.crack_count(); ++crack)
    if ((flags[crack] & kExists) && !(flags[crack] & kHasPredecessor)) walk(crack, false);
  for (std::size_t crack = 0; crack < grid.crack_count(); ++crack)
    if ((flags[crack] & kExists) && !(flags[crack] & kWalked))
      walk(crack, true);  // the rest closes on itself

  // 3. Every cell of the front raster must be on a line: a value elsewhere means the two rasters
  //    are not of one WaveStatistics (the front is exactly the ever-wet cells with a crack).
  std::vector<std::uint8_t> on_a_line(front.size(), 0);
  for (const RunupLine& line : lines)
    for (const RunupVertex& vertex : line.vertices)
      on_a_line[static_cast<std::size_t>(vertex.row) * front.columns() + vertex.column] = 1;
  for (int row = 0; row < front.rows(); ++row)
    for (int column = 0; column < front.columns(); ++column)
      if (!std::isnan(front(column, row)) &&
          !on_a_line[static_cast<std::size_t>(row) * front.columns() + column])
        throw Error(
            subject,
            fmt::format(
                "has a value at cell (column {}, row {}), which the envelope does not show ever wet beside a "
                "never-wet cell",
                column, row),
            fix);
  return lines;
}

}  // namespace nearshore::bake
