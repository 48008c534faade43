// The viewer (`nearshore play SEQ`): the runtime a simulator embeds, as an application. The
// streaming engine (runtime/) plays the bake by its plan inside the endless deep water; the
// renderer (playback/) draws it on the chosen grid; Dear ImGui shows the streaming state
// (viewer_panel.hpp). Headless (--frames N --screenshot out.png) it draws N frames on a fixed 30 fps
// clock, waiting for each frame's keyframes so identical inputs give identical pictures. With
// --ships a scenario's ships sail on the shown sea (viewer_ships.hpp), stepped on the same display
// clock, so a headless run with the scenario's orders is a script too; the arrow keys steer ship 0.
#include "nearshore/viewer/viewer.hpp"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "nearshore/core/geo_position.hpp"
#include "nearshore/core/map_projection.hpp"
#include "nearshore/ocean/sea_state_beaufort.hpp"
#include "nearshore/ocean/whitecap_coverage.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/runtime/library_player.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "viewer_panel.hpp"
#include "viewer_ships.hpp"

namespace nearshore::viewer {
namespace {

const char* const kPlanNames[] = {"auto", "period", "loop", "random", "order"};

runtime::PlanKind plan_kind_of(const std::string& name) {
  if (name == "auto") return runtime::PlanKind::kOptimalLoop;  // the period of a periodic bake, else the planned loop
  if (const auto kind = runtime::parse_plan_kind(name)) return *kind;
  throw Error("--plan " + name, "is not a plan", "use auto, period, loop, random or order");
}

using ocean::travel_direction_rad;  // compass "from" bearing -> travel direction

runtime::StreamingOptions streaming_options(const ViewerOptions& o, const std::string& plan) {
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

playback::Camera initial_camera(const ViewerOptions& o, const runtime::HarbourSite& site, const SiteFrame& frame) {
  playback::Camera camera = playback::Camera::overlooking_site(site.width_m, site.height_m);
  // --eye/--target: metres from the south-west corner, the grid's CRS or lat/lon, through the one
  // position parser (core/geo_position.hpp); z_m is the height above still water.
  const auto site_point = [&](const std::string& text, const std::string& flag, std::optional<double> default_z_m) {
    std::map<std::string, double> extras;
    const GeoPosition position = parse_geo_position(text, flag, {"z_m"}, &extras);
    if (!extras.count("z_m") && !default_z_m)
      throw Error(flag + " " + text, "has no height", "add z_m, the height above still water in metres: X,Y,Z or ...,z_m=30");
    const ProjectedPoint p = place_in_grid(position, frame.geometry, flag, "the camera", false);
    if (auto warning = land_warning(site.harbour, p, flag, flag == "--eye" ? "the camera" : "the point looked at"))
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

// The window's user pointer holds the CameraControl (the viewer's; playback's window and ImGui's
// backend use none), so the scroll callback needs no global.
void on_scroll(GLFWwindow* window, double, double y_offset) {
  if (auto* control = static_cast<CameraControl*>(glfwGetWindowUserPointer(window))) control->scroll += y_offset;
}

runtime::PlayedSea open_sea(const ViewerOptions& o, const std::string& plan) {
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
playback::Lighting scene_lighting(const ViewerOptions& o, const runtime::StreamingEngine& engine,
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
  lighting.structure_foam_onset_m_s = o.structure_foam_onset_m_s > 0 ? o.structure_foam_onset_m_s
                                                                      : std::numeric_limits<double>::infinity();
  lighting.wind_direction_rad = travel_direction_rad(o.wind_from_deg);
  lighting.wind_speed_m_s = ocean::beaufort_preset(o.beaufort_force).wind_speed_10_m_s;
  const auto& deep = engine.manifest().deep_water;
  if (engine.deep_water_is_bakes() && deep && deep->unresolved_slope_variance > 0.0)
    lighting.sub_grid_slope_variance = deep->unresolved_slope_variance;
  return lighting;
}

// The panel's figures before the first frame: the options, the sea and the lighting as opened.
ViewerPanelModel panel_model_at_start(const ViewerOptions& o, const std::string& plan, const playback::RendererSettings& settings,
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
void step_fleet(ViewerShips& ships, runtime::PlayedSea& sea, const ViewerOptions& o, GLFWwindow* keys_window, double display_time_s,
                double ship_dt_s, CameraControl& control, int& ship_events) {
  if (keys_window != nullptr) {
    auto key = [&](int k) { return glfwGetKey(keys_window, k) == GLFW_PRESS ? 1 : 0; };
    ships.steer_first_ship(key(GLFW_KEY_UP) - key(GLFW_KEY_DOWN), key(GLFW_KEY_LEFT) - key(GLFW_KEY_RIGHT),
                           key(GLFW_KEY_ENTER) != 0, ship_dt_s);
  }
  const Eigen::Vector3d before = o.follow_ship >= 0 ? ships.fleet().ship(std::size_t(o.follow_ship)).body().state().position_m
                                                    : Eigen::Vector3d::Zero();
  ships.step(sea.snapshot(), ship_dt_s);
  for (const std::string& event : ships.take_events()) {
    ++ship_events;
    if (!o.quiet) std::fprintf(stderr, "t = %.2f s: %s\n", display_time_s, event.c_str());
  }
  if (o.follow_ship >= 0) {  // the camera moves with the ship, keeping its view of it
    const Eigen::Vector3d moved = ships.fleet().ship(std::size_t(o.follow_ship)).body().state().position_m - before;
    for (int axis = 0; axis < 2; ++axis) control.camera.eye_m[axis] += moved[axis], control.camera.target_m[axis] += moved[axis];
  }
}

// The panel: this frame's figures in, then what the user changed on it applied (grid, plan, wind,
// lighting, a jump to a position).
void show_panel(ViewerPanel& panel, ViewerPanelModel& model, const ViewerOptions& o, double dt_s, double main_ms, double display_time_s,
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

}  // namespace

ViewerRun run_viewer(const ViewerOptions& o) {
  const bool headless = o.keep_last_picture || o.frames > 0;
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
  settings.refraction = o.refraction != "off";
  playback::WaterRenderer renderer(settings);
  std::unique_ptr<ViewerPanel> panel;
  if (!headless || o.panel) panel = std::make_unique<ViewerPanel>(window.glfw_window());
  glfwSetWindowUserPointer(window.glfw_window(), &control);
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
  ViewerRun run;
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
      step_fleet(*ships, sea, o, keys ? window.glfw_window() : nullptr, display_time_s, ship_dt_s, control, run.ship_events);
      ships_ms_sum += ships->last_step_ms();
    }
    renderer.render(sea.snapshot(), control.camera, lighting, window.framebuffer_width_px(),
                    window.framebuffer_height_px(), draw_options, ships ? &ships->layers() : nullptr);
    renderer.blit_to_window(window.framebuffer_width_px(), window.framebuffer_height_px());
    const double main_ms = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - main_start).count();
    main_ms_sum += main_ms;
    if (panel) show_panel(*panel, model, o, dt_s, main_ms, display_time_s, ships.get(), frame, plan, sea, renderer, lighting, control);
    ++frames_drawn;
    if (headless && frames_drawn >= std::max(o.frames, 1)) break;  // keep the last picture in the back buffer
    window.present();
  }
  run.stats = sea.engine().stats();
  run.last_frame = renderer.last_frame();
  run.frames_drawn = frames_drawn;
  // Up to now: a headless run leaves the loop right after its last frame, before the loop's clock
  // reads again (one frame read 0 s and printed millions of frames per second).
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.display_time_s = display_time_s;
  run.gl_description = window.gl_description();
  if (ships) {
    run.ships = ships->readouts();
    for (std::size_t i = 0; i < ships->fleet().size(); ++i) run.wake_angles.push_back(ships->wake_angle(i));
  }
  run.ships_ms_per_frame = frames_drawn > 0 ? ships_ms_sum / frames_drawn : 0.0;
  run.main_thread_ms_per_frame = frames_drawn > 0 ? main_ms_sum / frames_drawn : 0.0;
  if (o.keep_last_picture) run.last_picture = panel ? window.read_back_buffer() : renderer.read_pixels();
  return run;
}

}  // namespace nearshore::viewer
