#pragma once
// FleetLayers: a ships::ShipFleet as the generic layers a playback::WaterRenderer draws
// (playback/surface_layers.hpp, docs/ships.md "What a renderer needs"): each ship's bow wave as a
// height patch added to the sea, its stern-wake decals as foam, its hull mesh at its pose. The one
// place that turns ships into layers: the viewer (viewer/src/viewer_ships.cpp) and the C API's renderer
// (nearshore_renderer_set_fleet) both use it.
//
// Library nearshore_ships_layers (ships/layers): links nearshore_ships and nearshore_playback, so
// the ships library itself stays free of GL and playback free of ships.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nearshore/playback/surface_layers.hpp"
#include "nearshore/ships/hull_mesh.hpp"
#include "nearshore/ships/ship_body.hpp"
#include "nearshore/ships/ship_fleet.hpp"

namespace nearshore::ships {

class FleetLayers {
 public:
  /// The hull ship `index` is drawn with: `hull` in the body frame (ShipDefinition::hull), made
  /// relative to the centre of gravity of `particulars` (world = G + R (p_body - G_body), the pose
  /// of ShipState), its bottom paint up to the design waterline. Ships without one draw no mesh.
  void set_hull(std::size_t index, const HullMesh& hull, const ShipParticulars& particulars);

  /// Rebuilds the layers from the fleet as it stands (call after each ShipFleet::step): at most
  /// SurfaceLayers::kMaxHeightPatches bow waves (the first ships'), every wake decal (oldest first),
  /// every hull set. The layers point into the fleet's bow-wave heights and into this object:
  /// both must outlive the draw.
  const playback::SurfaceLayers& update(const ShipFleet& fleet);
  const playback::SurfaceLayers& layers() const { return layers_; }

 private:
  struct HullGeometry {
    std::vector<float> vertices_m;  // body frame, relative to the centre of gravity
    std::vector<std::uint32_t> triangles;
    double boot_top_z_m = 0.0;  // the design waterline, same frame
  };
  std::vector<HullGeometry> hulls_;  // by ship index; empty where none was set
  playback::SurfaceLayers layers_;
};

}  // namespace nearshore::ships
