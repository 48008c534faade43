// `nearshore bench play [SEQ]`: what the runtime costs a host (docs/commands/bench.md, issue 12).
//  1. streaming at a paced 30 fps display for --seconds: main-thread CPU per displayed frame
//     (advance + snapshot + the budgeted texture upload, no drawing), underruns, background decode
//     throughput (frames/s and x real time), upload bytes per displayed frame;
//  2. CPU surface queries per second on one core (batched elevations, both query points);
//  3. per grid: vertices drawn and frames/s on this machine's OpenGL at 640x360 and 1280x720, every
//     grid set to the same screen-space error (--screen-error px);
//  4. the lighting's cost (docs/lighting.md): frames/s at both sizes on the quadtree grid with the
//     full lighting and with lighting off (a flat-coloured sea, no sky);
//  5. the GPU time of each pass (FrameStatistics::gpu, timer queries) and frames/s at 1280x720 and
//     1920x1080, quadtree grid, full lighting, without anti-aliasing and with --msaa samples.
// Without SEQ it writes a 1024 x 1024 synthetic sequence (irregular linear sea) to --work first.
#include <time.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "command_support.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/loops/synthetic_sea.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/runtime/surface_sampler.hpp"

namespace nearshore::tools {
namespace {
namespace fs = std::filesystem;

std::string load_average() {
  double one = 0, five = 0, fifteen = 0;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf %lf %lf", &one, &five, &fifteen) != 3) one = five = fifteen = 0;
    std::fclose(f);
  }
  return fmt::format("{:.2f} {:.2f} {:.2f}", one, five, fifteen);
}

struct PlayBenchOptions {
  fs::path sequence, work = "nearshore-bench-play";
  int size = 1024, frames = 40;
  double seconds = 20.0, screen_error_px = 4.0;
  int msaa_samples = 4, draws = 5;
  long long queries = 2'000'000;
  bool json = false;
};

fs::path synthetic_sequence(const PlayBenchOptions& o) {
  const fs::path folder = o.work / fmt::format("sea_{}", o.size);
  if (fs::exists(folder / "manifest.json")) return folder;
  fs::remove_all(folder);
  GridGeometry geometry;
  geometry.columns = geometry.rows = o.size;
  geometry.spacing_m = 2.0;
  std::fprintf(stderr, "writing a %d x %d synthetic sequence of %d frames to %s\n", o.size, o.size, o.frames,
               folder.c_str());
  loops::write_sea_sequence(folder, loops::irregular_sea(8.0, 24, 1.5, 20.0, 0.5 * std::numbers::pi, 3), geometry,
                            o.frames, 0.5, 0.0);
  return folder;
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

void bench_play(const PlayBenchOptions& o) {
  ProgressBar::set_quiet(true);
  const fs::path folder = o.sequence.empty() ? synthetic_sequence(o) : o.sequence;
  nlohmann::json report = {{"sequence", folder.string()}, {"load_average_before", load_average()}};
  playback::GlWindow window(1280, 720, "nearshore bench play", false);
  report["opengl"] = window.gl_description();

  // 1. Streaming, paced at 30 fps.
  {
    runtime::StreamingEngine engine(folder, {});
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
    report["streaming"] = {
        {"grid", fmt::format("{} x {}", engine.manifest().geometry.columns, engine.manifest().geometry.rows)},
        {"display_fps", 30},
        {"seconds", o.seconds},
        {"main_thread_cpu_ms_mean", sum / double(main_ms.size())},
        {"main_thread_cpu_ms_p99", main_ms[static_cast<std::size_t>(0.99 * double(main_ms.size() - 1))]},
        {"underruns", s.underruns},
        {"decode_frames_per_s", s.decode_frames_per_s()},
        {"decode_real_time_multiple", s.decode_real_time_multiple()},
        {"decode_cpu_s_per_frame", s.keyframes_decoded > 0 ? s.decode_cpu_seconds / double(s.keyframes_decoded) : 0.0},
        {"deep_water_keyframes_per_s", s.deep_seconds > 0 ? double(s.deep_keyframes_synthesised) / s.deep_seconds : 0.0},
        {"upload_bytes_per_frame", upload_bytes / double(frames)},
        {"memory", engine.memory_summary()}};

    // 2. CPU queries on one core, on the last snapshot.
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
    for (auto [pattern, points] : {std::pair{"scattered", &scattered}, std::pair{"hulls", &hulls}}) {
      std::vector<double> out(points->size());
      for (auto [name, choppy] : {std::pair{"lattice", runtime::ChoppyPoint::kLattice},
                                  std::pair{"displaced", runtime::ChoppyPoint::kDisplaced}}) {
        const long long rounds = std::max<long long>(1, o.queries / static_cast<long long>(points->size()));
        const double cpu0 = thread_cpu_s();
        for (long long r = 0; r < rounds; ++r) sampler.elevations_m(*points, out, choppy);
        const double cpu = thread_cpu_s() - cpu0;
        report["queries_per_s_per_core"][pattern][name] = double(rounds) * double(points->size()) / cpu;
      }
    }
  }

  // 3. Grids at the same screen-space error.
  runtime::StreamingEngine engine(folder, {});
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
      playback::WaterRenderer renderer(settings);
      const auto site = engine.site();
      const playback::Camera camera = playback::Camera::overlooking_site(site->width_m, site->height_m);
      const FrameCost cost = measure_frames(renderer, engine.snapshot(), camera, {}, width, height, o.draws);
      report["grids"].push_back({{"grid", std::string(playback::grid_kind_name(kind))},
                                 {"size", fmt::format("{}x{}", width, height)},
                                 {"vertices_drawn", renderer.last_frame().vertices_drawn},
                                 {"frames_per_s", cost.frames_per_s}});
    }
  }
  // 4. Lighting on and off, quadtree grid, the same view.
  for (auto [width, height] : {std::pair{640, 360}, std::pair{1280, 720}}) {
    for (const bool lit : {true, false}) {
      playback::RendererSettings settings;
      settings.quadtree.screen_error_px = o.screen_error_px;
      settings.msaa_samples = o.msaa_samples;
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
      report["lighting"].push_back({{"lighting", lit ? "full" : "off"}, {"size", fmt::format("{}x{}", width, height)},
                                    {"frames_per_s", cost.frames_per_s}});
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
      playback::WaterRenderer renderer(settings);
      const auto site = engine.site();
      const playback::Camera camera = playback::Camera::overlooking_site(site->width_m, site->height_m);
      const FrameCost cost = measure_frames(renderer, engine.snapshot(), camera, {}, width, height, o.draws);
      nlohmann::json gpu_ms = nlohmann::json::object();
      for (int pass = 0; pass < playback::kGpuPassCount; ++pass)
        gpu_ms[playback::gpu_pass_name(playback::GpuPass(pass))] = cost.gpu_ms[std::size_t(pass)];
      gpu_ms["total"] = cost.gpu_total_ms;
      report["passes"].push_back({{"size", fmt::format("{}x{}", width, height)},
                                  {"msaa_samples", renderer.last_frame().msaa_samples},
                                  {"frames_per_s", cost.frames_per_s},
                                  {"gpu_timer", cost.gpu_timer},
                                  {"gpu_timed_frames", cost.timed_frames},
                                  {"gpu_ms", gpu_ms}});
    }
  }
  report["load_average_after"] = load_average();
  if (o.json) {
    std::printf("%s\n", report.dump(1).c_str());
    return;
  }
  const nlohmann::json& s = report["streaming"];
  std::printf("nearshore bench play: %s (%s), OpenGL %s\nload average before %s, after %s\n",
              report["sequence"].get<std::string>().c_str(), s["grid"].get<std::string>().c_str(),
              report["opengl"].get<std::string>().c_str(), report["load_average_before"].get<std::string>().c_str(),
              report["load_average_after"].get<std::string>().c_str());
  std::printf("streaming at 30 fps for %.0f s: main thread %.3f ms CPU per frame (p99 %.3f ms), %lld underruns\n",
              o.seconds, s["main_thread_cpu_ms_mean"].get<double>(), s["main_thread_cpu_ms_p99"].get<double>(),
              s["underruns"].get<long long>());
  std::printf("background decode: %.1f frames/s = %.1f x real time (%.1f ms CPU per frame); deep water %.1f keyframes/s\n",
              s["decode_frames_per_s"].get<double>(), s["decode_real_time_multiple"].get<double>(),
              1e3 * s["decode_cpu_s_per_frame"].get<double>(), s["deep_water_keyframes_per_s"].get<double>());
  std::printf("upload: %.0f bytes per displayed frame; %s\n", s["upload_bytes_per_frame"].get<double>(),
              s["memory"].get<std::string>().c_str());
  for (const char* pattern : {"hulls", "scattered"})
    std::printf("CPU queries per second per core, %s: %.2f million at lattice points, %.2f million at displaced points\n",
                pattern, 1e-6 * report["queries_per_s_per_core"][pattern]["lattice"].get<double>(),
                1e-6 * report["queries_per_s_per_core"][pattern]["displaced"].get<double>());
  std::printf("grids at %.1f px screen-space error (software OpenGL: relative figures only)\n| size | grid | vertices | fps |\n|---|---|---|---|\n",
              o.screen_error_px);
  for (const auto& g : report["grids"])
    std::printf("| %s | %s | %lld | %.2f |\n", g["size"].get<std::string>().c_str(), g["grid"].get<std::string>().c_str(),
                g["vertices_drawn"].get<long long>(), g["frames_per_s"].get<double>());
  std::printf("lighting (quadtree grid)\n| size | lighting | fps |\n|---|---|---|\n");
  for (const auto& g : report["lighting"])
    std::printf("| %s | %s | %.2f |\n", g["size"].get<std::string>().c_str(), g["lighting"].get<std::string>().c_str(),
                g["frames_per_s"].get<double>());
  std::printf("GPU ms per pass (quadtree grid, full lighting; timer queries, mean over the frames reported)\n| size | msaa | fps | frames |");
  for (int pass = 0; pass < playback::kGpuPassCount; ++pass) std::printf(" %s |", playback::gpu_pass_name(playback::GpuPass(pass)));
  std::printf(" total |\n|---|---|---|---|");
  for (int pass = 0; pass <= playback::kGpuPassCount; ++pass) std::printf("---|");
  std::printf("\n");
  for (const auto& g : report["passes"]) {
    std::printf("| %s | %d | %.2f | %d |", g["size"].get<std::string>().c_str(), g["msaa_samples"].get<int>(),
                g["frames_per_s"].get<double>(), g["gpu_timed_frames"].get<int>());
    if (!g["gpu_timer"].get<bool>()) {
      std::printf(" no GPU timer |\n");
      continue;
    }
    for (int pass = 0; pass < playback::kGpuPassCount; ++pass)
      std::printf(" %.2f |", g["gpu_ms"][playback::gpu_pass_name(playback::GpuPass(pass))].get<double>());
    std::printf(" %.2f |\n", g["gpu_ms"]["total"].get<double>());
  }
}

}  // namespace

void add_bench_play(CLI::App& bench) {
  auto o = std::make_shared<PlayBenchOptions>();
  CLI::App* command = bench.add_subcommand("play", "Runtime cost: main-thread CPU per frame, decode, uploads, CPU queries, grids, GPU ms per pass");
  command->add_option("sequence", o->sequence, "Baked sequence (default: a synthetic --size x --size one in --work)");
  command->add_option("--size", o->size, "Grid side of the synthetic sequence (cells)")->capture_default_str()
      ->check(number_in(at_least(16), at_most(8192)));
  command->add_option("--frames", o->frames, "Frames of the synthetic sequence")->capture_default_str()
      ->check(number_in(at_least(4), at_most(100000)));
  command->add_option("--seconds", o->seconds, "Paced streaming run, seconds of display time")->capture_default_str()
      ->check(number_in(at_least(1), at_most(36000)));
  command->add_option("--queries", o->queries, "CPU queries per measurement")->capture_default_str()
      ->check(number_in(at_least(65536), at_most(1e10)));
  command->add_option("--screen-error", o->screen_error_px, "Screen-space error every grid is set to (pixels)")
      ->capture_default_str()->check(number_in(at_least(0.5), at_most(64)));
  command->add_option("--msaa", o->msaa_samples, "Anti-aliasing samples per pixel of the frame-rate sections (the pass "
                                                  "section also runs at 1)")
      ->capture_default_str()->check(number_in(at_least(1), at_most(32)));
  command->add_option("--draws", o->draws, "Frames drawn per frame-rate measurement (after one to warm up)")
      ->capture_default_str()->check(number_in(at_least(2), at_most(1000)));
  command->add_option("--work", o->work, "Scratch folder for the synthetic sequence (kept for the next run)")->capture_default_str();
  command->add_flag("--json", o->json, "Print the figures as JSON");
  set_example(*command, "xvfb-run -a nearshore bench play --seconds 20");
  command->callback([o] { bench_play(*o); });
}

}  // namespace nearshore::tools
