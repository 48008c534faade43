#include "viewer_ships.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "nearshore/ships/scenario.hpp"

namespace nearshore::viewer {

ViewerShips::ViewerShips(const std::filesystem::path& scenario_toml, std::shared_ptr<const runtime::HarbourSite> site) {
  fleet_.set_site(std::move(site));
  // load_scenario places the ships (its errors name the file and the ship); the definitions give
  // the hull meshes to draw, in the same order.
  ships::load_scenario(scenario_toml, fleet_);
  const std::vector<ships::ShipDefinition> definitions = ships::read_scenario(scenario_toml);
  for (std::size_t index = 0; index < definitions.size(); ++index)
    layers_.set_hull(index, definitions[index].hull, fleet_.ship(index).body().particulars());
  build_layers();
}

void ViewerShips::steer_first_ship(int engine, int rudder, bool midships, double dt_s) {
  if (fleet_.size() == 0 || (!manual_ && engine == 0 && rudder == 0 && !midships)) return;
  ships::Ship& ship = fleet_.ship(0);
  if (!manual_) {  // take the helm from the scenario's orders where they left the controls
    manual_ = true;
    ship.manual_controls() = ship.controls();
    ship.set_orders({});
  }
  constexpr double kEngineRatePerS = 0.5;                          // stop to full ahead in 2 s
  constexpr double kRudderRateRadS = 20.0 * std::numbers::pi / 180;  // the helm, not the steering gear
  ships::ShipControls& controls = ship.manual_controls();
  controls.engine_order = std::clamp(controls.engine_order + engine * kEngineRatePerS * dt_s, -1.0, 1.0);
  const double max_rudder = ship.body().particulars().max_rudder_angle_rad;
  controls.rudder_order_rad = midships ? 0.0 : std::clamp(controls.rudder_order_rad + rudder * kRudderRateRadS * dt_s,
                                                          -max_rudder, max_rudder);
}

void ViewerShips::step(const runtime::SurfaceSnapshot& snapshot, double dt_s) {
  const auto start = std::chrono::steady_clock::now();
  if (dt_s > 0) fleet_.step(snapshot, dt_s);
  build_layers();
  last_step_ms_ = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void ViewerShips::build_layers() { layers_.update(fleet_); }

std::vector<ShipReadout> ViewerShips::readouts() const {
  std::vector<ShipReadout> rows;
  for (std::size_t i = 0; i < fleet_.size(); ++i) {
    const ships::Ship& ship = fleet_.ship(i);
    const ships::ShipState& s = ship.body().state();
    ShipReadout r;
    r.name = ship.name();
    r.x_m = s.position_m.x(), r.y_m = s.position_m.y();
    r.speed_kn = s.forward_speed_m_s() * 3600.0 / 1852.0;
    r.heading_deg = s.heading_deg();
    r.engine_order = ship.controls().engine_order;
    r.rudder_deg = ship.controls().rudder_order_rad * 180.0 / std::numbers::pi;
    r.heel_deg = s.roll_rad() * 180.0 / std::numbers::pi;
    r.aground = ship.status().aground;
    r.manual = i == 0 && manual_;
    rows.push_back(r);
  }
  return rows;
}

}  // namespace nearshore::viewer

namespace nearshore::viewer {

ships::WakeAngle ViewerShips::wake_angle(std::size_t i) const {
  const ships::Ship& ship = fleet_.ship(i);
  if (!ship.bow_wave()) return {};
  // The envelope's ray (robust: the largest |eta| per distance behind the bow), the hull's own
  // trough within half a beam of the track left out.
  // The layer the fleet shows (ship_fleet.hpp WakeLayerChoice): the dispersive wake when it is.
  const ships::ShipParticulars& p = ship.body().particulars();
  if (ship.dispersive_wake() && ship.dispersive_weight() >= 0.5)
    return ships::measure_wake_envelope_angle(*ship.dispersive_wake(), ship.body().state(), p.length_m, 1.0,
                                              0.5 * p.beam_m);
  return ships::measure_wake_envelope_angle(*ship.bow_wave(), ship.body().state(), p.length_m, 1.0, 0.5 * p.beam_m);
}

}  // namespace nearshore::viewer
