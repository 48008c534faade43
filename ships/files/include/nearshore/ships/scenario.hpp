#pragma once
// Scenario files: the ships of a scene as TOML (docs/ships.md, data/ships/*.toml).
//
//   [[ship]]
//   name = "Tug 1"
//   hull = "tug"                  # "box_barge", "wigley", "tug", or a mesh file (OBJ, PLY, glTF),
//                                 # relative to the scenario file
//   length_m = 24.0               # generic hulls' main dimensions (optional; defaults per hull)
//   beam_m = 9.0
//   depth_m = 4.5
//   draft_m = 3.0                 # the loading: draft_m or mass_kg (one of them)
//   # mass_kg = 3.2e5
//   # centre_of_gravity_height_m = 2.0   # KG above the hull's lowest point (default: the solid's centroid)
//   position_m = [820.0, 260.0]   # site metres (east, north of the harbour grid's south-west corner)
//   heading_deg = 0.0             # compass, clockwise from north
//   speed_m_s = 3.0               # held by the engine; or speed_kn, or engine_order in [-1, 1]
//   initial_speed_m_s = 3.0       # optional, along the heading
//   route = [[820.0, 700.0], [1000.0, 900.0]]   # optional waypoints (site metres)
//   hull_points = 2000            # optional
//   bow_wave = true               # optional
//   bow_wave_cells = 128          # optional, N of the N x N bow-wave grid
//
// Every error names the file, the ship (by name and number) and the key.
#include <filesystem>
#include <vector>

#include "nearshore/ships/ship_fleet.hpp"

namespace nearshore::ships {

/// Parses a scenario (hull files are loaded and checked here). Throws nearshore::Error naming the
/// file for a TOML syntax error, a missing or mistyped key, an unknown hull, a bad mesh.
std::vector<ShipDefinition> read_scenario(const std::filesystem::path& scenario_toml);

/// read_scenario, then add_ship for each; a ship the fleet refuses (a mass that cannot float, a
/// position on land or too shallow) throws nearshore::Error naming the file and the ship, before
/// any ship of the file is added. Returns the number of ships added.
std::size_t load_scenario(const std::filesystem::path& scenario_toml, ShipFleet& fleet);

}  // namespace nearshore::ships
