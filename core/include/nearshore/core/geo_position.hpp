#pragma once
// GeoPosition: a place as a person gives it (issue 14 item 2), in one of three frames, and the one
// road from it to the harbour grid. A case file's gauge or source line, `nearshore bathy --mark`
// and the viewer's --eye/--target (viewer/) all read their positions through parse_geo_position and
// place them with place_in_grid, so they accept the same forms and fail with the same messages. It
// lives in core, beside the grid and the projection it stands on, because both sides use it: the
// bake side (bathymetry/, bake/) and the runtime side (viewer/), which never links bathymetry.
//   x_m, y_m                 metres from the grid's south-west corner (the bake's historic frame);
//   easting_m, northing_m    the grid's own CRS (GridGeometry::crs_wkt: UTM eastings, or the local
//                            transverse Mercator's), as a chart plotter or GIS shows them;
//   lat, lon                 WGS 84 degrees, projected through the grid's MapProjection
//                            (GeographicLib, core/map_projection.hpp; round trip below 1 mm).
// A place outside the grid is an error naming the entry and the grid's extent (in lat/lon when the
// grid has a projection); a place on land or outside the chart is not an error but a warning
// (land_warning), since a camera on a hill is fine and a gauge on a quay is a mistake only the user
// can judge.
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/map_projection.hpp"

namespace nearshore {

struct GeoPosition {
  enum class Frame {
    kFromSouthWestCorner,  ///< first = x_m, second = y_m, metres from the grid's south-west corner
    kGridCrs,              ///< first = easting_m, second = northing_m in the grid's CRS
    kLatLon,               ///< first = latitude_deg, second = longitude_deg (WGS 84)
  };
  Frame frame = Frame::kFromSouthWestCorner;
  double first = 0.0, second = 0.0;
};

/// The key pairs a position may be given with, in Frame order: {"x_m", "y_m"}, {"easting_m",
/// "northing_m"}, {"lat", "lon"}.
const std::vector<std::pair<std::string, std::string>>& geo_position_keys();

/// A position from named numbers (a case-file table's keys, or KEY=VALUE on a command line): exactly
/// one complete pair of geo_position_keys(). `subject` (the case file, the flag) and `entry` (the key
/// or table, e.g. "gauges[2]") name it in messages. Throws nearshore::Error for no pair, two pairs, half
/// a pair, a key it does not know, a latitude beyond +-90 or a longitude beyond +-360 (0..360 is
/// wrapped to -180..180, as NOAA grids give it).
GeoPosition geo_position_from_keys(const std::map<std::string, double>& keys, const std::string& subject,
                                   const std::string& entry);

/// A position from text: "X,Y" (metres from the south-west corner) or "KEY=VALUE,KEY=VALUE" with a
/// pair of geo_position_keys(). `extra_keys` are further numbers the caller takes from the same text
/// (e.g. {"height_m"} for a camera): written as KEY=VALUE, or positionally as the third, fourth...
/// plain number; they are returned in `extras` (absent ones are not set).
GeoPosition parse_geo_position(const std::string& text, const std::string& subject,
                               const std::vector<std::string>& extra_keys = {},
                               std::map<std::string, double>* extras = nullptr);

/// The point in the grid's projected frame (GridGeometry origin included, the solver's frame).
/// Throws nearshore::Error naming `subject` and `entry` when it lies outside the grid (with the
/// grid's extent in lat/lon, or in metres for a laboratory frame), or when lat/lon is given for a
/// grid with no map projection.
/// `inside_only` false (a camera, which may look in from offshore) skips the extent check.
ProjectedPoint place_in_grid(const GeoPosition& position, const GridGeometry& geometry, const std::string& subject,
                             const std::string& entry, bool inside_only = true);

/// "x 1234.5 m, y 678.9 m from the south-west corner (47.27064 N, 122.43450 W)": a point of the
/// grid (projected frame) as a person reads it; the lat/lon part only when the grid has a projection.
std::string describe_grid_point(const GridGeometry& geometry, ProjectedPoint point);

/// The grid's extent for messages: "47.23090..47.32540 N, 122.55199..122.35352 W" (lat/lon of
/// the corners; for a laboratory frame "x 0..1500 m, y 0..900 m from the south-west corner").
std::string describe_grid_extent(const GridGeometry& geometry);

/// A warning when `point` (projected frame) falls in a land cell or a cell outside the chart's
/// coverage (the nearest cell: the one whose area holds the point), naming `entry` and the cell's
/// depth; nullopt on water.
std::optional<std::string> land_warning(const HarbourGrid& grid, ProjectedPoint point, const std::string& subject,
                                        const std::string& entry);

}  // namespace nearshore
