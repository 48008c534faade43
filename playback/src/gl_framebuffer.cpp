#include "gl_framebuffer.hpp"

#include <initializer_list>
#include <string>

#include "nearshore/core/error.hpp"

namespace nearshore::playback {

namespace {

// A renderbuffer of `format` attached to the bound GL_FRAMEBUFFER at `attachment`.
GLuint attach_renderbuffer(GLenum attachment, GLenum format, int width, int height, int samples) {
  GLuint renderbuffer = 0;
  glGenRenderbuffers(1, &renderbuffer);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer);
  if (samples > 1)
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
  else
    glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachment, GL_RENDERBUFFER, renderbuffer);
  return renderbuffer;
}

}  // namespace

Framebuffer Framebuffer::with_renderbuffer(int width, int height, GLenum colour_format, int samples,
                                           bool depth, const FramebufferRefusal& refusal) {
  return create(width, height, colour_format, 0, samples, depth, refusal);
}

Framebuffer Framebuffer::with_texture(GLuint texture, int width, int height, bool depth,
                                      const FramebufferRefusal& refusal) {
  return create(width, height, 0, texture, 1, depth, refusal);
}

Framebuffer Framebuffer::with_textures(GLuint colour_texture, GLuint depth_texture, int width, int height,
                                       const FramebufferRefusal& refusal) {
  return create(width, height, 0, colour_texture, 1, false, refusal, depth_texture);
}

Framebuffer Framebuffer::create(int width, int height, GLenum colour_format, GLuint colour_texture,
                                int samples, bool depth, const FramebufferRefusal& refusal, GLuint depth_texture) {
  Framebuffer made;
  made.width_ = width;
  made.height_ = height;
  made.samples_ = samples;
  glGenFramebuffers(1, &made.framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, made.framebuffer_);
  if (colour_texture)
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_texture, 0);
  else
    made.colour_ = attach_renderbuffer(GL_COLOR_ATTACHMENT0, colour_format, width, height, samples);
  // GL_DEPTH_COMPONENT32F in every target, as the renderer has always drawn: another depth format
  // changes which of two nearly coincident surfaces (a quay face and the sea) wins a pixel.
  if (depth_texture)
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_texture, 0);
  else if (depth)
    made.depth_ = attach_renderbuffer(GL_DEPTH_ATTACHMENT, GL_DEPTH_COMPONENT32F, width, height, samples);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    made.release();
    throw Error("water renderer", refusal.problem, refusal.fix);
  }
  return made;
}

void Framebuffer::release() {
  if (!framebuffer_) return;
  glDeleteFramebuffers(1, &framebuffer_);
  for (GLuint* renderbuffer : {&colour_, &depth_})
    if (*renderbuffer) glDeleteRenderbuffers(1, renderbuffer);
  *this = Framebuffer{};
}

void RenderTarget::resize(int width, int height, GLenum colour_format, int samples) {
  if (draw_ && width == draw_.width() && height == draw_.height() && samples == draw_.samples() &&
      colour_format == colour_format_)
    return;
  release();
  draw_ = Framebuffer::with_renderbuffer(
      width, height, colour_format, samples, true,
      {"the framebuffer object (" + std::to_string(samples) + " samples) is incomplete",
       samples > 1 ? "set RendererSettings::msaa_samples = 1" : "update the GPU driver"});
  if (samples > 1)
    resolved_ = Framebuffer::with_renderbuffer(
        width, height, colour_format, 1, false,
        {"the resolve framebuffer object is incomplete", "set RendererSettings::msaa_samples = 1"});
  colour_format_ = colour_format;
}

void RenderTarget::resolve() const {
  if (!resolved_) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_.id());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved_.id());
  glBlitFramebuffer(0, 0, width(), height(), 0, 0, width(), height(), GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void RenderTarget::copy_to(const Framebuffer& destination) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_.id());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, destination.id());
  glBlitFramebuffer(0, 0, width(), height(), 0, 0, width(), height(), GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT,
                    GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, draw_.id());
}

void RenderTarget::release() {
  draw_.release();
  resolved_.release();
  colour_format_ = 0;
}

}  // namespace nearshore::playback
