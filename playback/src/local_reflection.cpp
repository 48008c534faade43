#include "local_reflection.hpp"

#include "gl_program.hpp"
#include "gl_texture.hpp"

namespace nearshore::playback {

void LocalReflection::resize(int width, int height) {
  if (framebuffer_ && width == framebuffer_.width() && height == framebuffer_.height()) return;
  release();
  glActiveTexture(GLenum(GL_TEXTURE0 + kReflection));
  colour_ = new_texture(GL_TEXTURE_2D, GL_LINEAR, GL_CLAMP_TO_EDGE);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
  framebuffer_ = Framebuffer::with_texture(
      colour_, width, height, true,
      {"the reflection framebuffer is incomplete", "set RendererSettings::local_reflections = false"});
}

void LocalReflection::release() {
  framebuffer_.release();
  if (colour_) glDeleteTextures(1, &colour_);
  colour_ = 0;
}

}  // namespace nearshore::playback
