#pragma once
// The height pass (private to the water renderer; WaterRenderer::render_height_map): the surface
// the water draws, sent straight down through the same vertex path (height.vert.glsl) onto a
// lattice of cell centres, orthographic from above into an R32F target, and read back.
// Needs the renderer's current GL context.
#include <glad/gl.h>

#include "gl_framebuffer.hpp"
#include "gl_mesh.hpp"
#include "nearshore/core/raster.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "surface_uniforms.hpp"

namespace nearshore::playback {

class HeightPass {
 public:
  HeightPass();  ///< links height.vert/frag
  ~HeightPass();
  HeightPass(const HeightPass&) = delete;
  HeightPass& operator=(const HeightPass&) = delete;

  /// The surface elevation at the centres of columns x rows cells over `rectangle` (NaN where
  /// there is no water; where folds overlap, the highest surface). `displacement_bound_m`: how far
  /// the choppy shift may move a vertex, so the lattice reaches that far beyond the rectangle.
  /// Needs the surface's textures bound; leaves framebuffer 0 bound.
  Raster<float> render(const SurfaceFormula& formula, const SiteRectangle& rectangle, int columns, int rows,
                       double displacement_bound_m);

 private:
  GLuint program_ = 0;
  Mesh lattice_;
  int lattice_columns_ = 0, lattice_rows_ = 0;
  RenderTarget target_;
};

}  // namespace nearshore::playback
