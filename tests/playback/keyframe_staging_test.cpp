// The slope moments a staged keyframe gets from the worker thread (playback/src/keyframe_textures.cpp)
// against those computed on the render thread: the textures read back from the GPU, level by
// level, the same bits as slope_moment_pyramid's, whichever path and timing made them.
#include <gtest/gtest.h>
#include <glad/gl.h>

#include <cstring>
#include <vector>

#include "nearshore/playback/slope_moments.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "snapshot_fixtures.hpp"

namespace nearshore {
namespace {
using namespace playback;

// Every mip level of an RGBA32F texture, as the GPU holds it.
std::vector<SlopeMomentLevel> read_moments(unsigned texture, int columns, int rows) {
  std::vector<SlopeMomentLevel> levels;
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  for (const auto& [width, height] : slope_moment_level_sizes(columns, rows)) {
    SlopeMomentLevel level;
    level.columns = width;
    level.rows = height;
    level.texels.resize(std::size_t(width) * height * 4);
    glGetTexImage(GL_TEXTURE_2D, GLint(levels.size()), GL_RGBA, GL_FLOAT, level.texels.data());
    levels.push_back(std::move(level));
  }
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  return levels;
}

void expect_same_bits(const std::vector<SlopeMomentLevel>& got, const std::vector<SlopeMomentLevel>& expected,
                      const char* path) {
  ASSERT_EQ(got.size(), expected.size()) << path;
  for (std::size_t level = 0; level < got.size(); ++level) {
    ASSERT_EQ(got[level].texels.size(), expected[level].texels.size()) << path << ", level " << level;
    EXPECT_EQ(std::memcmp(got[level].texels.data(), expected[level].texels.data(), got[level].texels.size() * sizeof(float)), 0)
        << path << ", level " << level;
  }
}

TEST(KeyframeStaging, TheWorkersSlopeMomentsAreTheRenderThreadsOnes) {
  GlWindow window(64, 64, "test", false);
  test::SiteOptions options;
  options.columns = 150;  // even, then odd (75), ...
  options.rows = 97;      // odd from the start
  options.spacing_m = 2.0;
  runtime::SurfaceSnapshot shown;
  shown.site = test::make_site(options);
  shown.harbour_from = shown.harbour_to = test::make_harbour_keyframe(*shown.site, 0, 1);
  const auto next = test::make_harbour_keyframe(*shown.site, 1, 2);
  const auto expected = slope_moment_pyramid(next->surface_elevation_m);
  runtime::SurfaceSnapshot showing_next = shown;
  showing_next.harbour_from = showing_next.harbour_to = next;
  RendererSettings settings;
  settings.upload_budget_bytes_per_frame = 64 * 1024;  // a few dozen frames for the whole keyframe

  // 1. Staged: the worker computes, the render thread sends within the budget over many frames.
  {
    WaterRenderer renderer(settings);
    renderer.upload(shown);
    ASSERT_TRUE(renderer.stage(next));
    int frames = 0;
    for (; frames < 200; ++frames) {
      renderer.upload(shown);
      EXPECT_EQ(renderer.last_frame().forced_upload_bytes, 0u);
      if (renderer.last_frame().upload_bytes == 0) break;
    }
    EXPECT_GT(frames, 5);
    const GpuTextures& textures = renderer.upload(showing_next);
    EXPECT_EQ(renderer.last_frame().upload_bytes, 0u) << "already resident";
    expect_same_bits(read_moments(textures.harbour_slope_moments[0], options.columns, options.rows), expected, "staged");
  }
  // 2. Staged and needed at once: the render thread waits for the worker, then sends it whole.
  {
    WaterRenderer renderer(settings);
    renderer.upload(shown);
    ASSERT_TRUE(renderer.stage(next));
    const GpuTextures& textures = renderer.upload(showing_next);
    EXPECT_GT(renderer.last_frame().forced_upload_bytes, 0u);
    expect_same_bits(read_moments(textures.harbour_slope_moments[0], options.columns, options.rows), expected,
                     "staged, then forced");
  }
  // 3. Never staged: computed and sent on the render thread (the synchronous path).
  {
    WaterRenderer renderer(settings);
    const GpuTextures& textures = renderer.upload(showing_next);
    expect_same_bits(read_moments(textures.harbour_slope_moments[0], options.columns, options.rows), expected, "unstaged");
  }
}

}  // namespace
}  // namespace nearshore
