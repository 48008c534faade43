#pragma once
// One way to make a texture object (private to the renderer): every texture the renderer owns is
// filtered the same way in both directions and wrapped the same way along s and t.
#include <glad/gl.h>

namespace nearshore::playback {

/// A new texture of `target`, left bound to the active unit, with MIN and MAG filter `filter` and
/// S and T wrap `wrap`. Its storage is the caller's (glTexImage2D/3D).
inline GLuint new_texture(GLenum target, GLint filter, GLint wrap) {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(target, texture);
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(target, GL_TEXTURE_WRAP_S, wrap);
  glTexParameteri(target, GL_TEXTURE_WRAP_T, wrap);
  return texture;
}

}  // namespace nearshore::playback
