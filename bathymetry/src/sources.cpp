#include "nearshore/bathymetry/sources.hpp"

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "depth_readers.hpp"

namespace nearshore::bathymetry {
namespace fs = std::filesystem;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct DatasetCloser {
  void operator()(GDALDataset* dataset) const { GDALClose(dataset); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

void grow_extent(std::array<double, 4>& extent, LonLat p) {
  extent[0] = std::min(extent[0], p.longitude_deg);
  extent[1] = std::min(extent[1], p.latitude_deg);
  extent[2] = std::max(extent[2], p.longitude_deg);
  extent[3] = std::max(extent[3], p.latitude_deg);
}

// --- plausibility bounds (sources.hpp) --------------------------------------------------------------
bool plausible_depth(double depth_m) {
  return depth_m <= kDeepestPlausibleDepth_m && depth_m >= -kHighestPlausibleElevation_m;
}

// "beyond 11000 m, the deepest water on Earth (...)" or the same for heights, for a depth outside the bounds.
std::string plausibility_bound(double depth_m) {
  return depth_m > 0 ? fmt::format("deeper than {:.0f} m, the deepest water on Earth (the Challenger Deep, 10 935 m)",
                                   kDeepestPlausibleDepth_m)
                     : fmt::format("higher than {:.0f} m above the datum, the highest land on Earth (Everest, 8 849 m)",
                                   kHighestPlausibleElevation_m);
}

constexpr const char* kImplausibleDepthFix =
    "such a value is a fill value not declared as nodata, a unit other than metres or a wrong sign: declare "
    "it nodata, convert the file to metres, or check ReadOptions::sign";

// Soundings, contours and depth areas of a vector or S-57 input: the first value outside the bounds.
void check_plausible_vector_depths(const SourceData& data) {
  const auto refuse = [&](const std::string& what, double depth_m, LonLat place) {
    throw Error(data.path.string(),
                fmt::format("{} at lon {:.6f}, lat {:.6f} is {} m (positive down), {}", what, place.longitude_deg,
                            place.latitude_deg, depth_m, plausibility_bound(depth_m)),
                kImplausibleDepthFix);
  };
  for (const Sounding& s : data.soundings)
    if (!plausible_depth(s.depth_m)) refuse("a sounding", s.depth_m, s.place);
  for (const DepthContour& c : data.contours)
    if (!plausible_depth(c.depth_m)) refuse("a depth contour", c.depth_m, c.line.empty() ? LonLat{} : c.line.front());
  for (const auto* areas : {&data.depth_areas, &data.dredged_areas})
    for (const DepthArea& a : *areas) {
      const LonLat corner = a.polygon.rings.empty() || a.polygon.rings.front().empty() ? LonLat{} : a.polygon.rings.front().front();
      if (!plausible_depth(a.shallowest_m)) refuse("a depth area's shallowest depth (DRVAL1)", a.shallowest_m, corner);
      if (std::isfinite(a.deepest_m) && !plausible_depth(a.deepest_m))
        refuse("a depth area's deepest depth (DRVAL2)", a.deepest_m, corner);
    }
}

// --- OGR geometry -> our lon/lat lines, polygons and points --------------------------------------
struct Pieces {
  std::vector<GeoLine> lines;
  std::vector<GeoPolygon> polygons;
  std::vector<std::pair<LonLat, double>> points;  // with z (NaN if 2-D)
};

GeoLine line_of(const OGRSimpleCurve& curve) {
  GeoLine line;
  line.reserve(curve.getNumPoints());
  for (int i = 0; i < curve.getNumPoints(); ++i) line.push_back({curve.getX(i), curve.getY(i)});
  return line;
}

void collect(const OGRGeometry* geometry, Pieces& out) {
  if (!geometry || geometry->IsEmpty()) return;
  switch (wkbFlatten(geometry->getGeometryType())) {
    case wkbPoint: {
      const auto* point = geometry->toPoint();
      out.points.push_back({{point->getX(), point->getY()}, point->Is3D() ? point->getZ() : kNaN});
      break;
    }
    case wkbLineString:
    case wkbLinearRing:
      out.lines.push_back(line_of(*geometry->toLineString()));
      break;
    case wkbPolygon: {
      GeoPolygon polygon;
      for (const auto* ring : *geometry->toPolygon()) polygon.rings.push_back(line_of(*ring));
      out.polygons.push_back(std::move(polygon));
      break;
    }
    case wkbMultiPoint:
    case wkbMultiLineString:
    case wkbMultiPolygon:
    case wkbGeometryCollection:
      for (const auto* part : *geometry->toGeometryCollection()) collect(part, out);
      break;
    default: {  // curves (arcs) and the like: linearise first
      std::unique_ptr<OGRGeometry> linear(geometry->getLinearGeometry());
      if (linear && wkbFlatten(linear->getGeometryType()) != wkbFlatten(geometry->getGeometryType()))
        collect(linear.get(), out);
    }
  }
}

// Reprojects a feature's geometry to WGS 84 lon/lat (traditional GIS order) when its layer has
// another CRS; returns the geometry to read (owned by the feature or by `holder`).
const OGRGeometry* in_lon_lat(OGRFeature& feature, OGRCoordinateTransformation* to_wgs84,
                              std::unique_ptr<OGRGeometry>& holder) {
  const OGRGeometry* geometry = feature.GetGeometryRef();
  if (!geometry || !to_wgs84) return geometry;
  holder.reset(geometry->clone());
  if (holder->transform(to_wgs84) != OGRERR_NONE) return nullptr;
  return holder.get();
}

std::unique_ptr<OGRCoordinateTransformation> transformation_to_wgs84(const OGRSpatialReference* from) {
  if (!from) return nullptr;
  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference source(*from);
  source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (source.IsSame(&wgs84)) return nullptr;
  return std::unique_ptr<OGRCoordinateTransformation>(OGRCreateCoordinateTransformation(&source, &wgs84));
}

double field_or_nan(OGRFeature& feature, const char* name) {
  const int index = feature.GetFieldIndex(name);
  if (index < 0 || !feature.IsFieldSetAndNotNull(index)) return kNaN;
  return feature.GetFieldAsDouble(index);
}

// --- S-57 -----------------------------------------------------------------------------------------
// SLCONS CATSLC (IHO S-57 Object Catalogue, SLCONS) -> our structure categories. Landing steps,
// ramps, slipways and fenders are left out: they do not change how waves pass.
std::string structure_category_of_catslc(int catslc) {
  switch (catslc) {
    case 1: return "breakwater";
    case 2: return "groyne";
    case 3: return "mole";
    case 4: case 5: case 16: return "pier";  // pier, promenade pier, open-face wharf: on piles
    case 6: case 15: return "quay";          // wharf (quay), solid-face wharf: vertical walls
    case 7: return "training_wall";
    case 8: return "riprap";
    case 9: return "revetment";
    case 10: return "sea_wall";
    default: return {};
  }
}

void read_s57(GDALDataset& dataset, SourceData& out) {
  auto layer_features = [&](const char* name, auto&& each) {
    OGRLayer* layer = dataset.GetLayerByName(name);
    if (!layer) return;
    layer->ResetReading();
    for (auto& feature : *layer) each(*feature);
  };
  layer_features("SOUNDG", [&](OGRFeature& f) {
    Pieces pieces;
    collect(f.GetGeometryRef(), pieces);
    const double depth_field = field_or_nan(f, "DEPTH");
    for (const auto& [place, z] : pieces.points) {
      const double depth = std::isfinite(z) ? z : depth_field;
      if (std::isfinite(depth)) out.soundings.push_back({place, depth});
    }
  });
  layer_features("DEPCNT", [&](OGRFeature& f) {
    const double value = field_or_nan(f, "VALDCO");
    if (!std::isfinite(value)) return;  // a contour without a value constrains nothing
    Pieces pieces;
    collect(f.GetGeometryRef(), pieces);
    for (auto& line : pieces.lines) out.contours.push_back({std::move(line), value});
  });
  auto read_areas = [&](const char* name, std::vector<DepthArea>& areas) {
    layer_features(name, [&](OGRFeature& f) {
      const double shallowest = field_or_nan(f, "DRVAL1");
      if (!std::isfinite(shallowest)) return;
      Pieces pieces;
      collect(f.GetGeometryRef(), pieces);
      for (auto& polygon : pieces.polygons) areas.push_back({std::move(polygon), shallowest, field_or_nan(f, "DRVAL2")});
    });
  };
  read_areas("DEPARE", out.depth_areas);
  read_areas("DRGARE", out.dredged_areas);
  layer_features("LNDARE", [&](OGRFeature& f) {
    Pieces pieces;
    collect(f.GetGeometryRef(), pieces);
    for (auto& polygon : pieces.polygons) out.land.push_back(std::move(polygon));
  });
  layer_features("COALNE", [&](OGRFeature& f) {
    Pieces pieces;
    collect(f.GetGeometryRef(), pieces);
    for (auto& line : pieces.lines) out.coastlines.push_back(std::move(line));
  });
  layer_features("SLCONS", [&](OGRFeature& f) {
    const int index = f.GetFieldIndex("CATSLC");
    const int catslc = index >= 0 && f.IsFieldSetAndNotNull(index) ? f.GetFieldAsInteger(index) : 0;
    const std::string category = structure_category_of_catslc(catslc);
    if (category.empty()) return;
    Pieces pieces;
    collect(f.GetGeometryRef(), pieces);
    if (pieces.lines.empty() && pieces.polygons.empty()) return;
    ShoreStructure structure;
    structure.category = category;
    structure.lines = std::move(pieces.lines);
    structure.polygons = std::move(pieces.polygons);
    const int name_index = f.GetFieldIndex("OBJNAM");
    if (name_index >= 0 && f.IsFieldSetAndNotNull(name_index)) structure.name = f.GetFieldAsString(name_index);
    out.structures.push_back(std::move(structure));
  });
  layer_features("M_COVR", [&](OGRFeature& f) {
    const int index = f.GetFieldIndex("CATCOV");
    if (index < 0 || f.GetFieldAsInteger(index) != 1) return;  // 1 = coverage available, 2 = none
    Pieces pieces;
    collect(f.GetGeometryRef(), pieces);
    for (auto& polygon : pieces.polygons) out.coverage.push_back(std::move(polygon));
  });
  if (out.soundings.empty())
    throw Error(out.path.string(), "the S-57 cell has no soundings (layer SOUNDG is empty or missing)",
                "add a survey (GeoTIFF or XYZ soundings) as another input, or use a cell that has SOUNDG");
}

// --- Other vector files: role by `category` property, else by geometry ---------------------------
void read_vector(GDALDataset& dataset, const ReadOptions& options, SourceData& out) {
  for (OGRLayer* layer : dataset.GetLayers()) {
    auto to_wgs84 = transformation_to_wgs84(layer->GetSpatialRef());
    layer->ResetReading();
    for (auto& feature : *layer) {
      std::unique_ptr<OGRGeometry> holder;
      const OGRGeometry* geometry = in_lon_lat(*feature, to_wgs84.get(), holder);
      Pieces pieces;
      collect(geometry, pieces);
      const int category_index = feature->GetFieldIndex("category");
      const std::string category =
          category_index >= 0 && feature->IsFieldSetAndNotNull(category_index)
              ? lower(feature->GetFieldAsString(category_index)) : std::string{};
      const double depth_field = field_or_nan(*feature, "depth");
      for (const auto& [place, z] : pieces.points) {
        // A `depth` property is a depth; a bare z is a height (RFC 7946) unless --sign says otherwise.
        double depth = depth_field;
        if (!std::isfinite(depth) && std::isfinite(z)) depth = options.sign == DepthSign::kPositiveDown ? z : -z;
        if (std::isfinite(depth)) out.soundings.push_back({place, depth});
      }
      if (category.empty() || category == "land" || category == "coastline" || category == "contour") {
        for (auto& polygon : pieces.polygons) out.land.push_back(std::move(polygon));
        for (auto& line : pieces.lines) {
          if (category == "contour" && std::isfinite(depth_field)) out.contours.push_back({std::move(line), depth_field});
          else out.coastlines.push_back(std::move(line));
        }
        continue;
      }
      ShoreStructure structure;
      structure.category = category;
      structure.lines = std::move(pieces.lines);
      structure.polygons = std::move(pieces.polygons);
      const double crest = field_or_nan(*feature, "crest_width_m"), porosity = field_or_nan(*feature, "porosity");
      if (std::isfinite(crest)) structure.crest_width_m = crest;
      if (std::isfinite(porosity)) structure.porosity = porosity;
      structure.crest_elevation_m = field_or_nan(*feature, "crest_elevation_m");
      const double reflection = field_or_nan(*feature, "reflection_coefficient");
      const double transmission = field_or_nan(*feature, "transmission_coefficient");
      if (std::isfinite(reflection)) structure.reflection_coefficient = reflection;
      if (std::isfinite(transmission)) structure.transmission_coefficient = transmission;
      const int name_index = feature->GetFieldIndex("name");
      if (name_index >= 0 && feature->IsFieldSetAndNotNull(name_index)) structure.name = feature->GetFieldAsString(name_index);
      if (!structure.lines.empty() || !structure.polygons.empty()) out.structures.push_back(std::move(structure));
    }
  }
  if (out.soundings.empty() && out.land.empty() && out.coastlines.empty() && out.structures.empty() &&
      out.contours.empty())
    throw Error(out.path.string(), "has no features nearshore can use (no points with depth, lines or polygons)",
                "check the file's layers with ogrinfo");
}

// --- Rasters ----------------------------------------------------------------------------------------
// The sign of a raster's values: as requested, else metadata, else the name of the band or variable.
bool raster_is_depth(GDALDataset& dataset, GDALRasterBand& band, DepthSign sign, std::string& why) {
  if (sign != DepthSign::kAuto) {
    why = "from ReadOptions::sign";
    return sign == DepthSign::kPositiveDown;
  }
  // Our own tag, also as GDAL's netCDF driver renames it (NC_GLOBAL#GDAL_NEARSHORE_DEPTH_SIGN).
  for (char** md = dataset.GetMetadata(); md && *md; ++md) {
    const std::string entry = *md;
    const auto equals = entry.find('=');
    if (equals != std::string::npos && entry.substr(0, equals).ends_with("NEARSHORE_DEPTH_SIGN")) {
      why = "from metadata " + entry;
      return lower(entry.substr(equals + 1)) == "positive_down";
    }
  }
  // NetCDF CF: the variable's `positive` attribute ("down" = depth), band key "positive" or
  // dataset key "<variable>#positive".
  for (char** md : {band.GetMetadata(), dataset.GetMetadata()})
    for (; md && *md; ++md) {
      const std::string entry = lower(*md);
      if (entry.starts_with("positive=") || entry.find("#positive=") != std::string::npos) {
        why = "from NetCDF attribute " + std::string(*md);
        return entry.ends_with("=down");
      }
    }
  const std::string name = lower(std::string(band.GetDescription()) + " " +
                                 (dataset.GetMetadataItem("NETCDF_VARNAME") ? dataset.GetMetadataItem("NETCDF_VARNAME") : ""));
  if (name.find("depth") != std::string::npos) {
    why = "from the band name '" + std::string(band.GetDescription()) + "'";
    return true;
  }
  why = "default for rasters without sign metadata (elevation, as GEBCO); override with ReadOptions::sign";
  return false;
}

// A raster in longitude/latitude that runs east of 180 degrees (NOAA's grids and many NetCDF files
// count longitude 0..360): its geotransform shifted by -360 degrees when it lies wholly east of the
// antimeridian, or its columns rotated to -180..180 when it wraps the whole globe. A regional raster
// that straddles the antimeridian cannot be laid on one UTM grid and is refused.
void wrap_longitudes_to_180(GeoRaster& raster, const fs::path& path) {
  auto& gt = raster.geotransform;
  constexpr double kSlack_deg = 1e-9;
  const double west = gt[0], east = gt[0] + raster.columns * gt[1];
  if (east <= 180.0 + kSlack_deg) return;
  if (west >= 180.0 - kSlack_deg) {
    gt[0] -= 360.0;
    return;
  }
  const double columns_at_180 = (180.0 - west) / gt[1];
  const int split = static_cast<int>(std::lround(columns_at_180));
  const bool whole_globe = std::abs(east - west - 360.0) <= 0.5 * gt[1];
  if (!whole_globe || std::abs(columns_at_180 - split) > 1e-6)
    throw Error(path.string(),
                fmt::format("the raster runs from longitude {:.4f} to {:.4f}, across the antimeridian (180 degrees)",
                            west, east),
                "crop it to one side of 180 degrees (gdal_translate with a -projwin box), or wrap it to "
                "-180..180 with gdalwarp to EPSG:4326 under GDAL's configuration option CENTER_LONG = 0");
  for (int row = 0; row < raster.rows; ++row) {
    const auto first = raster.depth_m.begin() + static_cast<std::ptrdiff_t>(row) * raster.columns;
    std::rotate(first, first + split, first + raster.columns);
  }
  gt[0] = west + split * gt[1] - 360.0;
}

// The fix for a file whose coordinates are metres in a local frame with no CRS (a laboratory flume
// or basin, a survey in site coordinates): the bake reads such a grid directly.
constexpr const char* kLocalGridFix =
    "for a laboratory or survey grid in local metres, name it in a case file's [bathymetry] with "
    "kind = \"local_grid\" (docs/commands/bake.md), which needs no CRS";

// GDAL opens a file cut short after its header (a 300-byte GeoTIFF) and reports what the missing
// tags would have held as missing ("no georeference", issue 44): read the first and the last row,
// whose blocks a cut file lacks, before the georeference is judged. Rows only: cheap for any size.
void require_complete_raster(GDALDataset& dataset, const std::filesystem::path& path) {
  if (dataset.GetRasterCount() < 1 || dataset.GetRasterXSize() < 1 || dataset.GetRasterYSize() < 1)
    throw Error(path.string(), "holds no raster band (the file is empty, truncated or not a raster)",
                "give a GeoTIFF, an ESRI ASCII grid (.asc) or 'x y depth' text (.xyz, .csv, .txt)");
  GDALRasterBand* band = dataset.GetRasterBand(1);
  std::vector<double> row(static_cast<std::size_t>(dataset.GetRasterXSize()));
  for (const int line : {0, dataset.GetRasterYSize() - 1}) {
    CPLErrorReset();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    const CPLErr read = band->RasterIO(GF_Read, 0, line, dataset.GetRasterXSize(), 1, row.data(),
                                       dataset.GetRasterXSize(), 1, GDT_Float64, 0, 0);
    CPLPopErrorHandler();
    if (read != CE_None || CPLGetLastErrorType() >= CE_Failure)
      throw Error(path.string(),
                  fmt::format("is truncated or corrupt: row {} of its {} x {} pixels cannot be read ({})", line,
                              dataset.GetRasterXSize(), dataset.GetRasterYSize(), CPLGetLastErrorMsg()),
                  "copy or download the file again, or regenerate it");
  }
}

void read_raster(GDALDataset& dataset, const ReadOptions& options, SourceData& out) {
  GeoRaster raster;
  raster.columns = dataset.GetRasterXSize();
  raster.rows = dataset.GetRasterYSize();
  require_complete_raster(dataset, out.path);
  if (dataset.GetGeoTransform(raster.geotransform.data()) != CE_None)
    throw Error(out.path.string(), "the raster has no georeference (geotransform)",
                std::string("georeference it first, e.g. gdal_translate -a_srs EPSG:32610 -a_ullr ...; ") + kLocalGridFix);
  if (raster.geotransform[2] != 0.0 || raster.geotransform[4] != 0.0 || raster.geotransform[5] >= 0.0)
    throw Error(out.path.string(), "the raster is rotated or south-up", "warp it north-up with gdalwarp");
  const OGRSpatialReference* crs = dataset.GetSpatialRef();
  if (!crs)
    throw Error(out.path.string(), "the raster has no coordinate reference system",
                std::string("assign one with gdal_edit.py -a_srs; ") + kLocalGridFix);
  if (crs->IsLocal())
    throw Error(out.path.string(), "the raster is in a local engineering frame, not on the Earth",
                std::string(kLocalGridFix) + "; or assign a real CRS with gdal_edit.py -a_srs");
  char* wkt = nullptr;
  crs->exportToWkt(&wkt);
  raster.crs_wkt = wkt ? wkt : "";
  CPLFree(wkt);
  raster.depth_m = detail::read_depth_band(dataset, out.path, options.sign, raster.geotransform, out.sign_used);
  if (crs->IsGeographic()) wrap_longitudes_to_180(raster, out.path);
  const auto& gt = raster.geotransform;
  // Extent in lon/lat from the corners and edge midpoints.
  auto to_wgs84 = transformation_to_wgs84(crs);
  for (double u : {0.0, 0.5, 1.0})
    for (double v : {0.0, 0.5, 1.0}) {
      double x = gt[0] + u * raster.columns * gt[1], y = gt[3] + v * raster.rows * gt[5];
      if (to_wgs84 && !to_wgs84->Transform(1, &x, &y))
        throw Error(out.path.string(), "cannot transform the raster's corners to WGS 84", "check its CRS");
      grow_extent(out.extent_lon_lat, {x, y});
    }
  out.raster = std::move(raster);
}

// --- Text soundings in lon/lat (or in ReadOptions::text_crs) -----------------------------------------
// Soundings read as longitude/latitude that fall within a degree of 0 N 0 E lie in the Gulf of
// Guinea, open ocean 4 000-5 000 m deep (GEBCO) with no coast within 300 km: a file that puts
// depths of less than 1 000 m there counts x and y in metres from a local origin (a flume, a basin,
// a site survey), not in degrees. Read as degrees they would grid a grid thousands of kilometres
// wide, or fail deep in the projection ("Latitude 91d out of legal range").
constexpr double kNullIslandHalfWidth_deg = 1.0;
constexpr double kShallowestOceanNearNullIsland_m = 1000.0;

void read_lon_lat_soundings(const ReadOptions& options, SourceData& out) {
  std::unique_ptr<OGRCoordinateTransformation> to_wgs84;
  if (!options.text_crs.empty()) {
    OGRSpatialReference crs;
    if (crs.SetFromUserInput(options.text_crs.c_str()) != OGRERR_NONE)
      throw Error(out.path.string(), "the CRS '" + options.text_crs + "' is not one GDAL knows", "give it as EPSG:NNNN");
    to_wgs84 = transformation_to_wgs84(&crs);
  }
  const bool elevation = options.sign == DepthSign::kPositiveUp;
  out.sign_used = elevation ? "positive_up (from ReadOptions::sign)"
                            : "positive_down (soundings are depths; override with ReadOptions::sign)";
  const std::vector<detail::TextSounding> soundings = detail::read_text_soundings(out.path, elevation);
  if (!to_wgs84) {
    std::array<double, 4> box{INFINITY, INFINITY, -INFINITY, -INFINITY};
    double deepest_m = -INFINITY;
    for (const auto& s : soundings) {
      box = {std::min(box[0], s.x), std::min(box[1], s.y), std::max(box[2], s.x), std::max(box[3], s.y)};
      deepest_m = std::max(deepest_m, s.depth_m);
    }
    const std::string span = fmt::format("x runs {} .. {} and y {} .. {}", box[0], box[2], box[1], box[3]);
    const bool beyond_the_globe = box[0] < -180.0 || box[2] > 360.0 || box[1] < -90.0 || box[3] > 90.0;
    const bool at_null_island = box[0] <= kNullIslandHalfWidth_deg && box[2] >= -kNullIslandHalfWidth_deg &&
                                box[1] <= kNullIslandHalfWidth_deg && box[3] >= -kNullIslandHalfWidth_deg &&
                                deepest_m < kShallowestOceanNearNullIsland_m;
    if (beyond_the_globe || at_null_island)
      throw Error(out.path.string(),
                  fmt::format("{}, with no CRS given: {}, so these are metres, not longitude/latitude", span,
                              beyond_the_globe ? "that is not a longitude/latitude"
                                               : fmt::format("as degrees they would lie at 0 N 0 E in the Gulf of "
                                                             "Guinea, 4000 m deep, yet the deepest is {} m", deepest_m)),
                  std::string(kLocalGridFix) + "; for a projected survey give its CRS in ReadOptions::text_crs, e.g. EPSG:32610");
  }
  // Longitudes 0..360 (NOAA's convention) wrap to -180..180 where the file uses them.
  for (detail::TextSounding s : soundings) {
    if (to_wgs84) {
      if (!to_wgs84->Transform(1, &s.x, &s.y))
        throw Error(out.path.string(), fmt::format("line {}: cannot transform ({}, {})", s.line, s.x, s.y),
                    "check ReadOptions::text_crs, the CRS of the file's x y");
    } else if (s.x > 180.0) {
      s.x -= 360.0;
    }
    out.soundings.push_back({{s.x, s.y}, s.depth_m});
  }
}

}  // namespace

SourceData read_source(const fs::path& path, const ReadOptions& options) {
  require_readable_file(path, "a chart, raster or vector file");
  GDALAllRegister();
  SourceData out;
  out.path = path;
  out.extent_lon_lat = {INFINITY, INFINITY, -INFINITY, -INFINITY};
  const std::string extension = lower(path.extension().string());
  const bool s57_name = extension.size() == 4 && std::isdigit(static_cast<unsigned char>(extension[1])) &&
                        std::isdigit(static_cast<unsigned char>(extension[2])) && std::isdigit(static_cast<unsigned char>(extension[3]));
  if (extension == ".xyz" || extension == ".csv" || extension == ".txt") {
    out.format = "XYZ";
    read_lon_lat_soundings(options, out);
  } else {
    // S-57: apply the update files, one point per sounding with its depth as an attribute.
    const char* s57_options[] = {"UPDATES=APPLY", "SPLIT_MULTIPOINT=ON", "ADD_SOUNDG_DEPTH=ON", nullptr};
    CPLPushErrorHandler(CPLQuietErrorHandler);
    DatasetPtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr,
                                         s57_name ? s57_options : nullptr));
    CPLPopErrorHandler();
    const std::string driver = dataset ? dataset->GetDriver()->GetDescription() : "";
    if (s57_name && driver != "S57")
      throw Error(path.string(), "is not an S-57 chart (GDAL's S57 driver cannot open it)",
                  "give the base cell of an ENC (*.000, ISO 8211), or rename the file if it is something else");
    if (!dataset)
      throw Error(path.string(), "is not a chart, raster or vector file that GDAL can read",
                  "check the file (gdalinfo / ogrinfo) or convert it to GeoTIFF or GeoJSON");
    out.format = driver == "S57" ? "S-57" : driver;
    if (driver == "S57") read_s57(*dataset, out);
    else if (dataset->GetRasterCount() > 0) read_raster(*dataset, options, out);
    else read_vector(*dataset, options, out);
    check_plausible_vector_depths(out);
  }
  auto grow_lines = [&](const std::vector<GeoLine>& lines) {
    for (const auto& line : lines)
      for (const auto& p : line) grow_extent(out.extent_lon_lat, p);
  };
  for (const auto& polygon : out.coverage) grow_lines(polygon.rings);
  if (!out.coverage.empty()) return out;  // the chart's own statement of where it has data
  for (const auto& s : out.soundings) grow_extent(out.extent_lon_lat, s.place);
  for (const auto& c : out.contours) grow_lines({c.line});
  for (const auto& a : out.depth_areas) grow_lines(a.polygon.rings);
  for (const auto& polygon : out.land) grow_lines(polygon.rings);
  grow_lines(out.coastlines);
  for (const auto& s : out.structures) {
    grow_lines(s.lines);
    for (const auto& polygon : s.polygons) grow_lines(polygon.rings);
  }
  if (!(out.extent_lon_lat[0] <= out.extent_lon_lat[2]))
    throw Error(path.string(), "holds no data with a position", "check the file with gdalinfo / ogrinfo");
  return out;
}

namespace detail {

std::vector<float> read_depth_band(GDALDataset& dataset, const fs::path& path, DepthSign sign,
                                   const std::array<double, 6>& gt, std::string& sign_used) {
  const int columns = dataset.GetRasterXSize(), rows = dataset.GetRasterYSize();
  GDALRasterBand* band = dataset.GetRasterBand(1);
  std::string why;
  const bool is_depth = raster_is_depth(dataset, *band, sign, why);
  sign_used = std::string(is_depth ? "positive_down" : "positive_up") + " (" + why + ")";
  std::vector<float> depth_m(static_cast<std::size_t>(columns) * rows);
  if (band->RasterIO(GF_Read, 0, 0, columns, rows, depth_m.data(), columns, rows, GDT_Float32, 0, 0) != CE_None)
    throw Error(path.string(), std::string("reading the raster failed: ") + CPLGetLastErrorMsg(), "check the file is complete");
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  const bool nan_is_nodata = has_nodata && std::isnan(nodata);
  std::size_t nan_cells = 0, first_nan = 0, implausible_cells = 0, first_implausible = 0;
  float most_implausible = 0.0f;
  for (std::size_t i = 0; i < depth_m.size(); ++i) {
    float& v = depth_m[i];
    if (std::isnan(v)) {
      if (!nan_is_nodata && nan_cells++ == 0) first_nan = i;
      continue;
    }
    if (has_nodata && v == static_cast<float>(nodata)) {
      v = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    if (!is_depth) v = -v;
    if (!plausible_depth(v)) {
      if (implausible_cells++ == 0) first_implausible = i;
      if (std::abs(v) > std::abs(most_implausible)) most_implausible = v;
    }
  }
  // "pixel (c, r), x=... y=... in its CRS" of the cell at row-major index i (row 0 north).
  const auto where = [&](std::size_t i) {
    const double column = i % columns + 0.5, row = i / columns + 0.5;
    return fmt::format("pixel ({}, {}), x={:.1f} y={:.1f} in its CRS", static_cast<int>(column), static_cast<int>(row),
                       gt[0] + column * gt[1], gt[3] + row * gt[5]);
  };
  if (nan_cells > 0)
    throw Error(path.string(),
                fmt::format("{} cells are NaN but the band declares no NaN nodata, the first at {}", nan_cells,
                            where(first_nan)),
                "declare them nodata (gdal_edit.py -a_nodata nan) or fill them (gdal_fillnodata.py)");
  if (implausible_cells > 0)
    throw Error(path.string(),
                fmt::format("{} cells hold depths (positive down, {}) outside {:.0f} .. {:.0f} m, up to {} m: {}; "
                            "the first is {} m at {}",
                            implausible_cells, is_depth ? "as stored" : "the stored elevations negated",
                            -kHighestPlausibleElevation_m, kDeepestPlausibleDepth_m, most_implausible,
                            plausibility_bound(most_implausible), depth_m[first_implausible], where(first_implausible)),
                "such values are a fill value not declared as nodata (gdal_edit.py -a_nodata VALUE), a unit "
                "other than metres, or a wrong sign (ReadOptions::sign)");
  return depth_m;
}

std::vector<TextSounding> read_text_soundings(const fs::path& path, bool elevation) {
  std::ifstream in(path);
  std::vector<TextSounding> soundings;
  std::string text;
  int line_number = 0;
  while (std::getline(in, text)) {
    ++line_number;
    std::replace_if(text.begin(), text.end(), [](char c) { return c == ',' || c == ';' || c == '\t'; }, ' ');
    std::istringstream fields(text);
    double x = 0, y = 0, value = 0;
    if (!(fields >> x >> y >> value)) {
      if (soundings.empty() && line_number == 1) continue;  // a header line
      if (text.find_first_not_of(" \r") == std::string::npos) continue;
      throw Error(path.string(), fmt::format("line {} is not 'x y depth': '{}'", line_number, text),
                  "give three numbers per line");
    }
    if (!std::isfinite(value))
      throw Error(path.string(), fmt::format("line {} has a NaN depth", line_number), "remove the line");
    const double depth_m = elevation ? -value : value;
    if (!plausible_depth(depth_m))
      throw Error(path.string(),
                  fmt::format("line {} gives a depth of {} m (positive down), {}", line_number, depth_m,
                              plausibility_bound(depth_m)),
                  kImplausibleDepthFix);
    soundings.push_back({x, y, depth_m, line_number});
  }
  if (soundings.empty())
    throw Error(path.string(), "has no soundings", "give lines of 'x y depth' (lon lat depth by default)");
  return soundings;
}

}  // namespace detail

}  // namespace nearshore::bathymetry
