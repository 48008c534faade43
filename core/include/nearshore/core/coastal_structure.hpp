#pragma once
// CoastalStructure: a breakwater, quay, pier or revetment as a port engineer describes it (its
// kind, its geometry, its crest, and the reflection and transmission coefficients it should have),
// carried by the harbour grid (depth.exr's attribute "nearshore_structures", docs/formats.md) from
// `nearshore bathy` to `nearshore bake`. The bake turns the coefficients into the porous layers of
// seed 003 eq. (2)-(3) at its own cell size and wave period (bake/structure_layers.hpp), so the
// same chart gives the same structures whatever grid a case resamples it to.
//
// Geometry is in the grid's own frame (GridGeometry: projected metres, x east, y north), the frame
// of GridGeometry::cell_centre_x_m / cell_centre_y_m.
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace nearshore {

using StructureLine = std::vector<std::array<double, 2>>;  ///< (x_m, y_m) vertices; a ring when closed

struct CoastalStructure {
  std::string name;  ///< the feature's name, else "<kind> <index>": named in the bake's report and in ship contacts
  std::string kind;  ///< rubble_mound_breakwater, vertical_quay, pier, revetment... (bathymetry's style table)
  std::vector<StructureLine> lines;                  ///< centre lines of linear structures (a crest width wide)
  std::vector<std::vector<StructureLine>> polygons;  ///< outlines of areal structures (rings; holes are rings too)
  double crest_width_m = 0.0;      ///< width of the crest (lines), metres
  double crest_elevation_m = 0.0;  ///< crest above still water, metres (0: awash)
  /// Horizontal run per unit rise of the structure's faces (1.5 for a 1:1.5 rubble slope, 0 for a
  /// vertical wall): with the crest, it gives the footprint on the bed, which is where the
  /// structure meets the waves: half-width = crest_width_m / 2 + side_slope * (crest_elevation_m + d).
  double side_slope = 0.0;
  /// The fraction of the incident wave height the structure sends back (Kr, 0 .. 1). Negative: from
  /// the sea state the bake makes, by Zanuttigh & van der Meer (2008) for a sloping face of
  /// roughness `roughness_factor` (bake/structure_layers.hpp, reflection_of_slope).
  double reflection_coefficient = 1.0;
  /// gamma_f of the EurOtop / Zanuttigh & van der Meer (2008) tables: 1 smooth, 0.55 rock on an
  /// impermeable core, 0.40 rock on a permeable core. Used only where reflection_coefficient < 0.
  double roughness_factor = 1.0;
  /// The fraction of the incident wave height that passes through or over it (Kt, 0 .. 1). 0: an
  /// impermeable core (a wall at the centre line, the porous faces in front of it absorb what Kr
  /// does not reflect); > 0: the whole footprint is porous and its porosity is chosen for Kt.
  double transmission_coefficient = 0.0;
  /// A porosity the source gives explicitly (GeoJSON `porosity`, 0 .. 1): the footprint takes it as
  /// is and the coefficients are not fitted; negative = fit the porosity to the coefficients.
  double porosity = -1.0;

  /// The footprint's half-width, metres, where the still-water depth is `depth_m` (>= 0).
  double footprint_half_width_m(double depth_m) const;
};

void to_json(nlohmann::json& out, const CoastalStructure& structure);
/// Throws nearshore::Error naming `structures[i]` and the key for a missing or out-of-range value.
void from_json(const nlohmann::json& in, CoastalStructure& structure);

}  // namespace nearshore
