#pragma once
// Meshes of the water renderer (private to it): a vertex array with 2-D vertices on attribute 0
// and 32-bit triangle indices, optionally a per-instance buffer the caller lays out.
// Needs the renderer's current GL context.
#include <glad/gl.h>

#include <initializer_list>
#include <vector>

namespace nearshore::playback {

struct Mesh {
  GLuint vertex_array = 0, vertex_buffer = 0, index_buffer = 0, instance_buffer = 0;
  GLsizei index_count = 0;
  long long vertex_count = 0;
  void release();  ///< deletes what it holds (nothing when empty) and becomes empty
};

/// `vertices` (x, y pairs) and `indices` (three per triangle) into a new mesh.
Mesh upload_mesh(const std::vector<float>& vertices, const std::vector<GLuint>& indices);

/// `vertices` of several float attributes each (attribute k on location k, `attribute_sizes[k]`
/// floats, interleaved in that order) and `indices` (three per triangle) into a new mesh.
Mesh upload_mesh(const std::vector<float>& vertices, const std::vector<GLuint>& indices,
                 std::initializer_list<int> attribute_sizes);

/// A lattice of columns x rows vertices at (i, j) * scale, two triangles per quad.
Mesh lattice_mesh(int columns, int rows, float scale_x, float scale_y);

}  // namespace nearshore::playback
