#pragma once
// WaveStatistics: the maps coastal modellers expect from a run (issue 19), accumulated by the bake
// at EVERY solver step after time.spin_up_s, not from the frames: an extreme (the envelope, the
// run-up) falls between frames (a crest sampled every T/16 is read up to 1 - cos(pi/16) = 2 % low),
// and a bake keeps far fewer frames than steps. Written as DIR/wave_statistics.tif, and the run-up
// line also as lines in DIR/wave_statistics_runup.geojson (docs/formats/wave-statistics.md);
// `nearshore export --to geotiff` maps the frames instead.
//
//   maximum surface elevation   the envelope: max over the steps of eta in each cell while it is
//                               wet (total depth d + eta > solver.dry_depth_m), metres above still
//                               water; undefined (nodata) where the cell was never wet.
//   significant wave height     Hs = 4 sqrt(m0) over the steps (core/elevation_moments.hpp, the
//                               definition `export` uses on frames too).
//   mean surface elevation      the time mean of eta (set-up and set-down), metres.
//   run-up line                 the wet/dry front at its furthest reach: every cell that was ever
//                               wet and touches (4-neighbours) a cell that never was, with the
//                               highest water level it reached (on a beach: the inundation limit;
//                               at a quay wall: the highest level against the wall).
//   run-up                      R = the highest water level of any cell landward of the still-water
//                               shoreline (still-water depth d <= 0) while it was wet, with its
//                               place and ground elevation: the definition of Synolakis (1987) and
//                               of the NTHMP benchmarks (docs/validation.md).
// Hs and the mean are kept for water cells (d > 0); land never wet is nodata in every map.
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "nearshore/core/elevation_moments.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/raster.hpp"

namespace nearshore::bake {

/// The highest point the water reached above the still-water shoreline.
struct RunupPoint {
  double x_m = 0.0, y_m = 0.0;            ///< cell centre, grid frame (origin included), metres
  int column = 0, row = 0;
  double water_level_m = 0.0;              ///< R: surface elevation above still water, metres
  double ground_elevation_m = 0.0;         ///< the cell's ground above still water (-d), metres
};

class WaveStatistics {
 public:
  /// Bytes per grid cell the accumulator holds (for the bake's memory and checkpoint estimates).
  static constexpr double kBytesPerCell = 8 + 8 + 4;

  /// `dry_depth_m`: the solver's wet/dry threshold (SolverParameters::dry_depth_m).
  WaveStatistics(const HarbourGrid& harbour, double dry_depth_m);

  /// Adds one solver step's surface elevation (a raster of the grid's size, row 0 south).
  void add_step(const Raster<float>& surface_elevation_m);
  long step_count() const { return moments_.sample_count(); }

  /// The maps (row 0 south); NaN marks "no value" (never wet, or land for Hs and the mean).
  Raster<float> maximum_surface_elevation_m() const;
  Raster<float> significant_wave_height_m() const;
  Raster<float> mean_surface_elevation_m() const;
  /// The run-up line: the highest water level on each cell of the wet/dry front at its furthest
  /// reach, NaN elsewhere.
  Raster<float> runup_line_water_level_m() const;
  /// R and where it was reached; nullopt when no cell landward of the shoreline was ever wet.
  std::optional<RunupPoint> highest_runup() const;

  /// Binary state for the bake's checkpoint (a resumed bake's maps equal an uninterrupted one's).
  void save(std::ostream& out) const;
  /// Throws nearshore::Error naming `source` when the stored grid differs or the stream ends.
  void load(std::istream& in, const std::string& source);

 private:
  GridGeometry geometry_;
  std::vector<float> still_water_depth_m_;
  double dry_depth_m_;
  ElevationMoments moments_;
  std::vector<float> maximum_m_;  // -infinity until the cell is first wet
};

/// Writes `statistics` as a four-band float32 GeoTIFF (maximum_surface_elevation,
/// significant_wave_height, mean_surface_elevation, runup_line_water_level; nodata -9999),
/// north-up and georeferenced like the harbour grid, atomically (wave_statistics_geotiff.cpp; it and
/// wave_statistics_geojson.cpp are the files of bake/ that include GDAL). `first_time_s`/`last_time_s`
/// are recorded as metadata.
void write_wave_statistics_geotiff(const std::filesystem::path& path, const WaveStatistics& statistics,
                                   const GridGeometry& geometry, double first_time_s, double last_time_s);

/// Writes the run-up line as lines (trace_runup_lines, runup_line.hpp) to a GeoJSON file through
/// GDAL's GeoJSON driver, atomically (wave_statistics_geojson.cpp): one LineString feature per line
/// with a 3-D vertex per front cell (x, y = the cell centre in the grid's CRS, or local metres where
/// the grid has none; z = the highest water level there, metres above still water) and the
/// properties water_level_max_m, water_level_min_m, cells, length_m, closed
/// (docs/formats/wave-statistics.md). `first_time_s`/`last_time_s` go into the file's description.
void write_runup_line_geojson(const std::filesystem::path& path, const WaveStatistics& statistics,
                              const GridGeometry& geometry, double first_time_s, double last_time_s);

}  // namespace nearshore::bake
