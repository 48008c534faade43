#pragma once
// The seabed, land and structures (private to the water renderer): the site's terrain mesh
// (SiteTextures, built by build_site_terrain: the ground from the grid's depth with its skirt
// beyond the grid, the structures extruded from their geometry), shaded by height, slope and
// distance inland; and the same drawn mirrored in still water for the sea's local reflection.
#include <glad/gl.h>

#include "gl_mesh.hpp"
#include "nearshore/playback/camera.hpp"
#include "nearshore/playback/lighting.hpp"
#include "surface_uniforms.hpp"

namespace nearshore::playback {

class TerrainPass {
 public:
  TerrainPass();  ///< links terrain.vert/frag; needs the renderer's current GL context
  ~TerrainPass();
  TerrainPass(const TerrainPass&) = delete;
  TerrainPass& operator=(const TerrainPass&) = delete;

  /// The terrain seen from `view` into the bound framebuffer.
  void draw(const Mesh& terrain, const SurfaceFormula& formula, const LightingFrame& light,
            const CameraView& view, double earth_radius_m) const;
  /// The terrain again through `mirrored_view_projection` (view_projection * diag(1, 1, -1, 1)),
  /// only what stands above still water; after draw(), whose uniforms it keeps.
  void draw_mirrored(const Mesh& terrain, const Matrix4& mirrored_view_projection) const;

 private:
  GLuint program_ = 0;
};

}  // namespace nearshore::playback
