#pragma once
// Shader programs of the water renderer (private to it): compiled from the embedded GLSL files
// (cmake/EmbedShaders.cmake), every sampler of surface.glsl on its own texture unit, and the
// uniform setters the passes share. Needs the renderer's current GL context.
#include <glad/gl.h>

#include <array>
#include <initializer_list>
#include <string>

#include "nearshore/core/image.hpp"
#include "nearshore/playback/camera.hpp"
#include "nearshore/playback/lighting.hpp"

namespace nearshore::playback {

/// The texture unit of each sampler of surface.glsl (link_program assigns them in this order):
/// two sampler types on one unit is an error at draw time, and every sampler starts on unit 0.
enum SamplerUnit {
  kHarbourEta = 0,
  kHarbourBreaking = 2,
  kDepth = 4,
  kPorosity = 5,
  kLand = 6,
  kDeepFirst = 7,
  kCoast = 17,
  kReflection = 18,
  kPatches = 19,
  kDecalFoam = 20,
  kDeepFoam = 21,
  kPreviousFoam = 22,
  kHarbourEtaRate = 23,
  kRelativeWaveHeight = 25,
  kSceneColour = 26,  // the opaque scene the sea refracts (RefractionSource)
  kSceneDepth = 27,
  kStructureMask = 28,
  kHarbourSlopeMoments = 29,  // from, to: the keyframes' slope moments (slope_moments.hpp), 29 and 30
  kSurroundings = 31,         // the skirt's ground beyond the grid (site_terrain.hpp SurroundingGround)
  kSamplerUnitCount = 32      // the 32 fragment units of every GL 3.3 driver the project meets: all taken
};

/// A linked program: its vertex stage is `#version`, then the shared files `vertex_prefixes` in
/// order (common.glsl first), then `vertex_name`; the fragment stage likewise. Left in use, with
/// its samplers on their SamplerUnit. Throws nearshore::Error naming the shader file and the
/// driver's log when a stage does not compile or the two do not link.
GLuint link_program(std::initializer_list<const char*> vertex_prefixes, const std::string& vertex_name,
                    std::initializer_list<const char*> fragment_prefixes, const std::string& fragment_name);

inline GLint at(GLuint program, const char* name) {
  return glGetUniformLocation(program, name);
}
void set_uniform(GLuint program, const char* name, const std::array<double, 3>& value);
void set_uniform(GLuint program, const char* name, const Rgb& value);
void set_uniform(GLuint program, const char* name, float value);
void set_uniform(GLuint program, const char* name, int value);
void set_uniform(GLuint program, const char* name, const Matrix4& value);

/// The sun, sky, fog, water and foam of common.glsl from one frame's lighting (the same names).
void set_lighting_uniforms(GLuint program, const LightingFrame& frame);

}  // namespace nearshore::playback
