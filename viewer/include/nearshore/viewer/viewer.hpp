#pragma once
// The viewer: the application behind `nearshore play`. It opens a baked sequence (or a sea-state
// library) in the streaming engine (runtime/), draws it inside the endless deep water with the
// renderer (playback/), shows the streaming state on a Dear ImGui panel, and sails a scenario's
// ships on the shown sea (ships/). Headless (frames > 0 or keep_last_picture) it draws on a fixed
// 30 fps display clock, waiting for each frame's keyframes, so identical options give identical
// pictures.
//
// Runtime side: it links the runtime, the renderer and the ships, never the bake side
// (cmake/NearshoreArchitecture.cmake); positions go through core/geo_position.hpp and the bake's
// map projection (core/map_projection.hpp). Its messages name the flags of `nearshore play`
// (--eye, --switch, ...): it is that command's application, not a library a host embeds (a host
// embeds the runtime through capi/). It writes no files: the caller writes the last picture.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "nearshore/core/image.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/ships/bow_wave.hpp"
#include "nearshore/viewer/ship_readout.hpp"

namespace nearshore::viewer {

/// What to play and how: one field per flag of `nearshore play` (docs/commands/play.md).
struct ViewerOptions {
  std::filesystem::path sequence_folder;  ///< a baked sequence, or a sea-state library (library.json)
  std::string grid = "quadtree";          ///< radial, quadtree or projected
  std::string plan = "auto";              ///< auto, period, loop, random or order
  std::string deep_water = "auto";        ///< auto (the bake's own, else Beaufort), beaufort, none
  std::optional<std::uint64_t> seed;      ///< random-walk seed (default: loops.json's)
  double time_s = 0;                      ///< display time of the first frame
  double time_scale = 1.0;                ///< playback speed in a window (1: real time)
  double seconds = 0;                     ///< window: close after this many wall seconds (0: when closed)
  int frames = 0;                         ///< headless: frames drawn at 30 fps display time (0: a window)
  bool keep_last_picture = false;         ///< headless: hand back the last frame (ViewerRun::last_picture)
  std::array<int, 2> size_px = {1280, 720};  ///< window or picture width, height
  /// Camera and the point it looks at: core/geo_position.hpp's text form plus z_m, the height above
  /// still water (metres from the grid's south-west corner, the grid's CRS or lat/lon); empty: the overview.
  std::string eye, target;
  std::vector<double> eye_lat_lon;     ///< {latitude_deg, longitude_deg, height_m}, or empty
  std::vector<double> target_lat_lon;  ///< {latitude_deg, longitude_deg}, or empty
  int beaufort_force = 3;              ///< the deep water's force when it is not the bake's own
  double wind_from_deg = 225;          ///< compass bearing the wind blows from
  double sun_azimuth_deg = 200, sun_elevation_deg = 35;
  // Lighting (docs/lighting.md): the sun from a UTC time at the site (or lat_lon), the air, the water.
  std::string utc;                     ///< e.g. 2026-06-21T04:00:00Z; empty: sun_azimuth/elevation_deg
  std::vector<double> lat_lon;         ///< {latitude_deg, longitude_deg} the utc sun is seen from, or empty
  std::string weather = "clear";       ///< a playback::weather_presets() name
  double visibility_m = -1, cloud_cover = -1;  ///< < 0: the weather's; cloud_cover a fraction 0..1
  double haze = -1;                    ///< Preetham's atmospheric turbidity T (< 0: the weather's)
  double turbidity_ntu = 0.5, chlorophyll_mg_m3 = 0.3;
  double cdom_per_m = -1;              ///< CDOM absorption at 440 nm (< 0: from the chlorophyll)
  double exposure = 1.0;               ///< factor on the automatic exposure
  std::string lighting_mode = "full";  ///< full, or off (a flat sea, no sky: the cost baseline)
  double detail_parallax = 1.0, foam_decay_s = 3.0;
  double structure_foam_onset_m_s = 1.0;  ///< Lighting::structure_foam_onset_m_s (0: no foam at structures)
  int msaa_samples = 0;                ///< RendererSettings::msaa_samples (0: automatic)
  std::string refraction = "on";       ///< RendererSettings::refraction: "on" or "off" (the sea opaque)
  bool panel = false;                  ///< headless: draw the on-screen panel into the picture too
  bool quiet = false;                  ///< say nothing on stderr while playing
  /// A sea-state library: the conditions to start with (KEY=VALUE,...), scripted switches
  /// "TIME:KEY=VALUE,..." crossfaded over crossfade_s of display time.
  std::string state;
  std::vector<std::string> switches;
  double crossfade_s = 5.0;
  /// Ships (docs/ships.md): a scenario file; the camera may follow one of its ships (index, -1: none).
  std::filesystem::path ships_scenario;
  int follow_ship = -1;
};

/// What a run did, for the caller to report.
struct ViewerRun {
  runtime::StreamingStats stats;          ///< the streaming engine's at the end
  playback::FrameStatistics last_frame;   ///< the renderer's figures of the last frame
  int frames_drawn = 0;
  double wall_s = 0;                      ///< wall time of the drawing loop
  double display_time_s = 0;              ///< display time of the last frame
  std::string gl_description;             ///< the OpenGL renderer and version
  std::vector<ShipReadout> ships;         ///< where each ship is at the end (empty without ships)
  std::vector<ships::WakeAngle> wake_angles;  ///< each ship's wake half-angle at the end
  int ship_events = 0;                    ///< groundings and the like said during the run
  double ships_ms_per_frame = 0, main_thread_ms_per_frame = 0;
  std::optional<Image> last_picture;      ///< with keep_last_picture: the last frame (with the panel if drawn)
};

/// Plays `options` until the window closes, `seconds` pass or `frames` are drawn. Throws
/// nearshore::Error for a sequence it cannot open, a position off the grid, a bad switch or ship.
ViewerRun run_viewer(const ViewerOptions& options);

}  // namespace nearshore::viewer
