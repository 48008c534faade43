#include "surface_layer_gpu.hpp"
#include "gl_texture.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "nearshore/core/error.hpp"

namespace nearshore::playback {

SurfaceLayerGpu::SurfaceLayerGpu() = default;

SurfaceLayerGpu::~SurfaceLayerGpu() {
  if (atlas_) glDeleteTextures(1, &atlas_);
  if (foam_texture_) glDeleteTextures(1, &foam_texture_);
  foam_framebuffer_.release();
  if (decal_instances_) glDeleteBuffers(1, &decal_instances_);
  auto release = [](GpuMesh& m) {
    if (m.vertex_array) glDeleteVertexArrays(1, &m.vertex_array);
    for (GLuint* buffer : {&m.vertex_buffer, &m.index_buffer})
      if (*buffer) glDeleteBuffers(1, buffer);
  };
  release(decal_quad_);
  for (auto& entry : meshes_) release(entry.second);
}

std::size_t SurfaceLayerGpu::upload_patches(const std::vector<HeightPatch>& patches, int unit) {
  if (patches.size() > std::size_t(SurfaceLayers::kMaxHeightPatches))
    throw Error("surface layers", std::to_string(patches.size()) + " height patches, more than the " +
                                      std::to_string(SurfaceLayers::kMaxHeightPatches) + " one draw adds up",
                "merge patches or draw the nearest SurfaceLayers::kMaxHeightPatches");
  uniforms_ = PatchUniforms{};
  if (patches.empty()) return 0;
  // The layout: patches stacked from row 0 up, the atlas as wide as the widest.
  int columns = 0, rows = 0;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const HeightPatch& p = patches[k];
    if (!p.heights_m || p.columns < 2 || p.rows < 2 || !(p.spacing_m > 0))
      throw Error("height patch " + std::to_string(k),
                  std::to_string(p.columns) + " x " + std::to_string(p.rows) + " cells of " + std::to_string(p.spacing_m) +
                      " m" + (p.heights_m ? "" : " and no heights"),
                  "give at least 2 x 2 heights and a positive spacing");
    columns = std::max(columns, p.columns);
    uniforms_.origin_m[2 * k] = float(p.origin_x_m);
    uniforms_.origin_m[2 * k + 1] = float(p.origin_y_m);
    uniforms_.spacing_m[k] = float(p.spacing_m);
    uniforms_.cells[2 * k] = p.columns;
    uniforms_.cells[2 * k + 1] = p.rows;
    uniforms_.row0[k] = rows;
    rows += p.rows;
  }
  uniforms_.count = int(patches.size());
  glActiveTexture(GLenum(GL_TEXTURE0 + unit));
  bool all_new = false;
  if (!atlas_ || columns != atlas_columns_ || rows != atlas_rows_) {
    if (!atlas_) glGenTextures(1, &atlas_);
    glBindTexture(GL_TEXTURE_2D, atlas_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, columns, rows, 0, GL_RED, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // texelFetch only
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    atlas_columns_ = columns, atlas_rows_ = rows;
    all_new = true;
  }
  glBindTexture(GL_TEXTURE_2D, atlas_);
  std::size_t bytes = 0;
  atlas_layout_.resize(patches.size());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const HeightPatch& p = patches[k];
    const std::array<unsigned long long, 3> key = {static_cast<unsigned long long>(p.columns),
                                                   static_cast<unsigned long long>(p.rows), p.serial};
    if (!all_new && atlas_layout_[k] == key) continue;
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, uniforms_.row0[k], p.columns, p.rows, GL_RED, GL_FLOAT, p.heights_m);
    atlas_layout_[k] = key;
    bytes += std::size_t(p.columns) * std::size_t(p.rows) * sizeof(float);
  }
  glActiveTexture(GL_TEXTURE0);
  return bytes;
}

bool SurfaceLayerGpu::draw_decals(const std::vector<FoamDecal>& decals, GLuint program, int texels, double finest_m) {
  if (decals.empty()) return false;
  // 1. The map covers the decals' bounding box (each decal's half-diagonal round its centre).
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  std::vector<float> instances;
  instances.reserve(decals.size() * 7);
  for (const FoamDecal& d : decals) {
    const double reach = 0.5 * std::hypot(d.length_m, d.width_m);
    x0 = std::min(x0, d.x_m - reach), x1 = std::max(x1, d.x_m + reach);
    y0 = std::min(y0, d.y_m - reach), y1 = std::max(y1, d.y_m + reach);
    instances.insert(instances.end(), {float(d.x_m), float(d.y_m), float(d.yaw_rad), float(std::clamp(d.opacity, 0.0, 1.0)),
                                       float(d.length_m), float(d.width_m), float(d.variant)});
  }
  texels = std::max(texels, 16);
  const double side = std::max({x1 - x0, y1 - y0, finest_m * texels});
  foam_rect_m_ = {float(0.5 * (x0 + x1) - 0.5 * side), float(0.5 * (y0 + y1) - 0.5 * side), float(side), float(side)};
  // 2. The target (R8: cover 0..1), made once.
  if (foam_texels_ != texels) {
    if (!foam_texture_)
      foam_texture_ = new_texture(GL_TEXTURE_2D, GL_LINEAR, GL_CLAMP_TO_EDGE);
    else
      glBindTexture(GL_TEXTURE_2D, foam_texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, texels, texels, 0, GL_RED, GL_UNSIGNED_BYTE, nullptr);
    foam_framebuffer_.release();
    foam_framebuffer_ = Framebuffer::with_texture(foam_texture_, texels, texels, false,
                                                  {"the decal foam framebuffer (R8) is incomplete", "draw without foam decals"});
    foam_texels_ = texels;
  }
  // 3. A unit quad, one instance per decal.
  if (!decal_quad_.vertex_array) {
    const float corners[] = {-0.5f, -0.5f, 0.5f, -0.5f, 0.5f, 0.5f, -0.5f, -0.5f, 0.5f, 0.5f, -0.5f, 0.5f};
    glGenVertexArrays(1, &decal_quad_.vertex_array);
    glBindVertexArray(decal_quad_.vertex_array);
    glGenBuffers(1, &decal_quad_.vertex_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, decal_quad_.vertex_buffer);
    glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
    glGenBuffers(1, &decal_instances_);
    glBindBuffer(GL_ARRAY_BUFFER, decal_instances_);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 7 * sizeof(float), nullptr);
    glVertexAttribDivisor(1, 1);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, 7 * sizeof(float), reinterpret_cast<const void*>(4 * sizeof(float)));
    glVertexAttribDivisor(2, 1);
  }
  glBindVertexArray(decal_quad_.vertex_array);
  glBindBuffer(GL_ARRAY_BUFFER, decal_instances_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(instances.size() * sizeof(float)), instances.data(), GL_STREAM_DRAW);
  // 4. Where decals overlap the larger cover wins (GL_MAX): a wake crossing itself does not build up.
  glBindFramebuffer(GL_FRAMEBUFFER, foam_framebuffer_.id());
  glViewport(0, 0, texels, texels);
  const float none[4] = {0.f, 0.f, 0.f, 0.f};
  glClearBufferfv(GL_COLOR, 0, none);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendEquation(GL_MAX);
  glUseProgram(program);
  glUniform4f(glGetUniformLocation(program, "u_rect_m"), foam_rect_m_[0], foam_rect_m_[1], foam_rect_m_[2], foam_rect_m_[3]);
  glDrawArraysInstanced(GL_TRIANGLES, 0, 6, GLsizei(decals.size()));
  glBlendEquation(GL_FUNC_ADD);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return true;
}

const SurfaceLayerGpu::GpuMesh& SurfaceLayerGpu::mesh(const SolidMesh& solid, std::size_t& upload_bytes) {
  if (auto found = meshes_.find(solid.id); found != meshes_.end()) return found->second;
  if (!solid.vertices_m || !solid.triangles || solid.vertex_count == 0 || solid.triangle_count == 0)
    throw Error("solid mesh " + std::to_string(solid.id), "has no vertices or no triangles",
                "give x, y, z per vertex and three indices per triangle, and their counts");
  const std::size_t vertex_count = solid.vertex_count, index_count = 3 * solid.triangle_count;
  for (std::size_t k = 0; k < index_count; ++k)
    if (const std::uint32_t index = solid.triangles[k]; index >= vertex_count)
      throw Error("solid mesh " + std::to_string(solid.id),
                  "names vertex " + std::to_string(index) + " of " + std::to_string(vertex_count),
                  "give triangle indices below the vertex count");
  GpuMesh m;
  glGenVertexArrays(1, &m.vertex_array);
  glBindVertexArray(m.vertex_array);
  glGenBuffers(1, &m.vertex_buffer);
  glBindBuffer(GL_ARRAY_BUFFER, m.vertex_buffer);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(3 * vertex_count * sizeof(float)), solid.vertices_m, GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glGenBuffers(1, &m.index_buffer);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.index_buffer);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(index_count * sizeof(std::uint32_t)), solid.triangles, GL_STATIC_DRAW);
  glBindVertexArray(0);
  m.index_count = GLsizei(index_count);
  upload_bytes += 3 * vertex_count * sizeof(float) + index_count * sizeof(std::uint32_t);
  return meshes_.emplace(solid.id, m).first->second;
}

}  // namespace nearshore::playback
