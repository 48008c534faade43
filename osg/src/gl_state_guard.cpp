#include "gl_state_guard.hpp"

#include <osg/GLExtensions>

#include <algorithm>

// OpenGL 3.x names osg/GL may leave out on a GL2 build of OSG (Debian 12's).
#ifndef GL_VERTEX_ARRAY_BINDING
#define GL_VERTEX_ARRAY_BINDING 0x85B5
#endif
#ifndef GL_TEXTURE_BINDING_2D_ARRAY
#define GL_TEXTURE_BINDING_2D_ARRAY 0x8C1D
#endif
#ifndef GL_TEXTURE_2D_ARRAY
#define GL_TEXTURE_2D_ARRAY 0x8C1A
#endif
#ifndef GL_DRAW_FRAMEBUFFER_BINDING
#define GL_DRAW_FRAMEBUFFER_BINDING 0x8CA6
#endif
#ifndef GL_READ_FRAMEBUFFER_BINDING
#define GL_READ_FRAMEBUFFER_BINDING 0x8CAA
#endif
#ifndef GL_DRAW_FRAMEBUFFER
#define GL_DRAW_FRAMEBUFFER 0x8CA9
#endif
#ifndef GL_READ_FRAMEBUFFER
#define GL_READ_FRAMEBUFFER 0x8CA8
#endif

namespace nearshore::scenegraph {

GlStateGuard::GlStateGuard(::osg::State& state) : state_(state) {
  pending_error_ = glGetError();
  while (glGetError() != GL_NO_ERROR) {
  }
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_framebuffer_);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_framebuffer_);
  glGetIntegerv(GL_VIEWPORT, viewport_);
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
  glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &array_buffer_);
  glGetIntegerv(GL_ELEMENT_ARRAY_BUFFER_BINDING, &element_buffer_);
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pixel_pack_buffer_);
  glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &pixel_unpack_buffer_);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
  glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &texture_units_);
  texture_units_ = std::clamp(texture_units_, 0, kTextureUnits);
  const ::osg::GLExtensions* gl = state.get<::osg::GLExtensions>();
  for (int unit = 0; unit < texture_units_; ++unit) {
    gl->glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture_2d_[std::size_t(unit)]);
    glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &texture_2d_array_[std::size_t(unit)]);
  }
  gl->glActiveTexture(GLenum(active_texture_));
  depth_test_ = glIsEnabled(GL_DEPTH_TEST);
  blend_ = glIsEnabled(GL_BLEND);
  cull_face_ = glIsEnabled(GL_CULL_FACE);
  polygon_offset_line_ = glIsEnabled(GL_POLYGON_OFFSET_LINE);
  polygon_offset_fill_ = glIsEnabled(GL_POLYGON_OFFSET_FILL);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
  glGetIntegerv(GL_DEPTH_FUNC, &depth_func_);
  glGetIntegerv(GL_POLYGON_MODE, polygon_mode_);  // front and back (a compatibility context has both)
  glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &polygon_offset_factor_);
  glGetFloatv(GL_POLYGON_OFFSET_UNITS, &polygon_offset_units_);
  glGetFloatv(GL_COLOR_CLEAR_VALUE, clear_colour_);
  glGetDoublev(GL_DEPTH_CLEAR_VALUE, &clear_depth_);
  glGetIntegerv(GL_BLEND_EQUATION_RGB, &blend_equation_rgb_);
  glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &blend_equation_alpha_);
  glGetIntegerv(GL_BLEND_SRC_RGB, &blend_src_rgb_);
  glGetIntegerv(GL_BLEND_DST_RGB, &blend_dst_rgb_);
  glGetIntegerv(GL_BLEND_SRC_ALPHA, &blend_src_alpha_);
  glGetIntegerv(GL_BLEND_DST_ALPHA, &blend_dst_alpha_);
  glGetIntegerv(GL_PACK_ALIGNMENT, &pack_alignment_);
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &unpack_alignment_);
  glGetIntegerv(GL_UNPACK_ROW_LENGTH, &unpack_row_length_);
}

GlStateGuard::~GlStateGuard() {
  const ::osg::GLExtensions* gl = state_.get<::osg::GLExtensions>();
  auto set = [](GLenum capability, GLboolean on) { on ? glEnable(capability) : glDisable(capability); };
  gl->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_framebuffer_));
  gl->glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_framebuffer_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  // A program deleted while current stays current until replaced, and is gone once the sea's draw
  // replaced it: then none is restored (binding a deleted name is GL_INVALID_VALUE).
  gl->glUseProgram(program_ != 0 && gl->glIsProgram(GLuint(program_)) ? GLuint(program_) : 0u);
  gl->glBindVertexArray(GLuint(vertex_array_));
  gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, GLuint(element_buffer_));  // part of the vertex array's state
  gl->glBindBuffer(GL_ARRAY_BUFFER, GLuint(array_buffer_));
  gl->glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(pixel_pack_buffer_));
  gl->glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(pixel_unpack_buffer_));
  for (int unit = 0; unit < texture_units_; ++unit) {
    gl->glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D, GLuint(texture_2d_[std::size_t(unit)]));
    glBindTexture(GL_TEXTURE_2D_ARRAY, GLuint(texture_2d_array_[std::size_t(unit)]));
  }
  gl->glActiveTexture(GLenum(active_texture_));
  set(GL_DEPTH_TEST, depth_test_);
  set(GL_BLEND, blend_);
  set(GL_CULL_FACE, cull_face_);
  set(GL_POLYGON_OFFSET_LINE, polygon_offset_line_);
  set(GL_POLYGON_OFFSET_FILL, polygon_offset_fill_);
  glDepthMask(depth_mask_);
  glDepthFunc(GLenum(depth_func_));
  glPolygonMode(GL_FRONT, GLenum(polygon_mode_[0]));
  glPolygonMode(GL_BACK, GLenum(polygon_mode_[1]));
  glPolygonOffset(polygon_offset_factor_, polygon_offset_units_);
  glClearColor(clear_colour_[0], clear_colour_[1], clear_colour_[2], clear_colour_[3]);
  glClearDepth(clear_depth_);
  gl->glBlendEquationSeparate(GLenum(blend_equation_rgb_), GLenum(blend_equation_alpha_));
  gl->glBlendFuncSeparate(GLenum(blend_src_rgb_), GLenum(blend_dst_rgb_), GLenum(blend_src_alpha_),
                          GLenum(blend_dst_alpha_));
  glPixelStorei(GL_PACK_ALIGNMENT, pack_alignment_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, unpack_alignment_);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, unpack_row_length_);
  // The context is now as OSG left it and OSG's records are true again: they are left alone.
  // Neither State::dirtyAllModes nor dirtyAllAttributes is called. dirtyAllModes inverts each
  // mode's last applied value, which after an exact restore makes OSG skip the next change of
  // every mode (measured: a box with GL_LIGHTING off drawn lit after the sea); dirtyAllAttributes
  // makes OSG apply every attribute again at the next leaf, positional ones too, so the view's
  // headlight (osg::Light, GL_POSITION in eye space) was re-issued under the next object's
  // model-view and lit the ship from above (measured: the coaster's sides black after the sea).
  // Only the program record is cleared, so a program deleted while current is never taken for
  // the one in use, and the vertex arrays are marked for re-binding.
  state_.dirtyAllVertexArrays();
  state_.setLastAppliedProgramObject(nullptr);
}

}  // namespace nearshore::scenegraph
