// `nearshore play SEQ`: the command line of the viewer (viewer/, nearshore/viewer/viewer.hpp). Its
// flags become viewer::ViewerOptions; the viewer plays; the command writes the last frame as the
// --screenshot PNG (the plot library's writer, which the runtime-side viewer does not link) and
// prints the run's statistics, as JSON with --json.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "command_support.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/geo_position.hpp"
#include "nearshore/playback/lighting.hpp"
#include "nearshore/plot/plot.hpp"
#include "nearshore/viewer/viewer.hpp"

namespace nearshore::tools {
namespace fs = std::filesystem;
namespace {

// The command line: the viewer's options, and what the command itself does with the run.
struct PlayCommandLine {
  viewer::ViewerOptions viewer;
  fs::path screenshot;                     // headless: the last frame, as PNG
  std::vector<int> size_px = {1280, 720};  // --size WIDTH,HEIGHT (ViewerOptions::size_px)
  bool json = false;                       // the statistics as JSON on stdout
};

// --eye/--target's text is checked before any work, like every number on the command line (CLI11's
// status 105, tests/tools/cli_test.cpp); where it lies on the grid is known only once the sequence
// is read (the viewer's initial camera).
CLI::Validator position_text(const std::string& flag) {
  return CLI::Validator(
      [flag](std::string& text) -> std::string {
        try {
          std::map<std::string, double> extras;
          parse_geo_position(text, flag, {"z_m"}, &extras);
          return {};
        } catch (const Error& e) {
          return e.problem() + "; allowed: each coordinate any finite number";
        }
      },
      "POSITION");
}

nlohmann::json ships_json(const viewer::ViewerRun& run) {
  nlohmann::json ships = nlohmann::json::array();
  for (std::size_t i = 0; i < run.ships.size(); ++i) {
    const viewer::ShipReadout& r = run.ships[i];
    const ships::WakeAngle& wake = run.wake_angles[i];
    ships.push_back({{"name", r.name}, {"x_m", r.x_m}, {"y_m", r.y_m}, {"speed_kn", r.speed_kn},
                     {"heading_deg", r.heading_deg}, {"heel_deg", r.heel_deg}, {"aground", r.aground},
                     {"wake_half_angle_deg", wake.half_angle_deg}, {"wake_stations", wake.stations},
                     {"wake_r_squared", wake.r_squared}, {"wake_wedge", wake.wedge}});
  }
  return ships;
}

nlohmann::json stats_json(const viewer::ViewerRun& run) {
  const runtime::StreamingStats& s = run.stats;
  return {{"frames_drawn", run.frames_drawn},
          {"ships", ships_json(run)},
          {"ship_events", run.ship_events},
          {"ships_ms_per_frame", run.ships_ms_per_frame},
          {"main_thread_ms_per_frame", run.main_thread_ms_per_frame},
          {"wall_s", run.wall_s},
          {"plan", s.plan},
          {"plan_step", s.plan_step},
          {"transitions_taken", s.transitions_taken},
          {"underruns", s.underruns},
          {"bad_frames_held", s.bad_frames_held},
          {"ring_fill", s.ring_fill},
          {"ring_capacity", s.ring_capacity},
          {"decode_frames_per_s", s.decode_frames_per_s()},
          {"decode_real_time_multiple", s.decode_real_time_multiple()},
          {"last_message", s.last_message},
          {"vertices_drawn", run.last_frame.vertices_drawn},
          {"upload_bytes_last_frame", run.last_frame.upload_bytes}};
}

// What a run printed at its end: the JSON summary (--json) or the lines a user reads.
void print_play_results(const PlayCommandLine& c, const viewer::ViewerRun& run) {
  const runtime::StreamingStats& s = run.stats;
  if (c.viewer.quiet) {
  } else if (c.json) {
    std::printf("%s\n", stats_json(run).dump(1).c_str());
  } else {
    std::printf("played %.1f s of display time in %.1f s, %d frames drawn (%.1f fps); %lld underruns, %lld frames held, "
                "%lld transitions\n",
                run.display_time_s - c.viewer.time_s, run.wall_s, run.frames_drawn,
                run.frames_drawn / std::max(run.wall_s, 1e-9), s.underruns, s.bad_frames_held, s.transitions_taken);
    if (!s.last_message.empty()) std::printf("note: %s\n", s.last_message.c_str());
    for (const viewer::ShipReadout& r : run.ships)
      std::printf("ship '%s' at (%.1f, %.1f) m, %.1f kn, heading %03.0f deg, %s\n", r.name.c_str(), r.x_m, r.y_m, r.speed_kn,
                  r.heading_deg, r.aground ? "aground" : "afloat");
  }
}

// The viewer's run, then the picture and the statistics. Returns the one-line description of the
// picture (the demo prints it).
std::string play(const PlayCommandLine& c) {
  viewer::ViewerOptions o = c.viewer;
  o.size_px = {c.size_px[0], c.size_px[1]};
  o.keep_last_picture = !c.screenshot.empty();
  const viewer::ViewerRun run = viewer::run_viewer(o);
  const int width = o.size_px[0], height = o.size_px[1];
  const std::string summary = fmt::format("{} ({} x {}, t = {:.2f} s, {} grid, {}; {})", c.screenshot.string(), width,
                                          height, run.display_time_s, o.grid, run.stats.plan, run.gl_description);
  if (!c.screenshot.empty()) {
    write_png(*run.last_picture, c.screenshot);
    if (!o.quiet)  // stderr under --json: stdout is the JSON alone
      std::fprintf(c.json ? stderr : stdout, "screenshot: %s (%d x %d, t = %.2f s, %s grid)\n", c.screenshot.c_str(),
                   width, height, run.display_time_s, o.grid.c_str());
  }
  print_play_results(c, run);
  return summary;
}

}  // namespace

std::string write_playback_screenshot(const fs::path& sequence_folder, const fs::path& png, int width_px, int height_px) {
  PlayCommandLine c;
  c.viewer.sequence_folder = sequence_folder;
  c.screenshot = png;
  c.size_px = {width_px, height_px};
  c.viewer.frames = 15;  // half a second of display: the streaming engine and the renderer's first uploads settle
  c.viewer.quiet = true;
  return play(c);
}

void add_play_command(CLI::App& app) {
  auto o = std::make_shared<PlayCommandLine>();
  viewer::ViewerOptions& v = o->viewer;
  CLI::App* cmd = app.add_subcommand("play", "Play a baked sequence inside the endless sea (window, or headless screenshot)");
  cmd->add_option("sequence", v.sequence_folder, "Baked sequence folder (`nearshore bake`), or a sea-state library (`nearshore library`)")
      ->required();
  cmd->add_option("--grid", v.grid, "Surface grid: radial, quadtree or projected (Earth curvature, for high views)")
      ->capture_default_str()
      ->check(CLI::IsMember({"radial", "quadtree", "projected"}));
  cmd->add_option("--plan", v.plan, "Playback plan: auto (the period, else the planned loop), period, loop, random, order")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "period", "loop", "random", "order"}));
  cmd->add_option("--seed", v.seed, "Random-walk seed (default: the one loops.json records)");
  cmd->add_option("--deep-water", v.deep_water, "Sea beyond the harbour: auto (the bake's own, else Beaufort), beaufort, none")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "beaufort", "none"}));
  cmd->add_option("--beaufort", v.beaufort_force, "Beaufort force of the deep water when it is not the bake's own")
      ->capture_default_str()
      ->check(number_in(at_least(0), at_most(12)));
  cmd->add_option("--wind-from", v.wind_from_deg, "Compass bearing the wind blows from, degrees")
      ->capture_default_str()
      ->check(number_in(at_least(-360), at_most(360)));
  cmd->add_option("--time", v.time_s, "Display time of the first frame, seconds")
      ->capture_default_str()
      ->check(number_in(at_least(0), at_most(1e9)));
  cmd->add_option("--time-scale", v.time_scale, "Playback speed (1 = real time)")
      ->capture_default_str()
      ->check(number_in(at_least(0), at_most(16)));
  cmd->add_option("--eye", v.eye, "Camera position: X,Y,Z in metres from the grid's south-west corner (z up), or "
                                   "lat=..,lon=..,z_m=.. or easting_m=..,northing_m=..,z_m=.. in the grid's CRS (default: overview)")
      ->check(position_text("--eye"));
  cmd->add_option("--target", v.target, "Point looked at: X,Y[,Z] from the grid's south-west corner, or lat=..,lon=.. or "
                                         "easting_m=..,northing_m=.. (z_m=.. optional, default 0)")
      ->check(position_text("--target"));
  cmd->add_option("--eye-lat-lon", v.eye_lat_lon, "Camera at LAT,LON,HEIGHT (WGS 84 degrees, metres above the sea)")
      ->delimiter(',')->expected(3)->check(finite_number());
  cmd->add_option("--target-lat-lon", v.target_lat_lon, "Look at LAT,LON (WGS 84 degrees) on the sea")
      ->delimiter(',')->expected(2)->check(finite_number());
  CLI::Option* sun_azimuth = cmd->add_option("--sun-azimuth", v.sun_azimuth_deg, "Sun bearing, degrees from north")
      ->capture_default_str()
      ->check(number_in(at_least(-360), at_most(360)));
  CLI::Option* sun_elevation = cmd->add_option("--sun-elevation", v.sun_elevation_deg, "Sun height above the horizon, degrees")
      ->capture_default_str()
      ->check(number_in(at_least(-90), at_most(90)));
  cmd->add_option("--utc", v.utc, "Put the sun where it stands at this UTC time over the site, e.g. 2026-06-21T04:00:00Z")
      ->excludes(sun_azimuth)->excludes(sun_elevation);
  cmd->add_option("--lat-lon", v.lat_lon, "Place the --utc sun is seen from, LAT,LON (default: the site's own centre)")
      ->delimiter(',')->expected(2)->check(finite_number());
  std::string weather_names;
  for (const playback::WeatherPreset& preset : playback::weather_presets())
    weather_names += (weather_names.empty() ? "" : ", ") + preset.name + " (" + preset.description + ")";
  std::vector<std::string> weather_choices;
  for (const playback::WeatherPreset& preset : playback::weather_presets()) weather_choices.push_back(preset.name);
  cmd->add_option("--weather", v.weather, "Sky and air: " + weather_names)
      ->check(CLI::IsMember(weather_choices))->capture_default_str();
  cmd->add_option("--visibility", v.visibility_m, "Meteorological optical range, metres (fog < 1000, mist 1000-5000; 0 unlimited; default: the weather's)")
      ->check(number_in(at_least(0), at_most(1e6)));
  cmd->add_option("--cloud-cover", v.cloud_cover, "Cloud cover 0..1 (1: CIE overcast sky, sun hidden; default: the weather's)")
      ->check(number_in(at_least(0), at_most(1)));
  cmd->add_option("--haze", v.haze, "Atmospheric turbidity (Preetham's T): 2 very clear, 3 clear, 6 hazy, 10 thin fog (default: the weather's: 2.5 clear, 6 hazy, 4 overcast)")
      ->check(number_in(at_least(1.7), at_most(10)));
  cmd->add_option("--turbidity", v.turbidity_ntu, "Water turbidity from suspended sediment, NTU (0 clear ocean, 10 a muddy harbour)")
      ->check(number_in(at_least(0), at_most(200)))->capture_default_str();
  cmd->add_option("--chlorophyll", v.chlorophyll_mg_m3, "Chlorophyll, mg/m3 (0.05 open ocean, 1 coastal, 10 a bloom)")
      ->check(number_in(at_least(0), at_most(100)))->capture_default_str();
  cmd->add_option("--cdom", v.cdom_per_m, "Absorption of dissolved organic matter at 440 nm, 1/m (default: from the chlorophyll)")
      ->check(number_in(at_least(0), at_most(20)));
  cmd->add_option("--exposure", v.exposure, "Exposure compensation, a factor on the automatic exposure")
      ->check(number_in(at_least(0.01), at_most(100)))->capture_default_str();
  cmd->add_option("--detail-parallax", v.detail_parallax,
                  "Parallax of the detail normals at grazing views (seed 004 eq. 5): 1 on, 0 off")
      ->check(number_in(at_least(0), at_most(4)))->capture_default_str();
  cmd->add_option("--foam-decay", v.foam_decay_s, "Seconds over which the deep water's foam fades by 1/e (0: no lasting foam)")
      ->check(number_in(at_least(0), at_most(60)))->capture_default_str();
  cmd->add_option("--structure-foam", v.structure_foam_onset_m_s,
                  "Speed of the water along a breakwater's or quay's face (m/s) from which it foams (air entrainment; 0: no foam there)")
      ->check(number_in(at_least(0), at_most(100)))->capture_default_str();
  cmd->add_option("--lighting", v.lighting_mode, "full (docs/lighting.md) or off (a flat sea, no sky: the cost baseline)")
      ->check(CLI::IsMember({"full", "off"}))->capture_default_str();
  cmd->add_option("--msaa", v.msaa_samples, "Anti-aliasing: samples per pixel (1: off; more than the GPU offers: its most; 0: 4 on a GPU, 1 on a software renderer such as llvmpipe)")
      ->check(number_in(at_least(0), at_most(32)))->capture_default_str();
  cmd->add_option("--refraction", v.refraction, "What lies under the water seen through it (screen-space refraction): on, or off (the sea opaque over it)")
      ->check(CLI::IsMember({"on", "off"}))->capture_default_str();
  cmd->add_option("--frames", v.frames, "Headless: draw this many frames at 30 fps display time, then exit")
      ->check(number_in(at_least(1), at_most(1e6)));
  cmd->add_option("--screenshot", o->screenshot, "Headless: write the last frame to this PNG (hidden window)");
  cmd->add_option("--size", o->size_px, "Window or picture size WIDTH,HEIGHT in pixels")
      ->delimiter(',')->expected(2)->capture_default_str()
      ->check(number_in(at_least(16), at_most(8192)));
  cmd->add_flag("--panel", v.panel, "Headless: draw the on-screen panel into the screenshot too");
  cmd->add_option("--seconds", v.seconds, "Window: close after this many seconds (0: when closed)")
      ->check(number_in(at_least(0), at_most(1e9)));
  cmd->add_flag("--json", o->json, "Print the streaming statistics as JSON when done");
  cmd->add_option("--state", v.state, "Sea-state library (a folder with library.json): the conditions to start with, "
                                       "KEY=VALUE,... (e.g. wind_direction_deg=0,tide_m=0.5); default: the first state");
  cmd->add_option("--switch", v.switches, "Sea-state library: at display time T, crossfade to the state nearest the "
                                           "conditions, T:KEY=VALUE,... (repeatable)");
  cmd->add_option("--crossfade", v.crossfade_s, "Sea-state library: length of a switch's crossfade, seconds of display time")
      ->capture_default_str()
      ->check(number_in(at_least(0), at_most(3600)));
  cmd->add_option("--ships", v.ships_scenario, "Ships to sail on the sea: a scenario file (TOML, docs/ships.md); the "
                                                "arrow keys steer ship 0 in the window, Enter centres its rudder");
  cmd->add_option("--follow-ship", v.follow_ship, "Move the camera with this ship of --ships (index from 0)")
      ->check(number_in(at_least(0), at_most(1e6)));
  set_example(*cmd, "xvfb-run -a nearshore play demo-out/bake --frames 30 --screenshot shot.png --grid radial");
  // The sequence reader names the bake's options when a sequence is unfinished; the engine names
  // its own parameters.
  cmd->callback(naming_flags_in_errors({{"BakeOptions::resume", "nearshore bake --resume"},
                                        {"BakeOptions::output_folder", "nearshore bake -o"},
                                        {"StreamingOptions::seed", "--seed"},
                                        {"BeaufortSea::force", "--beaufort"}},
                                       [o] { play(*o); }));
}

}  // namespace nearshore::tools
