#include "nearshore/ships/hull_samples.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"

namespace nearshore::ships {

namespace {

struct TooManyPieces {};

// Longest-edge bisection until a piece is no larger than the target area and no longer than twice
// the target spacing: pieces stay well shaped (skinny lofted triangles are cut across, not along),
// and their number is close to area / target area.
void bisect(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& normal,
            double target_area, double max_edge, std::size_t max_count, HullSamples& out) {
  const double area = 0.5 * (b - a).cross(c - a).norm();
  const double ab = (b - a).squaredNorm(), bc = (c - b).squaredNorm(), ca = (a - c).squaredNorm();
  const double longest = std::sqrt(std::max({ab, bc, ca}));
  if (area <= target_area && longest <= max_edge) {
    if (out.size() >= max_count) throw TooManyPieces{};
    out.position_m.push_back((a + b + c) / 3.0);
    out.normal.push_back(normal);
    out.area_m2.push_back(area);
    out.corner_m.push_back({a, b, c});
    return;
  }
  if (ab >= bc && ab >= ca) {
    const Eigen::Vector3d m = 0.5 * (a + b);
    bisect(a, m, c, normal, target_area, max_edge, max_count, out);
    bisect(m, b, c, normal, target_area, max_edge, max_count, out);
  } else if (bc >= ca) {
    const Eigen::Vector3d m = 0.5 * (b + c);
    bisect(a, b, m, normal, target_area, max_edge, max_count, out);
    bisect(a, m, c, normal, target_area, max_edge, max_count, out);
  } else {
    const Eigen::Vector3d m = 0.5 * (c + a);
    bisect(a, b, m, normal, target_area, max_edge, max_count, out);
    bisect(m, b, c, normal, target_area, max_edge, max_count, out);
  }
}

}  // namespace

HullSamples sample_hull(const HullMesh& mesh, int target_count, std::size_t max_count) {
  double total_area = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices_m[t[0]];
    total_area += 0.5 * (mesh.vertices_m[t[1]] - a).cross(mesh.vertices_m[t[2]] - a).norm();
  }
  HullSamples out;
  if (total_area <= 0.0 || target_count < 1) return out;
  // Bisection leaves pieces between half and all of the area limit: a limit of 1.4 times the mean
  // area per point gives about target_count points.
  const double target_area = 1.4 * total_area / target_count;
  const double max_edge = 3.0 * std::sqrt(2.0 * target_area);  // three legs of a right isosceles piece
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices_m[t[0]], b = mesh.vertices_m[t[1]], c = mesh.vertices_m[t[2]];
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    if (!(0.5 * cross.norm() > 1e-12 * total_area)) continue;
    try {
      bisect(a, b, c, cross.normalized(), target_area, max_edge, max_count, out);
    } catch (const TooManyPieces&) {
      throw Error(mesh.name,
                  fmt::format("would be cut into more than {} pressure pieces for {} points ({} triangles)", max_count,
                              target_count, mesh.triangles.size()),
                  "decimate the mesh, or give a hull of ordinary proportions");
    }
  }
  return out;
}

double displaced_volume_m3(const HullSamples& samples, double waterline_z_m) {
  double volume = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double depth = waterline_z_m - samples.position_m[i].z();
    if (depth > 0.0) volume += depth * (-samples.normal[i].z()) * samples.area_m2[i];
  }
  return volume;
}

double waterline_for_volume_m(const HullSamples& samples, double volume_m3) {
  double low = 1e300, high = -1e300;
  for (const auto& p : samples.position_m) {
    low = std::min(low, p.z());
    high = std::max(high, p.z());
  }
  if (displaced_volume_m3(samples, high) < volume_m3) return high + 1.0;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double mid = 0.5 * (low + high);
    (displaced_volume_m3(samples, mid) < volume_m3 ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace nearshore::ships
