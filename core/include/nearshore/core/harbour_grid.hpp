#pragma once
// HarbourGrid: the solver-ready harbour that `nearshore bathy` writes and `nearshore bake` reads
// (docs/formats.md, "Harbour grid"). Stored as one OpenEXR file (depth.exr) with float channels
//   depth            still-water depth d, metres, positive DOWN; land cells hold minus their elevation
//   land             1 where the cell is land at still water, 0 water, 2 no data: outside the chart's
//                    coverage (issue 14 item 3; a reader that knows only land/water sees it as land,
//                    the safe default; the bake decides, [bathymetry] outside_chart)
//   porosity         n of seed 003 eq. (2)-(3): 1 open water, 0 < n < 1 porous structure
//                    (rubble-mound breakwater), 0 a solid vertical wall (quay)
//   coast_distance   signed distance to the coastline, metres, negative on land
//   stone_diameter   optional: the porous resistance's stone diameter D of seed 003 eq. (2)-(3)
//                    (Van Gent 1995) per cell, metres; absent: the solver's one D everywhere
//                    (boussinesq::PorousResistance::stone_diameter_m). The bake writes it where a
//                    structure's fit needed a resistance of its own (bake/structure_layers.hpp).
// and the grid geometry (GridGeometry as JSON) in the header attribute "nearshore_geometry", the
// coastal structures (CoastalStructure as a JSON array, coastal_structure.hpp) in
// "nearshore_structures" (absent in grids written before it: no structures, porosity as stored).
// EXR line 0 is the NORTHERN row (so image viewers show north up); Raster row 0 is the southern
// row; the reader and writer here are the one place that flips.
// Optional, the surroundings (issue 41): the ground round the grid, coarser cells over a larger box
// (HarbourGrid::surroundings), as a second part "surroundings" of the same EXR file (multi-part
// OpenEXR), channel "depth" (NaN: no data, beyond the chart) and its own geometry in
// "nearshore_geometry". The grid stays part 0, so a reader that knows only one part (OpenEXR's
// InputFile reads a multi-part file's first part) reads the grid as before; a file with one part has
// no surroundings.
#include <cstdint>
#include <filesystem>

#include <vector>

#include "nearshore/core/coastal_structure.hpp"
#include "nearshore/core/raster.hpp"

namespace nearshore {

/// Values of HarbourGrid::land. Code that tests `land(c, r)` as a flag treats outside-chart cells as land.
inline constexpr std::uint8_t kWaterCell = 0, kLandCell = 1, kOutsideChartCell = 2;

/// The ground round the harbour grid, for the renderer's land and seabed beyond the grid (the
/// sequence carries it in depth.exr; playback/site_terrain.hpp draws it). Gridded by `nearshore
/// bathy` from the same inputs as the grid (docs/commands/bathy.md, "Surroundings").
struct Surroundings {
  /// Its cells, in the grid's projection (crs_wkt and projection equal to the grid's): a box round
  /// the grid's (read_harbour_grid asks only that they overlap: a bake's resampling may round the
  /// grid's box out by half a cell), with cells several times the grid's. x, y in the same metres.
  GridGeometry geometry;
  /// d, positive down, land = -elevation (as the grid's); NaN where no input says anything (beyond
  /// the chart's coverage or the rasters' extent): there the renderer keeps its own rule.
  Raster<float> still_water_depth_m;
  bool empty() const { return still_water_depth_m.empty(); }
};

struct HarbourGrid {
  GridGeometry geometry;
  Raster<float> still_water_depth_m;  ///< d, positive down; land = -elevation
  Raster<std::uint8_t> land;          ///< kLandCell 1, kWaterCell 0, kOutsideChartCell 2 (no data)
  Raster<float> porosity;             ///< 1 open water .. 0 solid wall
  Raster<float> coast_distance_m;     ///< signed, negative on land
  /// D of the porous resistance per cell, metres (> 0); empty (0 x 0) when every cell takes the
  /// solver's own (boussinesq::PorousResistance::stone_diameter_m). Read only where 0 < n < 1.
  Raster<float> porous_stone_diameter_m;
  /// The structures whose footprints the porosity channel holds, as the chart describes them; the
  /// bake re-lays their porous layers at its own cells and wave period (bake/structure_layers.hpp).
  std::vector<CoastalStructure> structures;
  /// The ground round the grid; empty (no cells) in grids without it (laboratory grids, grids
  /// written before it).
  Surroundings surroundings;

  /// An open-water grid of the given geometry: depth `depth_m` everywhere, porosity 1,
  /// no land, coast distance +infinity. Laboratory cases start from this.
  static HarbourGrid open_water(const GridGeometry& geometry, float depth_m);
};

/// Writes atomically. Throws nearshore::Error naming the path on failure.
void write_harbour_grid(const std::filesystem::path& depth_exr, const HarbourGrid& grid);
/// Reads and validates (channels present, sizes agree, no NaN depth; the surroundings in the grid's
/// projection, overlapping its box, their depths NaN or finite). Throws
/// nearshore::Error naming the file, the problem and where.
HarbourGrid read_harbour_grid(const std::filesystem::path& depth_exr);

}  // namespace nearshore
