#pragma once
// Surroundings for the terrain tests (issue 41): cells of `spacing_m` over the grid's box grown by
// `margin_m` on every side (whole cells, from the grown box's south-west corner), each holding
// depth_at(x, y) at its centre in the site frame (metres from the grid's south-west corner).
#include <cmath>

#include "nearshore/core/harbour_grid.hpp"

namespace nearshore::test {

template <class DepthAt>
Surroundings surroundings_round(const GridGeometry& grid, double spacing_m, double margin_m, DepthAt depth_at) {
  Surroundings s;
  s.geometry = grid;
  s.geometry.spacing_m = spacing_m;
  s.geometry.columns = int(std::ceil((grid.width_m() + 2 * margin_m) / spacing_m - 1e-9));
  s.geometry.rows = int(std::ceil((grid.height_m() + 2 * margin_m) / spacing_m - 1e-9));
  s.geometry.origin_x_m = grid.origin_x_m - margin_m;
  s.geometry.origin_y_m = grid.origin_y_m - margin_m;
  s.still_water_depth_m = Raster<float>(s.geometry.columns, s.geometry.rows);
  for (int j = 0; j < s.geometry.rows; ++j)
    for (int i = 0; i < s.geometry.columns; ++i)
      s.still_water_depth_m(i, j) = float(depth_at(-margin_m + (i + 0.5) * spacing_m, -margin_m + (j + 0.5) * spacing_m));
  return s;
}

}  // namespace nearshore::test
