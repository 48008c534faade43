#pragma once
// WaterRenderer: draws one baked frame of a harbour: sky, seabed and land, breakwaters and quays,
// and the sea surface on a radial grid around the viewer displaced by the baked surface elevation
// (vertex texture), lit by seed 003 eq. (12)-(16) (shaders/common.glsl). Needs a current OpenGL
// 3.3+ context (GlWindow). Renders into its own framebuffer object, so screenshots are exact even
// from a hidden window; present() copies it to the window.
#include <array>
#include <memory>

#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/image.hpp"
#include "nearshore/playback/lighting.hpp"

namespace nearshore::playback {

struct Camera {
  Vector3 eye_m = {0, 0, 100};    ///< viewer position, harbour frame (x east, y north, z up), metres
  Vector3 target_m = {0, 100, 0}; ///< the point looked at
  double vertical_field_of_view_deg = 45.0;
  double near_m = 1.0, far_m = 30000.0;

  /// A viewpoint offshore to the south-south-west, looking into the harbour from a height of about
  /// a quarter of its extent: the view a pilot boarding from seaward would have.
  static Camera overlooking(const GridGeometry& geometry);
};

class WaterRenderer {
 public:
  explicit WaterRenderer(const HarbourGrid& harbour);
  ~WaterRenderer();
  WaterRenderer(const WaterRenderer&) = delete;
  WaterRenderer& operator=(const WaterRenderer&) = delete;

  /// Uploads one frame (cell-centred, the harbour grid's size). `breaking` may be null.
  void set_frame(const Raster<float>& surface_elevation_m, const Raster<float>* breaking);
  /// Draws into the renderer's framebuffer of the given size.
  void render(const Camera& camera, const Lighting& lighting, int width_px, int height_px);
  /// Copies the last render to the window's back buffer (call GlWindow::present after).
  void blit_to_window(int window_width_px, int window_height_px) const;
  /// The last render as an image (row 0 at the top).
  Image read_pixels() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nearshore::playback
