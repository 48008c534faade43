// `nearshore play SEQ`: the runtime a simulator embeds, as a viewer. The streaming engine
// (runtime/) plays the bake by its plan inside the endless deep water; the renderer (playback/)
// draws it on the chosen grid; Dear ImGui shows the streaming state (tools/viewer_panel.hpp).
// Headless (--frames N --screenshot out.png) it draws N frames on a fixed 30 fps clock, waiting
// for each frame's keyframes so identical inputs give identical pictures. With --ships a scenario's
// ships sail on the shown sea (tools/viewer_ships.hpp), stepped on the same display clock, so a
// headless run with the scenario's orders is a script too; the arrow keys steer ship 0.
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "command_support.hpp"
#include "nearshore/bathymetry/geo_position.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/map_projection.hpp"
#include "nearshore/ocean/sea_state_beaufort.hpp"
#include "nearshore/ocean/whitecap_coverage.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/plot/plot.hpp"
#include "nearshore/runtime/library_player.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "viewer_panel.hpp"
#include "viewer_ships.hpp"

namespace nearshore::tools {
namespace fs = std::filesystem;
namespace {

struct PlayOptions {
  fs::path sequence_folder;
  fs::path screenshot;
  std::string grid = "quadtree", plan = "auto", deep_water = "auto";
  std::optional<std::uint64_t> seed;
  double time_s = 0, time_scale = 1.0, seconds = 0;
  int frames = 0;
  std::vector<int> size_px = {1280, 720};
  std::string eye, target;  // bathymetry/geo_position.hpp's text form, plus z_m
  std::vector<double> eye_lat_lon, target_lat_lon;
  int beaufort_force = 3;
  double wind_from_deg = 225;
  double sun_azimuth_deg = 200, sun_elevation_deg = 35;
  // Lighting (docs/lighting.md): the sun from a UTC time at the site (or --lat-lon), the air, the water.
  std::string utc;
  std::vector<double> lat_lon;
  std::string weather = "clear";
  double visibility_m = -1, cloud_cover = -1;  // < 0: the weather's
  double haze = -1, turbidity_ntu = 0.5, chlorophyll_mg_m3 = 0.3, cdom_per_m = -1, exposure = 1.0;
  std::string lighting_mode = "full";
  double detail_parallax = 1.0, foam_decay_s = 3.0;
  int msaa_samples = 0;  // RendererSettings::msaa_samples (0: automatic)
  bool panel = false, json = false, quiet = false;
  // A sea-state library (a folder with library.json): the state to start with, and scripted
  // switches "TIME:KEY=VALUE,..." crossfaded over crossfade_s.
  std::string state;
  std::vector<std::string> switches;
  double crossfade_s = 5.0;
  // Ships (docs/ships.md): a scenario file; the camera may follow one of its ships.
  fs::path ships_scenario;
  int follow_ship = -1;
};

const char* const kPlanNames[] = {"auto", "period", "loop", "random", "order"};

runtime::PlanKind plan_kind_of(const std::string& name) {
  if (name == "auto") return runtime::PlanKind::kOptimalLoop;  // the period of a periodic bake, else the planned loop
  if (const auto kind = runtime::parse_plan_kind(name)) return *kind;
  throw Error("--plan " + name, "is not a plan", "use auto, period, loop, random or order");
}

using ocean::travel_direction_rad;  // compass "from" bearing -> travel direction

runtime::StreamingOptions streaming_options(const PlayOptions& o, const std::string& plan) {
  runtime::StreamingOptions options;
  options.plan = plan_kind_of(plan);
  options.seed = o.seed;
  options.beaufort.force = o.beaufort_force;
  options.beaufort.wind_direction_rad = travel_direction_rad(o.wind_from_deg);
  options.deep_water = o.deep_water == "beaufort" ? runtime::DeepWaterChoice::kBeaufort
                       : o.deep_water == "none"   ? runtime::DeepWaterChoice::kNone
                                                  : runtime::DeepWaterChoice::kBakeElseBeaufort;
  return options;
}

// Positions: site metres (from the grid's south-west corner), or latitude/longitude through the
// grid's own projection.
struct SiteFrame {
  GridGeometry geometry;
  std::optional<MapProjection> projection;

  std::array<double, 2> from_lat_lon(double latitude_deg, double longitude_deg, const std::string& flag) const {
    if (!projection)
      throw Error(flag, "gives a latitude/longitude but this bake's grid has no map projection (local metres)",
                  "give the position in metres from the grid's south-west corner instead");
    if (!(std::abs(latitude_deg) <= 90) || !(std::abs(longitude_deg) <= 360))
      throw Error(flag, fmt::format("{}, {} is not a latitude, longitude in degrees", latitude_deg, longitude_deg),
                  "give LAT,LON (WGS 84 degrees), e.g. 38.865,121.708");
    const ProjectedPoint p = projection->forward({longitude_deg, latitude_deg});
    return {p.x_m - geometry.origin_x_m, p.y_m - geometry.origin_y_m};
  }
  LonLat lat_lon_of(double x_m, double y_m) const {
    return projection ? projection->reverse({geometry.origin_x_m + x_m, geometry.origin_y_m + y_m}) : LonLat{};
  }
};

// --eye/--target's text is checked before any work, like every number on the command line (CLI11's
// status 105, tests/tools/cli_test.cpp); where it lies on the grid is known only once the sequence
// is read (initial_camera).
CLI::Validator position_text(const std::string& flag) {
  return CLI::Validator(
      [flag](std::string& text) -> std::string {
        try {
          std::map<std::string, double> extras;
          bathymetry::parse_geo_position(text, flag, {"z_m"}, &extras);
          return {};
        } catch (const Error& e) {
          return e.problem() + "; allowed: each coordinate any finite number";
        }
      },
      "POSITION");
}

playback::Camera initial_camera(const PlayOptions& o, const runtime::HarbourSite& site, const SiteFrame& frame) {
  playback::Camera camera = playback::Camera::overlooking_site(site.width_m, site.height_m);
  // --eye/--target: metres from the south-west corner, the grid's CRS or lat/lon, through the one
  // position parser (bathymetry/geo_position.hpp); z_m is the height above still water.
  const auto site_point = [&](const std::string& text, const std::string& flag, std::optional<double> default_z_m) {
    std::map<std::string, double> extras;
    const bathymetry::GeoPosition position = bathymetry::parse_geo_position(text, flag, {"z_m"}, &extras);
    if (!extras.count("z_m") && !default_z_m)
      throw Error(flag + " " + text, "has no height", "add z_m, the height above still water in metres: X,Y,Z or ...,z_m=30");
    const ProjectedPoint p = bathymetry::place_in_grid(position, frame.geometry, flag, "the camera", false);
    if (auto warning = bathymetry::land_warning(site.harbour, p, flag, flag == "--eye" ? "the camera" : "the point looked at"))
      std::fprintf(stderr, "warning: %s\n", warning->c_str());
    return std::array<double, 3>{p.x_m - frame.geometry.origin_x_m, p.y_m - frame.geometry.origin_y_m,
                                 extras.count("z_m") ? extras["z_m"] : *default_z_m};
  };
  if (!o.eye.empty()) camera.eye_m = site_point(o.eye, "--eye", std::nullopt);
  if (!o.target.empty()) camera.target_m = site_point(o.target, "--target", 0.0);
  if (!o.eye_lat_lon.empty()) {
    const auto xy = frame.from_lat_lon(o.eye_lat_lon[0], o.eye_lat_lon[1], "--eye-lat-lon");
    camera.eye_m = {xy[0], xy[1], o.eye_lat_lon[2]};
  }
  if (!o.target_lat_lon.empty()) {
    const auto xy = frame.from_lat_lon(o.target_lat_lon[0], o.target_lat_lon[1], "--target-lat-lon");
    camera.target_m = {xy[0], xy[1], 0.0};
  }
  if (camera.eye_m == camera.target_m)
    throw Error(fmt::format("--eye {},{},{}", camera.eye_m[0], camera.eye_m[1], camera.eye_m[2]),
                "is the point the camera looks at, so it looks in no direction", "give --target a point away from the eye");
  return camera;
}

// Mouse and keyboard camera: drag to orbit the target, scroll to move in and out, W/A/S/D to move
// over the sea, Q/E down and up, 1/2/3 for the grids, space to pause.
struct CameraControl {
  playback::Camera camera;
  double last_x = 0, last_y = 0, scroll = 0;
  bool dragging = false;

  void update(GLFWwindow* window, double dt_s, bool panel_has_input) {
    double x = 0, y = 0;
    glfwGetCursorPos(window, &x, &y);
    const bool pressed = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && !panel_has_input;
    std::array<double, 3> offset = {camera.eye_m[0] - camera.target_m[0], camera.eye_m[1] - camera.target_m[1],
                                    camera.eye_m[2] - camera.target_m[2]};
    double distance = std::max(std::hypot(offset[0], offset[1], offset[2]), 1.0);
    double azimuth = std::atan2(offset[1], offset[0]);
    double elevation = std::asin(std::clamp(offset[2] / distance, -1.0, 1.0));
    if (pressed && dragging) {
      azimuth -= 0.005 * (x - last_x);
      elevation = std::clamp(elevation + 0.005 * (y - last_y), 0.02, 1.5);
    }
    dragging = pressed;
    last_x = x, last_y = y;
    distance = std::clamp(distance * std::pow(0.9, scroll), 5.0, 2.0e6);
    scroll = 0;
    const double speed = 0.5 * distance * dt_s;  // half the viewing distance per second
    const double forward_x = -std::cos(azimuth), forward_y = -std::sin(azimuth);
    auto key = [&](int k) { return !panel_has_input && glfwGetKey(window, k) == GLFW_PRESS ? 1.0 : 0.0; };
    const double ahead = key(GLFW_KEY_W) - key(GLFW_KEY_S), aside = key(GLFW_KEY_D) - key(GLFW_KEY_A);
    camera.target_m[0] += speed * (ahead * forward_x + aside * forward_y);
    camera.target_m[1] += speed * (ahead * forward_y - aside * forward_x);
    camera.target_m[2] += speed * (key(GLFW_KEY_E) - key(GLFW_KEY_Q));
    camera.eye_m = {camera.target_m[0] + distance * std::cos(elevation) * std::cos(azimuth),
                    camera.target_m[1] + distance * std::cos(elevation) * std::sin(azimuth),
                    camera.target_m[2] + distance * std::sin(elevation)};
  }
};

CameraControl* g_camera_control = nullptr;  // GLFW's scroll callback has no user pointer of ours
void on_scroll(GLFWwindow*, double, double y_offset) {
  if (g_camera_control) g_camera_control->scroll += y_offset;
}

// Where each ship is at the end, and what the fleet cost.
struct ShipsSummary {
  std::vector<ShipReadout> ships;
  std::vector<ships::WakeAngle> wake_angles;
  int events = 0;
  double step_ms_mean = 0.0, main_thread_ms_mean = 0.0;
};

nlohmann::json ships_json(const ShipsSummary& summary) {
  nlohmann::json ships = nlohmann::json::array();
  for (std::size_t i = 0; i < summary.ships.size(); ++i) {
    const ShipReadout& r = summary.ships[i];
    const ships::WakeAngle& wake = summary.wake_angles[i];
    ships.push_back({{"name", r.name}, {"x_m", r.x_m}, {"y_m", r.y_m}, {"speed_kn", r.speed_kn},
                     {"heading_deg", r.heading_deg}, {"heel_deg", r.heel_deg}, {"aground", r.aground},
                     {"wake_half_angle_deg", wake.half_angle_deg}, {"wake_stations", wake.stations},
                     {"wake_r_squared", wake.r_squared}, {"wake_wedge", wake.wedge}});
  }
  return ships;
}

nlohmann::json stats_json(const runtime::StreamingStats& s, const playback::FrameStatistics& frame, int frames_drawn,
                          double wall_s, const ShipsSummary& ships) {
  return {{"frames_drawn", frames_drawn},
          {"ships", ships_json(ships)},
          {"ship_events", ships.events},
          {"ships_ms_per_frame", ships.step_ms_mean},
          {"main_thread_ms_per_frame", ships.main_thread_ms_mean},
          {"wall_s", wall_s},
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
          {"vertices_drawn", frame.vertices_drawn},
          {"upload_bytes_last_frame", frame.upload_bytes}};
}

runtime::PlayedSea open_sea(const PlayOptions& o, const std::string& plan) {
  return runtime::PlayedSea(o.sequence_folder, sequence::parse_sea_conditions(o.state, "--state " + o.state),
                            streaming_options(o, plan));
}

// "2.5:wind_direction_deg=30" -> (2.5 s, the conditions).
std::pair<double, sequence::SeaConditions> parse_switch(const std::string& text) {
  const auto colon = text.find(':');
  double at_s = -1;
  try {
    at_s = colon == std::string::npos ? -1 : std::stod(text.substr(0, colon));
  } catch (const std::exception&) {
  }
  if (!(at_s >= 0))
    throw Error("--switch " + text, "is not TIME:KEY=VALUE,...", "give e.g. --switch 2:wind_direction_deg=30");
  return {at_s, sequence::parse_sea_conditions(text.substr(colon + 1), "--switch " + text)};
}

// The lighting of the flags: the sun where it stands over the site (its own latitude/longitude
// through the grid's projection, or --lat-lon) at --utc, else --sun-azimuth/--sun-elevation; the
// wind of the deep water (its sub-grid roughness from the bake's spectrum when the bake carries
// the deep water, else Cox & Munk's for the Beaufort wind); what is in the air and the water.
playback::Lighting scene_lighting(const PlayOptions& o, const runtime::StreamingEngine& engine,
                                  const runtime::HarbourSite& site, const SiteFrame& frame) {
  playback::Lighting lighting;
  lighting.sun_azimuth_deg = o.sun_azimuth_deg;
  lighting.sun_elevation_deg = o.sun_elevation_deg;
  if (!o.utc.empty()) {
    const playback::UtcTime time = playback::UtcTime::parse(o.utc);
    LonLat place;
    if (!o.lat_lon.empty()) {
      place = {o.lat_lon[1], o.lat_lon[0]};
    } else if (frame.projection) {
      place = frame.lat_lon_of(0.5 * site.width_m, 0.5 * site.height_m);
    } else {
      throw Error("--utc " + o.utc, "needs a place, and this bake's grid has no map projection (local metres)",
                  "give the place with --lat-lon LAT,LON");
    }
    lighting.set_sun_for(place.latitude_deg, place.longitude_deg, time);
  }
  playback::apply_weather(lighting, o.weather);
  if (o.haze > 0) lighting.atmospheric_turbidity = o.haze;
  if (o.visibility_m >= 0) lighting.visibility_m = o.visibility_m;
  if (o.cloud_cover >= 0) lighting.cloud_cover = o.cloud_cover;
  lighting.water.turbidity_ntu = o.turbidity_ntu;
  lighting.water.chlorophyll_mg_m3 = o.chlorophyll_mg_m3;
  lighting.water.cdom_absorption_440_per_m = o.cdom_per_m;
  lighting.exposure_compensation = o.exposure;
  lighting.detail_parallax = o.detail_parallax;
  lighting.foam_decay_time_s = o.foam_decay_s;
  lighting.wind_direction_rad = travel_direction_rad(o.wind_from_deg);
  lighting.wind_speed_m_s = ocean::beaufort_preset(o.beaufort_force).wind_speed_10_m_s;
  const auto& deep = engine.manifest().deep_water;
  if (engine.deep_water_is_bakes() && deep && deep->unresolved_slope_variance > 0.0)
    lighting.sub_grid_slope_variance = deep->unresolved_slope_variance;
  return lighting;
}

// The panel's figures before the first frame: the options, the sea and the lighting as opened.
ViewerPanelModel panel_model_at_start(const PlayOptions& o, const std::string& plan, const playback::RendererSettings& settings,
                                      runtime::PlayedSea& sea, const playback::GlWindow& window, const playback::Lighting& lighting,
                                      const SiteFrame& frame, const CameraControl& control) {
  ViewerPanelModel model;
  model.grid = static_cast<int>(settings.grid);
  model.plan = static_cast<int>(std::find(std::begin(kPlanNames), std::end(kPlanNames), plan) - std::begin(kPlanNames));
  model.time_scale = o.time_scale;
  model.beaufort_force = o.beaufort_force;
  model.wind_from_deg = o.wind_from_deg;
  model.deep_water_from_bake = sea.engine().deep_water_is_bakes();
  model.gl_description = window.gl_description();
  model.sun_azimuth_deg = lighting.sun_azimuth_deg, model.sun_elevation_deg = lighting.sun_elevation_deg;
  model.haze = lighting.atmospheric_turbidity, model.turbidity_ntu = lighting.water.turbidity_ntu;
  model.chlorophyll_mg_m3 = lighting.water.chlorophyll_mg_m3, model.exposure = lighting.exposure_compensation;
  const LonLat looked_at = frame.lat_lon_of(control.camera.target_m[0], control.camera.target_m[1]);
  model.jump_lat_lon_deg = {looked_at.latitude_deg, looked_at.longitude_deg};
  return model;
}

// One step of the fleet over `ship_dt_s`: ship 0 steered from the arrow keys of `keys_window`
// (null: no keys), the events said, the camera carried along with --follow-ship.
void step_fleet(ViewerShips& ships, runtime::PlayedSea& sea, const PlayOptions& o, GLFWwindow* keys_window, double display_time_s,
                double ship_dt_s, CameraControl& control, ShipsSummary& ships_summary) {
  if (keys_window != nullptr) {
    auto key = [&](int k) { return glfwGetKey(keys_window, k) == GLFW_PRESS ? 1 : 0; };
    ships.steer_first_ship(key(GLFW_KEY_UP) - key(GLFW_KEY_DOWN), key(GLFW_KEY_LEFT) - key(GLFW_KEY_RIGHT),
                           key(GLFW_KEY_ENTER) != 0, ship_dt_s);
  }
  const Eigen::Vector3d before = o.follow_ship >= 0 ? ships.fleet().ship(std::size_t(o.follow_ship)).body().state().position_m
                                                    : Eigen::Vector3d::Zero();
  ships.step(sea.snapshot(), ship_dt_s);
  for (const std::string& event : ships.take_events()) {
    ++ships_summary.events;
    if (!o.quiet) std::fprintf(stderr, "t = %.2f s: %s\n", display_time_s, event.c_str());
  }
  if (o.follow_ship >= 0) {  // the camera moves with the ship, keeping its view of it
    const Eigen::Vector3d moved = ships.fleet().ship(std::size_t(o.follow_ship)).body().state().position_m - before;
    for (int axis = 0; axis < 2; ++axis) control.camera.eye_m[axis] += moved[axis], control.camera.target_m[axis] += moved[axis];
  }
}

// The panel: this frame's figures in, then what the user changed on it applied (grid, plan, wind,
// lighting, a jump to a position).
void show_panel(ViewerPanel& panel, ViewerPanelModel& model, const PlayOptions& o, double dt_s, double main_ms, double display_time_s,
                const ViewerShips* ships, const SiteFrame& frame, std::string& plan, runtime::PlayedSea& sea,
                playback::WaterRenderer& renderer, playback::Lighting& lighting, CameraControl& control) {
  const runtime::StreamingStats s = sea.engine().stats();
  model.frames_per_s = dt_s > 0 ? 1.0 / dt_s : 0.0;
  model.frame_time_ms = 1e3 * dt_s;
  model.main_thread_ms = main_ms;
  model.display_time_s = display_time_s;
  model.ring_filled = s.ring_fill, model.ring_capacity = s.ring_capacity;
  model.underruns = static_cast<unsigned long long>(s.underruns);
  model.bad_frames_held = static_cast<unsigned long long>(s.bad_frames_held);
  model.transitions_taken = static_cast<unsigned long long>(s.transitions_taken);
  model.decode_real_time_multiple = s.decode_real_time_multiple();
  model.plan_step = s.plan_step;
  model.crossfading = s.in_crossfade;
  model.plan_name = sea.library() ? fmt::format("sea state {} (crossfade {:.0f} %): {}", sea.library()->state_id(),
                                              100.0 * sea.library()->crossfade_weight(), s.plan)
                                : s.plan;
  model.message = s.last_message;
  const LonLat place = frame.lat_lon_of(control.camera.eye_m[0], control.camera.eye_m[1]);
  model.camera_latitude_deg = place.latitude_deg, model.camera_longitude_deg = place.longitude_deg;
  model.camera_height_m = control.camera.eye_m[2];
  if (ships) model.ships = ships->readouts(), model.ships_ms = ships->last_step_ms();
  const ViewerPanelModel before = model;
  if (panel.draw(model)) {
    if (model.grid != before.grid) renderer.settings().grid = static_cast<playback::GridKind>(model.grid);
    if (model.plan != before.plan) {  // a new plan restarts the stream on it, at the same time
      plan = kPlanNames[model.plan];
      sea = open_sea(o, plan);
    }
    if (!model.deep_water_from_bake &&
        (model.beaufort_force != before.beaufort_force || model.wind_from_deg != before.wind_from_deg)) {
      runtime::BeaufortSea beaufort;
      beaufort.force = model.beaufort_force;
      beaufort.wind_direction_rad = travel_direction_rad(model.wind_from_deg);
      sea.engine().set_beaufort(beaufort);
    }
    lighting.sun_azimuth_deg = model.sun_azimuth_deg, lighting.sun_elevation_deg = model.sun_elevation_deg;
    lighting.atmospheric_turbidity = model.haze, lighting.water.turbidity_ntu = model.turbidity_ntu;
    lighting.water.chlorophyll_mg_m3 = model.chlorophyll_mg_m3, lighting.exposure_compensation = model.exposure;
    if (model.beaufort_force != before.beaufort_force || model.wind_from_deg != before.wind_from_deg) {
      lighting.wind_direction_rad = travel_direction_rad(model.wind_from_deg);
      lighting.wind_speed_m_s = ocean::beaufort_preset(model.beaufort_force).wind_speed_10_m_s;
    }
    if (model.jump_requested) {
      model.jump_requested = false;
      const auto xy = frame.from_lat_lon(model.jump_lat_lon_deg[0], model.jump_lat_lon_deg[1], "the panel's position");
      control.camera.eye_m = {xy[0] - 0.5 * control.camera.eye_m[2], xy[1] - 0.5 * control.camera.eye_m[2],
                              control.camera.eye_m[2]};
      control.camera.target_m = {xy[0], xy[1], 0.0};
    }
  }
}

// What a run printed at its end: the JSON summary (--json) or the lines a user reads.
void print_play_results(const PlayOptions& o, const runtime::StreamingStats& s, const playback::WaterRenderer& renderer, int frames_drawn,
                        double wall_s, double display_time_s, const ShipsSummary& ships_summary) {
  if (o.quiet) {
  } else if (o.json) {
    std::printf("%s\n", stats_json(s, renderer.last_frame(), frames_drawn, wall_s, ships_summary).dump(1).c_str());
  } else {
    std::printf("played %.1f s of display time in %.1f s, %d frames drawn (%.1f fps); %lld underruns, %lld frames held, "
                "%lld transitions\n",
                display_time_s - o.time_s, wall_s, frames_drawn, frames_drawn / std::max(wall_s, 1e-9), s.underruns,
                s.bad_frames_held, s.transitions_taken);
    if (!s.last_message.empty()) std::printf("note: %s\n", s.last_message.c_str());
    for (const ShipReadout& r : ships_summary.ships)
      std::printf("ship '%s' at (%.1f, %.1f) m, %.1f kn, heading %03.0f deg, %s\n", r.name.c_str(), r.x_m, r.y_m, r.speed_kn,
                  r.heading_deg, r.aground ? "aground" : "afloat");
  }
}

std::string play(const PlayOptions& o) {
  const bool headless = !o.screenshot.empty() || o.frames > 0;
  std::string plan = o.plan;
  runtime::PlayedSea sea = open_sea(o, plan);
  std::vector<std::pair<double, sequence::SeaConditions>> switches;
  for (const std::string& text : o.switches) switches.push_back(parse_switch(text));
  if (!switches.empty() && !sea.library())
    throw Error("--switch", "switches between the states of a sea-state library, and " + o.sequence_folder.string() +
                                " is one sequence (no library.json)", "give the output folder of `nearshore library`");
  std::size_t next_switch = 0;
  const std::shared_ptr<const runtime::HarbourSite> site = sea.engine().site();
  SiteFrame frame{sea.engine().manifest().geometry, std::nullopt};
  if (frame.geometry.projection.is_object() && !frame.geometry.projection.empty())
    frame.projection = MapProjection::from_json(frame.geometry.projection, (o.sequence_folder / "manifest.json").string());
  CameraControl control{initial_camera(o, *site, frame)};  // before a window opens: it may refuse a position
  std::unique_ptr<ViewerShips> ships;  // before a window opens too: a bad scenario is said at once
  if (!o.ships_scenario.empty()) ships = std::make_unique<ViewerShips>(o.ships_scenario, site);
  if (o.follow_ship >= 0 && (!ships || std::size_t(o.follow_ship) >= ships->fleet().size()))
    throw Error("--follow-ship " + std::to_string(o.follow_ship),
                ships ? "is not a ship of " + o.ships_scenario.string() + " (it has " + std::to_string(ships->fleet().size()) + ")"
                      : "needs ships to follow",
                ships ? "give an index from 0" : "give a scenario with --ships");
  const int width = o.size_px[0], height = o.size_px[1];
  playback::GlWindow window(width, height, "nearshore play " + o.sequence_folder.string(), !headless);
  playback::RendererSettings settings;
  settings.grid = playback::grid_kind_from_name(o.grid);
  settings.msaa_samples = o.msaa_samples;
  playback::WaterRenderer renderer(settings);
  std::unique_ptr<ViewerPanel> panel;
  if (!headless || o.panel) panel = std::make_unique<ViewerPanel>(window.glfw_window());
  g_camera_control = &control;
  if (!headless) glfwSetScrollCallback(window.glfw_window(), on_scroll);  // before ImGui, which chains it

  playback::Lighting lighting = scene_lighting(o, sea.engine(), *site, frame);
  ocean::WhitecapFoamOnset whitecaps;
  playback::DrawOptions draw_options;
  if (o.lighting_mode == "off") {  // the cheapest picture: flat-coloured sea, no sky (bench baseline)
    draw_options.colouring = playback::SurfaceColouring::flat;
    draw_options.flat_colour = {0.05f, 0.25f, 0.35f};
    draw_options.sky = false;
    draw_options.background = {0.6f, 0.7f, 0.8f};
  }
  ViewerPanelModel model = panel_model_at_start(o, plan, settings, sea, window, lighting, frame, control);
  if (!o.quiet) {
    std::fprintf(stderr, "OpenGL %s\nplaying %s%s; %s\n", window.gl_description().c_str(),
                 sea.library() ? ("sea state " + sea.library()->state_id() + ": ").c_str() : "",
                 sea.engine().stats().plan.c_str(), sea.engine().memory_summary().c_str());
    if (!sea.engine().stats().last_message.empty())
      std::fprintf(stderr, "note: %s\n", sea.engine().stats().last_message.c_str());
  }

  const auto start = std::chrono::steady_clock::now();
  auto previous = start;
  double display_time_s = o.time_s;
  int frames_drawn = 0;
  double wall_s = 0;
  double ships_time_s = display_time_s;  // the display time the fleet has reached
  ShipsSummary ships_summary;
  double ships_ms_sum = 0, main_ms_sum = 0;
  for (;;) {
    const auto now = std::chrono::steady_clock::now();
    const double dt_s = std::chrono::duration<double>(now - previous).count();
    previous = now;
    wall_s = std::chrono::duration<double>(now - start).count();
    if (headless ? frames_drawn >= std::max(o.frames, 1) : (window.should_close() || (o.seconds > 0 && wall_s >= o.seconds)))
      break;
    if (headless) {
      display_time_s = o.time_s + frames_drawn / 30.0;
      sea.wait_until_ready(display_time_s, std::chrono::seconds(30));  // exact pictures, not real time
    } else if (!model.paused) {
      display_time_s += dt_s * model.time_scale;
    }
    const auto main_start = std::chrono::steady_clock::now();
    while (next_switch < switches.size() && display_time_s >= switches[next_switch].first) {
      const std::string& id = sea.library()->request(switches[next_switch++].second, o.crossfade_s);
      if (!o.quiet) std::fprintf(stderr, "t = %.2f s: crossfading to sea state %s over %.1f s\n", display_time_s, id.c_str(), o.crossfade_s);
      if (headless) sea.wait_until_ready(display_time_s, std::chrono::seconds(30));
    }
    sea.advance_to(display_time_s);
    // Issue 41: the deep water foams on the share of its drawn surface that Monahan &
    // O'Muircheartaigh (1980) give for the lighting's wind (the --beaufort force's, whether the
    // deep water is that preset or the bake's own field, whose spectrum records no wind), J_b
    // measured on the deep keyframe on screen when the sea or the wind changes.
    if (const auto deep = sea.snapshot().deep_from)
      if (const auto onset = whitecaps.update(deep->cascades, sea.engine().site()->choppiness, lighting.wind_speed_m_s)) {
        lighting.jacobian_foam_onset = onset->jacobian_foam_onset;
        if (!o.quiet)
          std::fprintf(stderr, "whitecaps: J_b %.3f foams %.2f %% of the deep water (Monahan & O'Muircheartaigh: %.2f %% at U10 %.1f m/s%s)\n",
                       onset->jacobian_foam_onset, 100.0 * onset->coverage, 100.0 * onset->target_coverage,
                       lighting.wind_speed_m_s, onset->clamped ? "; J_b held in [0, 1]" : "");
      }
    renderer.stage_upcoming(sea.engine());
    if (!headless) control.update(window.glfw_window(), dt_s, panel && panel->wants_input());
    if (ships) {
      // The fleet follows the display clock (at most 0.1 s a frame: a stalled window does not
      // throw the ships forward); ship 0 from the arrow keys in a window.
      const double ship_dt_s = std::clamp(display_time_s - ships_time_s, 0.0, 0.1);
      ships_time_s = display_time_s;
      const bool keys = !headless && !(panel && panel->wants_input());
      step_fleet(*ships, sea, o, keys ? window.glfw_window() : nullptr, display_time_s, ship_dt_s, control, ships_summary);
      ships_ms_sum += ships->last_step_ms();
    }
    renderer.render(sea.snapshot(), control.camera, lighting, window.framebuffer_width_px(),
                    window.framebuffer_height_px(), draw_options, ships ? &ships->layers() : nullptr);
    renderer.blit_to_window(window.framebuffer_width_px(), window.framebuffer_height_px());
    const double main_ms = 1e3 * seconds_since(main_start);
    main_ms_sum += main_ms;
    if (panel) show_panel(*panel, model, o, dt_s, main_ms, display_time_s, ships.get(), frame, plan, sea, renderer, lighting, control);
    ++frames_drawn;
    if (headless && frames_drawn >= std::max(o.frames, 1)) break;  // keep the last picture in the back buffer
    window.present();
  }
  const runtime::StreamingStats s = sea.engine().stats();
  if (ships) {
    ships_summary.ships = ships->readouts();
    for (std::size_t i = 0; i < ships->fleet().size(); ++i) ships_summary.wake_angles.push_back(ships->wake_angle(i));
  }
  ships_summary.step_ms_mean = frames_drawn > 0 ? ships_ms_sum / frames_drawn : 0.0;
  ships_summary.main_thread_ms_mean = frames_drawn > 0 ? main_ms_sum / frames_drawn : 0.0;
  const std::string summary = fmt::format("{} ({} x {}, t = {:.2f} s, {} grid, {}; {})", o.screenshot.string(), width,
                                          height, display_time_s, o.grid, s.plan, window.gl_description());
  if (!o.screenshot.empty()) {
    write_png(panel ? window.read_back_buffer() : renderer.read_pixels(), o.screenshot);
    if (!o.quiet)  // stderr under --json: stdout is the JSON alone
      std::fprintf(o.json ? stderr : stdout, "screenshot: %s (%d x %d, t = %.2f s, %s grid)\n", o.screenshot.c_str(),
                   width, height, display_time_s, o.grid.c_str());
  }
  print_play_results(o, s, renderer, frames_drawn, wall_s, display_time_s, ships_summary);
  g_camera_control = nullptr;
  return summary;
}

}  // namespace

std::string write_playback_screenshot(const fs::path& sequence_folder, const fs::path& png, int width_px, int height_px) {
  PlayOptions o;
  o.sequence_folder = sequence_folder;
  o.screenshot = png;
  o.size_px = {width_px, height_px};
  o.frames = 15;  // half a second of display: the streaming engine and the renderer's first uploads settle
  o.quiet = true;
  return play(o);
}

void add_play_command(CLI::App& app) {
  auto o = std::make_shared<PlayOptions>();
  CLI::App* cmd = app.add_subcommand("play", "Play a baked sequence inside the endless sea (window, or headless screenshot)");
  cmd->add_option("sequence", o->sequence_folder, "Baked sequence folder (`nearshore bake`), or a sea-state library (`nearshore library`)")
      ->required();
  cmd->add_option("--grid", o->grid, "Surface grid: radial, quadtree or projected (Earth curvature, for high views)")
      ->capture_default_str()
      ->check(CLI::IsMember({"radial", "quadtree", "projected"}));
  cmd->add_option("--plan", o->plan, "Playback plan: auto (the period, else the planned loop), period, loop, random, order")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "period", "loop", "random", "order"}));
  cmd->add_option("--seed", o->seed, "Random-walk seed (default: the one loops.json records)");
  cmd->add_option("--deep-water", o->deep_water, "Sea beyond the harbour: auto (the bake's own, else Beaufort), beaufort, none")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "beaufort", "none"}));
  cmd->add_option("--beaufort", o->beaufort_force, "Beaufort force of the deep water when it is not the bake's own")
      ->capture_default_str()
      ->check(number_in(at_least(0), at_most(12)));
  cmd->add_option("--wind-from", o->wind_from_deg, "Compass bearing the wind blows from, degrees")
      ->capture_default_str()
      ->check(number_in(at_least(-360), at_most(360)));
  cmd->add_option("--time", o->time_s, "Display time of the first frame, seconds")
      ->capture_default_str()
      ->check(number_in(at_least(0), at_most(1e9)));
  cmd->add_option("--time-scale", o->time_scale, "Playback speed (1 = real time)")
      ->capture_default_str()
      ->check(number_in(at_least(0), at_most(16)));
  cmd->add_option("--eye", o->eye, "Camera position: X,Y,Z in metres from the grid's south-west corner (z up), or "
                                   "lat=..,lon=..,z_m=.. or easting_m=..,northing_m=..,z_m=.. in the grid's CRS (default: overview)")
      ->check(position_text("--eye"));
  cmd->add_option("--target", o->target, "Point looked at: X,Y[,Z] from the grid's south-west corner, or lat=..,lon=.. or "
                                         "easting_m=..,northing_m=.. (z_m=.. optional, default 0)")
      ->check(position_text("--target"));
  cmd->add_option("--eye-lat-lon", o->eye_lat_lon, "Camera at LAT,LON,HEIGHT (WGS 84 degrees, metres above the sea)")
      ->delimiter(',')->expected(3)->check(finite_number());
  cmd->add_option("--target-lat-lon", o->target_lat_lon, "Look at LAT,LON (WGS 84 degrees) on the sea")
      ->delimiter(',')->expected(2)->check(finite_number());
  CLI::Option* sun_azimuth = cmd->add_option("--sun-azimuth", o->sun_azimuth_deg, "Sun bearing, degrees from north")
      ->capture_default_str()
      ->check(number_in(at_least(-360), at_most(360)));
  CLI::Option* sun_elevation = cmd->add_option("--sun-elevation", o->sun_elevation_deg, "Sun height above the horizon, degrees")
      ->capture_default_str()
      ->check(number_in(at_least(-90), at_most(90)));
  cmd->add_option("--utc", o->utc, "Put the sun where it stands at this UTC time over the site, e.g. 2026-06-21T04:00:00Z")
      ->excludes(sun_azimuth)->excludes(sun_elevation);
  cmd->add_option("--lat-lon", o->lat_lon, "Place the --utc sun is seen from, LAT,LON (default: the site's own centre)")
      ->delimiter(',')->expected(2)->check(finite_number());
  std::string weather_names;
  for (const playback::WeatherPreset& preset : playback::weather_presets())
    weather_names += (weather_names.empty() ? "" : ", ") + preset.name + " (" + preset.description + ")";
  std::vector<std::string> weather_choices;
  for (const playback::WeatherPreset& preset : playback::weather_presets()) weather_choices.push_back(preset.name);
  cmd->add_option("--weather", o->weather, "Sky and air: " + weather_names)
      ->check(CLI::IsMember(weather_choices))->capture_default_str();
  cmd->add_option("--visibility", o->visibility_m, "Meteorological optical range, metres (fog < 1000, mist 1000-5000; 0 unlimited; default: the weather's)")
      ->check(number_in(at_least(0), at_most(1e6)));
  cmd->add_option("--cloud-cover", o->cloud_cover, "Cloud cover 0..1 (1: CIE overcast sky, sun hidden; default: the weather's)")
      ->check(number_in(at_least(0), at_most(1)));
  cmd->add_option("--haze", o->haze, "Atmospheric turbidity (Preetham's T): 2 very clear, 3 clear, 6 hazy, 10 thin fog (default: the weather's: 2.5 clear, 6 hazy, 4 overcast)")
      ->check(number_in(at_least(1.7), at_most(10)));
  cmd->add_option("--turbidity", o->turbidity_ntu, "Water turbidity from suspended sediment, NTU (0 clear ocean, 10 a muddy harbour)")
      ->check(number_in(at_least(0), at_most(200)))->capture_default_str();
  cmd->add_option("--chlorophyll", o->chlorophyll_mg_m3, "Chlorophyll, mg/m3 (0.05 open ocean, 1 coastal, 10 a bloom)")
      ->check(number_in(at_least(0), at_most(100)))->capture_default_str();
  cmd->add_option("--cdom", o->cdom_per_m, "Absorption of dissolved organic matter at 440 nm, 1/m (default: from the chlorophyll)")
      ->check(number_in(at_least(0), at_most(20)));
  cmd->add_option("--exposure", o->exposure, "Exposure compensation, a factor on the automatic exposure")
      ->check(number_in(at_least(0.01), at_most(100)))->capture_default_str();
  cmd->add_option("--detail-parallax", o->detail_parallax,
                  "Parallax of the detail normals at grazing views (seed 004 eq. 5): 1 on, 0 off")
      ->check(number_in(at_least(0), at_most(4)))->capture_default_str();
  cmd->add_option("--foam-decay", o->foam_decay_s, "Seconds over which the deep water's foam fades by 1/e (0: no lasting foam)")
      ->check(number_in(at_least(0), at_most(60)))->capture_default_str();
  cmd->add_option("--lighting", o->lighting_mode, "full (docs/lighting.md) or off (a flat sea, no sky: the cost baseline)")
      ->check(CLI::IsMember({"full", "off"}))->capture_default_str();
  cmd->add_option("--msaa", o->msaa_samples, "Anti-aliasing: samples per pixel (1: off; more than the GPU offers: its most; 0: 4 on a GPU, 1 on a software renderer such as llvmpipe)")
      ->check(number_in(at_least(0), at_most(32)))->capture_default_str();
  cmd->add_option("--frames", o->frames, "Headless: draw this many frames at 30 fps display time, then exit")
      ->check(number_in(at_least(1), at_most(1e6)));
  cmd->add_option("--screenshot", o->screenshot, "Headless: write the last frame to this PNG (hidden window)");
  cmd->add_option("--size", o->size_px, "Window or picture size WIDTH,HEIGHT in pixels")
      ->delimiter(',')->expected(2)->capture_default_str()
      ->check(number_in(at_least(16), at_most(8192)));
  cmd->add_flag("--panel", o->panel, "Headless: draw the on-screen panel into the screenshot too");
  cmd->add_option("--seconds", o->seconds, "Window: close after this many seconds (0: when closed)")
      ->check(number_in(at_least(0), at_most(1e9)));
  cmd->add_flag("--json", o->json, "Print the streaming statistics as JSON when done");
  cmd->add_option("--state", o->state, "Sea-state library (a folder with library.json): the conditions to start with, "
                                       "KEY=VALUE,... (e.g. wind_direction_deg=0,tide_m=0.5); default: the first state");
  cmd->add_option("--switch", o->switches, "Sea-state library: at display time T, crossfade to the state nearest the "
                                           "conditions, T:KEY=VALUE,... (repeatable)");
  cmd->add_option("--crossfade", o->crossfade_s, "Sea-state library: length of a switch's crossfade, seconds of display time")
      ->capture_default_str()
      ->check(number_in(at_least(0), at_most(3600)));
  cmd->add_option("--ships", o->ships_scenario, "Ships to sail on the sea: a scenario file (TOML, docs/ships.md); the "
                                                "arrow keys steer ship 0 in the window, Enter centres its rudder");
  cmd->add_option("--follow-ship", o->follow_ship, "Move the camera with this ship of --ships (index from 0)")
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
