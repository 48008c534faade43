#include "nearshore/bathymetry/rasterise.hpp"

#include <algorithm>
#include <cmath>

namespace nearshore::bathymetry {

void for_each_cell_in_polygon(const GridGeometry& g, std::span<const PlaneLine> rings, const CellVisitor& visit) {
  double y_min = INFINITY, y_max = -INFINITY;
  for (const auto& ring : rings)
    for (const auto& p : ring) y_min = std::min(y_min, p.y_m), y_max = std::max(y_max, p.y_m);
  if (!(y_min <= y_max)) return;
  const int row_first = std::max(0, static_cast<int>(std::ceil((y_min - g.origin_y_m) / g.spacing_m - 0.5)));
  const int row_last = std::min(g.rows - 1, static_cast<int>(std::floor((y_max - g.origin_y_m) / g.spacing_m - 0.5)));
  std::vector<double> crossings;
  for (int row = row_first; row <= row_last; ++row) {
    const double y = g.cell_centre_y_m(row);
    crossings.clear();
    for (const auto& ring : rings) {
      const std::size_t n = ring.size();
      for (std::size_t i = 0; i < n; ++i) {
        const ProjectedPoint& a = ring[i];
        const ProjectedPoint& b = ring[(i + 1) % n];  // closes open rings; a zero edge if already closed
        // Half-open rule (a.y <= y < b.y or b.y <= y < a.y): a vertex exactly on the scan line counts once.
        if ((a.y_m <= y) != (b.y_m <= y)) crossings.push_back(a.x_m + (y - a.y_m) / (b.y_m - a.y_m) * (b.x_m - a.x_m));
      }
    }
    std::sort(crossings.begin(), crossings.end());
    for (std::size_t k = 0; k + 1 < crossings.size(); k += 2) {
      const int first = std::max(0, static_cast<int>(std::ceil((crossings[k] - g.origin_x_m) / g.spacing_m - 0.5)));
      const int last = std::min(g.columns - 1,
                                static_cast<int>(std::ceil((crossings[k + 1] - g.origin_x_m) / g.spacing_m - 0.5)) - 1);
      for (int column = first; column <= last; ++column) visit(column, row);
    }
  }
}

void for_each_cell_near_line(const GridGeometry& g, const PlaneLine& line, double half_width_m,
                             const CellVisitor& visit) {
  if (line.empty()) return;
  // A structure narrower than a cell still blocks the cell it crosses: widen to half a diagonal.
  const double reach = std::max(half_width_m, 0.5 * g.spacing_m * std::sqrt(0.5));
  auto cell_of = [&](double v, double origin) { return static_cast<int>(std::floor((v - origin) / g.spacing_m)); };
  for (std::size_t i = 0; i < line.size(); ++i) {
    const ProjectedPoint a = line[i];
    const ProjectedPoint b = line[std::min(i + 1, line.size() - 1)];
    const int c0 = std::max(0, cell_of(std::min(a.x_m, b.x_m) - reach, g.origin_x_m));
    const int c1 = std::min(g.columns - 1, cell_of(std::max(a.x_m, b.x_m) + reach, g.origin_x_m));
    const int r0 = std::max(0, cell_of(std::min(a.y_m, b.y_m) - reach, g.origin_y_m));
    const int r1 = std::min(g.rows - 1, cell_of(std::max(a.y_m, b.y_m) + reach, g.origin_y_m));
    const double dx = b.x_m - a.x_m, dy = b.y_m - a.y_m, length_sq = dx * dx + dy * dy;
    for (int row = r0; row <= r1; ++row)
      for (int column = c0; column <= c1; ++column) {
        // Distance from the cell centre to segment ab.
        const double px = g.cell_centre_x_m(column) - a.x_m, py = g.cell_centre_y_m(row) - a.y_m;
        const double t = length_sq > 0 ? std::clamp((px * dx + py * dy) / length_sq, 0.0, 1.0) : 0.0;
        if (std::hypot(px - t * dx, py - t * dy) <= reach) visit(column, row);
      }
    if (line.size() == 1) break;
  }
}

}  // namespace nearshore::bathymetry
