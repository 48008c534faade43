// The agitation coefficient and berth values (agitation.hpp): the incident Hs from the manifest,
// the ratio, berth files and the wet-cell bilinear reading. No GDAL here (agitation_files.cpp).
#include "nearshore/export/agitation.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "nearshore/core/csv_fields.hpp"
#include "nearshore/core/map_projection.hpp"

namespace nearshore::exports {
namespace {

// Grid frame of a WGS 84 place: metres from the south-west corner (the cell centre of column i is
// at (i + 0.5) dx, grid_position_of puts it at column i).
Berth berth_at_lon_lat(const std::string& name, double longitude_deg, double latitude_deg, const GridGeometry& geometry,
                       const std::string& place, const std::string& subject) {
  if (geometry.projection.is_null() || geometry.projection.empty())
    throw Error(subject, fmt::format("{}: berth '{}' is given by longitude and latitude, but the sequence's grid has no map "
                                     "projection (a laboratory frame in local metres)",
                                     place, name),
                "give the berths as name,x_m,y_m: metres from the grid's south-west corner");
  if (!(longitude_deg >= -180.0 && longitude_deg <= 360.0 && latitude_deg >= -90.0 && latitude_deg <= 90.0))
    throw Error(subject, fmt::format("{}: berth '{}' has longitude {} and latitude {}, not WGS 84 degrees", place, name,
                                     longitude_deg, latitude_deg),
                "give longitude (east, -180 .. 180) then latitude (north, -90 .. 90) in decimal degrees");
  const GridPosition position = grid_position_of(geometry, LonLat{longitude_deg, latitude_deg});
  Berth berth;
  berth.name = name;
  berth.x_m = (position.column + 0.5) * geometry.spacing_x_m();
  berth.y_m = (position.row + 0.5) * geometry.spacing_y_m();
  berth.longitude_deg = longitude_deg;
  berth.latitude_deg = latitude_deg;
  berth.place = place;
  return berth;
}

std::vector<Berth> read_berths_csv(const std::filesystem::path& file, const GridGeometry& geometry) {
  std::ifstream in(file);
  const std::string subject = file.string();
  if (!in) throw Error(subject, "cannot be opened", "check the path of the berths file");
  enum class Columns { kUnknown, kGrid, kLonLat } columns = Columns::kUnknown;
  std::vector<Berth> berths;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string text = trimmed(line);
    if (text.empty() || text.front() == '#') continue;
    const std::vector<std::string> fields = csv_fields(text);
    const std::string place = fmt::format("{}:{}", file.filename().string(), number);
    if (columns == Columns::kUnknown) {
      if (fields == std::vector<std::string>{"name", "x_m", "y_m"})
        columns = Columns::kGrid;
      else if (fields == std::vector<std::string>{"name", "longitude", "latitude"})
        columns = Columns::kLonLat;
      else
        throw Error(subject, fmt::format("line {}: the header is '{}', not one of the berth headers", number, text),
                    "start the file with the line name,x_m,y_m (metres from the grid's south-west corner) or "
                    "name,longitude,latitude (WGS 84 degrees)");
      continue;
    }
    if (fields.size() != 3)
      throw Error(subject, fmt::format("line {}: '{}' has {} fields", number, text, fields.size()),
                  columns == Columns::kGrid ? "write name,x_m,y_m: three fields separated by commas (no comma in the name)"
                                            : "write name,longitude,latitude: three fields separated by commas (no comma in the name)");
    if (fields[0].empty())
      throw Error(subject, fmt::format("line {}: the berth has no name", number), "give each berth a name in the first field");
    const std::optional<double> a = finite_number(fields[1]), b = finite_number(fields[2]);
    if (!a || !b)
      throw Error(subject, fmt::format("line {}: berth '{}': '{}' is not a number", number, fields[0], !a ? fields[1] : fields[2]),
                  columns == Columns::kGrid ? "give x_m and y_m in metres, e.g. 812.5"
                                            : "give longitude and latitude in decimal degrees, e.g. 121.6953");
    if (columns == Columns::kGrid) {
      Berth berth;
      berth.name = fields[0];
      berth.x_m = *a;
      berth.y_m = *b;
      berth.place = place;
      berths.push_back(berth);
    } else {
      berths.push_back(berth_at_lon_lat(fields[0], *a, *b, geometry, place, subject));
    }
  }
  if (columns == Columns::kUnknown)
    throw Error(subject, "is empty", "write the header name,x_m,y_m (or name,longitude,latitude) and one berth a line");
  return berths;
}

std::vector<Berth> read_berths_geojson(const std::filesystem::path& file, const GridGeometry& geometry) {
  std::ifstream in(file);
  const std::string subject = file.string();
  if (!in) throw Error(subject, "cannot be opened", "check the path of the berths file");
  const nlohmann::json document = nlohmann::json::parse(in, nullptr, false);
  const std::string fix = "write a GeoJSON FeatureCollection of Point features (longitude, latitude) with a "
                          "\"name\" property each";
  if (document.is_discarded()) throw Error(subject, "is not JSON", fix);
  if (!document.is_object() || document.value("type", "") != "FeatureCollection" || !document.contains("features") ||
      !document["features"].is_array())
    throw Error(subject, "is not a GeoJSON FeatureCollection", fix);
  std::vector<Berth> berths;
  int index = 0;
  for (const nlohmann::json& feature : document["features"]) {
    const std::string place = fmt::format("{} feature {}", file.filename().string(), index++);
    const nlohmann::json* geometry_json = feature.is_object() && feature.contains("geometry") ? &feature["geometry"] : nullptr;
    if (!geometry_json || !geometry_json->is_object() || geometry_json->value("type", "") != "Point" ||
        !geometry_json->contains("coordinates") || !(*geometry_json)["coordinates"].is_array() ||
        (*geometry_json)["coordinates"].size() < 2 || !(*geometry_json)["coordinates"][0].is_number() ||
        !(*geometry_json)["coordinates"][1].is_number())
      throw Error(subject, place + " is not a Point with [longitude, latitude] coordinates", fix);
    const nlohmann::json properties = feature.value("properties", nlohmann::json::object());
    if (!properties.is_object() || !properties.contains("name") || !properties["name"].is_string() ||
        trimmed(properties["name"].get<std::string>()).empty())
      throw Error(subject, place + " has no \"name\" property (a string)", "give each berth a property \"name\": \"...\"");
    berths.push_back(berth_at_lon_lat(trimmed(properties["name"].get<std::string>()),
                                      (*geometry_json)["coordinates"][0].get<double>(),
                                      (*geometry_json)["coordinates"][1].get<double>(), geometry, place, subject));
  }
  return berths;
}

}  // namespace

std::optional<double> recorded_incident_significant_wave_height_m(const nlohmann::json& wave_conditions) {
  if (!wave_conditions.is_object()) return std::nullopt;
  // A split spectrum: the bake made only its carried band; the rest is the deep-water layer's, drawn
  // by the runtime and absent from the frames and the bake's statistics alike.
  if (wave_conditions.contains("spectrum_split")) {
    const nlohmann::json& split = wave_conditions["spectrum_split"];
    if (split.is_object() && split.contains("bake_significant_wave_height_m") &&
        split["bake_significant_wave_height_m"].is_number())
      return split["bake_significant_wave_height_m"].get<double>();
  }
  // Hm0 = 4 sqrt(m0), m0 = sum a_i^2 / 2 (the variance of a sum of independent linear components).
  if (wave_conditions.contains("components") && wave_conditions["components"].is_array() &&
      !wave_conditions["components"].empty()) {
    double variance_m2 = 0.0;
    for (const nlohmann::json& component : wave_conditions["components"]) {
      if (!component.is_object() || !component.contains("amplitude_m") || !component["amplitude_m"].is_number())
        return std::nullopt;
      const double a = component["amplitude_m"].get<double>();
      variance_m2 += 0.5 * a * a;
    }
    return 4.0 * std::sqrt(variance_m2);
  }
  return std::nullopt;
}

Raster<float> agitation_coefficient(const Raster<float>& significant_wave_height_m, double incident_significant_wave_height_m) {
  Raster<float> coefficient(significant_wave_height_m.columns(), significant_wave_height_m.rows(),
                            std::numeric_limits<float>::quiet_NaN());
  for (std::size_t cell = 0; cell < coefficient.size(); ++cell)
    coefficient.values()[cell] =
        static_cast<float>(significant_wave_height_m.values()[cell] / incident_significant_wave_height_m);
  return coefficient;
}

std::vector<Berth> read_berths(const std::filesystem::path& file, const GridGeometry& geometry) {
  require_readable_file(file, "a berths file: CSV (name,x_m,y_m or name,longitude,latitude) or GeoJSON points");
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  std::vector<Berth> berths = extension == ".geojson" || extension == ".json" ? read_berths_geojson(file, geometry)
                                                                                : read_berths_csv(file, geometry);
  if (berths.empty())
    throw Error(file.string(), "names no berth", "add one berth a line after the header (or one Point feature)");
  std::set<std::string> names;
  for (const Berth& berth : berths) {
    if (berth.name.find_first_of(",\"\n") != std::string::npos)
      throw Error(file.string(), fmt::format("{}: the name '{}' holds a comma or a quote", berth.place, berth.name),
                  "name the berth without commas or quotes (the names head columns of CSV tables)");
    if (!names.insert(berth.name).second)
      throw Error(file.string(), fmt::format("{}: the name '{}' is given to two berths", berth.place, berth.name),
                  "give every berth its own name");
  }
  return berths;
}

std::optional<double> wet_bilinear_value(const Raster<float>& field, const HarbourGrid& harbour, double x_m, double y_m) {
  const GridGeometry& g = harbour.geometry;
  if (!(x_m >= 0.0 && x_m <= g.width_m() && y_m >= 0.0 && y_m <= g.height_m())) return std::nullopt;
  const auto wet = [&](int column, int row) {
    return harbour.land(column, row) == kWaterCell && std::isfinite(field(column, row));
  };
  // The cell the point lies in must be water: a berth is where a ship floats.
  const int own_column = std::min(static_cast<int>(x_m / g.spacing_x_m()), g.columns - 1);
  const int own_row = std::min(static_cast<int>(y_m / g.spacing_y_m()), g.rows - 1);
  if (!wet(own_column, own_row)) return std::nullopt;
  // Fractional position between cell centres (centre of cell i at i), clamped within the grid's
  // outer half cells, where the value is the edge cells'.
  const double column = std::clamp(x_m / g.spacing_x_m() - 0.5, 0.0, g.columns - 1.0);
  const double row = std::clamp(y_m / g.spacing_y_m() - 0.5, 0.0, g.rows - 1.0);
  const int i0 = std::min(static_cast<int>(column), std::max(g.columns - 2, 0));
  const int j0 = std::min(static_cast<int>(row), std::max(g.rows - 2, 0));
  const double tx = column - i0, ty = row - j0;
  double sum = 0.0, weights = 0.0;
  for (int dj = 0; dj <= 1; ++dj)
    for (int di = 0; di <= 1; ++di) {
      const int i = std::min(i0 + di, g.columns - 1), j = std::min(j0 + dj, g.rows - 1);
      const double weight = (di ? tx : 1.0 - tx) * (dj ? ty : 1.0 - ty);
      if (weight <= 0.0 || !wet(i, j)) continue;
      sum += weight * field(i, j);
      weights += weight;
    }
  // The own cell is one of the four corners with weight >= 1/4 unless the point sits exactly on a
  // far edge of it; fall back to its value then.
  if (weights <= 0.0) return field(own_column, own_row);
  return sum / weights;
}

std::vector<BerthValue> berth_values(const std::vector<Berth>& berths, const Raster<float>& significant_wave_height_m,
                                     double incident_significant_wave_height_m, const HarbourGrid& harbour) {
  const GridGeometry& g = harbour.geometry;
  std::vector<BerthValue> values;
  for (const Berth& berth : berths) {
    const auto subject = fmt::format("berth '{}' ({})", berth.name, berth.place);
    if (!(berth.x_m >= 0.0 && berth.x_m <= g.width_m() && berth.y_m >= 0.0 && berth.y_m <= g.height_m()))
      throw Error(subject,
                  fmt::format("at x = {:.1f} m, y = {:.1f} m lies outside the grid, which spans x 0 .. {:.1f} m and y 0 .. "
                              "{:.1f} m from its south-west corner",
                              berth.x_m, berth.y_m, g.width_m(), g.height_m()),
                  "give the berth's position in metres from the grid's south-west corner (as the case file's gauges), "
                  "or by longitude and latitude");
    const std::optional<double> hs = wet_bilinear_value(significant_wave_height_m, harbour, berth.x_m, berth.y_m);
    if (!hs)
      throw Error(subject,
                  fmt::format("at x = {:.1f} m, y = {:.1f} m lies on land (or outside the chart): cell ({}, {})", berth.x_m,
                              berth.y_m, std::min(static_cast<int>(berth.x_m / g.spacing_x_m()), g.columns - 1),
                              std::min(static_cast<int>(berth.y_m / g.spacing_y_m()), g.rows - 1)),
                  "move the berth onto the water beside the quay (a cell or two off the wall)");
    values.push_back({berth, *hs, *hs / incident_significant_wave_height_m});
  }
  return values;
}

nlohmann::json berth_value_json(const BerthValue& value) {
  nlohmann::json json = {{"name", value.berth.name}, {"x_m", value.berth.x_m}, {"y_m", value.berth.y_m}};
  if (value.berth.longitude_deg) {
    json["longitude"] = *value.berth.longitude_deg;
    json["latitude"] = *value.berth.latitude_deg;
  }
  json["significant_wave_height_m"] = value.significant_wave_height_m;
  json["agitation_coefficient"] = value.agitation_coefficient;
  return json;
}

}  // namespace nearshore::exports
