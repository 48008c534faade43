// Hull mesh files through assimp (hull_file.hpp): kept apart from nearshore_ships so that the
// ships library itself links no file-format library.
#include "nearshore/ships/hull_file.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "nearshore/core/error.hpp"

namespace nearshore::ships {

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

}  // namespace nearshore::ships
