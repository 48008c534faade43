#pragma once
// Offscreen framebuffers of the water renderer (private to it). Every framebuffer object it draws
// into is made here, one way: one colour attachment (a renderbuffer it owns, or the caller's
// texture), a float depth renderbuffer when the pass depth-tests, and a completeness check whose
// error says which target and what to turn off. Needs the renderer's current GL context.
#include <glad/gl.h>

#include <string>

namespace nearshore::playback {

/// What a framebuffer's error says when the driver refuses its combination of attachments.
struct FramebufferRefusal {
  std::string problem;  ///< e.g. "the reflection framebuffer is incomplete"
  std::string fix;      ///< the setting that avoids it
};

class Framebuffer {
 public:
  /// Colour: a renderbuffer of `colour_format`; `samples` per pixel (1: a plain renderbuffer).
  static Framebuffer with_renderbuffer(int width, int height, GLenum colour_format, int samples, bool depth,
                                       const FramebufferRefusal& refusal);
  /// Colour: level 0 of `texture` (its storage already `width` x `height`), which stays the
  /// caller's: release() does not delete it.
  static Framebuffer with_texture(GLuint texture, int width, int height, bool depth,
                                  const FramebufferRefusal& refusal);

  /// Colour and depth: level 0 of `colour_texture` and of `depth_texture` (GL_DEPTH_COMPONENT32F,
  /// the format of every depth buffer here, so a depth blit from another target is allowed), both
  /// `width` x `height` and the caller's.
  static Framebuffer with_textures(GLuint colour_texture, GLuint depth_texture, int width, int height,
                                   const FramebufferRefusal& refusal);

  GLuint id() const { return framebuffer_; }
  GLuint colour_renderbuffer() const { return colour_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }
  explicit operator bool() const { return framebuffer_ != 0; }
  void release();  ///< deletes the framebuffer and its renderbuffers (not a caller's texture)

 private:
  // Leaves the new framebuffer bound to GL_FRAMEBUFFER and no renderbuffer bound.
  static Framebuffer create(int width, int height, GLenum colour_format, GLuint colour_texture, int samples,
                            bool depth, const FramebufferRefusal& refusal, GLuint depth_texture = 0);
  GLuint framebuffer_ = 0, colour_ = 0, depth_ = 0;  // colour_: 0 when the colour is a texture
  int width_ = 0, height_ = 0, samples_ = 0;
};

/// The frame's target: a colour and a float depth buffer with `samples` per pixel. A multisampled
/// target is resolved (the samples of a pixel averaged by glBlitFramebuffer, a box filter) into a
/// single-sample colour renderbuffer, read_framebuffer(), which WaterRenderer::read_pixels() and
/// blit_to_window() read: a multisampled buffer cannot be read with glReadPixels nor blitted at
/// another size.
class RenderTarget {
 public:
  /// Makes the buffers anew only when the size, format or sample count changed.
  void resize(int width, int height, GLenum colour_format, int samples = 1);
  /// The samples averaged into the single-sample colour buffer (nothing to do without MSAA).
  void resolve() const;
  GLuint draw_framebuffer() const { return draw_.id(); }
  GLuint read_framebuffer() const { return resolved_ ? resolved_.id() : draw_.id(); }
  int width() const { return draw_.width(); }
  int height() const { return draw_.height(); }
  void release();
  /// The colour and depth drawn so far copied into `destination` (its colour one sample, depth
  /// GL_DEPTH_COMPONENT32F, the same size): a multisampled target's samples averaged (colour) or
  /// one of them taken (depth, GL_NEAREST). Leaves the draw framebuffer bound for drawing on.
  void copy_to(const Framebuffer& destination) const;

 private:
  Framebuffer draw_, resolved_;  // resolved_ empty when draw_ has one sample
  GLenum colour_format_ = 0;
};

}  // namespace nearshore::playback
