#pragma once
// The harbour site's ground and structures as the renderer draws them, built on the CPU from the
// sequence's harbour grid (no GL here, so a test or another renderer can use it):
//  - the ground: one height field over the site and a skirt beyond it. Inside the site its
//    elevation is z = -d(x, y), d the still-water depth interpolated bilinearly between the cell
//    centres (the same interpolation the water's mask uses, surface.glsl), sampled on a lattice
//    through the cell centres with up to 2 vertices per cell, so its still-water line is the
//    bilinear depth's zero contour: a smooth line, not the cells' staircase;
//  - the skirt: beyond the grid's edges the ground continues from the edge's elevation (smoothed
//    along the edge more the further out), land standing at its edge height out to the skirt's
//    end (as far as the sea is drawn: the land meets the sky at the horizon), water deepening to
//    the open sea's depth; no cut-off slab. Where the grid carries surroundings (HarbourGrid::
//    surroundings: the chart's ground round the grid, `nearshore bathy`), the skirt takes their
//    ground instead, turning to it over two of their cells from the grid's edge and back to the
//    edge's rule over four cells towards where they end (no data beyond the chart, or their box);
//  - the structures: extruded from the CoastalStructure geometry the grid carries (centre lines a
//    crest width wide, polygons' outer rings) up to their crest, with faces sloped at their side
//    slope (rubble) or vertical (side slope 0: quays, piers, walls) down to the bed. A grid
//    without that geometry (written before it) raises its porous cells (porosity < 1) to a
//    crest along the structure indicator's smooth half-level contour instead;
//  - the structures' dry mask: 1 where a structure stands above still water, on texels over the
//    site rectangle (finer than the cells where the geometry is known), which the water's mask
//    reads (surface.glsl, is_dry) so no water is drawn inside them.
#include <cstdint>
#include <vector>

#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/raster.hpp"

namespace nearshore::playback {

/// What a terrain vertex is made of (TerrainMesh::vertices' last float); the shader shades ground
/// by height, slope and distance inland, the two structure kinds as rock and concrete.
enum class TerrainMaterial : int { ground = 0, rubble = 1, concrete = 2 };

/// The skirt's default reach beyond the grid (m): the water grids' (RadialGridSettings::
/// outer_radius_m, QuadtreeSettings::reach_m), so land beyond the edge goes on as far as the sea.
inline constexpr double kDefaultSkirtWidthM = 100000.0;

/// The surroundings as the skirt reads them: the twin of the RG texture surface.glsl samples
/// (u_surroundings). Per cell of HarbourGrid::surroundings, the weight w (0 on cells without data
/// and on the box's outer cells, rising to 1 over kSurroundingsFadeCells cells inwards) and w times
/// the elevation (-depth); both read bilinearly, the elevation is their quotient, so cells without
/// data never enter it.
struct SurroundingGround {
  GridGeometry cells;                  ///< their cells, origin in the site frame (from the grid's south-west corner)
  Raster<float> weighted_elevation_m;  ///< w * elevation, metres up from still water
  Raster<float> weight;                ///< w, 0 .. 1
  /// How far beyond the grid's edge the skirt has turned from the edge's rule to the surroundings
  /// (two of their cells: the grid's edge and their cells there hold the same chart).
  double edge_blend_m = 0.0;
  bool empty() const { return weight.empty(); }
};

/// Cells over which the surroundings' weight rises from 0 at their last cell with data to 1.
inline constexpr int kSurroundingsFadeCells = 4;

/// The surroundings of `harbour` as the skirt reads them; empty when it has none.
SurroundingGround surrounding_ground(const HarbourGrid& harbour);

struct TerrainOptions {
  /// The crest, above still water, of structures known only by their porous cells (metres).
  double cell_structure_crest_m = 2.5;
  /// The ground lattice inside the site holds at most this squared vertices: cells are cut in two
  /// each way when that fits, strided (every 2nd, 3rd.. centre) when even one vertex a cell does not.
  int max_lattice_vertices = 700;
  /// How far the skirt reaches beyond the grid, metres; <= 0: max(kDefaultSkirtWidthM, the site's
  /// longer side).
  double skirt_width_m = -1.0;
  /// The depth the ground beyond the grid reaches under water (the renderer's open-sea depth).
  double open_sea_depth_m = 20.0;
};

struct TerrainMesh {
  /// Per vertex: x_m, y_m (site frame: from the grid's south-west corner), z_m (up from still
  /// water), inland_m (distance from the still-water line, positive on land), material.
  static constexpr int kFloatsPerVertex = 5;
  std::vector<float> vertices;
  std::vector<std::uint32_t> indices;  ///< three per triangle
  /// Texels over the site rectangle, texel (i, j) centred at ((i + 0.5) W / columns, (j + 0.5) H /
  /// rows): 1 inside a structure's outline at still water, 0 elsewhere; read bilinearly, > 0.5 dry.
  Raster<float> structure_mask;
  std::size_t ground_vertex_count = 0;  ///< the first vertices are the ground's lattice
  double skirt_width_m = 0.0;
  /// The surroundings the skirt was built on (empty without): the shader's u_surroundings.
  SurroundingGround surroundings;
};

/// The ground's elevation at a site point inside the grid (metres up from still water): minus the
/// still-water depth interpolated bilinearly between cell centres, clamped to the outer centres.
double ground_elevation_m(const HarbourGrid& harbour, double x_m, double y_m);

/// The skirt's ground at a site point beyond the grid (metres up from still water): the edge's
/// ground averaged along the edge over +-the distance beyond (at most a quarter of the shorter
/// side); land (average above still water) stays at that height, water deepens to
/// `open_sea_depth_m` over the site's extent, blended by the average from -1 to 1 m. Where
/// `surroundings` has data, that rule turns to their ground: weight w(p) * smoothstep(0,
/// edge_blend_m, distance beyond). The twin of shaders/surface.glsl skirt_ground_m, where the sea
/// is not drawn over the skirt's land.
double skirt_ground_m(const HarbourGrid& harbour, const SurroundingGround& surroundings, double open_sea_depth_m,
                      double x_m, double y_m);

/// Builds the ground, skirt and structures of `harbour` (see the top of this file).
TerrainMesh build_site_terrain(const HarbourGrid& harbour, const TerrainOptions& options = {});

}  // namespace nearshore::playback
