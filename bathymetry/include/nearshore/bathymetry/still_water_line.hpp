#pragma once
// The still-water line of a gridded depth: where depth = 0 between the cell centres, traced with
// GDAL's contour generator (GDALContourGenerate: marching squares over the cell centres, segments
// joined into polylines). The preview draws it in red for inputs that bring no coastline of their
// own (a raster or XYZ survey), so every preview shows where the water ends (issue 19).
#include <vector>

#include "nearshore/bathymetry/rasterise.hpp"
#include "nearshore/core/harbour_grid.hpp"

namespace nearshore::bathymetry {

/// The depth-0 polylines of `grid.still_water_depth_m` (positive down, land negative) in the grid's
/// projected metres. Cells outside the chart (land channel kOutsideChartCell) and NaN depths are
/// no data: no line is drawn through them. Throws nearshore::Error if GDAL cannot trace.
std::vector<PlaneLine> trace_still_water_line(const HarbourGrid& grid);

}  // namespace nearshore::bathymetry
