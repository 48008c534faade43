#pragma once
// The seabed under the ships: the harbour grid's still-water depth (depth.exr, positive down, land
// negative), bilinear at cell centres with clamping at the rectangle's edge (the rule of
// surface_sampler.hpp formula 1), so grounding, the bow-wave grids and a scenario's placement
// check all see the depth the bake used.
#include <memory>

#include "nearshore/runtime/surface_snapshot.hpp"
#include "nearshore/ships/harbour_obstacles.hpp"

namespace nearshore::ships {

class Seabed {
 public:
  /// A seabed from a site's harbour grid (the site must outlive nothing: it is held), with its
  /// structures and land as obstacles (harbour_obstacles.hpp).
  explicit Seabed(std::shared_ptr<const runtime::HarbourSite> site, HarbourObstacleOptions obstacles = {});
  /// A flat seabed `depth_m` deep everywhere (open sea, laboratory tests).
  static Seabed flat(double depth_m);

  /// Still-water depth (m, positive down; negative on land) at site point (x, y); NaN when x or y
  /// is NaN, the edge's depth beyond the grid (infinities included).
  double depth_m(double x_m, double y_m) const;
  /// Whether (x, y) lies inside the harbour grid (always true for a flat seabed).
  bool covers(double x_m, double y_m) const;
  const runtime::HarbourSite* site() const { return site_.get(); }
  /// The structures and land that stop hulls sideways; null for a flat seabed or a grid without
  /// solid cells.
  const HarbourObstacles* obstacles() const { return obstacles_ && obstacles_->any() ? obstacles_.get() : nullptr; }

 private:
  Seabed() = default;
  std::shared_ptr<const runtime::HarbourSite> site_;
  std::shared_ptr<const HarbourObstacles> obstacles_;
  double flat_depth_m_ = 0.0;
};

}  // namespace nearshore::ships
