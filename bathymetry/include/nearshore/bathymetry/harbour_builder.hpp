#pragma once
// The bathymetry stage in one call: inputs (charts, rasters, soundings, vectors) -> a solver-ready
// HarbourGrid plus a summary of what was done where. `nearshore bathy` and `nearshore demo` both
// call build_harbour_grid and then write_bathymetry_outputs.
//
// Steps (each reported in the summary):
//   1. read every input (sources.hpp); choose the projection (UTM zone of the area, or as asked);
//   2. lay the grid over the bounding box (lon/lat or projected metres; default: all the data),
//      estimating its memory before allocating anything;
//   3. depth per input: rasters resampled bilinearly, scattered data (soundings, contour vertices,
//      depth-area boundaries, coastline at 0 m) by Sibson natural-neighbour interpolation; combined
//      in priority order (the first input that covers a cell wins);
//   4. chart depth areas bound the gridded depth: DRVAL1 <= d <= DRVAL2, dredged areas d >= DRVAL1;
//   5. cells no input covers (outside a chart's M_COVR coverage, beyond a raster) become land, or
//      with fill_uncovered_from_nearest take the depth of the nearest covered cell (counted);
//   6. still water raised by water_level_m above the sounding datum (depths grow by it); land: land
//      polygons and cells with depth <= 0; porosity: structures rasterised with a crest
//      width and porosity per category; signed coastline distance (negative on land);
//   7. conditioning for the Boussinesq solver: minimum depth clamp, optional slope limiting;
//   8. the surroundings (issue 41): steps 3-6 again, on coarser cells over a larger box round the
//      grid (surroundings_geometry), for the renderer's ground beyond the grid; cells no input covers
//      stay NaN (no data), and no conditioning (the solver never sees them).
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nearshore/bathymetry/rasterise.hpp"
#include "nearshore/bathymetry/sources.hpp"
#include "nearshore/core/harbour_grid.hpp"

namespace nearshore::bathymetry {

/// A kind of shoreline structure as engineers describe it: its cross-section and how it treats
/// waves. Becomes a CoastalStructure in the harbour grid (core/coastal_structure.hpp), whose
/// footprint (structure_footprint.hpp) the bake fills with porous layers fitted to the coefficients.
struct StructureStyle {
  double crest_width_m = 10.0;      ///< crest width of line features, metres
  double crest_elevation_m = 2.5;   ///< crest above still water, metres
  double side_slope = 0.0;          ///< horizontal run per unit rise of the faces (0: vertical)
  /// Kr, 0 .. 1; negative: from the bake's sea state by Zanuttigh & van der Meer (2008) with
  /// `roughness_factor` (sloping rubble faces, whose reflection depends on the Iribarren number).
  double reflection_coefficient = 1.0;
  double roughness_factor = 1.0;    ///< gamma_f (EurOtop): 0.40 rock on a permeable core, 0.55 impermeable
  double transmission_coefficient = 0.0;  ///< Kt, 0 .. 1 (0: an impermeable core)
  /// n shown in the harbour grid's preview porosity until the bake fits the faces; 0 .. 1.
  double porosity = 1.0;
};

/// The defaults per category (S-57 SLCONS CATSLC mapped to names in sources.cpp; GeoJSON
/// `category`), with the literature each number is from in harbour_builder.cpp.
std::map<std::string, StructureStyle> default_structure_styles();

/// Depth of a structure's porous faces beyond its core, at least, in cells (structure_footprint.hpp):
/// two cells are the thinnest layer whose porosity can be fitted to a reflection coefficient (one
/// cell has no inside to dissipate in: it acts as a partial wall).
inline constexpr int kMinimumStructureFaceCells = 2;

/// Bound of |BathyRequest::water_level_m|: still water more than 30 m above or below the sounding
/// datum is no tide or surge on Earth (the largest tidal range, the Bay of Fundy's, is 16 m).
inline constexpr double kMaxWaterLevel_m = 30.0;

/// What build_harbour_grid grids. Levels in metres are bounded by what the Earth has: water_level_m
/// within +-kMaxWaterLevel_m, minimum_depth_m in 0 .. kDeepestPlausibleDepth_m, land_elevation_m in
/// 0 .. kHighestPlausibleElevation_m (sources.hpp), and so is every depth the inputs give.
struct BathyRequest {
  std::vector<std::filesystem::path> inputs;  ///< highest priority first
  double spacing_m = 10.0;
  std::optional<std::array<double, 4>> bbox_lon_lat;   ///< lon0, lat0, lon1, lat1
  std::optional<std::array<double, 4>> bbox_projected_m;  ///< x0, y0, x1, y1 in the chosen projection
  DepthSign sign = DepthSign::kAuto;
  std::string text_crs;               ///< CRS of projected x/y in text sounding files
  std::string projection = "utm";     ///< "utm" (zone from the area), "utm:10N", or "local-tm"
  std::map<std::string, StructureStyle> structure_styles = default_structure_styles();
  double water_level_m = 0.0;         ///< still water above the sounding datum (e.g. MSL over MLLW), metres
  double minimum_depth_m = 0.5;       ///< water shallower than this is deepened to it (solver stability)
  double maximum_slope = 0.0;         ///< |grad d| limit for slope smoothing; 0 = off
  double land_elevation_m = 2.0;      ///< elevation given to land cells when no input has one
  bool fill_uncovered_from_nearest = false;  ///< cells no input covers: nearest depth, else land
  double coastline_band_m = 200.0;    ///< half-width of the narrow band stored in coastline.vdb
  double memory_limit_bytes = 0.0;    ///< 0 = the machine's available memory (/proc/meminfo)
  bool leave_one_out = false;         ///< also cross-validate the chart soundings (summary "leave_one_out")
  /// How far the surroundings reach beyond the grid on every side, metres; negative: the grid's
  /// longer side (the box three times the grid's); 0: no surroundings.
  double surroundings_margin_m = -1.0;
};

/// Cells of the surroundings: at least kSurroundingsCellFactor times the grid's, and at most
/// kSurroundingsMaxCells along the box's longer side. The renderer draws them beyond the grid,
/// seen from hundreds of metres to kilometres off, where a cell of 4 grid cells (40-120 m for
/// harbour grids of 10-30 m) is a few pixels; 384 cells a side keep the texture and the skirt's
/// mesh small (147 k cells, 0.6 MB of float) whatever the margin.
inline constexpr double kSurroundingsCellFactor = 4.0;
inline constexpr int kSurroundingsMaxCells = 384;

/// The surroundings' cells round `grid` (its projection, a box grown by `margin_m` on every side,
/// centred on the grid's): see kSurroundingsCellFactor. `margin_m` > 0.
GridGeometry surroundings_geometry(const GridGeometry& grid, double margin_m);

struct BathyResult {
  HarbourGrid grid;
  nlohmann::json summary;                 ///< what summary.json holds (docs/formats/harbour-grid.md)
  std::vector<PlaneLine> coastline_m;     ///< coastline polylines in grid metres, for the preview
  /// True when no input brought a coastline or land outline (a raster or XYZ survey): coastline_m
  /// is then the gridded depth's still-water line (depth 0, still_water_line.hpp).
  bool coastline_from_depth = false;
  std::vector<double> leave_one_out_error_m;  ///< estimate - charted depth per sounding (if asked)
  /// What was done to the data that the caller should know, in words naming the BathyRequest
  /// field that controls it (e.g. water cells raised to minimum_depth_m); also summary "warnings".
  std::vector<std::string> warnings;
};

/// Runs steps 1-8. Throws nearshore::Error (naming the file, the problem and the fix) before
/// anything is written: missing or unreadable input, bbox outside the data, a grid too large for
/// memory, no water cell, ...
BathyResult build_harbour_grid(const BathyRequest& request);

/// A named place drawn on the preview (a case's gauges, its source line), in the grid's projected
/// frame: placed with geo_position.hpp, so a gauge given by lat/lon shows where the bake will put it.
struct PreviewMark {
  std::string name;
  ProjectedPoint point;
};

/// Writes depth.tif, depth.exr, coastline.vdb, preview.png and summary.json into `folder`
/// (created if needed), each atomically. Returns the summary with the output list added. `marks`
/// are drawn on the preview and listed in summary.json `marks` (name, x/y, lon/lat); one on land or
/// outside the chart also adds a sentence to `warnings` (geo_position.hpp's land_warning).
nlohmann::json write_bathymetry_outputs(const std::filesystem::path& folder, const BathyResult& result,
                                        double coastline_band_m = 200.0, const std::vector<PreviewMark>& marks = {});

/// Bytes the grid of `cells` cells needs at the peak of build_harbour_grid (an upper estimate).
double estimated_peak_bytes(double cells, std::size_t input_count);

}  // namespace nearshore::bathymetry
