#pragma once
// Hull mesh files (library nearshore_ships_mesh, through assimp): the one road from a file to a
// HullMesh (hull_mesh.hpp). Body frame as there: x forward, y port, z up, metres; the loader
// cannot guess other units or axes.
#include <filesystem>

#include "nearshore/ships/hull_mesh.hpp"

namespace nearshore::ships {

/// Loads a hull from a mesh file (OBJ, PLY, glTF 2.0 / GLB, STL, anything assimp reads), welds
/// coincident vertices (a file's per-face normals or UVs split them), applies the node transforms,
/// and runs require_closed_outward. Throws nearshore::Error naming the file for a missing or
/// unreadable file, no triangles, an open or inverted surface.
HullMesh load_hull_mesh(const std::filesystem::path& path);

}  // namespace nearshore::ships
