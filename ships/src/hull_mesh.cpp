#include "nearshore/ships/hull_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <unordered_map>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
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

namespace {

// Welds vertices that coincide to within 1e-7 of the mesh size: files split a vertex per face
// normal or texture coordinate, which would make every edge look open.
HullMesh weld(const std::string& name, const std::vector<Eigen::Vector3d>& points,
              const std::vector<std::array<int, 3>>& triangles) {
  HullMesh mesh;
  mesh.name = name;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = Eigen::Vector3d::Constant(-1e300);
  for (const auto& p : points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const double quantum = std::max((high - low).maxCoeff(), 1e-9) * 1e-7;
  std::map<std::array<long long, 3>, int> index_of;
  std::vector<int> remap(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::array<long long, 3> q = {std::llround(points[i].x() / quantum), std::llround(points[i].y() / quantum),
                                        std::llround(points[i].z() / quantum)};
    auto [it, inserted] = index_of.emplace(q, static_cast<int>(mesh.vertices_m.size()));
    if (inserted) mesh.vertices_m.push_back(points[i]);
    remap[i] = it->second;
  }
  for (const auto& t : triangles) {
    const std::array<int, 3> w = {remap[t[0]], remap[t[1]], remap[t[2]]};
    if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue;  // collapsed by the weld: no area
    mesh.triangles.push_back(w);
  }
  return mesh;
}

}  // namespace

HullMesh load_hull_mesh(const std::filesystem::path& path) {
  require_readable_file(path, "a hull mesh (OBJ, PLY, glTF, STL)");
  Assimp::Importer importer;
  // No normal fixing: an inverted hull must be refused, not silently repaired.
  const aiScene* scene =
      importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr)
    throw Error(path.string(), fmt::format("cannot be read as a mesh: {}", importer.GetErrorString()),
                "give an OBJ, PLY, glTF/GLB or STL file of the closed hull");
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const int base = static_cast<int>(points.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v)
      points.emplace_back(mesh->mVertices[v].x, mesh->mVertices[v].y, mesh->mVertices[v].z);
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines (sorted out by aiProcess_SortByPType)
      triangles.push_back({base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                           base + static_cast<int>(face.mIndices[2])});
    }
  }
  if (triangles.empty())
    throw Error(path.string(), "holds no triangles", "export the hull as a surface mesh (faces, not points or lines)");
  HullMesh mesh = weld(path.string(), points, triangles);
  require_closed_outward(mesh);
  return mesh;
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
