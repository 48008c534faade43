#include "nearshore/ships/fleet_layers.hpp"

namespace nearshore::ships {

void FleetLayers::set_hull(std::size_t index, const HullMesh& hull, const ShipParticulars& particulars) {
  if (hulls_.size() <= index) hulls_.resize(index + 1);
  HullGeometry& geometry = hulls_[index];
  geometry = {};
  // Relative to G, so that world = position + R p (ShipState::position_m is G).
  const Eigen::Vector3d& g = particulars.centre_of_gravity_m;
  geometry.vertices_m.reserve(3 * hull.vertices_m.size());
  for (const Eigen::Vector3d& v : hull.vertices_m)
    geometry.vertices_m.insert(geometry.vertices_m.end(),
                               {float(v.x() - g.x()), float(v.y() - g.y()), float(v.z() - g.z())});
  geometry.triangles.reserve(3 * hull.triangles.size());
  for (const auto& t : hull.triangles)
    geometry.triangles.insert(geometry.triangles.end(),
                              {std::uint32_t(t[0]), std::uint32_t(t[1]), std::uint32_t(t[2])});
  // The generic hulls' origin is on the keel: the design waterline is design_draft_m above it.
  geometry.boot_top_z_m = particulars.design_draft_m - g.z();
}

const playback::SurfaceLayers& FleetLayers::update(const ShipFleet& fleet) {
  layers_.height_patches.clear();
  layers_.foam_decals.clear();
  layers_.meshes.clear();
  for (std::size_t i = 0; i < fleet.size(); ++i) {
    const Ship& ship = fleet.ship(i);
    // The shown bow-wave layers: the shallow-water grid and/or the dispersive wake, each with its
    // weight already in its heights (ship_fleet.hpp WakeLayerChoice); a layer at weight 0 is skipped.
    auto add_patch = [&](const BowWaveField& f, double weight) {
      if (weight > 0.0 && f.heights_m && f.columns >= 2 &&
          layers_.height_patches.size() < std::size_t(playback::SurfaceLayers::kMaxHeightPatches))
        layers_.height_patches.push_back(
            {f.origin_x_m, f.origin_y_m, f.spacing_m, f.columns, f.rows, f.heights_m->data(), f.serial});
    };
    if (ship.bow_wave()) add_patch(ship.bow_wave()->field(), ship.bow_wave()->shown_weight());
    if (ship.dispersive_wake()) add_patch(ship.dispersive_wake()->field(), ship.dispersive_wake()->shown_weight());
    for (const WakeDecal& d : ship.wake().decals())  // oldest first
      layers_.foam_decals.push_back({d.x_m, d.y_m, d.yaw_rad, d.length_m, d.width_m, d.opacity(), d.variant});
    for (const WakeDecal& d : ship.crest_foam().decals())  // the breaking crests' foam, oldest first
      layers_.foam_decals.push_back({d.x_m, d.y_m, d.yaw_rad, d.length_m, d.width_m, d.opacity(), d.variant});
    if (i >= hulls_.size() || hulls_[i].triangles.empty()) continue;
    const HullGeometry& hull = hulls_[i];
    const ShipState& state = ship.body().state();
    playback::SolidMesh mesh;
    mesh.id = i + 1;
    mesh.vertices_m = hull.vertices_m.data();
    mesh.vertex_count = hull.vertices_m.size() / 3;
    mesh.triangles = hull.triangles.data();
    mesh.triangle_count = hull.triangles.size() / 3;
    mesh.position_m = {state.position_m.x(), state.position_m.y(), state.position_m.z()};
    const Eigen::Matrix3d r = state.orientation.toRotationMatrix();
    for (int row = 0; row < 3; ++row)
      for (int column = 0; column < 3; ++column) mesh.rotation[std::size_t(3 * row + column)] = r(row, column);
    mesh.boot_top_z_m = hull.boot_top_z_m;
    layers_.meshes.push_back(mesh);
  }
  return layers_;
}

}  // namespace nearshore::ships
