#pragma once
// Hull meshes: a closed, outward-oriented triangle surface in the BODY frame of a ship, its mass
// properties by closed-mesh integrals, and an OBJ writer. Mesh files are read by load_hull_mesh
// (hull_file.hpp, library nearshore_ships_mesh: assimp).
//
// Body frame (every ship quantity in ships/ uses it): x forward (towards the bow), y to port, z up
// (right-handed), metres. The generic hulls (generic_hulls.hpp) put the origin on the keel at
// midships; a loaded mesh keeps its file's origin (its units must be metres and its axes x forward,
// z up, as the loader cannot guess them).
//
// Mass properties of the solid the surface encloses, by the divergence theorem over tetrahedra
// (origin, a, b, c) of each triangle (Mirtich 1996; Tonon 2004):
//   V   = sum v_t,              v_t = a . (b x c) / 6           (signed: > 0 when normals point out)
//   c   = sum v_t (a + b + c) / 4 / V
//   C   = sum v_t / 20 (a a^T + b b^T + c c^T + s s^T),  s = a + b + c   (covariance, integral x x^T dV)
//   I_o = trace(C) Id - C;  I_c = I_o - V (|c|^2 Id - c c^T)            (per unit density)
// exact for any closed polyhedron, whatever its triangulation.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace nearshore::ships {

struct HullMesh {
  std::string name;                          ///< the file, or the generator ("box barge 20 x 8 x 4 m"), for messages
  std::vector<Eigen::Vector3d> vertices_m;   ///< body frame
  std::vector<std::array<int, 3>> triangles; ///< counter-clockwise seen from outside (normals point out)
};

/// What closed-mesh integrals give for the solid a hull encloses (uniform density).
struct MeshMassProperties {
  double volume_m3 = 0.0;
  Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();  ///< body frame
  /// Inertia tensor about the centroid per unit density (m^5): multiply by mass / volume for kg m^2.
  Eigen::Matrix3d inertia_per_density_m5 = Eigen::Matrix3d::Zero();
  double surface_area_m2 = 0.0;
};

MeshMassProperties mesh_mass_properties(const HullMesh& mesh);

/// Checks that the mesh is a closed, consistently and outwardly oriented surface: every directed
/// edge a->b appears once and its reverse b->a once (watertight, two-manifold, consistent winding)
/// and the signed volume is positive (normals point out). Throws nearshore::Error naming
/// mesh.name, the problem (open edges and where, edges used twice in one direction, inward normals)
/// and the fix.
void require_closed_outward(const HullMesh& mesh);

/// Writes a hull as Wavefront OBJ (v/f lines, 1-based), for the tests and for users who want to
/// edit a generic hull. Throws nearshore::Error naming the path.
void write_hull_obj(const std::filesystem::path& path, const HullMesh& mesh);

}  // namespace nearshore::ships
