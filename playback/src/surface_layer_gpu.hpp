#pragma once
// The GPU side of playback::SurfaceLayers (surface_layers.hpp): the height patches' atlas, the foam
// map the decals are drawn into, and the meshes' buffers, each uploaded only when it changed.
// Needs the renderer's current GL context; not thread-safe.
#include <glad/gl.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "gl_framebuffer.hpp"
#include "nearshore/playback/surface_layers.hpp"

namespace nearshore::playback {

/// What surface.glsl's patch uniforms hold for the patches uploaded last.
struct PatchUniforms {
  int count = 0;
  std::array<float, 2 * SurfaceLayers::kMaxHeightPatches> origin_m{};
  std::array<float, SurfaceLayers::kMaxHeightPatches> spacing_m{};
  std::array<int, 2 * SurfaceLayers::kMaxHeightPatches> cells{};
  std::array<int, SurfaceLayers::kMaxHeightPatches> row0{};
};

class SurfaceLayerGpu {
 public:
  SurfaceLayerGpu();
  ~SurfaceLayerGpu();
  SurfaceLayerGpu(const SurfaceLayerGpu&) = delete;
  SurfaceLayerGpu& operator=(const SurfaceLayerGpu&) = delete;

  /// 1. The patches into one R32F atlas (a band of rows each) on texture unit `unit`; a patch is
  /// sent again only when its serial or the atlas layout changed. Returns the bytes sent. Throws
  /// nearshore::Error for too many patches, or one without data or smaller than 2 x 2.
  std::size_t upload_patches(const std::vector<HeightPatch>& patches, int unit);
  const PatchUniforms& patch_uniforms() const { return uniforms_; }
  GLuint patch_atlas() const { return atlas_; }

  /// 2. Draws the decals (program: decal.vert/frag) into the foam map over their bounding box, at
  /// most `texels` square and no finer than finest_m. Returns false (nothing drawn) without decals.
  /// Leaves the framebuffer binding at 0 and the viewport to the caller.
  bool draw_decals(const std::vector<FoamDecal>& decals, GLuint program, int texels, double finest_m);
  GLuint decal_foam() const { return foam_texture_; }
  const std::array<float, 4>& decal_rect_m() const { return foam_rect_m_; }  ///< x0, y0, width, height

  /// 3. The vertex and index buffers of a mesh, uploaded on first sight of its id.
  struct GpuMesh {
    GLuint vertex_array = 0, vertex_buffer = 0, index_buffer = 0;
    GLsizei index_count = 0;
  };
  const GpuMesh& mesh(const SolidMesh& mesh, std::size_t& upload_bytes);

 private:
  GLuint atlas_ = 0;
  int atlas_columns_ = 0, atlas_rows_ = 0;
  std::vector<std::array<unsigned long long, 3>> atlas_layout_;  // columns, rows, serial per patch
  PatchUniforms uniforms_;
  Framebuffer foam_framebuffer_;
  GLuint foam_texture_ = 0;
  int foam_texels_ = 0;
  std::array<float, 4> foam_rect_m_{};
  GpuMesh decal_quad_;
  GLuint decal_instances_ = 0;
  std::map<std::uint64_t, GpuMesh> meshes_;
};

}  // namespace nearshore::playback
