#include "nearshore/bathymetry/demo_harbour.hpp"

#include <GeographicLib/UTMUPS.hpp>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/core.h>

#include "nearshore/bathymetry/geotiff.hpp"
#include "nearshore/bathymetry/projection.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bathymetry {
namespace fs = std::filesystem;
namespace {

constexpr double kPi = std::numbers::pi;

// --- The site, in local metres from the south-west corner (x east, y north) -------------------
// A shallow bay: the natural shoreline bows north in the middle.
double natural_shoreline_y_m(double x_m) { return 1010.0 + 50.0 * std::cos(2.0 * kPi * x_m / 1600.0); }
// The quay front of the basin: a vertical wall 40 m seaward of the natural shore.
constexpr double kQuayY_m = 930.0, kQuayWest_m = 520.0, kQuayEast_m = 1080.0;
double shoreline_y_m(double x_m) {
  return (x_m >= kQuayWest_m && x_m <= kQuayEast_m) ? kQuayY_m : natural_shoreline_y_m(x_m);
}
// Breakwater arms (rubble mound): from the shore south to y = 640 m, then towards the entrance.
constexpr double kArmY_m = 640.0, kWestArmX_m = 420.0, kEastArmX_m = 1180.0;
// The harbour entrance: 140 m between the mounds' toes on the 8 m bed (x = 730-870 m); the crest
// heads stand 21.5 m further out, the toe of a 10 m crest at 1:1.5 from +3 m down to -8 m.
constexpr double kEntranceWest_m = 730.0, kEntranceEast_m = 870.0;
constexpr double kCrestWidth_m = 10.0, kCrestElevation_m = 3.0, kArmourSlope = 1.5, kBasinDepth_m = 8.0;
constexpr double kHeadToToe_m = 0.5 * kCrestWidth_m + kArmourSlope * (kCrestElevation_m + kBasinDepth_m);
constexpr double kGapWest_m = kEntranceWest_m - kHeadToToe_m, kGapEast_m = kEntranceEast_m + kHeadToToe_m;
// A detached breakwater across the approach, 160 m south of the entrance (its toe 110 m from the
// arms' toes): no wave from the south sees the entrance directly, every one must bend round one of
// its heads and again into the gap, as harbours facing their waves are built (a straight run from
// the sea to a vertical quay makes a standing wave in the basin whatever the structures reflect).
constexpr double kDetachedY_m = 480.0, kDetachedWest_m = 640.0, kDetachedEast_m = 960.0;

struct LocalPoint {
  double x_m, y_m;
};

std::vector<std::vector<LocalPoint>> breakwater_arms() {
  return {{{kWestArmX_m, natural_shoreline_y_m(kWestArmX_m)}, {kWestArmX_m, kArmY_m}, {kGapWest_m, kArmY_m}},
          {{kEastArmX_m, natural_shoreline_y_m(kEastArmX_m)}, {kEastArmX_m, kArmY_m}, {kGapEast_m, kArmY_m}}};
}

// UTM frame of the site: zone from the centre, origin at the grid's south-west corner.
struct SiteFrame {
  int zone = 0;
  bool northp = true;
  double origin_easting_m = 0, origin_northing_m = 0;

  explicit SiteFrame(const DemoHarbourOptions& o) {
    double easting = 0, northing = 0;
    GeographicLib::UTMUPS::Forward(o.centre_latitude_deg, o.centre_longitude_deg, zone, northp, easting, northing);
    origin_easting_m = easting - 0.5 * o.width_m;
    origin_northing_m = northing - 0.5 * o.height_m;
  }
  std::pair<double, double> lon_lat(const LocalPoint& p) const {
    double latitude = 0, longitude = 0;
    GeographicLib::UTMUPS::Reverse(zone, northp, origin_easting_m + p.x_m, origin_northing_m + p.y_m, latitude,
                                   longitude);
    return {longitude, latitude};
  }
};

void require_gdal_ok(bool ok, const fs::path& path, const std::string& what) {
  if (!ok) throw Error(path.string(), what + ": " + CPLGetLastErrorMsg(), "check the output folder is writable");
}

// A survey grid over the site grown by `margin_m` on every side at `spacing_m`, sampled from the
// analytic depth at cell centres, in the site's UTM frame: depth.tif (no margin) and surroundings.tif.
void write_survey_geotiff(const fs::path& path, const DemoHarbourOptions& o, const SiteFrame& frame, double margin_m,
                          double spacing_m) {
  GridGeometry geometry;
  geometry.columns = static_cast<int>(std::lround((o.width_m + 2 * margin_m) / spacing_m));
  geometry.rows = static_cast<int>(std::lround((o.height_m + 2 * margin_m) / spacing_m));
  geometry.spacing_m = spacing_m;
  geometry.origin_x_m = frame.origin_easting_m - margin_m;
  geometry.origin_y_m = frame.origin_northing_m - margin_m;
  const MapProjection projection = MapProjection::utm(frame.zone, frame.northp);
  geometry.crs_wkt = crs_wkt(projection);
  geometry.projection = projection.to_json();
  Raster<float> depth(geometry.columns, geometry.rows);
  for (int row = 0; row < geometry.rows; ++row)
    for (int column = 0; column < geometry.columns; ++column)
      depth(column, row) = static_cast<float>(
          demo_harbour_depth_m(o, (column + 0.5) * spacing_m - margin_m, (row + 0.5) * spacing_m - margin_m));
  write_depth_geotiff(path, geometry, depth, "mean sea level");
}

// One GeoJSON file with one layer: a feature per geometry, WGS84 lon/lat as RFC 7946 requires.
struct Feature {
  std::unique_ptr<OGRGeometry> geometry;
  std::string category;
  double crest_width_m = 0, crest_elevation_m = 0;
  std::string name;
};

void write_geojson(const fs::path& path, const std::string& layer_name, OGRwkbGeometryType type,
                   std::vector<Feature> features) {
  write_file_atomically(path, [&](const fs::path& temporary) {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GeoJSON");
    require_gdal_ok(driver != nullptr, path, "GDAL has no GeoJSON driver");
    GDALDataset* dataset = driver->Create(temporary.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
    require_gdal_ok(dataset != nullptr, path, "cannot create GeoJSON");
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    const char* layer_options[] = {"RFC7946=YES", "COORDINATE_PRECISION=9", nullptr};
    OGRLayer* layer = dataset->CreateLayer(layer_name.c_str(), &wgs84, type, const_cast<char**>(layer_options));
    require_gdal_ok(layer != nullptr, path, "cannot create layer " + layer_name);
    OGRFieldDefn category("category", OFTString);
    OGRFieldDefn crest("crest_width_m", OFTReal);
    OGRFieldDefn crest_elevation("crest_elevation_m", OFTReal);
    OGRFieldDefn name("name", OFTString);
    layer->CreateField(&category);
    layer->CreateField(&crest);
    layer->CreateField(&crest_elevation);
    layer->CreateField(&name);
    bool ok = true;
    for (auto& f : features) {
      OGRFeature* feature = OGRFeature::CreateFeature(layer->GetLayerDefn());
      feature->SetField("category", f.category.c_str());
      if (f.crest_width_m > 0) feature->SetField("crest_width_m", f.crest_width_m);
      if (f.crest_elevation_m > 0) feature->SetField("crest_elevation_m", f.crest_elevation_m);
      if (!f.name.empty()) feature->SetField("name", f.name.c_str());
      feature->SetGeometry(f.geometry.get());
      ok = ok && layer->CreateFeature(feature) == OGRERR_NONE;
      OGRFeature::DestroyFeature(feature);
    }
    CPLErrorReset();
    GDALClose(dataset);  // void in GDAL 3.6: failures surface through CPLGetLastErrorType
    const bool closed = CPLGetLastErrorType() < CE_Failure;
    require_gdal_ok(ok && closed, path, "writing features failed");
  });
}

std::unique_ptr<OGRLineString> line_string(const SiteFrame& frame, const std::vector<LocalPoint>& points) {
  auto line = std::make_unique<OGRLineString>();
  for (const auto& p : points) {
    auto [longitude, latitude] = frame.lon_lat(p);
    line->addPoint(longitude, latitude);
  }
  return line;
}

// The shoreline traced west to east at 10 m steps, with the quay front's corners kept exactly.
std::vector<LocalPoint> shoreline_points(const DemoHarbourOptions& o) {
  std::vector<LocalPoint> points;
  for (double x = 0; x <= o.width_m + 1e-9; x += 10.0) {
    if (x > kQuayWest_m && points.back().x_m < kQuayWest_m) {
      points.push_back({kQuayWest_m, natural_shoreline_y_m(kQuayWest_m)});
      points.push_back({kQuayWest_m, kQuayY_m});
    }
    if (x > kQuayEast_m && points.back().x_m <= kQuayEast_m && points.back().y_m == kQuayY_m) {
      points.push_back({kQuayEast_m, kQuayY_m});
      points.push_back({kQuayEast_m, natural_shoreline_y_m(kQuayEast_m)});
    }
    points.push_back({x, shoreline_y_m(x)});
  }
  return points;
}

}  // namespace

double demo_harbour_depth_m(const DemoHarbourOptions& o, double x_m, double y_m) {
  (void)o;
  const double shore_y = shoreline_y_m(x_m);
  if (y_m >= shore_y) {
    // Land: a quay top 2.5 m above the water, otherwise a beach rising 1:15 to a 12 m terrace.
    if (x_m >= kQuayWest_m && x_m <= kQuayEast_m && y_m < natural_shoreline_y_m(x_m) + 30.0) return -2.5;
    return -std::min(12.0, (y_m - shore_y) / 15.0);
  }
  // Offshore: 15 m at the southern edge, a concave beach profile d ~ (distance)^(2/3) (Dean 1977)
  // reaching 0 at the natural shoreline.
  const double distance_m = natural_shoreline_y_m(x_m) - y_m;
  double depth = std::min(15.0, 15.0 * std::pow(std::max(distance_m, 0.0) / 900.0, 2.0 / 3.0));
  // An elliptic shoal offshore of the eastern arm (refraction and focusing), cos^2 profile.
  const double r = std::hypot((x_m - 1230.0) / 190.0, (y_m - 380.0) / 130.0);
  if (r < 1.0) depth -= 9.0 * std::pow(std::cos(0.5 * kPi * r), 2);
  // The dredged basin and approach channel inside the breakwaters: 8 m.
  const bool in_basin = x_m > kWestArmX_m && x_m < kEastArmX_m && y_m > kArmY_m - 60.0;
  if (in_basin) depth = std::max(depth, 8.0);
  return std::max(depth, 0.3);
}

DemoHarbourFiles write_demo_harbour(const fs::path& folder, const DemoHarbourOptions& o) {
  if (!(o.width_m > 0 && o.height_m > 0 && o.source_spacing_m > 0 && o.source_spacing_m < o.width_m))
    throw Error("demo harbour", fmt::format("invalid size {} x {} m at {} m spacing", o.width_m, o.height_m,
                                            o.source_spacing_m),
                "use positive sizes larger than the spacing");
  create_output_folder(folder);
  GDALAllRegister();
  const SiteFrame frame(o);
  DemoHarbourFiles files{folder / "depth.tif", folder / "coastline.geojson", folder / "land.geojson",
                         folder / "structures.geojson", folder / "surroundings.tif",
                         {frame.origin_easting_m, frame.origin_northing_m, frame.origin_easting_m + o.width_m,
                          frame.origin_northing_m + o.height_m}};
  write_survey_geotiff(files.depth_geotiff, o, frame, 0.0, o.source_spacing_m);
  if (o.surroundings_margin_m > 0)
    write_survey_geotiff(files.surroundings_geotiff, o, frame, o.surroundings_margin_m, o.surroundings_spacing_m);

  const std::vector<LocalPoint> shore = shoreline_points(o);
  std::vector<Feature> coastline;
  coastline.push_back({line_string(frame, shore), "coastline", 0.0, 0.0, ""});
  write_geojson(files.coastline_geojson, "coastline", wkbLineString, std::move(coastline));

  // Land: the shoreline closed along the northern edge of the grid.
  auto ring = std::make_unique<OGRLinearRing>();
  std::vector<LocalPoint> land_outline = shore;
  land_outline.push_back({o.width_m, o.height_m});
  land_outline.push_back({0.0, o.height_m});
  land_outline.push_back(shore.front());
  for (const auto& p : land_outline) {
    auto [longitude, latitude] = frame.lon_lat(p);
    ring->addPoint(longitude, latitude);
  }
  auto polygon = std::make_unique<OGRPolygon>();
  polygon->addRingDirectly(ring.release());
  std::vector<Feature> land;
  land.push_back({std::move(polygon), "land", 0.0, 0.0, ""});
  write_geojson(files.land_geojson, "land", wkbPolygon, std::move(land));

  // Structures: the two rubble-mound arms (their reflection from the sea state, Zanuttigh & van der
  // Meer 2008; an impermeable core) and the vertical quay front with its two returns to the shore
  // (Kr 0.95): kinds and defaults in bathymetry's style table (harbour_builder.cpp).
  std::vector<Feature> structures;
  const char* arm_names[] = {"west breakwater", "east breakwater"};
  for (std::size_t i = 0; i < breakwater_arms().size(); ++i)
    structures.push_back({line_string(frame, breakwater_arms()[i]), "rubble_mound_breakwater", kCrestWidth_m, kCrestElevation_m, arm_names[i]});
  structures.push_back({line_string(frame, {{kDetachedWest_m, kDetachedY_m}, {kDetachedEast_m, kDetachedY_m}}), "rubble_mound_breakwater",
                        kCrestWidth_m, kCrestElevation_m, "detached breakwater"});
  const std::vector<LocalPoint> quay_front = {{kQuayWest_m, natural_shoreline_y_m(kQuayWest_m)},
                                              {kQuayWest_m, kQuayY_m},
                                              {kQuayEast_m, kQuayY_m},
                                              {kQuayEast_m, natural_shoreline_y_m(kQuayEast_m)}};
  structures.push_back({line_string(frame, quay_front), "vertical_quay", 0.0, 0.0, "quay"});
  write_geojson(files.structures_geojson, "structures", wkbLineString, std::move(structures));
  return files;
}

}  // namespace nearshore::bathymetry
