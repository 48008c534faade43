#pragma once
// The ships of `nearshore play --ships SCENARIO.toml`: a ships::ShipFleet loaded from a scenario
// file (ships/files/scenario.hpp), stepped once per displayed frame on the sea the viewer shows,
// and handed to the renderer as playback::SurfaceLayers (bow waves as height patches, stern-wake
// decals as foam, hulls as lit meshes) through ships::FleetLayers (ships/layers), the conversion
// the C API's renderer uses too (docs/ships.md "What a renderer needs").
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "nearshore/playback/surface_layers.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"
#include "nearshore/ships/fleet_layers.hpp"
#include "nearshore/ships/ship_fleet.hpp"
#include "viewer_panel.hpp"

namespace nearshore::viewer {

class ViewerShips {
 public:
  /// Reads the scenario and places its ships on `site` (errors name the file and the ship).
  ViewerShips(const std::filesystem::path& scenario_toml, std::shared_ptr<const runtime::HarbourSite> site);

  /// The helm of ship 0 from the keyboard: the first call takes it off its scenario orders; the
  /// engine order moves by engine_rate_per_s * dt, the rudder by rudder_rate_rad_s * dt (each -1,
  /// 0 or +1; rudder > 0 to port), `midships` centres the rudder.
  void steer_first_ship(int engine, int rudder, bool midships, double dt_s);

  /// One frame: the fleet on the snapshot's sea (dt_s of display time), then the layers rebuilt.
  void step(const runtime::SurfaceSnapshot& snapshot, double dt_s);
  const playback::SurfaceLayers& layers() const { return layers_.layers(); }
  /// Events since the last call ("ship 'Tug 1' ran aground at ..."), oldest first.
  std::vector<std::string> take_events() { return fleet_.take_events(); }
  std::vector<ShipReadout> readouts() const;
  /// The half-angle of ship i's wake envelope on its bow-wave grid (ships::measure_wake_envelope_angle;
  /// Kelvin's 19.47 degrees in deep water) with its r^2 and whether a wedge was found; zero
  /// stations without a bow wave.
  ships::WakeAngle wake_angle(std::size_t i) const;
  const ships::ShipFleet& fleet() const { return fleet_; }
  /// CPU time of the last step() (the fleet and the layers), milliseconds.
  double last_step_ms() const { return last_step_ms_; }

 private:
  void build_layers();

  ships::ShipFleet fleet_;
  ships::FleetLayers layers_;
  bool manual_ = false;
  double last_step_ms_ = 0;
};

}  // namespace nearshore::viewer
