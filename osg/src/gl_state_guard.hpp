#pragma once
// The OpenGL state SeaNode's draw changes, saved before it and put back after (private to
// nearshore_osg; docs/osg.md "The GL-state contract"). osg::State keeps its own record of what it
// applied and skips calls it thinks redundant, so a foreign draw must leave the context as OSG
// recorded it: every binding and setting playback::WaterRenderer touches is restored exactly,
// so OSG's own record of what it applied is true again; only its program and vertex-array records
// are marked stale (State::dirtyAllModes and dirtyAllAttributes would do harm after an exact
// restore: gl_state_guard.cpp says what was measured).
#include <osg/GL>
#include <osg/State>

#include <array>

namespace nearshore::scenegraph {

class GlStateGuard {
 public:
  /// Texture units saved: playback's samplers use units 0-25 (playback/src/gl_program.hpp).
  static constexpr int kTextureUnits = 32;

  explicit GlStateGuard(::osg::State& state);  ///< saves
  ~GlStateGuard();                              ///< restores, then dirties osg::State's records
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

  /// An OpenGL error OSG left pending before the draw (reported by the caller, cleared so the
  /// renderer's own error check sees only its own); GL_NO_ERROR when none.
  GLenum pending_error() const { return pending_error_; }

 private:
  ::osg::State& state_;
  GLenum pending_error_ = GL_NO_ERROR;
  GLint draw_framebuffer_ = 0, read_framebuffer_ = 0, viewport_[4] = {0, 0, 0, 0};
  GLint program_ = 0, vertex_array_ = 0, array_buffer_ = 0, element_buffer_ = 0;
  GLint pixel_pack_buffer_ = 0, pixel_unpack_buffer_ = 0;
  GLint active_texture_ = GL_TEXTURE0, texture_units_ = 0;
  std::array<GLint, kTextureUnits> texture_2d_{}, texture_2d_array_{};
  GLboolean depth_test_ = GL_FALSE, blend_ = GL_FALSE, cull_face_ = GL_FALSE;
  GLboolean polygon_offset_line_ = GL_FALSE, polygon_offset_fill_ = GL_FALSE, depth_mask_ = GL_TRUE;
  GLint depth_func_ = GL_LESS, polygon_mode_[2] = {GL_FILL, GL_FILL};
  GLfloat polygon_offset_factor_ = 0.f, polygon_offset_units_ = 0.f;
  GLfloat clear_colour_[4] = {0.f, 0.f, 0.f, 0.f};
  GLdouble clear_depth_ = 1.0;
  GLint blend_equation_rgb_ = 0, blend_equation_alpha_ = 0;
  GLint blend_src_rgb_ = 0, blend_dst_rgb_ = 0, blend_src_alpha_ = 0, blend_dst_alpha_ = 0;
  GLint pack_alignment_ = 4, unpack_alignment_ = 4, unpack_row_length_ = 0;
};

}  // namespace nearshore::scenegraph
