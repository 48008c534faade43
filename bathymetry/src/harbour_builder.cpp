#include "nearshore/bathymetry/harbour_builder.hpp"

#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include <fmt/core.h>

#include "nearshore/bathymetry/coastline_level_set.hpp"
#include "nearshore/bathymetry/still_water_line.hpp"
#include "nearshore/bathymetry/structure_footprint.hpp"
#include "nearshore/bathymetry/distance_transform.hpp"
#include "nearshore/bathymetry/geotiff.hpp"
#include "nearshore/bathymetry/natural_neighbour.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/output_folder.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/geo_position.hpp"
#include "nearshore/core/map_projection.hpp"
#include "nearshore/plot/plot.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::bathymetry {
namespace fs = std::filesystem;
namespace {

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();
constexpr std::uint8_t kNoSource = 255;

// --- Projection and grid ----------------------------------------------------------------------------
MapProjection choose_projection(const std::string& spec, LonLat centre) {
  if (spec == "utm") return MapProjection::utm_for(centre);
  if (spec == "local-tm") return MapProjection::local_transverse_mercator(centre);
  if (spec.starts_with("utm:") && spec.size() >= 6) {
    const char hemisphere = static_cast<char>(std::toupper(static_cast<unsigned char>(spec.back())));
    try {
      const int zone = std::stoi(spec.substr(4, spec.size() - 5));
      if (hemisphere == 'N' || hemisphere == 'S') return MapProjection::utm(zone, hemisphere == 'N');
    } catch (const std::logic_error&) {
    }
  }
  throw Error("BathyRequest::projection = '" + spec + "'", "is not a projection nearshore knows",
              "use utm, utm:10N (zone and hemisphere) or local-tm");
}

double available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024.0;
  return 8.0 * 1024 * 1024 * 1024;  // unknown: assume a modest 8 GiB
}

// The grid over a box in projected metres, from its south-west corner (so a grid over a survey
// raster at a multiple of its cell size lines up with it). Memory is checked before any allocation.
GridGeometry lay_grid(const std::array<double, 4>& box_m, double spacing_m, const MapProjection& projection,
                      const BathyRequest& request) {
  GridGeometry g;
  g.spacing_m = spacing_m;
  g.origin_x_m = box_m[0];
  g.origin_y_m = box_m[1];
  // The box rounded up to whole cells (a micrometre of slack so 1600 m / 20 m stays 80 cells).
  const double columns = std::ceil((box_m[2] - g.origin_x_m) / spacing_m - 1e-9);
  const double rows = std::ceil((box_m[3] - g.origin_y_m) / spacing_m - 1e-9);
  const double cells = columns * rows;
  const double needed = estimated_peak_bytes(cells, request.inputs.size());
  const double available = request.memory_limit_bytes > 0 ? request.memory_limit_bytes : available_memory_bytes();
  const bool area_given = request.bbox_lon_lat || request.bbox_projected_m;  // name a box only when given
  if (needed > available || columns > 1e9 || rows > 1e9)
    throw Error(fmt::format("grid of {:.0f} x {:.0f} cells at {} m", columns, rows, spacing_m),
                fmt::format("would need about {:.3g} GB of memory but {:.3g} GB are available", needed / 1e9, available / 1e9),
                fmt::format("use a BathyRequest::spacing_m of about {:.3g} m or more, or {} BathyRequest::bbox_lon_lat",
                            spacing_m * std::sqrt(needed / available) * 1.05,
                            area_given ? "a smaller" : "grid part of the data with"));
  if (columns < 2 || rows < 2)
    throw Error(fmt::format("grid at {} m", spacing_m), fmt::format("has only {:.0f} x {:.0f} cells", columns, rows),
                area_given ? "use a finer BathyRequest::spacing_m or a larger BathyRequest::bbox_lon_lat"
                           : "use a finer BathyRequest::spacing_m: the data cover less than two cells");
  g.columns = static_cast<int>(columns);
  g.rows = static_cast<int>(rows);
  g.crs_wkt = crs_wkt(projection);
  g.projection = projection.to_json();
  return g;
}

// Projected bounding box of a lon/lat box: its outline sampled densely (a UTM grid is rotated
// against meridians and parallels, so the corners alone are not enough).
std::array<double, 4> projected_box(const std::array<double, 4>& lon_lat, const MapProjection& projection) {
  std::array<double, 4> box{INFINITY, INFINITY, -INFINITY, -INFINITY};
  for (int k = 0; k <= 64; ++k) {
    const double t = k / 64.0;
    for (LonLat p : {LonLat{lon_lat[0] + t * (lon_lat[2] - lon_lat[0]), lon_lat[1]},
                     LonLat{lon_lat[0] + t * (lon_lat[2] - lon_lat[0]), lon_lat[3]},
                     LonLat{lon_lat[0], lon_lat[1] + t * (lon_lat[3] - lon_lat[1])},
                     LonLat{lon_lat[2], lon_lat[1] + t * (lon_lat[3] - lon_lat[1])}}) {
      const ProjectedPoint q = projection.forward(p);
      box = {std::min(box[0], q.x_m), std::min(box[1], q.y_m), std::max(box[2], q.x_m), std::max(box[3], q.y_m)};
    }
  }
  return box;
}

// Where a source's data lie in the grid's projection: a raster's own outline (exact when it is in
// the same CRS), otherwise the outline of its lon/lat extent.
std::array<double, 4> projected_extent(const SourceData& source, const MapProjection& projection) {
  if (!source.raster) return projected_box(source.extent_lon_lat, projection);
  const GeoRaster& raster = *source.raster;
  OGRSpatialReference raster_crs, wgs84;
  raster_crs.importFromWkt(raster.crs_wkt.c_str());
  raster_crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_wgs84(OGRCreateCoordinateTransformation(&raster_crs, &wgs84));
  OGRSpatialReference grid_crs;
  grid_crs.importFromWkt(crs_wkt(projection).c_str());
  const bool same_crs = grid_crs.IsSame(&raster_crs);
  const auto& gt = raster.geotransform;
  std::array<double, 4> box{INFINITY, INFINITY, -INFINITY, -INFINITY};
  for (int k = 0; k <= 64; ++k) {
    const double t = k / 64.0;
    for (auto [u, v] : {std::pair{t, 0.0}, {t, 1.0}, {0.0, t}, {1.0, t}}) {
      double x = gt[0] + u * raster.columns * gt[1], y = gt[3] + v * raster.rows * gt[5];
      if (!same_crs) {
        if (!to_wgs84 || !to_wgs84->Transform(1, &x, &y))
          throw Error(source.path.string(), "cannot transform the raster's outline to WGS 84", "check its CRS");
        const ProjectedPoint p = projection.forward({x, y});
        x = p.x_m, y = p.y_m;
      }
      box = {std::min(box[0], x), std::min(box[1], y), std::max(box[2], x), std::max(box[3], y)};
    }
  }
  return box;
}

// --- Projected geometry -----------------------------------------------------------------------------
PlaneLine project_line(const GeoLine& line, const MapProjection& projection) {
  PlaneLine out;
  out.reserve(line.size());
  for (const auto& p : line) out.push_back(projection.forward(p));
  return out;
}

std::vector<PlaneLine> project_polygon(const GeoPolygon& polygon, const MapProjection& projection) {
  std::vector<PlaneLine> rings;
  for (const auto& ring : polygon.rings) rings.push_back(project_line(ring, projection));
  return rings;
}

// Vertices along a line at most `step_m` apart (the constraint densification of natural_neighbour.hpp).
void densify(const PlaneLine& line, double step_m, double depth_m, std::vector<ScatteredDepth>& out) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    out.push_back({line[i].x_m, line[i].y_m, depth_m});
    if (i + 1 == line.size()) break;
    const double dx = line[i + 1].x_m - line[i].x_m, dy = line[i + 1].y_m - line[i].y_m;
    const int pieces = static_cast<int>(std::ceil(std::hypot(dx, dy) / step_m));
    for (int k = 1; k < pieces; ++k)
      out.push_back({line[i].x_m + dx * k / pieces, line[i].y_m + dy * k / pieces, depth_m});
  }
}

// --- Depth from a raster: bilinear where the four neighbours have data, nearest where only that has ---
Raster<float> resample_raster(const GeoRaster& raster, const GridGeometry& g, const MapProjection& projection) {
  OGRSpatialReference grid_crs, raster_crs;
  grid_crs.importFromWkt(g.crs_wkt.c_str());
  raster_crs.importFromWkt(raster.crs_wkt.c_str());
  grid_crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  raster_crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_raster;
  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const bool same_crs = grid_crs.IsSame(&raster_crs);
  if (!same_crs) to_raster.reset(OGRCreateCoordinateTransformation(&wgs84, &raster_crs));
  const auto& gt = raster.geotransform;
  auto value = [&](int column, int row) -> float {
    if (column < 0 || row < 0 || column >= raster.columns || row >= raster.rows) return kNaNf;
    return raster.depth_m[static_cast<std::size_t>(row) * raster.columns + column];
  };
  Raster<float> depth(g.columns, g.rows, kNaNf);
  std::vector<double> xs(g.columns), ys(g.columns);
  for (int row = 0; row < g.rows; ++row) {
    for (int column = 0; column < g.columns; ++column) {
      xs[column] = g.cell_centre_x_m(column);
      ys[column] = g.cell_centre_y_m(row);
      if (!same_crs) {
        const LonLat p = projection.reverse({xs[column], ys[column]});
        xs[column] = p.longitude_deg;
        ys[column] = p.latitude_deg;
      }
    }
    if (to_raster) to_raster->Transform(g.columns, xs.data(), ys.data());
    for (int column = 0; column < g.columns; ++column) {
      // Fractional pixel position measured from pixel centres.
      const double u = (xs[column] - gt[0]) / gt[1] - 0.5, v = (ys[column] - gt[3]) / gt[5] - 0.5;
      const int i = static_cast<int>(std::floor(u)), j = static_cast<int>(std::floor(v));
      const double fu = u - i, fv = v - j;
      const float a = value(i, j), b = value(i + 1, j), c = value(i, j + 1), d = value(i + 1, j + 1);
      if (std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && std::isfinite(d))
        depth(column, row) = static_cast<float>((1 - fv) * ((1 - fu) * a + fu * b) + fv * ((1 - fu) * c + fu * d));
      else
        depth(column, row) = value(static_cast<int>(std::lround(u)), static_cast<int>(std::lround(v)));
    }
  }
  return depth;
}

// --- Scattered chart data ---------------------------------------------------------------------------
struct ScatteredInput {
  std::vector<ScatteredDepth> points;  // soundings first (they win over coincident constraint vertices)
  std::size_t sounding_count = 0;
  std::size_t contour_vertices = 0, depth_area_vertices = 0, coastline_vertices = 0;
};

bool inside_box(const ProjectedPoint& p, const std::array<double, 4>& box) {
  return p.x_m >= box[0] && p.x_m <= box[2] && p.y_m >= box[1] && p.y_m <= box[3];
}

// Depth-area boundary vertices shared by two or more areas lie on the contour between them, whose
// value is the deeper area's DRVAL1 (= the shallower one's DRVAL2): the maximum DRVAL1 of the areas
// sharing the vertex. S-57 areas share edges exactly (one spatial record), so coordinates match bit for bit.
void add_depth_area_vertices(const std::vector<DepthArea>& areas, const MapProjection& projection,
                             const std::array<double, 4>& box, ScatteredInput& out) {
  struct Shared {
    int areas = 0;
    double value = -INFINITY;
    const void* last_area = nullptr;
  };
  std::map<std::pair<double, double>, Shared> vertices;
  for (const auto& area : areas)
    for (const auto& ring : area.polygon.rings)
      for (const auto& p : ring) {
        Shared& s = vertices[{p.longitude_deg, p.latitude_deg}];
        if (s.last_area != &area) ++s.areas;  // a ring's closing vertex repeats the first
        s.last_area = &area;
        s.value = std::max(s.value, area.shallowest_m);
      }
  for (const auto& [place, shared] : vertices) {
    if (shared.areas < 2) continue;
    const ProjectedPoint p = projection.forward({place.first, place.second});
    if (!inside_box(p, box)) continue;
    out.points.push_back({p.x_m, p.y_m, shared.value});
    ++out.depth_area_vertices;
  }
}

ScatteredInput gather_scattered(const SourceData& source, const std::vector<SourceData>& all,
                                const MapProjection& projection, const GridGeometry& g) {
  // Data a little outside the grid still shapes the surface at its edges.
  const double margin = 20.0 * g.spacing_m;
  const std::array<double, 4> box{g.origin_x_m - margin, g.origin_y_m - margin, g.origin_x_m + g.width_m() + margin,
                                  g.origin_y_m + g.height_m() + margin};
  ScatteredInput out;
  for (const auto& s : source.soundings) {
    const ProjectedPoint p = projection.forward(s.place);
    if (inside_box(p, box)) out.points.push_back({p.x_m, p.y_m, s.depth_m});
  }
  out.sounding_count = out.points.size();
  auto add_line = [&](const GeoLine& line, double depth, std::size_t& counter) {
    const std::size_t before = out.points.size();
    std::vector<ScatteredDepth> dense;
    densify(project_line(line, projection), g.spacing_m, depth, dense);
    for (const auto& d : dense)
      if (inside_box({d.x_m, d.y_m}, box)) out.points.push_back(d);
    counter += out.points.size() - before;
  };
  for (const auto& c : source.contours) add_line(c.line, c.depth_m, out.contour_vertices);
  add_depth_area_vertices(source.depth_areas, projection, box, out);
  // The coastline (and land outlines) of every input is a depth-0 constraint.
  for (const auto& other : all) {
    for (const auto& line : other.coastlines) add_line(line, 0.0, out.coastline_vertices);
    for (const auto& polygon : other.land)
      for (const auto& ring : polygon.rings) add_line(ring, 0.0, out.coastline_vertices);
  }
  return out;
}

// --- Reports of changed cells -----------------------------------------------------------------------
struct ChangeReport {
  std::size_t cells = 0;
  double max_change_m = 0.0;
  int column_min = std::numeric_limits<int>::max(), row_min = std::numeric_limits<int>::max(), column_max = -1, row_max = -1;
  int worst_column = -1, worst_row = -1;

  void record(int column, int row, double change_m) {
    ++cells;
    column_min = std::min(column_min, column), column_max = std::max(column_max, column);
    row_min = std::min(row_min, row), row_max = std::max(row_max, row);
    if (worst_column < 0 || std::abs(change_m) > max_change_m) max_change_m = std::abs(change_m), worst_column = column, worst_row = row;
  }
  nlohmann::json to_json(const GridGeometry& g, const MapProjection& projection) const {
    nlohmann::json j{{"cells", cells}, {"max_change_m", max_change_m}};
    if (cells == 0) return j;
    j["x_range_m"] = {g.origin_x_m + column_min * g.spacing_m, g.origin_x_m + (column_max + 1) * g.spacing_m};
    j["y_range_m"] = {g.origin_y_m + row_min * g.spacing_m, g.origin_y_m + (row_max + 1) * g.spacing_m};
    const LonLat worst = projection.reverse({g.cell_centre_x_m(worst_column), g.cell_centre_y_m(worst_row)});
    j["largest_change_at"] = {{"column", worst_column}, {"row", worst_row}, {"lon", worst.longitude_deg},
                              {"lat", worst.latitude_deg}};
    return j;
  }
};

double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(std::min<double>(values.size() - 1, q * values.size()))];
}

// The fix when every cell came out land. A raster read as elevations by default (no sign in its
// metadata) whose values are in fact depths is the usual cause: every depth negated is land. Only a
// box the caller gave is named (issue 19: "check --bbox" was said when no box was given).
std::string every_cell_land_fix(const std::vector<SourceData>& sources, const BathyRequest& request) {
  std::vector<std::string> fixes;
  for (const SourceData& source : sources)
    if ((source.raster || !source.soundings.empty()) && source.sign_used.starts_with("positive_up"))
      fixes.push_back(fmt::format("{} was read as elevations, positive up{}: if its values are depths (positive "
                                  "down), set BathyRequest::sign to DepthSign::kPositiveDown",
                                  source.path.filename().string(), source.sign_used.substr(std::string_view("positive_up").size())));
  if (request.bbox_lon_lat || request.bbox_projected_m)  // only a box the caller gave
    fixes.emplace_back("move BathyRequest::bbox_lon_lat (or BathyRequest::bbox_projected_m) over water");
  if (request.water_level_m < 0.0)
    fixes.push_back(fmt::format("BathyRequest::water_level_m = {} m lowers still water below the datum; raise it",
                                request.water_level_m));
  if (fixes.empty())
    fixes.emplace_back("check that the inputs give depths below the datum (positive down) somewhere in the area: "
                       "every cell is at or above still water");
  std::string text;
  for (const auto& fix : fixes) text += (text.empty() ? "" : "; or ") + fix;
  return text;
}

// The warning when the minimum depth raised water cells (issue 19: a whole 0.45 m laboratory basin
// was silently flattened to the 0.5 m default). Says how many, by how much, and how to keep them.
std::string minimum_depth_warning(std::size_t raised_cells, std::size_t water_cells, double shallowest_m,
                                  double largest_raise_m, double minimum_depth_m) {
  const double share = water_cells > 0 ? 100.0 * static_cast<double>(raised_cells) / static_cast<double>(water_cells) : 0.0;
  return fmt::format("{} of {} water cells ({:.1f} %) were shallower than BathyRequest::minimum_depth_m = {} m and "
                     "were raised to it, by up to {:.3g} m (the shallowest was {:.3g} m){}; to keep the depths as "
                     "given, lower BathyRequest::minimum_depth_m (0 keeps every wet cell as it is)",
                     raised_cells, water_cells, share, minimum_depth_m, largest_raise_m, shallowest_m,
                     share > 50.0 ? ": most of the water changed depth" : "");
}

}  // namespace

std::map<std::string, StructureStyle> default_structure_styles() {
  // Cross-sections: conventional rubble mounds have 1:1.5 - 1:2 armour slopes and crests 2-4 m
  // above high water (CEM, USACE 2002, Part VI-2); quays stand ~2.5 m above mean water.
  // Reflection: sloping rock faces by Zanuttigh & van der Meer (2008), Kr = tanh(a xi^b) with
  // gamma_f 0.40 on a permeable core (breakwaters, groynes, training walls) and 0.55 on an
  // impermeable one (revetments, riprap) (reflection_coefficient < 0: computed by the bake from the
  // sea state it makes); vertical walls 0.9-1.0 (Goda 2000, Table 6.1; CEM II-7: 0.7-1.0), 0.95
  // taken; perforated (wave-absorbing) caissons 0.3-0.6 (Tanimoto et al. 1982), 0.5 taken.
  // Transmission: conventional emerged mounds and walls 0 (d'Angremond et al. 1996 give Kt at its
  // lower bound 0.075 for crests well above the waves: overtopping, which a porous layer cannot
  // make); a pier on piles passes most of a wave: Kt 0.9 (Hayashi et al. 1966 for piles three
  // diameters apart), its reflection what a layer of that transmission gives.
  StructureStyle rubble_mound{20.0, 3.0, 1.5, -1.0, 0.40, 0.0, 0.45};
  StructureStyle groyne{8.0, 1.5, 1.5, -1.0, 0.40, 0.0, 0.45};
  StructureStyle training_wall{5.0, 1.5, 1.5, -1.0, 0.40, 0.0, 0.45};
  StructureStyle revetment{5.0, 2.0, 2.0, -1.0, 0.55, 0.0, 0.5};
  // The nominal porosity (last) is what the preview shows until the bake fits the faces: for
  // vertical kinds the faces are the numerical layer in front of the wall, mostly open water.
  StructureStyle vertical{10.0, 2.5, 0.0, 0.95, 1.0, 0.0, 0.9};
  StructureStyle absorbing_quay{10.0, 2.5, 0.0, 0.5, 1.0, 0.0, 0.7};
  StructureStyle pier{6.0, 2.5, 0.0, 0.1, 1.0, 0.9, 0.9};
  return {{"breakwater", rubble_mound},     {"rubble_mound_breakwater", rubble_mound},
          {"groyne", groyne},               {"training_wall", training_wall},
          {"riprap", revetment},            {"revetment", revetment},
          {"mole", {15.0, 3.0, 0.0, 0.95, 1.0, 0.0, 0.9}},
          {"quay", vertical},               {"vertical_quay", vertical},
          {"sea_wall", {5.0, 3.0, 0.0, 0.95, 1.0, 0.0, 0.9}},
          {"wave_absorbing_quay", absorbing_quay}, {"pier", pier}};
}

GridGeometry surroundings_geometry(const GridGeometry& grid, double margin_m) {
  const double width_m = grid.width_m() + 2 * margin_m, height_m = grid.height_m() + 2 * margin_m;
  GridGeometry g = grid;
  g.rectangular_spacing_y_m = 0.0;  // square cells
  g.spacing_m = std::max(kSurroundingsCellFactor * std::max(grid.spacing_x_m(), grid.spacing_y_m()),
                         std::max(width_m, height_m) / kSurroundingsMaxCells);
  g.columns = std::max(2, static_cast<int>(std::ceil(width_m / g.spacing_m - 1e-9)));
  g.rows = std::max(2, static_cast<int>(std::ceil(height_m / g.spacing_m - 1e-9)));
  // Centred on the grid's box (whole cells hold it and the margin, a little more where they round up).
  g.origin_x_m = grid.origin_x_m + 0.5 * grid.width_m() - 0.5 * g.width_m();
  g.origin_y_m = grid.origin_y_m + 0.5 * grid.height_m() - 0.5 * g.height_m();
  return g;
}

double estimated_peak_bytes(double cells, std::size_t input_count) {
  // Per cell: depth, porosity, distance (3 x 4 B), land and masks (3 x 1 B), bounds (8 B), one
  // float layer per input, the distance transform's working set (column pass 8 + 4 B, result 12 B,
  // two results kept 8 B), the EXR and GeoTIFF line copies (5 x 4 B). Rounded up to 96 + 4/input.
  return cells * (96.0 + 4.0 * static_cast<double>(input_count));
}

namespace {

// --- The steps of build_harbour_grid, in order ------------------------------------------------------

// Step 0: the request's own numbers, checked before any file is opened, so a mistyped level fails in
// a second and not after minutes of gridding. Levels in metres are bounded by what the Earth has
// (sources.hpp) and, for the still-water level above the sounding datum, by the largest tides and
// surges (Bay of Fundy: 16 m range).
void check_request(const BathyRequest& request) {
  if (request.inputs.empty())
    throw Error("BathyRequest::inputs", "is empty", "name at least one chart, raster or sounding file");
  if (!(request.spacing_m > 0))
    throw Error(fmt::format("BathyRequest::spacing_m = {}", request.spacing_m), "is not a positive cell size",
                "give the cell size in metres, e.g. 10");
  const auto check_level = [](const char* field, double value_m, double lowest_m, double highest_m, const char* why) {
    if (!(value_m >= lowest_m && value_m <= highest_m))
      throw Error(fmt::format("BathyRequest::{} = {} m", field, value_m),
                  fmt::format("is outside {:.0f} .. {:.0f} m ({})", lowest_m, highest_m, why),
                  fmt::format("give BathyRequest::{} in metres, inside those bounds", field));
  };
  check_level("water_level_m", request.water_level_m, -kMaxWaterLevel_m, kMaxWaterLevel_m,
              "still water above the sounding datum; the largest tidal range on Earth, the Bay of Fundy's, is 16 m");
  check_level("minimum_depth_m", request.minimum_depth_m, 0.0, kDeepestPlausibleDepth_m,
              "no water is deeper than the Challenger Deep, 10 935 m");
  check_level("land_elevation_m", request.land_elevation_m, 0.0, kHighestPlausibleElevation_m,
              "no land is higher than Everest, 8 849 m");
}

// Every input read (sources.hpp), in the caller's priority order, and the lon/lat box they cover
// together (the default area, and what a box outside the data is told it missed).
struct ChartInputs {
  std::vector<SourceData> sources;
  std::array<double, 4> extent_lon_lat{INFINITY, INFINITY, -INFINITY, -INFINITY};
};

// Step 1: reads every input. Takes the request (paths, sign, text CRS); gives the sources. Throws
// when none of them holds a depth: coastlines, land and structures alone leave nothing to grid.
ChartInputs read_chart_inputs(const BathyRequest& request) {
  ChartInputs inputs;
  const ReadOptions read_options{request.sign, request.text_crs};
  std::array<double, 4>& data_extent = inputs.extent_lon_lat;
  for (const auto& path : request.inputs) {
    inputs.sources.push_back(read_source(path, read_options));
    const auto& e = inputs.sources.back().extent_lon_lat;
    data_extent = {std::min(data_extent[0], e[0]), std::min(data_extent[1], e[1]), std::max(data_extent[2], e[2]),
                   std::max(data_extent[3], e[3])};
  }
  const bool has_depth = std::any_of(inputs.sources.begin(), inputs.sources.end(), [](const SourceData& s) {
    return s.raster.has_value() || !s.soundings.empty() || !s.contours.empty();
  });
  if (!has_depth)
    throw Error(request.inputs.front().string(), "no input holds depths (only coastlines, land or structures)",
                "add a chart, a depth raster or soundings");
  return inputs;
}

// The map projection and the grid laid in it.
struct GridFrame {
  MapProjection projection;
  GridGeometry geometry;
};

// Step 2: chooses the projection (at the centre of the area) and lays the grid over the area: the
// box asked for (lon/lat or projected metres), else where the depth-bearing inputs are (coastline or
// structure files may reach further). Takes the request and the inputs; gives the frame. Throws for
// a box that is empty or misses the data, and (lay_grid) for a grid too large for memory.
GridFrame lay_grid_frame(const BathyRequest& request, const ChartInputs& inputs) {
  const std::array<double, 4>& data_extent = inputs.extent_lon_lat;
  std::array<double, 4> lon_lat_box = request.bbox_lon_lat.value_or(data_extent);
  if (request.bbox_lon_lat) {
    const auto& b = *request.bbox_lon_lat;
    if (!(b[0] < b[2] && b[1] < b[3]))
      throw Error(fmt::format("BathyRequest::bbox_lon_lat = {},{},{},{}", b[0], b[1], b[2], b[3]),
                  "is empty or reversed", "give LON0,LAT0,LON1,LAT1 with LON0 < LON1 and LAT0 < LAT1");
    if (b[2] <= data_extent[0] || b[0] >= data_extent[2] || b[3] <= data_extent[1] || b[1] >= data_extent[3])
      throw Error(fmt::format("BathyRequest::bbox_lon_lat = {},{},{},{}", b[0], b[1], b[2], b[3]),
                  fmt::format("lies outside the data, which covers lon {:.5f}..{:.5f}, lat {:.5f}..{:.5f}", data_extent[0],
                              data_extent[2], data_extent[1], data_extent[3]),
                  "give a box that overlaps the inputs, or leave BathyRequest::bbox_lon_lat unset to grid all of them");
  }
  const LonLat centre{0.5 * (lon_lat_box[0] + lon_lat_box[2]), 0.5 * (lon_lat_box[1] + lon_lat_box[3])};
  const MapProjection projection = choose_projection(request.projection, centre);
  std::array<double, 4> data_box_m{INFINITY, INFINITY, -INFINITY, -INFINITY};
  for (const auto& source : inputs.sources) {
    if (!source.raster && source.soundings.empty() && source.contours.empty()) continue;
    const auto b = projected_extent(source, projection);
    data_box_m = {std::min(data_box_m[0], b[0]), std::min(data_box_m[1], b[1]), std::max(data_box_m[2], b[2]),
                  std::max(data_box_m[3], b[3])};
  }
  std::array<double, 4> box_m = request.bbox_projected_m.value_or(
      request.bbox_lon_lat ? projected_box(*request.bbox_lon_lat, projection) : data_box_m);
  if (request.bbox_projected_m) {
    const auto& b = box_m;
    if (!(b[0] < b[2] && b[1] < b[3]) || b[2] <= data_box_m[0] || b[0] >= data_box_m[2] || b[3] <= data_box_m[1] ||
        b[1] >= data_box_m[3])
      throw Error(fmt::format("BathyRequest::bbox_projected_m = {},{},{},{}", b[0], b[1], b[2], b[3]),
                  fmt::format("is empty or lies outside the data, which covers x {:.0f}..{:.0f} m, y {:.0f}..{:.0f} m in {}",
                              data_box_m[0], data_box_m[2], data_box_m[1], data_box_m[3], projection.describe()),
                  "give X0,Y0,X1,Y1 in metres overlapping the data");
  }
  return {projection, lay_grid(box_m, request.spacing_m, projection, request)};
}

// What the chart's depth areas say per cell: DRVAL1 <= d <= DRVAL2 (NaN where no area says), and
// whether the cell lies in an area that is wet at the datum.
struct DepthAreaBounds {
  Raster<float> lower_m, upper_m;
  Raster<std::uint8_t> chart_water;  // inside a depth area that is never dry
};

// The depth-area and dredged-area bounds of every input rasterised on the grid (step 4 applies them;
// leave-one-out cross-validation bounds its estimates by them too). Overlapping areas narrow the band:
// the deepest DRVAL1 and the shallowest DRVAL2. Dredged areas are dredged to at least DRVAL1.
DepthAreaBounds rasterise_depth_area_bounds(const std::vector<SourceData>& sources, const GridGeometry& g,
                                            const MapProjection& projection) {
  DepthAreaBounds bounds{Raster<float>(g.columns, g.rows, kNaNf), Raster<float>(g.columns, g.rows, kNaNf),
                         Raster<std::uint8_t>(g.columns, g.rows, 0)};
  Raster<float>& lower = bounds.lower_m;
  Raster<float>& upper = bounds.upper_m;
  Raster<std::uint8_t>& chart_water = bounds.chart_water;
  for (const auto& source : sources) {
    for (const auto& area : source.depth_areas) {
      const auto rings = project_polygon(area.polygon, projection);
      for_each_cell_in_polygon(g, rings, [&](int c, int r) {
        lower(c, r) = std::isnan(lower(c, r)) ? float(area.shallowest_m) : std::max(lower(c, r), float(area.shallowest_m));
        if (std::isfinite(area.deepest_m))
          upper(c, r) = std::isnan(upper(c, r)) ? float(area.deepest_m) : std::min(upper(c, r), float(area.deepest_m));
        if (area.shallowest_m >= 0.0) chart_water(c, r) = 1;
      });
    }
    for (const auto& area : source.dredged_areas) {
      const auto rings = project_polygon(area.polygon, projection);
      for_each_cell_in_polygon(g, rings, [&](int c, int r) {
        lower(c, r) = std::isnan(lower(c, r)) ? float(area.shallowest_m) : std::max(lower(c, r), float(area.shallowest_m));
        if (area.shallowest_m >= 0.0) chart_water(c, r) = 1;
      });
    }
  }
  return bounds;
}

// The land polygons of every input rasterised (1 = land). They come before the depth: scattered
// interpolation skips them, and they start the land mask of step 6.
Raster<std::uint8_t> rasterise_land_polygons(const std::vector<SourceData>& sources, const GridGeometry& g,
                                             const MapProjection& projection) {
  Raster<std::uint8_t> land_polygons(g.columns, g.rows, 0);
  for (const auto& source : sources)
    for (const auto& polygon : source.land)
      for_each_cell_in_polygon(g, project_polygon(polygon, projection), [&](int c, int r) { land_polygons(c, r) = 1; });
  return land_polygons;
}

// Leave-one-out cross-validation of a chart's soundings: each removed in turn, interpolated from the
// rest and bounded by the depth areas as the grid is. Appends estimate - charted depth per sounding
// to `errors_m` (BathyResult::leave_one_out_error_m); gives the input's summary entry.
nlohmann::json cross_validate_soundings(NaturalNeighbourSurface& surface, const ScatteredInput& scattered,
                                        const GridGeometry& g, const DepthAreaBounds& bounds,
                                        std::vector<double>& errors_m) {
  ProgressBar progress("leave-one-out", static_cast<double>(scattered.sounding_count), "soundings");
  std::vector<double> absolute;
  for (std::size_t k = 0; k < scattered.sounding_count; ++k) {
    const ScatteredDepth& s = scattered.points[k];
    double estimate = surface.leave_one_out(k);
    const int c = static_cast<int>(std::floor((s.x_m - g.origin_x_m) / g.spacing_m));
    const int r = static_cast<int>(std::floor((s.y_m - g.origin_y_m) / g.spacing_m));
    if (!std::isfinite(estimate) || c < 0 || r < 0 || c >= g.columns || r >= g.rows) continue;
    if (std::isfinite(bounds.lower_m(c, r))) estimate = std::max<double>(estimate, bounds.lower_m(c, r));
    if (std::isfinite(bounds.upper_m(c, r))) estimate = std::min<double>(estimate, bounds.upper_m(c, r));
    errors_m.push_back(estimate - s.depth_m);
    absolute.push_back(std::abs(estimate - s.depth_m));
    if (k % 64 == 0) progress.update(static_cast<double>(k));
  }
  progress.finish();
  return {{"soundings", absolute.size()},
          {"median_absolute_error_m", median(absolute)},
          {"p90_absolute_error_m", percentile(absolute, 0.9)}};
}

// Step 3 for a chart or soundings file: its soundings, contour vertices, depth-area boundaries and
// every input's coastline at 0 m (gather_scattered) interpolated by Sibson natural neighbours on the
// grid's cells, except land polygons and cells outside the input's coverage (M_COVR). Records the
// counts in `info` (the input's summary entry); with leave_one_out also cross-validates the
// soundings. Gives the input's depth layer (NaN where it says nothing). Throws when the input has no
// sounding or contour inside the grid's area.
Raster<float> interpolate_scattered_depth(const SourceData& source, const std::vector<SourceData>& sources,
                                          const GridGeometry& g, const MapProjection& projection,
                                          const Raster<std::uint8_t>& land_polygons, const DepthAreaBounds& bounds,
                                          const BathyRequest& request, nlohmann::json& info,
                                          std::vector<double>& leave_one_out_error_m) {
  const bool area_given = request.bbox_lon_lat || request.bbox_projected_m;  // messages name a box only when given
  ScatteredInput scattered = gather_scattered(source, sources, projection, g);
  info["soundings_used"] = scattered.sounding_count;
  info["contour_vertices"] = scattered.contour_vertices;
  info["depth_area_vertices"] = scattered.depth_area_vertices;
  info["coastline_vertices"] = scattered.coastline_vertices;
  if (scattered.sounding_count == 0 && scattered.contour_vertices == 0)
    throw Error(source.path.string(), "has no soundings or contours inside the grid's area",
                area_given ? "widen BathyRequest::bbox_lon_lat (or BathyRequest::bbox_projected_m), or drop this input"
                           : "drop this input, or give soundings inside the area the other inputs cover");
  NaturalNeighbourSurface surface(scattered.points);
  info["triangulation_vertices"] = surface.vertex_count();
  Raster<float> layer;
  {
    ProgressBar progress("gridding " + source.path.filename().string(), g.rows, "rows");
    Raster<std::uint8_t> skip = land_polygons;
    if (!source.coverage.empty()) {
      Raster<std::uint8_t> inside(g.columns, g.rows, 0);
      for (const auto& polygon : source.coverage)
        for_each_cell_in_polygon(g, project_polygon(polygon, projection), [&](int c, int r) { inside(c, r) = 1; });
      for (std::size_t i = 0; i < skip.size(); ++i) skip.values()[i] |= !inside.values()[i];
    }
    layer = surface.sample(g, &skip, &progress);
  }
  if (request.leave_one_out)
    info["leave_one_out"] = cross_validate_soundings(surface, scattered, g, bounds, leave_one_out_error_m);
  return layer;
}

// The gridded depth before conditioning, and which input gave each cell's depth (kNoSource: none).
struct MergedDepth {
  Raster<float> depth_m;
  Raster<std::uint8_t> source_of_cell;
};

// Step 3: depth per input, merged by priority: the first input (in the caller's order) that gives a
// cell a depth wins it. Rasters are resampled (bilinear, nearest at their edges), charts and soundings
// interpolated; inputs with coastlines, land or structures only give no depth. Appends each input's
// summary entry to `inputs_json` and leave-one-out errors to `leave_one_out_error_m`.
MergedDepth grid_depth_by_priority(const std::vector<SourceData>& sources, const GridFrame& frame,
                                   const Raster<std::uint8_t>& land_polygons, const DepthAreaBounds& bounds,
                                   const BathyRequest& request, nlohmann::json& inputs_json,
                                   std::vector<double>& leave_one_out_error_m) {
  const GridGeometry& g = frame.geometry;
  MergedDepth merged{Raster<float>(g.columns, g.rows, kNaNf), Raster<std::uint8_t>(g.columns, g.rows, kNoSource)};
  Raster<float>& depth = merged.depth_m;
  Raster<std::uint8_t>& source_of_cell = merged.source_of_cell;
  for (std::size_t index = 0; index < sources.size(); ++index) {
    const SourceData& source = sources[index];
    nlohmann::json info{{"path", source.path.string()}, {"format", source.format}, {"priority", index + 1}};
    if (!source.sign_used.empty()) info["sign"] = source.sign_used;
    Raster<float> layer;
    if (source.raster) {
      info["raster_size"] = {source.raster->columns, source.raster->rows};
      layer = resample_raster(*source.raster, g, frame.projection);
    } else if (!source.soundings.empty() || !source.contours.empty()) {
      layer = interpolate_scattered_depth(source, sources, g, frame.projection, land_polygons, bounds, request, info,
                                          leave_one_out_error_m);
    } else {
      inputs_json.push_back(info);
      continue;  // coastlines, land and structures only
    }
    std::size_t covered = 0;
    for (std::size_t i = 0; i < depth.size(); ++i)
      if (source_of_cell.values()[i] == kNoSource && std::isfinite(layer.values()[i])) {
        depth.values()[i] = layer.values()[i];
        source_of_cell.values()[i] = static_cast<std::uint8_t>(std::min<std::size_t>(index, 254));
        ++covered;
      }
    info["cells_taken"] = covered;
    inputs_json.push_back(info);
  }
  return merged;
}

// Step 4: the chart's depth areas bound the gridded depth, DRVAL1 <= d <= DRVAL2; a cell no input
// covered but an area bounds takes the middle of its band. Chart-interpolated and uncovered cells
// only: a survey raster is measured, not bounded. Gives the report of the cells changed.
ChangeReport bound_by_depth_areas(const std::vector<SourceData>& sources, const DepthAreaBounds& bounds,
                                  MergedDepth& merged) {
  Raster<float>& depth = merged.depth_m;
  ChangeReport bounded;
  for (int r = 0; r < depth.rows(); ++r)
    for (int c = 0; c < depth.columns(); ++c) {
      const std::uint8_t s = merged.source_of_cell(c, r);
      if (s != kNoSource && sources[s].raster) continue;
      const float lo = bounds.lower_m(c, r), hi = bounds.upper_m(c, r), d = depth(c, r);
      if (std::isnan(lo) && std::isnan(hi)) continue;
      float bounded_depth = d;
      if (std::isnan(d)) bounded_depth = std::isnan(hi) ? lo : std::isnan(lo) ? hi : 0.5f * (lo + hi);  // no data: mid-band
      if (!std::isnan(lo)) bounded_depth = std::max(bounded_depth, lo);
      if (!std::isnan(hi)) bounded_depth = std::min(bounded_depth, hi);
      if (!(bounded_depth == d)) {
        if (std::isfinite(d)) bounded.record(c, r, bounded_depth - d);
        depth(c, r) = bounded_depth;
      }
    }
  return bounded;
}

// Step 5: cells no input covers (land polygons aside). With fill_uncovered_from_nearest they take the
// depth of the nearest covered cell (the report's change: how far it was carried); otherwise they are
// no data (issue 14 item 3): not land, but outside what the chart says, kept apart in the land
// channel (kOutsideChartCell) so the bake decides ([bathymetry] outside_chart) and the preview shows
// them; a reader that knows only land and water sees land, as before. Throws when no cell is covered.
ChangeReport fill_uncovered_cells(const BathyRequest& request, const GridFrame& frame, Raster<float>& depth,
                                  Raster<std::uint8_t>& land_polygons) {
  const GridGeometry& g = frame.geometry;
  const bool area_given = request.bbox_lon_lat || request.bbox_projected_m;  // messages name a box only when given
  Raster<std::uint8_t> covered(g.columns, g.rows, 0);
  std::size_t covered_cells = 0;
  for (std::size_t i = 0; i < depth.size(); ++i) covered_cells += covered.values()[i] = std::isfinite(depth.values()[i]);
  if (covered_cells == 0)
    throw Error("grid " + frame.projection.describe(), "no input covers any cell of the grid",
                area_given ? "check BathyRequest::bbox_lon_lat or BathyRequest::bbox_projected_m against the inputs' "
                             "extent (gdalinfo / ogrinfo)"
                           : "check that the inputs hold depths where they claim to (gdalinfo / ogrinfo): their "
                             "extent was gridded, yet none gave a depth there");
  ChangeReport uncovered;
  if (covered_cells < depth.size()) {
    std::optional<NearestSeed> nearest;
    if (request.fill_uncovered_from_nearest) nearest = nearest_seed_transform(covered, g.spacing_m);
    for (int r = 0; r < g.rows; ++r)
      for (int c = 0; c < g.columns; ++c) {
        if (covered(c, r) || land_polygons(c, r)) continue;
        if (nearest) {
          depth(c, r) = depth(nearest->nearest_column(c, r), nearest->nearest_row(c, r));
          uncovered.record(c, r, nearest->distance_m(c, r));
        } else {
          land_polygons(c, r) = kOutsideChartCell;
          uncovered.record(c, r, 0.0);
        }
      }
  }
  return uncovered;
}

// Step 6: still water at water_level_m above the sounding datum, from which every depth (and land
// elevation) is then measured; then the land mask: land polygons, and cells at or above still water
// unless a depth area that never dries says water (a depth area with DRVAL1 >= 0 is wet at the
// datum, so wet at any still water above it). Land cells without an elevation from the inputs stand
// land_elevation_m above still water. Takes the land polygons (with step 5's outside-chart cells) in
// `land`; gives the number of land cells. Throws when every cell is land.
std::size_t lay_land_mask(const BathyRequest& request, const std::vector<SourceData>& sources,
                          const GridFrame& frame, const Raster<std::uint8_t>& chart_water, Raster<float>& depth,
                          Raster<std::uint8_t>& land) {
  if (request.water_level_m != 0.0)
    for (float& d : depth.values()) d += static_cast<float>(request.water_level_m);
  std::size_t land_cells = 0;
  for (std::size_t i = 0; i < depth.size(); ++i) {
    std::uint8_t& is_land = land.values()[i];
    float& d = depth.values()[i];
    if (!is_land && d <= 0.0f && !(chart_water.values()[i] && request.water_level_m >= 0.0)) is_land = 1;
    if (is_land) {
      land_cells++;
      if (!(d < 0.0f)) d = -static_cast<float>(request.land_elevation_m);
    }
  }
  if (land_cells == depth.size())
    throw Error("grid " + frame.projection.describe(), "every cell is land", every_cell_land_fix(sources, request));
  return land_cells;
}

// Step 7a, conditioning for the Boussinesq solver: water cells shallower than minimum_depth_m are
// deepened to it (the solver's total depth must stay positive under the waves). Adds a warning to
// `warnings` when any cell was raised (issue 19); gives the report of the cells changed.
ChangeReport clamp_minimum_depth(const BathyRequest& request, const Raster<std::uint8_t>& land, std::size_t land_cells,
                                 Raster<float>& depth, std::vector<std::string>& warnings) {
  ChangeReport clamped;
  double shallowest_water_m = INFINITY;
  for (int r = 0; r < depth.rows(); ++r)
    for (int c = 0; c < depth.columns(); ++c)
      if (!land(c, r) && depth(c, r) < request.minimum_depth_m) {
        shallowest_water_m = std::min<double>(shallowest_water_m, depth(c, r));
        clamped.record(c, r, request.minimum_depth_m - depth(c, r));
        depth(c, r) = static_cast<float>(request.minimum_depth_m);
      }
  if (clamped.cells > 0)
    warnings.push_back(minimum_depth_warning(clamped.cells, depth.size() - land_cells, shallowest_water_m,
                                             clamped.max_change_m, request.minimum_depth_m));
  return clamped;
}

// The cells the slope limiting changed, and the sweeps it took.
struct SlopeLimiting {
  ChangeReport smoothed;
  int sweeps = 0;
};

// Step 7b, optional (maximum_slope > 0): the sea bed smoothed where |grad d| exceeds maximum_slope,
// water cells only. Jacobi relaxation of the steep cells towards their water neighbours' mean until
// no step between water neighbours exceeds the limit (or 200 sweeps).
SlopeLimiting limit_bed_slope(const BathyRequest& request, const GridGeometry& g, const Raster<std::uint8_t>& land,
                              Raster<float>& depth) {
  SlopeLimiting limiting;
  if (!(request.maximum_slope > 0)) return limiting;
  int& slope_iterations = limiting.sweeps;
  const Raster<float> before = depth;
  const double max_step = request.maximum_slope * g.spacing_m;
  for (; slope_iterations < 200; ++slope_iterations) {
    Raster<float> next = depth;
    std::size_t steep = 0;
    for (int r = 0; r < g.rows; ++r)
      for (int c = 0; c < g.columns; ++c) {
        if (land(c, r)) continue;
        double sum = 0, worst = 0;
        int n = 0;
        for (auto [dc, dr] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const int cc = c + dc, rr = r + dr;
          if (cc < 0 || rr < 0 || cc >= g.columns || rr >= g.rows || land(cc, rr)) continue;
          sum += depth(cc, rr), ++n;
          worst = std::max(worst, std::abs(double(depth(cc, rr)) - depth(c, r)));
        }
        if (n > 0 && worst > max_step) {
          next(c, r) = static_cast<float>(0.5 * depth(c, r) + 0.5 * sum / n);
          ++steep;
        }
      }
    depth = std::move(next);
    if (steep == 0) break;
  }
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c)
      if (depth(c, r) != before(c, r)) limiting.smoothed.record(c, r, depth(c, r) - before(c, r));
  return limiting;
}

// One structure of an input as the harbour grid carries it (core/coastal_structure.hpp): the style
// of its category (BathyRequest::structure_styles) overridden by the feature's own properties, its
// lines and polygons in grid metres. Gives nothing for a structure that passes waves unchanged
// (porosity 1, or a style that is fully open and transmits everything): it is not an obstacle. Throws
// for a category without a style when the feature lacks width or porosity, and for coefficients
// outside 0 .. 1. `ordinal` names a structure that has no name ("breakwater 3").
struct LaidStructure {
  CoastalStructure structure;
  float face_porosity = 1.0f;  // nominal porosity of the faces beyond the solid core, 0 .. 1
};
std::optional<LaidStructure> lay_structure(const SourceData& source, const ShoreStructure& structure,
                                           const BathyRequest& request, const MapProjection& projection,
                                           std::size_t ordinal) {
  auto style_it = request.structure_styles.find(structure.category);
  if (style_it == request.structure_styles.end() && (structure.porosity < 0 || structure.crest_width_m <= 0))
    throw Error(source.path.string(), "structure category '" + structure.category + "' has no width and porosity",
                "give the feature crest_width_m and porosity properties, or add '" + structure.category +
                    "' with a crest width and porosity to BathyRequest::structure_styles");
  StructureStyle style = style_it != request.structure_styles.end() ? style_it->second : StructureStyle{};
  auto in_unit_range = [&](const char* key, double value) {
    if (!(value >= 0.0 && value <= 1.0))
      throw Error(source.path.string(), fmt::format("structure '{}' ({}): {} = {} is outside 0 .. 1", structure.name,
                                                    structure.category, key, value),
                  fmt::format("give {} as a fraction of the incident wave height, 0 .. 1", key));
  };
  if (structure.crest_width_m > 0) style.crest_width_m = structure.crest_width_m;
  if (std::isfinite(structure.crest_elevation_m)) style.crest_elevation_m = structure.crest_elevation_m;
  if (structure.reflection_coefficient >= 0) in_unit_range("reflection_coefficient", style.reflection_coefficient = structure.reflection_coefficient);
  if (structure.transmission_coefficient >= 0) in_unit_range("transmission_coefficient", style.transmission_coefficient = structure.transmission_coefficient);
  if (structure.porosity >= 0) in_unit_range("porosity", structure.porosity);
  if (structure.porosity >= 1.0 || (structure.porosity < 0 && style.porosity >= 1.0 && style.transmission_coefficient >= 1.0)) return std::nullopt;
  LaidStructure result;
  CoastalStructure& laid = result.structure;
  laid.name = structure.name.empty() ? fmt::format("{} {}", structure.category, ordinal) : structure.name;
  laid.kind = structure.category;
  for (const auto& line : structure.lines) {
    StructureLine plane;
    for (const ProjectedPoint& p : project_line(line, projection)) plane.push_back({p.x_m, p.y_m});
    laid.lines.push_back(std::move(plane));
  }
  for (const auto& polygon : structure.polygons) {
    std::vector<StructureLine> rings;
    for (const PlaneLine& ring : project_polygon(polygon, projection)) {
      StructureLine plane;
      for (const ProjectedPoint& p : ring) plane.push_back({p.x_m, p.y_m});
      rings.push_back(std::move(plane));
    }
    laid.polygons.push_back(std::move(rings));
  }
  laid.crest_width_m = style.crest_width_m;
  laid.crest_elevation_m = style.crest_elevation_m;
  laid.side_slope = style.side_slope;
  laid.reflection_coefficient = style.reflection_coefficient;
  laid.roughness_factor = style.roughness_factor;
  laid.transmission_coefficient = style.transmission_coefficient;
  laid.porosity = structure.porosity;
  result.face_porosity = static_cast<float>(std::clamp(structure.porosity >= 0 ? structure.porosity : style.porosity, 0.0, 1.0));
  return result;
}

// Structures' footprints: every input's structures laid (lay_structure) and burnt into the grid's
// porosity, the core solid (n = 0) and the faces at the nominal porosity of their kind (the bake fits
// it), over the final still-water depth (structure_footprint.hpp). A structure whose footprint misses
// the grid (a chart's structures beyond the box asked for) is left out. Fills grid.porosity and
// grid.structures; gives the footprint cells per category (summary "structure_cells").
std::map<std::string, std::size_t> lay_structure_footprints(const BathyRequest& request,
                                                            const std::vector<SourceData>& sources,
                                                            const MapProjection& projection, HarbourGrid& grid) {
  const GridGeometry& g = grid.geometry;
  const Raster<float>& depth_of_structures = grid.still_water_depth_m;
  grid.porosity = Raster<float>(g.columns, g.rows, 1.0f);
  std::map<std::string, std::size_t> structure_cells;
  for (const auto& source : sources)
    for (const auto& structure : source.structures) {
      std::optional<LaidStructure> laid = lay_structure(source, structure, request, projection, grid.structures.size() + 1);
      if (!laid) continue;
      std::unordered_set<std::size_t> footprint;
      for_each_footprint_cell(g, depth_of_structures, laid->structure, kMinimumStructureFaceCells, [&](int c, int r, FootprintPart part) {
        const float n = part == FootprintPart::kCore ? 0.0f : laid->face_porosity;
        if (grid.porosity(c, r) > n) grid.porosity(c, r) = n;
        footprint.insert(static_cast<std::size_t>(r) * g.columns + c);
      });
      if (footprint.empty()) continue;
      structure_cells[structure.category] += footprint.size();
      grid.structures.push_back(std::move(laid->structure));
    }
  return structure_cells;
}

// The preview's coastline (docs/formats/harbour-grid.md): the inputs' coastlines, else the outlines of
// their land polygons, else (raster or XYZ inputs alone) the gridded depth's still-water line. Fills
// result.coastline_m and result.coastline_from_depth; needs result.grid's depth and land.
void trace_preview_coastline(const std::vector<SourceData>& sources, const MapProjection& projection,
                             BathyResult& result) {
  for (const auto& source : sources) {
    for (const auto& line : source.coastlines) result.coastline_m.push_back(project_line(line, projection));
    if (source.coastlines.empty())
      for (const auto& polygon : source.land)
        for (const auto& ring : polygon.rings) result.coastline_m.push_back(project_line(ring, projection));
  }
  if (result.coastline_m.empty()) {
    result.coastline_m = trace_still_water_line(result.grid);
    result.coastline_from_depth = true;
  }
}

// What each step reported, for the summary.
struct StepReports {
  nlohmann::json inputs = nlohmann::json::array();  // step 3, one entry per input
  ChangeReport bounded;                             // step 4
  ChangeReport uncovered;                           // step 5
  std::size_t land_cells = 0;                       // step 6 (outside-chart cells included)
  ChangeReport clamped;                             // step 7a
  SlopeLimiting slope;                              // step 7b
  std::map<std::string, std::size_t> structure_cells;
};

// The summary (summary.json, docs/formats/harbour-grid.md): the inputs, the grid and where it lies,
// the water's depth range, the cell counts, and what each step changed where. Takes the finished
// result (grid, warnings, leave-one-out errors) and the steps' reports; gives the summary.
nlohmann::json summarise_harbour_grid(const BathyRequest& request, const MapProjection& projection,
                                      const BathyResult& result, const StepReports& reports) {
  const HarbourGrid& grid = result.grid;
  const GridGeometry& g = grid.geometry;
  const ChangeReport& uncovered = reports.uncovered;
  float depth_min = INFINITY, depth_max = -INFINITY;
  for (std::size_t i = 0; i < grid.still_water_depth_m.size(); ++i)
    if (!grid.land.values()[i])
      depth_min = std::min(depth_min, grid.still_water_depth_m.values()[i]),
      depth_max = std::max(depth_max, grid.still_water_depth_m.values()[i]);
  const LonLat south_west = projection.reverse({g.origin_x_m, g.origin_y_m});
  const LonLat north_east = projection.reverse({g.origin_x_m + g.width_m(), g.origin_y_m + g.height_m()});
  nlohmann::json summary;
  summary["format"] = "nearshore bathymetry summary 1";
  summary["inputs"] = reports.inputs;
  summary["projection"] = projection.to_json();
  summary["crs"] = projection.describe();
  summary["spacing_m"] = g.spacing_m;
  summary["columns"] = g.columns;
  summary["rows"] = g.rows;
  summary["extent_m"] = {{"x_min", g.origin_x_m}, {"y_min", g.origin_y_m}, {"x_max", g.origin_x_m + g.width_m()},
                         {"y_max", g.origin_y_m + g.height_m()}};
  summary["extent_lon_lat"] = {{"south_west", {south_west.longitude_deg, south_west.latitude_deg}},
                               {"north_east", {north_east.longitude_deg, north_east.latitude_deg}}};
  summary["water_depth_m"] = {{"min", depth_min}, {"max", depth_max}};
  const std::size_t outside_chart_cells = request.fill_uncovered_from_nearest ? 0 : uncovered.cells;
  summary["cells"] = {{"total", g.cell_count()}, {"land", reports.land_cells - outside_chart_cells},
                      {"water", g.cell_count() - reports.land_cells}, {"outside_chart", outside_chart_cells},
                      {"uncovered", uncovered.cells}, {"bounded_by_depth_areas", reports.bounded.cells}};
  summary["structure_cells"] = reports.structure_cells;
  summary["uncovered"] = uncovered.to_json(g, projection);
  summary["uncovered"]["treatment"] = request.fill_uncovered_from_nearest
                                          ? "depth of the nearest covered cell (max_change_m: farthest carried, metres)"
                                          : "no data: land channel 2 in depth.exr (a land/water reader sees land), nodata in "
                                            "depth.tif; the bake treats them as its case says (bathymetry.outside_chart)";
  summary["bounded_by_depth_areas"] = reports.bounded.to_json(g, projection);
  summary["water_level_m"] = request.water_level_m;
  summary["conditioning"] = {{"minimum_depth_m", request.minimum_depth_m},
                             {"minimum_depth_clamp", reports.clamped.to_json(g, projection)},
                             {"maximum_slope", request.maximum_slope},
                             {"slope_smoothing", reports.slope.smoothed.to_json(g, projection)},
                             {"slope_smoothing_sweeps", reports.slope.sweeps},
                             {"land_elevation_m_where_unknown", request.land_elevation_m}};
  summary["warnings"] = result.warnings;
  if (request.leave_one_out && !result.leave_one_out_error_m.empty()) {
    std::vector<double> absolute;
    for (double e : result.leave_one_out_error_m) absolute.push_back(std::abs(e));
    summary["leave_one_out"] = {{"soundings", absolute.size()}, {"median_absolute_error_m", median(absolute)},
                                {"p90_absolute_error_m", percentile(absolute, 0.9)},
                                {"median_error_m", median(result.leave_one_out_error_m)}};
  }
  return summary;
}

// Step 8: the surroundings (harbour_builder.hpp): steps 3-6, the same functions, on the coarser
// cells of surroundings_geometry, without leave-one-out (the grid's pass did it) and without the
// solver's conditioning. Cells no input covers stay NaN (no data: the renderer keeps its own rule
// there), whatever fill_uncovered_from_nearest says (it is the solver's need, not the eye's).
// Gives the surroundings and their summary entry.
std::pair<Surroundings, nlohmann::json> grid_surroundings(const BathyRequest& request, const ChartInputs& inputs,
                                                          const GridFrame& frame) {
  const double longer_side_m = std::max(frame.geometry.width_m(), frame.geometry.height_m());
  const double margin_m = request.surroundings_margin_m < 0 ? longer_side_m : request.surroundings_margin_m;
  if (!(margin_m > 0)) return {};
  BathyRequest outer_request = request;
  outer_request.leave_one_out = false;
  outer_request.fill_uncovered_from_nearest = false;
  const GridFrame outer{frame.projection, surroundings_geometry(frame.geometry, margin_m)};
  const GridGeometry& g = outer.geometry;
  const std::vector<SourceData>& sources = inputs.sources;
  const DepthAreaBounds bounds = rasterise_depth_area_bounds(sources, g, outer.projection);
  Raster<std::uint8_t> land = rasterise_land_polygons(sources, g, outer.projection);
  nlohmann::json inputs_json = nlohmann::json::array();
  std::vector<double> no_errors;
  MergedDepth merged = grid_depth_by_priority(sources, outer, land, bounds, outer_request, inputs_json, no_errors);
  bound_by_depth_areas(sources, bounds, merged);
  Raster<float> depth = std::move(merged.depth_m);
  const ChangeReport uncovered = fill_uncovered_cells(outer_request, outer, depth, land);
  Raster<std::uint8_t> no_data = land;  // kOutsideChartCell where no input covers (step 5)
  std::size_t land_cells = 0;
  try {
    land_cells = lay_land_mask(outer_request, sources, outer, bounds.chart_water, depth, land);
  } catch (const Error&) {
    land_cells = depth.size();  // every cell land: a valid picture of the surroundings, no failure
  }
  for (std::size_t i = 0; i < depth.size(); ++i)
    if (no_data.values()[i] == kOutsideChartCell) depth.values()[i] = kNaNf;
  const std::size_t outside = uncovered.cells;
  nlohmann::json summary = {{"margin_m", margin_m},
                            {"spacing_m", g.spacing_m},
                            {"columns", g.columns},
                            {"rows", g.rows},
                            {"extent_m", {{"x_min", g.origin_x_m}, {"y_min", g.origin_y_m}, {"x_max", g.origin_x_m + g.width_m()},
                                          {"y_max", g.origin_y_m + g.height_m()}}},
                            {"cells", {{"total", g.cell_count()}, {"land", land_cells - outside},
                                       {"water", g.cell_count() - land_cells}, {"no_data", outside}}}};
  return {Surroundings{g, std::move(depth)}, summary};
}

}  // namespace

// The steps in order (harbour_builder.hpp numbers them; each function above says what it takes and
// gives). Each step reports what it changed where, for the summary.
BathyResult build_harbour_grid(const BathyRequest& request) {
  check_request(request);
  const ChartInputs inputs = read_chart_inputs(request);  // 1
  const std::vector<SourceData>& sources = inputs.sources;
  const GridFrame frame = lay_grid_frame(request, inputs);  // 2
  const GridGeometry& g = frame.geometry;
  BathyResult result;
  StepReports reports;
  // 3. Depth per input, merged by priority; 4. bounded by the chart's depth areas.
  const DepthAreaBounds bounds = rasterise_depth_area_bounds(sources, g, frame.projection);
  Raster<std::uint8_t> land = rasterise_land_polygons(sources, g, frame.projection);
  MergedDepth merged = grid_depth_by_priority(sources, frame, land, bounds, request, reports.inputs,
                                              result.leave_one_out_error_m);
  reports.bounded = bound_by_depth_areas(sources, bounds, merged);
  Raster<float> depth = std::move(merged.depth_m);
  // 5. Cells no input covers; 6. still water and the land mask.
  reports.uncovered = fill_uncovered_cells(request, frame, depth, land);
  reports.land_cells = lay_land_mask(request, sources, frame, bounds.chart_water, depth, land);
  HarbourGrid& grid = result.grid;
  grid.geometry = g;
  grid.land = std::move(land);
  // 7. Conditioning for the solver.
  reports.clamped = clamp_minimum_depth(request, grid.land, reports.land_cells, depth, result.warnings);
  reports.slope = limit_bed_slope(request, g, grid.land, depth);
  grid.still_water_depth_m = std::move(depth);
  // Structures' footprints on the conditioned depth, the coast distance from the final land mask,
  // the preview's coastline and the summary.
  reports.structure_cells = lay_structure_footprints(request, sources, frame.projection, grid);
  grid.coast_distance_m = signed_coast_distance(grid.land, g.spacing_m);
  trace_preview_coastline(sources, frame.projection, result);
  result.summary = summarise_harbour_grid(request, frame.projection, result, reports);
  // 8. The ground round the grid, for the renderer.
  auto [surroundings, surroundings_summary] = grid_surroundings(request, inputs, frame);
  grid.surroundings = std::move(surroundings);
  if (!grid.surroundings.empty()) result.summary["surroundings"] = surroundings_summary;
  return result;
}

nlohmann::json write_bathymetry_outputs(const fs::path& folder, const BathyResult& result, double coastline_band_m,
                                        const std::vector<PreviewMark>& marks) {
  // The output folder rules (core/output_folder.hpp): not the folder of an input (a harbour grid's
  // depth.tif read again would be replaced), nor a sequence or a library (`bathy -o SEQ` replaced
  // the sequence's depth.exr, which its frames and checksums were baked on).
  std::vector<InputFolder> input_folders;
  for (const nlohmann::json& input : result.summary.value("inputs", nlohmann::json::array()))
    if (input.contains("path"))
      input_folders.push_back({fs::absolute(fs::path(input.at("path").get<std::string>())).parent_path(),
                               "the input " + input.at("path").get<std::string>()});
  check_output_folder(folder, OutputKind::kHarbourGrid, false, input_folders, "write_bathymetry_outputs(folder)", "");
  const HarbourGrid& grid = result.grid;
  const GridGeometry& g = grid.geometry;
  // Everything that can fail on content is computed before the first file is written.
  HeatMapStyle style;
  style.title = "still-water depth, " + result.summary.value("crs", std::string{}) + fmt::format(", {} m cells", g.spacing_m);
  style.value_label = "depth (m)";
  style.map = ColourMap::kBathymetry;
  style.low = 0.0;
  style.high = result.summary["water_depth_m"].value("max", 1.0);
  style.map_axes = map_axes_of(g);
  const Rgb no_data_colour{0.78f, 0.78f, 0.78f};  // outside the chart: hatched grey (issue 14 item 3)
  style.second_mask_colour = no_data_colour;
  Image preview = render_heat_map(grid.still_water_depth_m, style, &grid.land);
  // Overlays go where render_heat_map put the field (north at the top).
  const HeatMapPlacement placement = heat_map_placement(g.columns, g.rows, style);
  const double scale = placement.pixels_per_cell, left = placement.left_px, top = placement.top_px;
  auto pixel_x = [&](double x_m) { return left + (x_m - g.origin_x_m) / g.spacing_m * scale; };
  auto pixel_y = [&](double y_m) { return top + (g.rows - (y_m - g.origin_y_m) / g.spacing_m) * scale; };
  const double right = pixel_x(g.origin_x_m + g.width_m()), bottom = pixel_y(g.origin_y_m);
  // Structures over the depth colours: solid walls black, porous ones orange (seed 003 porosity).
  const Rgb wall_colour{0.08f, 0.08f, 0.08f}, porous_colour{1.0f, 0.55f, 0.0f}, coast_colour{0.9f, 0.1f, 0.05f};
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c) {
      const float n = grid.porosity(c, r);
      if (n >= 1.0f) continue;
      const double x0 = pixel_x(g.origin_x_m + c * g.spacing_m), y1 = pixel_y(g.origin_y_m + r * g.spacing_m);
      preview.fill_rectangle(static_cast<int>(x0), static_cast<int>(y1 - scale),
                             static_cast<int>(std::max(x0, x0 + scale - 1)), static_cast<int>(std::max(y1 - scale, y1 - 1)),
                             n <= 0.0f ? wall_colour : porous_colour);
    }
  const int legend_y = placement.legend_top_px + 14, legend_x = static_cast<int>(left);
  draw_text(preview, legend_x, legend_y, result.coastline_from_depth ? "depth 0 (grid)" : "coastline (chart)",
            coast_colour, 14);
  draw_text(preview, legend_x + 145, legend_y, "vertical walls (n = 0)", wall_colour, 14);
  draw_text(preview, legend_x + 325, legend_y, "porous structures (0 < n < 1)", porous_colour, 14);
  draw_text(preview, legend_x + 560, legend_y, "land", style.mask_colour, 14);
  preview.fill_rectangle(legend_x + 610, legend_y - 11, legend_x + 630, legend_y + 1, no_data_colour);
  draw_line(preview, legend_x + 610, legend_y + 1, legend_x + 622, legend_y - 11, Rgb{0.45f, 0.45f, 0.45f}, 1);
  draw_text(preview, legend_x + 636, legend_y, "no data (outside the chart)", Rgb{0.35f, 0.35f, 0.35f}, 14);
  for (const auto& line : result.coastline_m)
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const double x0 = pixel_x(line[i].x_m), y0 = pixel_y(line[i].y_m), x1 = pixel_x(line[i + 1].x_m), y1 = pixel_y(line[i + 1].y_m);
      if (std::max(x0, x1) < left || std::min(x0, x1) > right || std::max(y0, y1) < top || std::min(y0, y1) > bottom)
        continue;
      // Clip by points: draw only segments whose both ends are on the field.
      if (x0 >= left && x0 <= right && x1 >= left && x1 <= right && y0 >= top && y0 <= bottom && y1 >= top &&
          y1 <= bottom)
        draw_line(preview, x0, y0, x1, y1, coast_colour, 1);
    }
  // Marks (gauges, a source line's point): a black-rimmed white ring and the name beside it.
  nlohmann::json mark_list = nlohmann::json::array();
  std::vector<std::string> mark_warnings;
  for (const PreviewMark& mark : marks) {
    const double x = pixel_x(mark.point.x_m), y = pixel_y(mark.point.y_m);
    for (int ring = 0; ring < 2; ++ring) {
      const double radius = 6.0 - 2.0 * ring;
      const Rgb colour = ring == 0 ? Rgb{0.f, 0.f, 0.f} : Rgb{1.f, 1.f, 1.f};
      for (int step = 0; step < 24; ++step) {
        const double a0 = step * M_PI / 12.0, a1 = (step + 1) * M_PI / 12.0;
        draw_line(preview, x + radius * std::cos(a0), y + radius * std::sin(a0), x + radius * std::cos(a1),
                  y + radius * std::sin(a1), colour, 2);
      }
    }
    draw_text(preview, static_cast<int>(x + 9), static_cast<int>(y + 5), mark.name, Rgb{0.f, 0.f, 0.f}, 13);
    nlohmann::json entry = {{"name", mark.name}, {"x_m", mark.point.x_m}, {"y_m", mark.point.y_m}};
    if (!g.projection.is_null() && !g.projection.empty()) {
      const LonLat place = MapProjection::from_json(g.projection, "the harbour grid's projection").reverse(mark.point);
      entry["lon"] = place.longitude_deg;
      entry["lat"] = place.latitude_deg;
    }
    mark_list.push_back(entry);
    if (auto warning = land_warning(grid, mark.point, "preview mark", "\"" + mark.name + "\"")) mark_warnings.push_back(*warning);
  }
  create_output_folder(folder);
  // Outside the chart's coverage is nodata (-9999) in the GeoTIFF, so GIS tools and a later
  // `nearshore bathy` reading it as a survey skip those cells.
  Raster<float> charted_depth_m = grid.still_water_depth_m;
  for (std::size_t i = 0; i < charted_depth_m.size(); ++i)
    if (grid.land.values()[i] == kOutsideChartCell) charted_depth_m.values()[i] = std::numeric_limits<float>::quiet_NaN();
  write_depth_geotiff(folder / "depth.tif", g, charted_depth_m, "chart sounding datum of the inputs");
  write_harbour_grid(folder / "depth.exr", grid);
  const std::size_t voxels = write_coastline_level_set(folder / "coastline.vdb", g, grid.coast_distance_m, coastline_band_m);
  write_png(preview, folder / "preview.png");
  nlohmann::json summary = result.summary;
  if (!marks.empty()) {
    summary["marks"] = mark_list;
    for (const std::string& warning : mark_warnings) summary["warnings"].push_back(warning);
  }
  summary["outputs"] = {{"depth_tif", "depth.tif"}, {"depth_exr", "depth.exr"},
                        {"coastline_vdb", {{"file", "coastline.vdb"}, {"active_voxels", voxels}, {"half_band_m", coastline_band_m}}},
                        {"preview_png", "preview.png"}, {"summary_json", "summary.json"}};
  write_text_atomically(folder / "summary.json", summary.dump(2) + "\n");
  return summary;
}

}  // namespace nearshore::bathymetry
