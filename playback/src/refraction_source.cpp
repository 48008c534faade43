#include "refraction_source.hpp"

#include "gl_program.hpp"
#include "gl_texture.hpp"

namespace nearshore::playback {

void RefractionSource::resize(int width, int height) {
  if (framebuffer_ && width == framebuffer_.width() && height == framebuffer_.height()) return;
  release();
  // Colour filtered linearly (a refracted lookup lands between pixels); depth read as it is: a
  // linear blend of two depths across an edge is a point on neither surface.
  glActiveTexture(GLenum(GL_TEXTURE0 + kSceneColour));
  colour_ = new_texture(GL_TEXTURE_2D, GL_LINEAR, GL_CLAMP_TO_EDGE);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glActiveTexture(GLenum(GL_TEXTURE0 + kSceneDepth));
  depth_ = new_texture(GL_TEXTURE_2D, GL_NEAREST, GL_CLAMP_TO_EDGE);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, width, height, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  glActiveTexture(GL_TEXTURE0);
  framebuffer_ = Framebuffer::with_textures(
      colour_, depth_, width, height,
      {"the refraction's scene copy framebuffer is incomplete", "set RendererSettings::refraction = false"});
}

void RefractionSource::copy_from(const RenderTarget& target) {
  resize(target.width(), target.height());
  target.copy_to(framebuffer_);
}

void RefractionSource::release() {
  framebuffer_.release();
  for (GLuint* texture : {&colour_, &depth_})
    if (*texture) glDeleteTextures(1, texture);
  colour_ = depth_ = 0;
}

}  // namespace nearshore::playback
