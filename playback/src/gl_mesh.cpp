#include "gl_mesh.hpp"

#include <cstddef>
#include <initializer_list>

namespace nearshore::playback {

void Mesh::release() {
  glDeleteVertexArrays(1, &vertex_array);
  for (GLuint* buffer : {&vertex_buffer, &index_buffer, &instance_buffer})
    if (*buffer) glDeleteBuffers(1, buffer);
  *this = Mesh{};
}

Mesh upload_mesh(const std::vector<float>& vertices, const std::vector<GLuint>& indices) {
  return upload_mesh(vertices, indices, {2});
}

Mesh upload_mesh(const std::vector<float>& vertices, const std::vector<GLuint>& indices,
                 std::initializer_list<int> attribute_sizes) {
  int stride = 0;
  for (int size : attribute_sizes) stride += size;
  Mesh mesh;
  glGenVertexArrays(1, &mesh.vertex_array);
  glBindVertexArray(mesh.vertex_array);
  glGenBuffers(1, &mesh.vertex_buffer);
  glBindBuffer(GL_ARRAY_BUFFER, mesh.vertex_buffer);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(float)), vertices.data(), GL_STATIC_DRAW);
  GLuint location = 0;
  std::size_t offset = 0;
  for (int size : attribute_sizes) {
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location++, size, GL_FLOAT, GL_FALSE, GLsizei(stride * sizeof(float)),
                          reinterpret_cast<const void*>(offset * sizeof(float)));
    offset += std::size_t(size);
  }
  glGenBuffers(1, &mesh.index_buffer);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.index_buffer);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(GLuint)), indices.data(),
               GL_STATIC_DRAW);
  mesh.index_count = GLsizei(indices.size());
  mesh.vertex_count = static_cast<long long>(vertices.size() / std::size_t(stride));
  glBindVertexArray(0);
  return mesh;
}

Mesh lattice_mesh(int columns, int rows, float scale_x, float scale_y) {
  std::vector<float> vertices;
  vertices.reserve(std::size_t(columns) * rows * 2);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i)
      vertices.insert(vertices.end(), {float(i) * scale_x, float(j) * scale_y});
  std::vector<GLuint> indices;
  indices.reserve(std::size_t(columns - 1) * (rows - 1) * 6);
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i + 1 < columns; ++i) {
      const GLuint a = GLuint(j * columns + i), b = a + 1, c = a + GLuint(columns), d = c + 1;
      indices.insert(indices.end(), {a, b, d, a, d, c});
    }
  return upload_mesh(vertices, indices);
}

}  // namespace nearshore::playback
