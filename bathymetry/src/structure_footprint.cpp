#include "nearshore/bathymetry/structure_footprint.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "nearshore/bathymetry/rasterise.hpp"

namespace nearshore::bathymetry {
namespace {

PlaneLine plane_line(const StructureLine& line) {
  PlaneLine out;
  out.reserve(line.size());
  for (const auto& [x_m, y_m] : line) out.push_back({x_m, y_m});
  return out;
}

double distance_to_segment_m(double x_m, double y_m, const ProjectedPoint& a, const ProjectedPoint& b) {
  const double dx = b.x_m - a.x_m, dy = b.y_m - a.y_m, length_sq = dx * dx + dy * dy;
  const double px = x_m - a.x_m, py = y_m - a.y_m;
  const double t = length_sq > 0 ? std::clamp((px * dx + py * dy) / length_sq, 0.0, 1.0) : 0.0;
  return std::hypot(px - t * dx, py - t * dy);
}

// Visits every cell within `reach_of(column, row)` (at most `largest_reach_m`) of the polyline
// (closed when `closed`), with its distance to the line.
template <typename Visit>
void for_each_cell_near(const GridGeometry& g, const PlaneLine& line, bool closed, double largest_reach_m, Visit&& visit) {
  const double dx = g.spacing_x_m(), dy = g.spacing_y_m();
  const std::size_t segments = line.size() < 2 ? line.size() : (closed ? line.size() : line.size() - 1);
  for (std::size_t i = 0; i < segments; ++i) {
    const ProjectedPoint a = line[i], b = line[(i + 1) % line.size()];
    const int c0 = std::max(0, static_cast<int>(std::floor((std::min(a.x_m, b.x_m) - largest_reach_m - g.origin_x_m) / dx)));
    const int c1 = std::min(g.columns - 1, static_cast<int>(std::floor((std::max(a.x_m, b.x_m) + largest_reach_m - g.origin_x_m) / dx)));
    const int r0 = std::max(0, static_cast<int>(std::floor((std::min(a.y_m, b.y_m) - largest_reach_m - g.origin_y_m) / dy)));
    const int r1 = std::min(g.rows - 1, static_cast<int>(std::floor((std::max(a.y_m, b.y_m) + largest_reach_m - g.origin_y_m) / dy)));
    for (int row = r0; row <= r1; ++row)
      for (int column = c0; column <= c1; ++column)
        visit(column, row, distance_to_segment_m(g.cell_centre_x_m(column), g.cell_centre_y_m(row), a, b));
  }
}

}  // namespace

bool has_impermeable_core(const CoastalStructure& structure) {
  return structure.transmission_coefficient <= 0.0 && structure.porosity < 0.0;
}

void for_each_footprint_cell(const GridGeometry& g, const Raster<float>& depth, const CoastalStructure& structure,
                             int minimum_face_cells, const FootprintVisitor& visit, double widening_m) {
  const bool impermeable = has_impermeable_core(structure);
  const double larger_cell_m = std::max(g.spacing_x_m(), g.spacing_y_m());
  // Half a cell diagonal: the cells a line passes through (and so a chain without gaps between faces).
  const double core_reach_m = 0.5 * std::hypot(g.spacing_x_m(), g.spacing_y_m()) * std::sqrt(0.5);
  const double minimum_face_m = minimum_face_cells * larger_cell_m;
  float deepest_m = 0.0f;
  for (float d : depth.values()) deepest_m = std::max(deepest_m, d);
  // How far the footprint reaches from the centre line (lines) or the outline (areas) at a cell.
  auto line_reach_m = [&](int c, int r) {
    return std::max(structure.footprint_half_width_m(depth(c, r)), (impermeable ? core_reach_m : 0.0) + minimum_face_m) + widening_m;
  };
  auto outline_reach_m = [&](int c, int r) {
    return std::max(structure.side_slope * (structure.crest_elevation_m + std::max(0.0f, depth(c, r))), minimum_face_m) + widening_m;
  };
  const double largest_line_reach_m =
      std::max(structure.footprint_half_width_m(deepest_m), (impermeable ? core_reach_m : 0.0) + minimum_face_m) + widening_m + larger_cell_m;
  for (const StructureLine& centre_line : structure.lines) {
    const PlaneLine line = plane_line(centre_line);
    for_each_cell_near(g, line, false, std::max(largest_line_reach_m, core_reach_m), [&](int c, int r, double distance_m) {
      if (impermeable && distance_m <= core_reach_m)
        visit(c, r, FootprintPart::kCore);
      else if (distance_m <= line_reach_m(c, r) || distance_m <= core_reach_m)
        visit(c, r, FootprintPart::kFace);
    });
  }
  const double largest_outline_reach_m =
      std::max(structure.side_slope * (structure.crest_elevation_m + deepest_m), minimum_face_m) + widening_m + larger_cell_m;
  for (const auto& polygon : structure.polygons) {
    std::vector<PlaneLine> rings;
    for (const StructureLine& ring : polygon) rings.push_back(plane_line(ring));
    for_each_cell_in_polygon(g, rings, [&](int c, int r) { visit(c, r, impermeable ? FootprintPart::kCore : FootprintPart::kFace); });
    for (const PlaneLine& ring : rings) {
      // A pier narrower than a cell still blocks (or porously fills) the cells its outline crosses.
      for_each_cell_near(g, ring, true, std::max(largest_outline_reach_m, core_reach_m), [&](int c, int r, double distance_m) {
        if (distance_m <= core_reach_m && impermeable)
          visit(c, r, FootprintPart::kCore);
        else if (distance_m <= outline_reach_m(c, r) || distance_m <= core_reach_m)
          visit(c, r, FootprintPart::kFace);
      });
    }
  }
}

}  // namespace nearshore::bathymetry
