#pragma once
// Exact Euclidean distance transform on a harbour grid (Felzenszwalb & Huttenlocher 2012,
// "Distance transforms of sampled functions": two separable passes, one down the columns and one
// along the rows, each the lower envelope of parabolas; O(cells)). It also returns the nearest
// seed cell (the feature transform), which fills cells that no data source covers.
#include <cstdint>

#include "nearshore/core/raster.hpp"

namespace nearshore::bathymetry {

struct NearestSeed {
  Raster<float> distance_m;             ///< centre-to-centre distance to the nearest seed; +inf if none
  Raster<std::int32_t> nearest_column;  ///< column of that seed, -1 if none
  Raster<std::int32_t> nearest_row;     ///< row of that seed, -1 if none
};

/// Seeds are the cells where `seed` is non-zero.
NearestSeed nearest_seed_transform(const Raster<std::uint8_t>& seed, double spacing_m);

/// Signed distance to the land/water boundary, metres: positive in water, negative on land,
/// measured to the edge between cells (centre distance minus half a cell). +inf everywhere if
/// there is no land, -inf if there is no water.
Raster<float> signed_coast_distance(const Raster<std::uint8_t>& land, double spacing_m);

}  // namespace nearshore::bathymetry
