#include "viewer_ships.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "nearshore/ships/scenario.hpp"

namespace nearshore::tools {

ViewerShips::ViewerShips(const std::filesystem::path& scenario_toml, std::shared_ptr<const runtime::HarbourSite> site) {
  fleet_.set_site(std::move(site));
  // load_scenario places the ships (its errors name the file and the ship); the definitions give
  // the hull meshes to draw, in the same order.
  ships::load_scenario(scenario_toml, fleet_);
  const std::vector<ships::ShipDefinition> definitions = ships::read_scenario(scenario_toml);
  for (std::size_t index = 0; index < definitions.size(); ++index) {
    const ships::ShipDefinition& definition = definitions[index];
    // The hull as the renderer draws it: relative to G, so that world = position + R p
    // (ShipState::position_m is G; docs/ships.md "What a renderer needs").
    const ships::ShipParticulars& particulars = fleet_.ship(index).body().particulars();
    const Eigen::Vector3d& g = particulars.centre_of_gravity_m;
    HullGeometry hull;
    for (const Eigen::Vector3d& v : definition.hull.vertices_m)
      hull.vertices_m.insert(hull.vertices_m.end(), {float(v.x() - g.x()), float(v.y() - g.y()), float(v.z() - g.z())});
    for (const auto& t : definition.hull.triangles)
      hull.triangles.insert(hull.triangles.end(), {std::uint32_t(t[0]), std::uint32_t(t[1]), std::uint32_t(t[2])});
    hull.boot_top_z_m = particulars.design_draft_m - g.z();
    hulls_.push_back(std::move(hull));
  }
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

void ViewerShips::build_layers() {
  layers_.height_patches.clear();
  layers_.foam_decals.clear();
  layers_.meshes.clear();
  for (std::size_t i = 0; i < fleet_.size(); ++i) {
    const ships::Ship& ship = fleet_.ship(i);
    if (ship.bow_wave() && layers_.height_patches.size() < std::size_t(playback::SurfaceLayers::kMaxHeightPatches)) {
      const ships::BowWaveField f = ship.bow_wave()->field();
      if (f.heights_m && f.columns >= 2)
        layers_.height_patches.push_back(
            {f.origin_x_m, f.origin_y_m, f.spacing_m, f.columns, f.rows, f.heights_m->data(), f.serial});
    }
    for (const ships::WakeDecal& d : ship.wake().decals())  // oldest first
      layers_.foam_decals.push_back({d.x_m, d.y_m, d.yaw_rad, d.length_m, d.width_m, d.opacity(), d.variant});
    const ships::ShipState& state = ship.body().state();
    playback::SolidMesh mesh;
    mesh.id = i + 1;
    mesh.vertices_m = hulls_[i].vertices_m.data();
    mesh.vertex_count = hulls_[i].vertices_m.size() / 3;
    mesh.triangles = hulls_[i].triangles.data();
    mesh.triangle_count = hulls_[i].triangles.size() / 3;
    mesh.position_m = {state.position_m.x(), state.position_m.y(), state.position_m.z()};
    const Eigen::Matrix3d r = state.orientation.toRotationMatrix();
    for (int row = 0; row < 3; ++row)
      for (int column = 0; column < 3; ++column) mesh.rotation[std::size_t(3 * row + column)] = r(row, column);
    mesh.boot_top_z_m = hulls_[i].boot_top_z_m;
    layers_.meshes.push_back(mesh);
  }
}

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

}  // namespace nearshore::tools

namespace nearshore::tools {

ships::WakeAngle ViewerShips::wake_angle(std::size_t i) const {
  const ships::Ship& ship = fleet_.ship(i);
  if (!ship.bow_wave()) return {};
  return ships::measure_wake_half_angle(*ship.bow_wave(), ship.body().state(), ship.body().particulars().length_m);
}

}  // namespace nearshore::tools
