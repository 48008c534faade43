#pragma once
// The run-up line as polylines (issue 19): the cells of the wet/dry front at its furthest reach
// (WaveStatistics::runup_line_water_level_m, band 4 of wave_statistics.tif) chained in order along
// the shore, so that a GIS or a coastal modeller gets lines, not a scatter of cells
// (DIR/wave_statistics_runup.geojson, docs/formats/wave-statistics.md). No GDAL here: the writer is
// wave_statistics_geojson.cpp.
//
// How the cells are chained: by following the cracks between ever-wet and never-wet cells, the
// "crack following" of binary-image contour tracing (Rosenfeld & Kak 1982, "Digital Picture
// Processing", 2nd ed., vol. 2, on the borders of a region; the boundary marching squares draws).
// Every crack (a cell side with an ever-wet cell on one hand and a never-wet cell on the other) is
// walked with the never-wet side on the LEFT and the water on the right, the convention of
// OpenStreetMap's natural=coastline (so a ring round an island runs anticlockwise, a ring round a
// flooded hollow clockwise). The wet cell of each crack in turn, repeats dropped, is the line. Why
// cracks and not a walk over the front cells' 8-neighbours:
//   - the order and the side are those of the shore itself: a walk over cells has to choose at every
//     cell where the front is two cells thick (a staircase, a corner), cracks never do;
//   - a one-cell creek is followed up one bank and down the other, as a shore is, instead of
//     splitting the coast into three pieces at a junction;
//   - every front cell lies on a crack by definition (it is ever wet with a never-wet 4-neighbour),
//     so the lines' vertices are exactly the band's cells, none invented, none lost.
// The grid's edge is no shore (the water goes on beyond it; WaveStatistics says the same), so a
// crack path that reaches the edge ends there: an open line. A path that closes on itself is a ring.
// Where two wet cells touch only at a corner between two never-wet cells, the line passes through
// the corner from one to the other (the water is taken as 8-connected there, the land as
// 4-connected), which keeps the two cells consecutive, as they are along the shore.
#include <vector>

#include "nearshore/core/raster.hpp"

namespace nearshore::bake {

/// One vertex of a run-up line: a front cell (row 0 south) and the highest water level it reached.
struct RunupVertex {
  int column = 0, row = 0;
  float water_level_m = 0.0f;  ///< metres above still water (the band's value)
  bool operator==(const RunupVertex&) const = default;
};

/// A chain of front cells in order along the shore, never-wet ground on the left.
struct RunupLine {
  /// Consecutive vertices are 4- or 8-neighbours; a cell may come twice where the shore doubles
  /// back (both banks of a one-cell creek). A ring does not repeat its first vertex at the end.
  std::vector<RunupVertex> vertices;
  bool closed = false;  ///< a ring (round an island or a hollow): the last vertex joins the first

  float highest_water_level_m() const;
  float lowest_water_level_m() const;
  /// Distinct cells along the line.
  int cell_count() const;
  /// Length through the cell centres (the closing segment of a ring included), metres.
  double length_m(const GridGeometry& geometry) const;
};

/// Traces the run-up line. `runup_line_water_level_m` is the front (NaN elsewhere) and
/// `maximum_surface_elevation_m` the envelope (NaN where never wet), both of one WaveStatistics
/// (row 0 south, the grid's size). Lines come in the order their first crack is met scanning the
/// grid row by row from the south-west; an open line starts where it leaves the grid's edge, a ring
/// at its south-westernmost crack. Throws nearshore::Error when the rasters differ in size or a
/// cell the envelope puts on the front has no value in the front raster.
std::vector<RunupLine> trace_runup_lines(const Raster<float>& runup_line_water_level_m,
                                         const Raster<float>& maximum_surface_elevation_m);

}  // namespace nearshore::bake
