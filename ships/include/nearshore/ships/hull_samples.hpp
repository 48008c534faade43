#pragma once
// Hull feature points (seed 000 section 4.2.2, fig. 4.4): the hull surface as points with outward
// normals and areas, over which the water pressure is integrated. Partial submersion is by the
// points: a point is wet when it lies below the water surface over it, so the wetted surface
// follows waves, heel and trim without any box approximation.
//
// Sampling: each triangle is cut by longest-edge bisection until every piece is no larger than
// area / target count and no longer than three times its spacing; each piece becomes one point at its
// centroid with its area and the face normal. The midpoint rule is exact for a pressure linear over
// a piece, so a flat bottom in still water gets its buoyancy exactly, and sum(area * normal) = 0
// for a closed hull.
#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "nearshore/ships/hull_mesh.hpp"

namespace nearshore::ships {

struct HullSamples {
  std::vector<Eigen::Vector3d> position_m;  ///< body frame (the piece's centroid)
  std::vector<Eigen::Vector3d> normal;      ///< unit, outward
  std::vector<double> area_m2;
  /// The piece's three corners (body frame): a piece cut by the waterline is integrated exactly
  /// over its wet part (ship_body.hpp), so the point sampling adds no force of its own.
  std::vector<std::array<Eigen::Vector3d, 3>> corner_m;
  std::size_t size() const { return area_m2.size(); }
};

/// About `target_count` points (more for meshes with many or long skinny triangles, at least one per
/// triangle with area); triangles without area are skipped.
/// Throws nearshore::Error naming the hull when it would take more than max_count pieces (a mesh of
/// more triangles than that, or of extreme proportions: each piece costs time every substep).
HullSamples sample_hull(const HullMesh& mesh, int target_count, std::size_t max_count = 1000000);

/// Displaced volume (m^3) below the plane z = waterline_z_m (body frame, upright), by the vertical
/// projection of the sampled surface: V = sum over points below the plane of (z_w - z) (-n_z) A
/// (the divergence theorem for the field (0, 0, z - z_w) over the closed wetted body).
double displaced_volume_m3(const HullSamples& samples, double waterline_z_m);

/// The upright draft (body z of the waterline) at which the hull displaces `volume_m3`, by
/// bisection of displaced_volume_m3 between the lowest and highest point. Returns a value above
/// the highest point when the whole hull displaces less (the caller refuses such a mass).
double waterline_for_volume_m(const HullSamples& samples, double volume_m3);

}  // namespace nearshore::ships
