#pragma once
// What stops a hull sideways: the harbour grid's structures (breakwaters, quays, piers: cells of
// porosity n < 1, seed 003 eq. 2-3) and its land, as solid obstacles (issue 42).
//
// The harbour grid (core/harbour_grid.hpp) knows a structure only as cells; a hull must meet its
// face where the face is, not on the cells' staircase, and be pushed along the face's normal. So the
// solid cells become a signed distance field phi (m, > 0 in water, < 0 inside), sampled at the cell
// centres and interpolated bilinearly:
//   1. a cell centre's distance to the nearest cell centre of the other kind (Euclidean, searched
//      within band_cells of the boundary; phi = +-band beyond), less half a cell, so that phi = 0
//      on the face between a solid and a water cell: exact for walls along the grid axes;
//   2. two binomial (1 2 1)/4 passes in x and y, which keep a linear field (a straight face at any
//      angle, away from corners) and take the sharpest steps off the staircase;
//   3. the normal, near the faces (cells within normal_fit_cells of one): a weighted
//      least-squares line through the midpoints of the solid/water cell edges ("boundary edges")
//      within normal_fit_radius_cells of the cell's nearest boundary edge, i.e. the face the
//      staircase digitises rather than the staircase itself. A straight face at any angle puts its
//      edge midpoints within half a cell of the true line, scattered evenly either side, so the fit's
//      direction is the face's to a few degrees over a 3.5-cell radius (tested at 30 deg: the
//      staircase's own edges would give 0 or 90 deg; the gradient of a smoothed solid/water
//      indicator, the earlier normal, came out 7.7 deg off because its 1.7-cell kernel sees only two
//      or three steps of the staircase). The fit is the total least-squares line (the principal
//      axis of the weighted midpoints' covariance, weights (1 - r^2/R^2)^2), oriented out of the
//      solid by the nearest edge's own outward normal; edges facing the other way (the far side of
//      a thin pier) are left out. Corners are rounded over the fit radius. Farther from any face the
//      normal is the gradient of the +-1 indicator after smoothing_passes binomial passes, which
//      points away from the solid everywhere within the band. Both are interpolated bilinearly; a
//      sample uses the fitted normals only where all four surrounding cells have one.
// Structures are the 8-connected components of structure cells, numbered from 1 in the order of
// their south-westernmost cell (row by row from the south); land is 0. Each has its lowest
// porosity: below 0.05 it is a wall (a quay, a caisson: the Boussinesq solver's kWallPorosity),
// else a porous (rubble-mound) breakwater.
//
// Heights. The harbour grid carries no crest heights: a structure stands from the seabed to
// structure_crest_m above still water (2.5 m by default, what the renderer draws:
// playback WaterRendererSettings::structure_crest_m); land to its own elevation (-depth), at least
// still water. A hull point below that top and inside (phi < 0) is in contact.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nearshore/core/harbour_grid.hpp"

namespace nearshore::ships {

struct HarbourStructure {
  int id = 0;                 ///< 1, 2, ... (0 is land)
  double porosity = 1.0;      ///< the lowest of its cells
  bool wall = false;          ///< porosity below 0.05: a quay wall or caisson
  int cells = 0;
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();  ///< mean of its cell centres, site frame
  /// "structure 2 (a rubble-mound breakwater, porosity 0.40, 120 cells about (520.0, 880.0) m)",
  /// "the land".
  std::string describe() const;
};

/// The obstacle field at a point.
struct ObstacleSample {
  double signed_distance_m = 0.0;  ///< > 0 in water, < 0 inside a structure or land
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();  ///< unit, out of the solid (0 where no face is near)
  int structure = -1;              ///< the nearest solid: 0 land, k >= 1 structure k, -1 none within the band
  double top_m = 0.0;              ///< that solid's top above still water
};

struct HarbourObstacleOptions {
  double structure_crest_m = 2.5;  ///< structures stand this high above still water
  int band_cells = 8;              ///< phi is exact within this many cells of a face, clamped beyond
  int smoothing_passes = 6;        ///< binomial passes over the indicator (step 3 above)
  int normal_fit_cells = 3;        ///< cells this close to a face get the fitted normal (step 3)
  double normal_fit_radius_cells = 4.5;  ///< the line fit's radius about the nearest boundary edge
};

class HarbourObstacles {
 public:
  /// The obstacles of a harbour grid whose cell (i, j) is centred at ((i + 0.5) dx, (j + 0.5) dy)
  /// of the site frame.
  explicit HarbourObstacles(const HarbourGrid& grid, HarbourObstacleOptions options = {});

  /// Whether the grid has any solid cell (land or structure).
  bool any() const { return any_; }
  ObstacleSample sample(double x_m, double y_m) const;
  /// phi alone (m), the cheap test.
  double signed_distance_m(double x_m, double y_m) const;
  const std::vector<HarbourStructure>& structures() const { return structures_; }
  /// The structure (or land, id 0) named by `id`; throws std::out_of_range for another id.
  HarbourStructure describe(int id) const;
  const HarbourObstacleOptions& options() const { return options_; }

 private:
  int columns_ = 0, rows_ = 0;
  double dx_ = 1.0, dy_ = 1.0;
  HarbourObstacleOptions options_;
  bool any_ = false;
  std::vector<float> phi_;           ///< signed distance at cell centres (m), smoothed
  std::vector<float> indicator_;     ///< +1 water, -1 solid, smoothed: its gradient is the far normal
  std::vector<Eigen::Vector2f> fitted_normal_;  ///< per cell near a face: the line fit's normal (0: none)
  std::vector<std::int32_t> owner_;  ///< per cell: the index of the nearest solid cell (-1: none)
  std::vector<std::int32_t> label_;  ///< per solid cell: 0 land, k >= 1 structure k; -1 water
  std::vector<float> top_;           ///< per solid cell: its top above still water (m)
  std::vector<HarbourStructure> structures_;

  /// Step 4 of the constructor: fitted_normal_ from the boundary edges (`distance`: each cell
  /// centre's distance to the nearest centre of the other kind, m).
  void fit_normals(const std::vector<float>& distance);
};

}  // namespace nearshore::ships
