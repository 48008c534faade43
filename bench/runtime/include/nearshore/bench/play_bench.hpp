#pragma once
// `nearshore bench play SEQ` (runtime side: runtime, playback; never the bake side): what the
// runtime costs a host (docs/commands/bench.md, issue 12).
//  1. streaming at a paced 30 fps display for `seconds`: main-thread CPU per displayed frame
//     (advance + snapshot + the budgeted texture upload, no drawing), underruns, background decode
//     throughput (frames/s and x real time), upload bytes per displayed frame;
//  2. CPU surface queries per second on one core (batched elevations, both query points);
//  3. per grid: vertices drawn and frames/s on this machine's OpenGL at 640x360 and 1280x720, every
//     grid set to the same screen-space error (`screen_error_px`);
//  4. the lighting's cost (docs/lighting.md): frames/s at both sizes on the quadtree grid with the
//     full lighting and with lighting off (a flat-coloured sea, no sky);
//  5. the GPU time of each pass (FrameStatistics::gpu, timer queries) and frames/s at 1280x720 and
//     1920x1080, quadtree grid, full lighting, without anti-aliasing and with `msaa_samples`.
// The sequence is a baked one; a synthetic one is written by the bake side (play_bench_sequence.hpp).
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nearshore/playback/water_renderer.hpp"

namespace nearshore::bench {

struct PlayBenchOptions {
  std::filesystem::path sequence;  ///< the baked sequence folder measured
  double seconds = 20.0;           ///< paced streaming run, seconds of display time
  double screen_error_px = 4.0;    ///< screen-space error every grid is set to
  int msaa_samples = 4;            ///< of the frame-rate sections (the pass section also runs at 1)
  int draws = 5;                   ///< frames drawn per frame-rate measurement (after one to warm up)
  long long queries = 2'000'000;   ///< CPU queries per measurement
  bool refraction = true;          ///< RendererSettings::refraction of every renderer measured
};

/// 1. Streaming, paced at 30 fps.
struct PlayStreamingResult {
  std::string grid;  ///< "1024 x 1024"
  int display_fps = 30;
  double seconds = 0.0;
  double main_thread_cpu_ms_mean = 0.0, main_thread_cpu_ms_p99 = 0.0;
  long long underruns = 0;
  double decode_frames_per_s = 0.0, decode_real_time_multiple = 0.0, decode_cpu_s_per_frame = 0.0;
  double deep_water_keyframes_per_s = 0.0, upload_bytes_per_frame = 0.0;
  std::string memory;  ///< StreamingEngine::memory_summary()
};

/// 2. CPU queries per second on one core, at lattice and at displaced points.
struct PlayQueryRates {
  double lattice_per_s = 0.0, displaced_per_s = 0.0;
};

/// 3. A grid at the same screen-space error.
struct PlayGridRow {
  std::string grid, size;
  long long vertices_drawn = 0;
  double frames_per_s = 0.0;
};

/// 4. Lighting on or off.
struct PlayLightingRow {
  std::string lighting, size;  ///< "full" or "off"; "640x360"
  double frames_per_s = 0.0;
};

/// 5. GPU time per pass (mean over the frames the timer queries reported).
struct PlayPassRow {
  std::string size;
  int msaa_samples = 0;
  double frames_per_s = 0.0;
  bool gpu_timer = false;
  int gpu_timed_frames = 0;
  std::array<double, playback::kGpuPassCount> gpu_ms{};
  double gpu_total_ms = 0.0;
};

struct PlayBenchResult {
  PlayBenchOptions options;
  std::string opengl;  ///< GlWindow::gl_description()
  std::string load_average_before, load_average_after;  ///< "0.52 0.61 0.70"
  PlayStreamingResult streaming;
  PlayQueryRates scattered, hulls;  ///< points over the harbour and around it; 64 ships' hulls
  std::vector<PlayGridRow> grids;
  std::vector<PlayLightingRow> lighting;
  std::vector<PlayPassRow> passes;
};

/// Opens a hidden 1280 x 720 OpenGL window (a display is needed: xvfb-run on a server).
PlayBenchResult run_play_bench(const PlayBenchOptions& options);

nlohmann::json play_bench_json(const PlayBenchResult& result);
std::string play_bench_text(const PlayBenchResult& result);

}  // namespace nearshore::bench
