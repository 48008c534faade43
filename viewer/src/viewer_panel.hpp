#pragma once
// The viewer's on-screen panel (`nearshore play`): Dear ImGui (Debian's libimgui-dev, GLFW and
// OpenGL 3 backends) over the rendered sea. It shows what an operator watching a simulator needs
// to trust the picture (frame rate, frame time, the streaming ring, underruns, held frames, the
// loop step) and the controls of the issue (grid, plan, time scale, wind, jump to a position).
// The panel knows nothing of the runtime: viewer.cpp fills ViewerPanelModel from the engine's
// statistics and applies the controls it returns.
#include <array>
#include <string>
#include <vector>

#include "nearshore/viewer/ship_readout.hpp"

struct GLFWwindow;

namespace nearshore::viewer {

struct ViewerPanelModel {
  // ---- shown ----
  double frames_per_s = 0.0, frame_time_ms = 0.0, main_thread_ms = 0.0;
  double display_time_s = 0.0;
  int ring_filled = 0, ring_capacity = 0;
  unsigned long long underruns = 0, bad_frames_held = 0, transitions_taken = 0;
  double decode_real_time_multiple = 0.0;
  long long plan_step = 0;
  bool crossfading = false;
  std::string plan_name, message, gl_description;
  double camera_latitude_deg = 0.0, camera_longitude_deg = 0.0, camera_height_m = 0.0;
  std::vector<ShipReadout> ships;  ///< empty without --ships
  double ships_ms = 0.0;           ///< CPU time of the fleet's step and its layers this frame
  // ---- controls (the panel edits these; the viewer applies what changed) ----
  int grid = 0;             ///< 0 radial, 1 quadtree, 2 projected
  int plan = 0;             ///< 0 auto, 1 exact period, 2 optimal loop, 3 random walk, 4 frame order
  double time_scale = 1.0;
  int beaufort_force = 3;
  double wind_from_deg = 225.0;
  bool deep_water_from_bake = true;  ///< the wind controls apply only when the bake has no deep water
  std::array<double, 2> jump_lat_lon_deg = {0.0, 0.0};
  bool jump_requested = false;
  bool paused = false;
  double sun_azimuth_deg = 200.0, sun_elevation_deg = 35.0;  ///< compass bearing, apparent height
  double haze = 2.5;               ///< Preetham's atmospheric turbidity T
  double turbidity_ntu = 0.5, chlorophyll_mg_m3 = 0.3;  ///< what is in the water
  double exposure = 1.0;           ///< factor on the automatic exposure
};

class ViewerPanel {
 public:
  /// Creates the ImGui context on `window` (its GL context current). Throws nearshore::Error.
  explicit ViewerPanel(GLFWwindow* window);
  ~ViewerPanel();
  ViewerPanel(const ViewerPanel&) = delete;
  ViewerPanel& operator=(const ViewerPanel&) = delete;

  /// Builds and draws the panel into the currently bound framebuffer (the window's, after the sea
  /// is blitted). Returns true if a control changed.
  bool draw(ViewerPanelModel& model);
  /// True while the mouse or keyboard is over the panel (the camera then ignores them).
  bool wants_input() const;
};

}  // namespace nearshore::viewer
