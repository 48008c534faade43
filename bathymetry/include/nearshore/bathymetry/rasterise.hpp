#pragma once
// Burning projected vector geometry into a harbour grid: which cell centres lie inside a polygon,
// and which lie within a given distance of a line (a breakwater of a given crest width).
#include <functional>
#include <span>
#include <vector>

#include "nearshore/bathymetry/projection.hpp"
#include "nearshore/core/raster.hpp"

namespace nearshore::bathymetry {

using PlaneLine = std::vector<ProjectedPoint>;  ///< a polyline or a ring (closed or not), metres

using CellVisitor = std::function<void(int column, int row)>;

/// Visits every cell whose centre is inside the polygon made of `rings` (even-odd rule, so the
/// holes of a polygon are rings too). Scan-line fill: each row's crossings are sorted and the
/// spans between pairs visited, so the cost is O(rows * edges) plus the cells inside.
void for_each_cell_in_polygon(const GridGeometry& geometry, std::span<const PlaneLine> rings,
                              const CellVisitor& visit);

/// Visits every cell whose centre lies within `half_width_m` of the polyline, and at least the
/// cell under each vertex and segment (so a structure narrower than a cell still marks cells).
void for_each_cell_near_line(const GridGeometry& geometry, const PlaneLine& line, double half_width_m,
                             const CellVisitor& visit);

}  // namespace nearshore::bathymetry
