// Not a test: what a keyframe change costs the render thread (issue 41, docs/rendering.md, the
// slope moments' paragraph). For each grid size, on the thread that draws: slope_moment_pyramid
// alone (the median of 5 runs); then ten keyframe changes as a host makes them (stage the next
// keyframe, WaterRenderer::upload every frame at the default 2 MiB budget until it is up, then
// show it), timing stage() and every frame's upload; last, a keyframe a snapshot needs unstaged
// (forced: computed and sent whole in one frame). Columns: pyramid_ms; stage_ms, worst_frame_ms,
// median_frame_ms over changes 7 to 10 (the texture slots reused: the steady state); frames: the
// last change's; cold_worst_ms: the worst frame of changes 1 to 6, which fill fresh slots (the
// driver allocates their textures in the first frame); forced_ms.
// The frames are paced at 60 Hz (a frame's upload, then a sleep to 16.7 ms), as a host drawing at
// 60 Hz gives a worker its time between them; --unpaced draws them back to back.
// Usage: playback_keyframe_staging_probe [--unpaced] [columns rows]... (default 1024 921 1470 1323);
// run it under tests/under_xvfb.sh (Mesa llvmpipe: the figures are the CPU's, the upload's copies).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <utility>
#include <vector>

#include "nearshore/playback/slope_moments.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "snapshot_fixtures.hpp"

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}
}  // namespace

int main(int argc, char** argv) {
  using namespace nearshore;
  std::vector<std::pair<int, int>> grids;
  int first = 1;
  const bool paced = !(argc > 1 && std::strcmp(argv[1], "--unpaced") == 0);
  if (!paced) ++first;
  for (int a = first; a + 1 < argc; a += 2) grids.emplace_back(std::atoi(argv[a]), std::atoi(argv[a + 1]));
  if (grids.empty()) grids = {{1024, 921}, {1470, 1323}};
  playback::GlWindow window(64, 64, "probe", false);
  std::printf("%-11s %10s %8s %14s %15s %6s %13s %9s\n", "grid", "pyramid_ms", "stage_ms", "worst_frame_ms",
              "median_frame_ms", "frames", "cold_worst_ms", "forced_ms");
  for (const auto& [columns, rows] : grids) {
    test::SiteOptions options;
    options.columns = columns;
    options.rows = rows;
    options.spacing_m = 1.0;
    options.land = false;
    runtime::SurfaceSnapshot snapshot;
    snapshot.site = test::make_site(options);
    snapshot.harbour_from = snapshot.harbour_to = test::make_harbour_keyframe(*snapshot.site, 0, 1);
    const auto unstaged = test::make_harbour_keyframe(*snapshot.site, 0, 100);

    std::vector<double> pyramid_ms;
    for (int run = 0; run < 5; ++run) {
      const auto start = Clock::now();
      const auto pyramid = playback::slope_moment_pyramid(unstaged->surface_elevation_m);
      pyramid_ms.push_back(ms_since(start));
    }
    std::sort(pyramid_ms.begin(), pyramid_ms.end());

    // Keyframe changes one after another: stage the next, upload paced frames until it is up,
    // show it. The first changes fill fresh texture slots (the driver allocates them: the first
    // frame of each pays that); from the seventh on (RendererSettings::harbour_texture_slots = 6)
    // the slots are reused, the steady state a long run lives in. The figures are that state's:
    // the worst of stage() and of any frame over changes 7 to 10, the median frame.
    playback::WaterRenderer renderer;
    renderer.upload(snapshot);  // the first keyframe, forced
    double stage_ms = 0, worst_ms = 0, cold_worst_ms = 0;
    std::vector<double> frame_ms;
    int frames = 0;
    for (int change = 1; change <= 10; ++change) {
      const auto next = test::make_harbour_keyframe(*snapshot.site, change % 2, std::uint64_t(change) + 1);
      const bool steady = change >= 7;
      double& worst = steady ? worst_ms : cold_worst_ms;
      auto start = Clock::now();
      renderer.stage(next);
      if (steady) stage_ms = std::max(stage_ms, ms_since(start));
      for (int frame = 0; frame < 1000; ++frame) {
        start = Clock::now();
        renderer.upload(snapshot);
        const double ms = ms_since(start);
        worst = std::max(worst, ms);
        if (steady) frame_ms.push_back(ms);
        if (steady && change == 10) ++frames;
        if (paced) std::this_thread::sleep_until(start + std::chrono::microseconds(16667));
        if (renderer.last_frame().upload_bytes == 0) break;  // the staged keyframe is up
      }
      snapshot.harbour_from = snapshot.harbour_to;
      snapshot.harbour_to = next;
      snapshot.harbour_fraction = 0.5;
      start = Clock::now();
      renderer.upload(snapshot);  // the change itself: nothing left to send
      worst = std::max(worst, ms_since(start));
    }
    std::nth_element(frame_ms.begin(), frame_ms.begin() + frame_ms.size() / 2, frame_ms.end());
    const double median_ms = frame_ms[frame_ms.size() / 2];
    snapshot.harbour_from = snapshot.harbour_to;
    snapshot.harbour_to = unstaged;
    auto start = Clock::now();
    renderer.upload(snapshot);
    const double forced_ms = ms_since(start);
    std::printf("%5d x %-4d %10.1f %8.2f %14.2f %15.2f %6d %13.1f %9.1f\n", columns, rows, pyramid_ms[2], stage_ms,
                worst_ms, median_ms, frames, cold_worst_ms, forced_ms);
  }
  return 0;
}
