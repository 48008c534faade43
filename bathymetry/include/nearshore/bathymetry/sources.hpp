#pragma once
// What `nearshore bathy` reads, each through GDAL/OGR, into one plain description in WGS 84
// longitude/latitude (before any projection):
//   S-57 ENC cells (.000 with its update files .001... applied): SOUNDG, DEPCNT, DEPARE, DRGARE,
//     LNDARE, COALNE, SLCONS;
//   gridded depth or elevation (any GDAL raster: GeoTIFF, NetCDF, ESRI ASCII grid, ...);
//   vector files (GeoJSON, Shapefile, GeoPackage...): land polygons, coastlines, breakwaters and
//     quays (by a `category` property), soundings as 3-D points or with a `depth` property;
//   scattered soundings as text (.xyz, .csv, .txt): x y depth per line, lon/lat unless a CRS is given.
#include <array>
#include <filesystem>
#include <optional>
#include <limits>
#include <string>
#include <vector>

#include "nearshore/bathymetry/projection.hpp"

namespace nearshore::bathymetry {

/// Plausibility bounds of every depth an input gives (metres, positive down, after its sign is
/// applied): no water on Earth is deeper than the Challenger Deep (10 935 m) and no land higher than
/// Everest (8 849 m). A value beyond them is a nodata value that is not declared as such, a wrong
/// unit or a wrong sign; gridded as a depth it would make the bake's time step vanish (a 6e28 m
/// deep cell gave a 1e-14 s step).
inline constexpr double kDeepestPlausibleDepth_m = 11000.0;
inline constexpr double kHighestPlausibleElevation_m = 9000.0;

/// How the values of a raster or text sounding file are signed.
enum class DepthSign {
  kAuto,          ///< from metadata (NEARSHORE_DEPTH_SIGN, NetCDF `positive`, band name); else see read_source
  kPositiveDown,  ///< depths: 12 means 12 m below the datum
  kPositiveUp,    ///< elevations: -12 means 12 m below the datum (GEBCO, most DEMs)
};

using GeoLine = std::vector<LonLat>;  ///< a polyline, or a ring of a polygon

struct GeoPolygon {
  std::vector<GeoLine> rings;  ///< outer ring first, then holes
};

struct Sounding {
  LonLat place;
  double depth_m = 0.0;  ///< positive down, from the sounding datum
};

struct DepthContour {
  GeoLine line;
  double depth_m = 0.0;  ///< VALDCO
};

/// A depth area (DEPARE) or dredged area (DRGARE): the depth inside lies in [shallowest, deepest].
struct DepthArea {
  GeoPolygon polygon;
  double shallowest_m = 0.0;  ///< DRVAL1 (negative: drying above the datum)
  double deepest_m = 0.0;     ///< DRVAL2; NaN when the chart gives none (open below)
};

/// A breakwater, quay, pier... as lines (rasterised with a crest width) or polygons (filled).
/// Each number left negative (or NaN) takes the category's default (harbour_builder.hpp, StructureStyle).
struct ShoreStructure {
  std::string category;  ///< breakwater, groyne, mole, pier, quay, sea_wall, riprap, revetment, ...
  std::vector<GeoLine> lines;
  std::vector<GeoPolygon> polygons;
  double crest_width_m = 0.0;  ///< from the feature (GeoJSON crest_width_m); 0 = use the category default
  double porosity = -1.0;      ///< from the feature; negative = fit the porosity to the coefficients
  std::string name;            ///< GeoJSON `name`, S-57 OBJNAM; empty = "<category> <index>"
  double crest_elevation_m = std::numeric_limits<double>::quiet_NaN();  ///< GeoJSON crest_elevation_m
  double reflection_coefficient = -1.0;    ///< GeoJSON reflection_coefficient (Kr, 0 .. 1)
  double transmission_coefficient = -1.0;  ///< GeoJSON transmission_coefficient (Kt, 0 .. 1)
};

/// A north-up raster in its own CRS (GDAL geotransform, no rotation), values as depth positive down.
struct GeoRaster {
  int columns = 0, rows = 0;
  std::array<double, 6> geotransform{};  ///< GDAL: x = gt0 + col*gt1, y = gt3 + row*gt5 (row 0 north)
  std::string crs_wkt;
  std::vector<float> depth_m;  ///< row-major, row 0 NORTH; NaN where the source had no data
};

struct SourceData {
  std::filesystem::path path;
  std::string format;         ///< "S-57", "XYZ" or the GDAL driver's short name
  std::string sign_used;      ///< for rasters and text: "positive_down" or "positive_up", and why
  std::vector<Sounding> soundings;
  std::vector<DepthContour> contours;
  std::vector<DepthArea> depth_areas;    ///< DEPARE
  std::vector<DepthArea> dredged_areas;  ///< DRGARE (deepest_m usually NaN)
  std::vector<GeoLine> coastlines;
  std::vector<GeoPolygon> land;
  std::vector<ShoreStructure> structures;
  std::optional<GeoRaster> raster;
  std::vector<GeoPolygon> coverage;  ///< where the source has data (S-57 M_COVR CATCOV=1); empty = its whole extent
  std::array<double, 4> extent_lon_lat{};  ///< lon_min, lat_min, lon_max, lat_max of everything read (or of the coverage)
};

struct ReadOptions {
  DepthSign sign = DepthSign::kAuto;
  std::string text_crs;  ///< CRS of x/y in text sounding files ("EPSG:32610"); empty = lon/lat
};

/// Reads one input. Throws nearshore::Error naming the file, the problem and the fix: missing
/// file, nothing GDAL can read, a .000 that is not an S-57 chart, an S-57 cell with no soundings,
/// raster cells that are NaN without being declared nodata, an empty file, and any depth, sounding,
/// contour or depth-area value deeper than kDeepestPlausibleDepth_m or higher than
/// kHighestPlausibleElevation_m (the message gives the value, where it is, and the bound).
/// Sign default when nothing says: rasters are elevations (GEBCO's convention), text soundings depths.
SourceData read_source(const std::filesystem::path& path, const ReadOptions& options);

}  // namespace nearshore::bathymetry
