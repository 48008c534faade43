// `nearshore play SEQ`: the OpenGL runtime on a baked sequence, in a window or as a screenshot.
#include <chrono>
#include <cstdio>
#include <optional>
#include <filesystem>
#include <memory>
#include <vector>

#include <fmt/core.h>

#include "command_support.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/playback/sequence_player.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/plot/plot.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/sequence/loop_playback.hpp"

namespace nearshore::tools {
namespace fs = std::filesystem;
namespace {

struct PlayOptions {
  fs::path sequence_folder;
  fs::path screenshot;
  double time_s = 0;
  int width_px = 1280, height_px = 720;
  std::vector<double> eye_m, target_m;
  double sun_azimuth_deg = 200, sun_elevation_deg = 35;
  double seconds = 0;
};

playback::Camera camera_from(const PlayOptions& o, const GridGeometry& geometry) {
  playback::Camera camera = playback::Camera::overlooking(geometry);
  // Given from the grid's south-west corner, like every position in a case file.
  const double x0 = geometry.origin_x_m, y0 = geometry.origin_y_m;
  if (!o.eye_m.empty()) camera.eye_m = {x0 + o.eye_m[0], y0 + o.eye_m[1], o.eye_m[2]};
  if (!o.target_m.empty()) camera.target_m = {x0 + o.target_m[0], y0 + o.target_m[1], o.target_m[2]};
  if (camera.eye_m == camera.target_m)
    throw Error(fmt::format("--eye {},{},{}", camera.eye_m[0] - x0, camera.eye_m[1] - y0, camera.eye_m[2]),
                "is the point the camera looks at, so it looks in no direction",
                "give --target a point away from the eye");
  return camera;
}

void play(const PlayOptions& o) {
  const sequence::SequenceReader reader(o.sequence_folder);
  const HarbourGrid harbour = reader.read_harbour_grid();
  const playback::Camera camera = camera_from(o, harbour.geometry);  // before a window opens: it may refuse --eye
  const bool screenshot = !o.screenshot.empty();
  playback::GlWindow window(o.width_px, o.height_px, "nearshore play " + o.sequence_folder.string(), !screenshot);
  playback::WaterRenderer renderer(harbour);
  // The loop `nearshore loops` planned (with its crossfades), else the frames in order.
  const std::optional<sequence::LoopSchedule> loop = sequence::read_loop_schedule(o.sequence_folder);
  playback::SequencePlayer player = loop ? playback::SequencePlayer(reader, *loop) : playback::SequencePlayer(reader);
  if (loop)
    std::fprintf(stderr, "playing the %s loop of loops.json: %.1f s, %zu steps\n", loop->kind.c_str(), loop->length_s,
                 loop->shown.size());
  else
    std::fprintf(stderr, "no loops.json: playing frames 0..%d in order (run `nearshore loops` for a seamless loop)\n",
                 reader.frame_count() - 1);
  playback::Lighting lighting;
  lighting.sun_azimuth_deg = o.sun_azimuth_deg;
  lighting.sun_elevation_deg = o.sun_elevation_deg;
  std::fprintf(stderr, "OpenGL %s; %d frames of %d x %d cells at %.3g s\n", window.gl_description().c_str(),
               reader.frame_count(), harbour.geometry.columns, harbour.geometry.rows, reader.frame_interval_s());
  if (screenshot) {
    player.advance_to(o.time_s);
    renderer.set_frame(player.surface_elevation_m(), &player.breaking());
    renderer.render(camera, lighting, o.width_px, o.height_px);
    write_png(renderer.read_pixels(), o.screenshot);
    std::printf("screenshot: %s (%d x %d, t = %.2f s)\n", o.screenshot.c_str(), o.width_px, o.height_px, o.time_s);
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  int frames = 0;
  double elapsed = 0;
  while (!window.should_close() && (o.seconds <= 0 || elapsed < o.seconds)) {
    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    player.advance_to(o.time_s + elapsed);
    renderer.set_frame(player.surface_elevation_m(), &player.breaking());
    renderer.render(camera, lighting, window.framebuffer_width_px(), window.framebuffer_height_px());
    renderer.blit_to_window(window.framebuffer_width_px(), window.framebuffer_height_px());
    window.present();
    ++frames;
  }
  std::printf("played %.1f s, %d frames drawn (%.1f fps)\n", elapsed, frames, frames / std::max(elapsed, 1e-9));
}

}  // namespace

void add_play_command(CLI::App& app) {
  auto o = std::make_shared<PlayOptions>();
  CLI::App* cmd = app.add_subcommand("play", "Play a baked sequence with the OpenGL runtime (window or screenshot)");
  cmd->add_option("sequence", o->sequence_folder, "Baked sequence folder (from `nearshore bake`)")->required();
  cmd->add_option("--screenshot", o->screenshot, "Render one picture to this PNG and exit (hidden window)");
  cmd->add_option("--time", o->time_s, "Playback time of the first picture, seconds")
      ->capture_default_str()
      ->check(number_in(at_least(0), at_most(1e9)));
  cmd->add_option("--width", o->width_px, "Picture width, pixels")->capture_default_str()->check(number_in(at_least(16), at_most(8192)));
  cmd->add_option("--height", o->height_px, "Picture height, pixels")->capture_default_str()->check(number_in(at_least(16), at_most(8192)));
  cmd->add_option("--eye", o->eye_m, "Camera position x,y,z in metres from the grid's south-west corner, z up (default: overview)")
      ->delimiter(',')->expected(3)->check(finite_number());
  cmd->add_option("--target", o->target_m, "Point looked at x,y,z in metres")->delimiter(',')->expected(3)->check(finite_number());
  cmd->add_option("--sun-azimuth", o->sun_azimuth_deg, "Sun bearing, degrees from north")
      ->capture_default_str()
      ->check(number_in(at_least(-360), at_most(360)));
  cmd->add_option("--sun-elevation", o->sun_elevation_deg, "Sun height above the horizon, degrees")
      ->capture_default_str()
      ->check(number_in(at_least(-90), at_most(90)));
  cmd->add_option("--seconds", o->seconds, "Close the window after this many seconds (0: when closed)")
      ->check(number_in(at_least(0), at_most(1e9)));
  set_example(*cmd, "xvfb-run -a nearshore play demo-out/bake --screenshot shot.png");
  // The sequence reader names the bake's options when a sequence is unfinished.
  cmd->callback(naming_flags_in_errors({{"BakeOptions::resume", "nearshore bake --resume"}, {"BakeOptions::output_folder", "nearshore bake -o"}},
                                       [o] { play(*o); }));
}

}  // namespace nearshore::tools
