#include "nearshore/bench/play_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>
#include <thread>
#include <utility>

#include <fmt/format.h>
#include <fmt/printf.h>

#include "nearshore/core/process_usage.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/runtime/surface_sampler.hpp"

namespace nearshore::bench {
namespace {
namespace fs = std::filesystem;

// "0.52 0.61 0.70": the three load averages ("0.00 0.00 0.00" where /proc/loadavg cannot be read).
std::string load_average_text() {
  const LoadAverage load = load_average().value_or(LoadAverage{});
  return fmt::format("{:.2f} {:.2f} {:.2f}", load.one_minute, load.five_minutes, load.fifteen_minutes);
}

// Frames/s of `draws` renders of one view (each read back: llvmpipe renders on read, and a GPU
// finishes the frame), after one to upload and build; and the GPU time per pass averaged over the
// frames the timer queries report on (each render reports an earlier one: FrameStatistics::gpu).
struct FrameCost {
  double frames_per_s = 0;
  bool gpu_timer = false;
  int timed_frames = 0;
  std::array<double, playback::kGpuPassCount> gpu_ms{};
  double gpu_total_ms = 0;
};

FrameCost measure_frames(playback::WaterRenderer& renderer, const runtime::SurfaceSnapshot& snapshot,
                         const playback::Camera& camera, const playback::DrawOptions& options, int width, int height,
                         int draws) {
  renderer.render(snapshot, camera, {}, width, height, options);  // uploads, builds the grid
  (void)renderer.read_pixels();
  FrameCost cost;
  int timed = 0, last_reported = 0;  // frame 0: the warm-up (shader compilation, uploads), never counted
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < draws; ++k) {
    renderer.render(snapshot, camera, {}, width, height, options);  // frame k + 1
    (void)renderer.read_pixels();
    // Each frame counted once: a render reports the newest earlier frame whose queries are done.
    const playback::GpuPassTimes& gpu = renderer.last_frame().gpu;
    const int reported = k + 1 - gpu.frames_behind;
    if (!gpu.measured || reported <= last_reported) continue;
    last_reported = reported;
    ++timed;
    for (int pass = 0; pass < playback::kGpuPassCount; ++pass) cost.gpu_ms[std::size_t(pass)] += gpu.ms[std::size_t(pass)];
    cost.gpu_total_ms += gpu.total_ms;
  }
  cost.frames_per_s = draws / seconds_since(t0);
  cost.gpu_timer = timed > 0;
  cost.timed_frames = timed;
  for (double& ms : cost.gpu_ms) ms /= std::max(timed, 1);
  cost.gpu_total_ms /= std::max(timed, 1);
  return cost;
}

// 1 and 2: streaming paced at 30 fps, then CPU queries on one core on the last snapshot.
void measure_streaming(const PlayBenchOptions& o, PlayBenchResult& result) {
  runtime::StreamingEngine engine(o.sequence, {});
  playback::WaterRenderer renderer;
  engine.wait_until_ready(0.0, std::chrono::seconds(60));
  std::vector<double> main_ms;
  double upload_bytes = 0;
  const double frame_s = 1.0 / 30.0;
  const int frames = static_cast<int>(std::lround(o.seconds * 30.0));
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < frames; ++k) {
    std::this_thread::sleep_until(start + std::chrono::duration<double>(k * frame_s));
    const double cpu0 = thread_cpu_s();
    engine.advance_to(k * frame_s);
    renderer.stage_upcoming(engine);
    const playback::GpuTextures& uploaded = renderer.upload(engine.snapshot());
    (void)uploaded;
    main_ms.push_back(1e3 * (thread_cpu_s() - cpu0));
    upload_bytes += double(renderer.last_frame().upload_bytes);
  }
  std::sort(main_ms.begin(), main_ms.end());
  double sum = 0;
  for (double v : main_ms) sum += v;
  const runtime::StreamingStats s = engine.stats();
  PlayStreamingResult& streaming = result.streaming;
  streaming.grid = fmt::format("{} x {}", engine.manifest().geometry.columns, engine.manifest().geometry.rows);
  streaming.seconds = o.seconds;
  streaming.main_thread_cpu_ms_mean = sum / double(main_ms.size());
  streaming.main_thread_cpu_ms_p99 = main_ms[static_cast<std::size_t>(0.99 * double(main_ms.size() - 1))];
  streaming.underruns = s.underruns;
  streaming.decode_frames_per_s = s.decode_frames_per_s();
  streaming.decode_real_time_multiple = s.decode_real_time_multiple();
  streaming.decode_cpu_s_per_frame = s.keyframes_decoded > 0 ? s.decode_cpu_seconds / double(s.keyframes_decoded) : 0.0;
  streaming.deep_water_keyframes_per_s = s.deep_seconds > 0 ? double(s.deep_keyframes_synthesised) / s.deep_seconds : 0.0;
  streaming.upload_bytes_per_frame = upload_bytes / double(frames);
  streaming.memory = engine.memory_summary();

  const runtime::SurfaceSampler sampler(engine.snapshot());
  const auto site = engine.site();
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> x(-0.25 * site->width_m, 1.25 * site->width_m);
  std::uniform_real_distribution<double> y(-0.25 * site->height_m, 1.25 * site->height_m);
  // Two patterns: points scattered over the harbour and the sea around it (cache-cold, the worst
  // case), and hulls: 64 ships at scattered places, 1024 points each over 60 m x 15 m (what a
  // ship's buoyancy asks for).
  std::vector<runtime::SitePoint> scattered(65536), hulls;
  for (auto& p : scattered) p = {x(random), y(random)};
  std::uniform_real_distribution<double> along(-30.0, 30.0), across(-7.5, 7.5);
  for (int ship = 0; ship < 64; ++ship) {
    const double cx = x(random), cy = y(random);
    for (int k = 0; k < 1024; ++k) hulls.push_back({cx + along(random), cy + across(random)});
  }
  for (auto [points, rates] : {std::pair{&scattered, &result.scattered}, std::pair{&hulls, &result.hulls}}) {
    std::vector<double> out(points->size());
    for (auto [choppy, rate] : {std::pair{runtime::ChoppyPoint::kLattice, &rates->lattice_per_s},
                                std::pair{runtime::ChoppyPoint::kDisplaced, &rates->displaced_per_s}}) {
      const long long rounds = std::max<long long>(1, o.queries / static_cast<long long>(points->size()));
      const double cpu0 = thread_cpu_s();
      for (long long r = 0; r < rounds; ++r) sampler.elevations_m(*points, out, choppy);
      const double cpu = thread_cpu_s() - cpu0;
      *rate = double(rounds) * double(points->size()) / cpu;
    }
  }
}

}  // namespace

PlayBenchResult run_play_bench(const PlayBenchOptions& o) {
  PlayBenchResult result;
  result.options = o;
  result.load_average_before = load_average_text();
  playback::GlWindow window(1280, 720, "nearshore bench play", false);
  result.opengl = window.gl_description();
  measure_streaming(o, result);

  // 3. Grids at the same screen-space error.
  runtime::StreamingEngine engine(o.sequence, {});
  engine.wait_until_ready(0.0, std::chrono::seconds(60));
  engine.advance_to(0.0);
  for (auto [width, height] : {std::pair{640, 360}, std::pair{1280, 720}}) {
    for (playback::GridKind kind : {playback::GridKind::radial, playback::GridKind::quadtree, playback::GridKind::projected}) {
      playback::RendererSettings settings;
      settings.grid = kind;
      // Equal error: quadtree quads and projected-grid cells span screen_error_px; the radial grid's
      // arc step 2 pi r / M spans 2 pi f / M px at any distance r (f: focal length in px), so M = 2 pi f / error.
      const double focal_px = height / (2.0 * std::tan(45.0 * std::numbers::pi / 360.0));
      settings.radial.segment_count = static_cast<int>(std::lround(2.0 * std::numbers::pi * focal_px / o.screen_error_px));
      settings.quadtree.screen_error_px = o.screen_error_px;
      settings.projected.vertex_spacing_px = o.screen_error_px;
      settings.msaa_samples = o.msaa_samples;
      settings.refraction = o.refraction;
      playback::WaterRenderer renderer(settings);
      const auto site = engine.site();
      const playback::Camera camera = playback::Camera::overlooking_site(site->width_m, site->height_m);
      const FrameCost cost = measure_frames(renderer, engine.snapshot(), camera, {}, width, height, o.draws);
      result.grids.push_back({std::string(playback::grid_kind_name(kind)), fmt::format("{}x{}", width, height),
                              renderer.last_frame().vertices_drawn, cost.frames_per_s});
    }
  }
  // 4. Lighting on and off, quadtree grid, the same view.
  for (auto [width, height] : {std::pair{640, 360}, std::pair{1280, 720}}) {
    for (const bool lit : {true, false}) {
      playback::RendererSettings settings;
      settings.quadtree.screen_error_px = o.screen_error_px;
      settings.msaa_samples = o.msaa_samples;
      settings.refraction = o.refraction;
      playback::WaterRenderer renderer(settings);
      const auto site = engine.site();
      const playback::Camera camera = playback::Camera::overlooking_site(site->width_m, site->height_m);
      playback::DrawOptions options;
      if (!lit) {
        options.colouring = playback::SurfaceColouring::flat;
        options.flat_colour = {0.05f, 0.25f, 0.35f};
        options.sky = false;
      }
      const FrameCost cost = measure_frames(renderer, engine.snapshot(), camera, options, width, height, o.draws);
      result.lighting.push_back({lit ? "full" : "off", fmt::format("{}x{}", width, height), cost.frames_per_s});
    }
  }
  // 5. GPU time per pass, quadtree grid, full lighting, the same view; without and with MSAA.
  std::vector<int> sample_counts = {1};
  if (o.msaa_samples > 1) sample_counts.push_back(o.msaa_samples);
  for (auto [width, height] : {std::pair{1280, 720}, std::pair{1920, 1080}}) {
    for (const int samples : sample_counts) {
      playback::RendererSettings settings;
      settings.quadtree.screen_error_px = o.screen_error_px;
      settings.msaa_samples = samples;
      settings.refraction = o.refraction;
      playback::WaterRenderer renderer(settings);
      const auto site = engine.site();
      const playback::Camera camera = playback::Camera::overlooking_site(site->width_m, site->height_m);
      const FrameCost cost = measure_frames(renderer, engine.snapshot(), camera, {}, width, height, o.draws);
      result.passes.push_back({fmt::format("{}x{}", width, height), renderer.last_frame().msaa_samples, cost.frames_per_s,
                               cost.gpu_timer, cost.timed_frames, cost.gpu_ms, cost.gpu_total_ms});
    }
  }
  result.load_average_after = load_average_text();
  return result;
}

nlohmann::json play_bench_json(const PlayBenchResult& result) {
  const PlayStreamingResult& s = result.streaming;
  nlohmann::json report = {{"sequence", result.options.sequence.string()},
                           {"load_average_before", result.load_average_before},
                           {"load_average_after", result.load_average_after},
                           {"opengl", result.opengl}};
  report["streaming"] = {{"grid", s.grid},
                         {"display_fps", s.display_fps},
                         {"seconds", s.seconds},
                         {"main_thread_cpu_ms_mean", s.main_thread_cpu_ms_mean},
                         {"main_thread_cpu_ms_p99", s.main_thread_cpu_ms_p99},
                         {"underruns", s.underruns},
                         {"decode_frames_per_s", s.decode_frames_per_s},
                         {"decode_real_time_multiple", s.decode_real_time_multiple},
                         {"decode_cpu_s_per_frame", s.decode_cpu_s_per_frame},
                         {"deep_water_keyframes_per_s", s.deep_water_keyframes_per_s},
                         {"upload_bytes_per_frame", s.upload_bytes_per_frame},
                         {"memory", s.memory}};
  for (auto [pattern, rates] : {std::pair{"scattered", &result.scattered}, std::pair{"hulls", &result.hulls}}) {
    report["queries_per_s_per_core"][pattern]["lattice"] = rates->lattice_per_s;
    report["queries_per_s_per_core"][pattern]["displaced"] = rates->displaced_per_s;
  }
  for (const PlayGridRow& g : result.grids)
    report["grids"].push_back(
        {{"grid", g.grid}, {"size", g.size}, {"vertices_drawn", g.vertices_drawn}, {"frames_per_s", g.frames_per_s}});
  for (const PlayLightingRow& g : result.lighting)
    report["lighting"].push_back({{"lighting", g.lighting}, {"size", g.size}, {"frames_per_s", g.frames_per_s}});
  for (const PlayPassRow& p : result.passes) {
    nlohmann::json gpu_ms = nlohmann::json::object();
    for (int pass = 0; pass < playback::kGpuPassCount; ++pass)
      gpu_ms[playback::gpu_pass_name(playback::GpuPass(pass))] = p.gpu_ms[std::size_t(pass)];
    gpu_ms["total"] = p.gpu_total_ms;
    report["passes"].push_back({{"size", p.size},
                                {"msaa_samples", p.msaa_samples},
                                {"frames_per_s", p.frames_per_s},
                                {"gpu_timer", p.gpu_timer},
                                {"gpu_timed_frames", p.gpu_timed_frames},
                                {"gpu_ms", gpu_ms}});
  }
  return report;
}

std::string play_bench_text(const PlayBenchResult& result) {
  const PlayStreamingResult& s = result.streaming;
  std::string text = fmt::sprintf("nearshore bench play: %s (%s), OpenGL %s\nload average before %s, after %s\n",
                                  result.options.sequence.string(), s.grid, result.opengl, result.load_average_before,
                                  result.load_average_after);
  text += fmt::sprintf("streaming at 30 fps for %.0f s: main thread %.3f ms CPU per frame (p99 %.3f ms), %lld underruns\n",
                       result.options.seconds, s.main_thread_cpu_ms_mean, s.main_thread_cpu_ms_p99, s.underruns);
  text += fmt::sprintf("background decode: %.1f frames/s = %.1f x real time (%.1f ms CPU per frame); deep water %.1f keyframes/s\n",
                       s.decode_frames_per_s, s.decode_real_time_multiple, 1e3 * s.decode_cpu_s_per_frame,
                       s.deep_water_keyframes_per_s);
  text += fmt::sprintf("upload: %.0f bytes per displayed frame; %s\n", s.upload_bytes_per_frame, s.memory);
  for (auto [pattern, rates] : {std::pair{"hulls", &result.hulls}, std::pair{"scattered", &result.scattered}})
    text += fmt::sprintf("CPU queries per second per core, %s: %.2f million at lattice points, %.2f million at displaced points\n",
                         pattern, 1e-6 * rates->lattice_per_s, 1e-6 * rates->displaced_per_s);
  text += fmt::sprintf(
      "grids at %.1f px screen-space error (software OpenGL: relative figures only)\n| size | grid | vertices | fps |\n|---|---|---|---|\n",
      result.options.screen_error_px);
  for (const PlayGridRow& g : result.grids)
    text += fmt::sprintf("| %s | %s | %lld | %.2f |\n", g.size, g.grid, g.vertices_drawn, g.frames_per_s);
  text += "lighting (quadtree grid)\n| size | lighting | fps |\n|---|---|---|\n";
  for (const PlayLightingRow& g : result.lighting) text += fmt::sprintf("| %s | %s | %.2f |\n", g.size, g.lighting, g.frames_per_s);
  text += "GPU ms per pass (quadtree grid, full lighting; timer queries, mean over the frames reported)\n| size | msaa | fps | frames |";
  for (int pass = 0; pass < playback::kGpuPassCount; ++pass)
    text += fmt::sprintf(" %s |", playback::gpu_pass_name(playback::GpuPass(pass)));
  text += " total |\n|---|---|---|---|";
  for (int pass = 0; pass <= playback::kGpuPassCount; ++pass) text += "---|";
  text += "\n";
  for (const PlayPassRow& p : result.passes) {
    text += fmt::sprintf("| %s | %d | %.2f | %d |", p.size, p.msaa_samples, p.frames_per_s, p.gpu_timed_frames);
    if (!p.gpu_timer) {
      text += " no GPU timer |\n";
      continue;
    }
    for (int pass = 0; pass < playback::kGpuPassCount; ++pass) text += fmt::sprintf(" %.2f |", p.gpu_ms[std::size_t(pass)]);
    text += fmt::sprintf(" %.2f |\n", p.gpu_total_ms);
  }
  return text;
}

}  // namespace nearshore::bench
