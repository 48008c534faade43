// samples/own_renderer.cpp: a host that draws the sea ITSELF (C++ API). nearshore streams the
// baked harbour on its worker thread; the host takes each keyframe's surface elevation (a plain
// float array, uploaded once per keyframe) and blends the displayed pair in its own shader, here a
// top-down map coloured by elevation, with the land grey.
//
//   own_renderer SEQUENCE_FOLDER [FRAMES]
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "nearshore/runtime/streaming_engine.hpp"

namespace {

const char* kVertexShader = R"(#version 330 core
out vec2 uv;  // (0, 0) the harbour's south-west corner, (1, 1) its north-east corner
void main() {
  vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1);
  uv = corner;
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
})";
const char* kFragmentShader = R"(#version 330 core
in vec2 uv;
uniform sampler2D elevation_from, elevation_to, land;
uniform float fraction;  // the snapshot's harbour_fraction
out vec4 colour;
void main() {
  float eta = mix(texture(elevation_from, uv).r, texture(elevation_to, uv).r, fraction);
  float t = clamp(0.5 + eta / 2.0, 0.0, 1.0);  // -1 m deep blue .. +1 m white
  colour = texture(land, uv).r > 0.5 ? vec4(0.45, 0.42, 0.38, 1.0) : vec4(mix(vec3(0.0, 0.15, 0.45), vec3(0.9), t), 1.0);
})";

GLuint texture_of(const float* values, int columns, int rows) {  // row 0 south = texture row 0
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, columns, rows, 0, GL_RED, GL_FLOAT, values);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return texture;
}

GLuint program_of(const char* vertex_source, const char* fragment_source) {
  GLuint program = glCreateProgram();
  for (auto [stage, source] : {std::pair{GL_VERTEX_SHADER, vertex_source}, {GL_FRAGMENT_SHADER, fragment_source}}) {
    GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    glAttachShader(program, shader);
  }
  glLinkProgram(program);
  return program;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return std::fprintf(stderr, "usage: own_renderer SEQUENCE_FOLDER [FRAMES]\n"), 2;
  const int frame_limit = argc > 2 ? std::atoi(argv[2]) : 0;
  if (!glfwInit()) return std::fprintf(stderr, "own_renderer: no display (run under xvfb-run -a)\n"), 1;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_VISIBLE, frame_limit > 0 ? GLFW_FALSE : GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(640, 480, "host's own renderer", nullptr, nullptr);
  if (!window) return std::fprintf(stderr, "own_renderer: no OpenGL 3.3 core context\n"), 1;
  glfwMakeContextCurrent(window);
  try {
    nearshore::runtime::StreamingEngine sea(argv[1]);
    const auto site = sea.site();
    const int columns = site->harbour.geometry.columns, rows = site->harbour.geometry.rows;
    std::vector<float> land(site->harbour.land.values().begin(), site->harbour.land.values().end());
    const GLuint land_texture = texture_of(land.data(), columns, rows);
    GLuint elevation[2] = {0, 0};
    std::uint64_t uploaded[2] = {0, 0};  // the keyframe serial each texture holds
    const GLuint program = program_of(kVertexShader, kFragmentShader);
    GLuint vertex_array = 0;
    glGenVertexArrays(1, &vertex_array);
    sea.wait_until_ready(0.0, std::chrono::seconds(10));
    for (int frame = 0; !glfwWindowShouldClose(window) && (frame_limit == 0 || frame < frame_limit); ++frame) {
      sea.advance_to(frame_limit > 0 ? frame / 30.0 : glfwGetTime());
      const nearshore::runtime::SurfaceSnapshot snapshot = sea.snapshot();
      const nearshore::runtime::HarbourKeyframe* pair[2] = {snapshot.harbour_from.get(), snapshot.harbour_to.get()};
      for (int k = 0; k < 2; ++k) {
        if (!pair[k] || pair[k]->serial == uploaded[k]) continue;  // each keyframe goes up once
        glDeleteTextures(1, &elevation[k]);
        elevation[k] = texture_of(pair[k]->surface_elevation_m.values().data(), columns, rows);
        uploaded[k] = pair[k]->serial;
      }
      glUseProgram(program);
      const GLuint textures[3] = {elevation[0], elevation[1] ? elevation[1] : elevation[0], land_texture};
      const char* names[3] = {"elevation_from", "elevation_to", "land"};
      for (int unit = 0; unit < 3; ++unit) {
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_2D, textures[unit]);
        glUniform1i(glGetUniformLocation(program, names[unit]), unit);
      }
      glUniform1f(glGetUniformLocation(program, "fraction"), float(snapshot.harbour_fraction));
      glBindVertexArray(vertex_array);
      glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
      glfwSwapBuffers(window);
      glfwPollEvents();
    }
    std::printf("own_renderer: %s, %lld underruns\n", sea.stats().plan.c_str(), sea.stats().underruns);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "own_renderer: %s\n", error.what());
    return 1;
  }
  glfwTerminate();
  return 0;
}
