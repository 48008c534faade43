#include "nearshore/ships/hull_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <unordered_map>

#include <fmt/format.h>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::ships {

MeshMassProperties mesh_mass_properties(const HullMesh& mesh) {
  MeshMassProperties out;
  double volume = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices_m[t[0]];
    const Eigen::Vector3d& b = mesh.vertices_m[t[1]];
    const Eigen::Vector3d& c = mesh.vertices_m[t[2]];
    const double v = a.dot(b.cross(c)) / 6.0;
    const Eigen::Vector3d s = a + b + c;
    volume += v;
    first_moment += v * s / 4.0;
    covariance += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    out.surface_area_m2 += 0.5 * (b - a).cross(c - a).norm();
  }
  out.volume_m3 = volume;
  if (volume != 0.0) out.centroid_m = first_moment / volume;
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d inertia_origin = covariance.trace() * identity - covariance;
  const Eigen::Vector3d& g = out.centroid_m;
  out.inertia_per_density_m5 = inertia_origin - volume * (g.squaredNorm() * identity - g * g.transpose());
  return out;
}

void require_closed_outward(const HullMesh& mesh) {
  if (mesh.triangles.empty())
    throw Error(mesh.name, "has no triangles", "give a closed triangle mesh of the hull (deck included)");
  const long long n = static_cast<long long>(mesh.vertices_m.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= n)
        throw Error(mesh.name, fmt::format("a triangle refers to vertex {} of {}", t[k], n), "repair the mesh file");
  // Count every directed edge: a closed, consistently wound two-manifold uses each exactly once,
  // and its reverse exactly once.
  std::unordered_map<long long, int> directed;
  directed.reserve(mesh.triangles.size() * 3);
  auto key = [n](int a, int b) { return static_cast<long long>(a) * n + b; };
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++directed[key(t[k], t[(k + 1) % 3])];
  long long open = 0, doubled = 0;
  Eigen::Vector3d open_at = Eigen::Vector3d::Zero(), doubled_at = Eigen::Vector3d::Zero();
  for (const auto& [edge, count] : directed) {
    const int a = static_cast<int>(edge / n), b = static_cast<int>(edge % n);
    if (count > 1) {
      if (doubled++ == 0) doubled_at = 0.5 * (mesh.vertices_m[a] + mesh.vertices_m[b]);
    }
    if (directed.find(key(b, a)) == directed.end()) {
      if (open++ == 0) open_at = 0.5 * (mesh.vertices_m[a] + mesh.vertices_m[b]);
    }
  }
  if (doubled > 0)
    throw Error(mesh.name,
                fmt::format("is not consistently oriented: {} edges are used twice in the same direction, e.g. near "
                            "body point ({:.3f}, {:.3f}, {:.3f}) m",
                            doubled, doubled_at.x(), doubled_at.y(), doubled_at.z()),
                "orient every face counter-clockwise seen from outside (e.g. Blender: Recalculate Outside)");
  if (open > 0)
    throw Error(mesh.name,
                fmt::format("is not closed: {} edges border a hole, e.g. near body point ({:.3f}, {:.3f}, {:.3f}) m",
                            open, open_at.x(), open_at.y(), open_at.z()),
                "close the hull (deck and transom included) so that it encloses a volume");
  const MeshMassProperties properties = mesh_mass_properties(mesh);
  if (!(properties.volume_m3 > 0.0))
    throw Error(mesh.name,
                fmt::format("has its normals pointing inward (signed volume {:.6g} m^3)", properties.volume_m3),
                "flip the faces (reverse every triangle's winding) so that the normals point out of the hull");
}

void write_hull_obj(const std::filesystem::path& path, const HullMesh& mesh) {
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary);
    out << "# " << mesh.name << "\n# body frame: x forward, y port, z up, metres\n";
    out.precision(10);
    for (const auto& v : mesh.vertices_m) out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const auto& t : mesh.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
    out.flush();
    if (!out) throw Error(path.string(), "could not be written", "check the disk space and permissions");
  });
}

}  // namespace nearshore::ships
