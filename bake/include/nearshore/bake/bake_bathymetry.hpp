#pragma once
// The bathymetries a bake case can ask for besides a harbour grid from `nearshore bathy`: the
// laboratory flumes of the validation cases (docs/validation.md), and resampling a harbour grid to
// the spacing the case wants. All depths are still-water depths d in metres, positive down;
// negative values are dry land (elevation above still water).
#include <utility>
#include <vector>

#include "nearshore/core/harbour_grid.hpp"

namespace nearshore::bake {

/// The size of a cell along x and y, metres: one number for square cells, two for rectangular
/// cells (dx != dy, issue 15; GridGeometry::set_spacing). Converts from a number (square cells).
struct CellSize {
  double x_m = 1.0, y_m = 1.0;
  CellSize(double square_m) : x_m(square_m), y_m(square_m) {}  // implicit: a number means square cells
  CellSize(double along_x_m, double along_y_m) : x_m(along_x_m), y_m(along_y_m) {}
  bool square() const { return x_m == y_m; }
};

/// A flume `length_m` (x, along the waves) by `width_m` (y) with cells of `spacing`, whose depth
/// varies only along x: piecewise linear through `profile` = (x_m, depth_m) points with increasing
/// x, constant beyond the first and last points. Cells with depth <= 0 are marked land.
/// Throws nearshore::Error(subject, ...) for a profile that is not increasing or a bad size.
HarbourGrid flume_from_profile(double length_m, double width_m, CellSize spacing,
                               const std::vector<std::pair<double, double>>& profile, const std::string& subject);

/// Depth of a piecewise-linear profile at x (constant beyond the ends). `profile` must be increasing in x.
double profile_depth_m(const std::vector<std::pair<double, double>>& profile, double x_m);

/// Berkhoff, Booij & Radder (1982) elliptic shoal on a plane slope, in the rotated frame of the
/// experiment (x' across, y' pointing UP-wave, both rotated by `rotation_deg` from the grid, centre
/// of the shoal at `centre`):
///   slope  d = deep_depth_m                                   for y' >= slope_start_m
///          d = deep_depth_m - slope * (slope_start_m - y')     below, clipped at minimum_depth_m
///   shoal  d -= 0.5 sqrt(1 - (x'/5)^2 - (y'/3.75)^2) - 0.3     where (x'/4)^2 + (y'/3)^2 < 1
/// Waves travel along +x in the grid, so y' = -(x - x_c) cos(rot) + ... (see the implementation).
struct BerkhoffShoal {
  double centre_x_m = 13.15, centre_y_m = 10.0;
  double rotation_deg = 20.0;
  double deep_depth_m = 0.45;
  double slope = 0.02;
  double slope_start_m = 5.84;   ///< FUNWAVE's DEPTH.F value; the paper states 5.82
  double minimum_depth_m = 0.07;
};
double berkhoff_shoal_depth_m(const BerkhoffShoal& shoal, double x_m, double y_m);
HarbourGrid berkhoff_shoal_grid(double length_m, double width_m, CellSize spacing, const BerkhoffShoal& shoal);

/// The grid resampled to cells of `spacing` (square or rectangular, from square or rectangular
/// cells) over the same extent (bilinear depth and coast distance, on each axis' own spacing;
/// nearest-cell land and porosity so walls stay walls; the coastal structures carried along, for the
/// bake to lay at the new cells). Returns the input unchanged when both
/// spacings already match to 1e-9 relative.
HarbourGrid resample_harbour_grid(const HarbourGrid& grid, CellSize spacing);

/// The grid under still water `level_m` above the datum its depths refer to (a tide, or a surge):
/// every still-water depth d becomes d + level_m, so land lower than the level floods, higher
/// water reaches further up the beaches, and the wet/dry line moves; the land mask follows the new
/// depths. Porosity and coast distance are kept (the coastline of the chart, not of the tide).
/// Case key `bathymetry.still_water_level_m`; the sea-state library sweeps it (library/).
void raise_still_water_level(HarbourGrid& grid, double level_m);

/// What the bake does with the harbour grid's cells outside the chart's coverage (land ==
/// kOutsideChartCell, issue 14 item 3; case key `bathymetry.outside_chart`).
struct OutsideChartRule {
  enum class Treatment {
    kLand,  ///< solid land, as high as the grid says (bathy's land elevation, 2 m): a wall that reflects
    kSea,   ///< open water: `depth_m` if > 0, else the depth of the nearest charted water cell
  };
  Treatment treatment = Treatment::kLand;
  double depth_m = 0.0;  ///< kSea only: a constant depth, metres; 0 = the nearest charted water depth
};

/// Resolves every outside-chart cell by `rule`, so the grid the solver sees holds only land and water.
/// kSea: the nearest charted water cell is the exact Euclidean one (Felzenszwalb-Huttenlocher feature
/// transform, bathymetry/distance_transform.hpp); porosity becomes 1 and the coastline distance is
/// recomputed, since the coast moved. Returns the number of cells changed. Throws nearshore::Error
/// naming `subject` when kSea has no charted water cell to extend.
std::size_t resolve_outside_chart(HarbourGrid& grid, const OutsideChartRule& rule, const std::string& subject);

}  // namespace nearshore::bake
