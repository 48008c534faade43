#pragma once
// Where a coastal structure stands on a grid: the cells of its footprint on the bed, split into the
// core (the impermeable wall at its centre line, porosity 0: no flux through it) and the faces (the
// porous layer of seed 003 eq. (2)-(3) that absorbs what the structure does not reflect, or lets
// through what it transmits). `nearshore bathy` lays the faces with a nominal porosity for its
// preview; the bake lays them again at its own cells with the porosity fitted to the structure's
// reflection or transmission coefficient (bake/structure_layers.hpp).
//
// Footprint: a line structure covers the cells whose centres lie within
//   b(d) = crest_width / 2 + side_slope * (crest_elevation + d)
// of its centre line (d the cell's still-water depth: a rubble mound widens with depth), an areal
// one its outline and the cells within side_slope * (crest_elevation + d) outside it. Faces are at
// least `minimum_face_cells` cells deep beyond the core, so even a vertical quay has a layer in
// which its reflection below 1 is absorbed (the porosity-layer technique of MIKE 21 BW and of
// Madsen & Warren's partially reflecting walls).
//
// A structure is impermeable when transmission_coefficient == 0 and no porosity is given: its
// core cells are the ones the centre line crosses (within half a cell diagonal of it, so a chain of
// them never leaves a face between two water cells: the staggered grid's fluxes cross faces only),
// or the inside of its outline. Otherwise every footprint cell is a face.
#include <functional>

#include "nearshore/core/coastal_structure.hpp"
#include "nearshore/core/raster.hpp"

namespace nearshore::bathymetry {

enum class FootprintPart { kCore, kFace };

/// Called once or more per cell (a cell near two segments is visited for each): the caller keeps
/// the core where any visit says core.
using FootprintVisitor = std::function<void(int column, int row, FootprintPart part)>;

/// True when the structure has an impermeable core (see above).
bool has_impermeable_core(const CoastalStructure& structure);

/// Visits the footprint cells of `structure` on the grid of `geometry` whose still-water depths
/// (positive down; land negative) are `still_water_depth_m`.
/// `widening_m` > 0 moves the faces' outer edge that much further out (the bake widens a layer too
/// thin to absorb what its structure does not reflect: bake/structure_layers.hpp).
void for_each_footprint_cell(const GridGeometry& geometry, const Raster<float>& still_water_depth_m,
                             const CoastalStructure& structure, int minimum_face_cells, const FootprintVisitor& visit,
                             double widening_m = 0.0);

}  // namespace nearshore::bathymetry
