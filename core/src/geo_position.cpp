#include "nearshore/core/geo_position.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "nearshore/core/error.hpp"

namespace nearshore {
namespace {

std::string key_list() {
  std::string text;
  for (const auto& [a, b] : geo_position_keys()) text += (text.empty() ? "" : ", or ") + a + " and " + b;
  return text;
}

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

bool parse_number(const std::string& text, double& value) {
  const std::string t = trimmed(text);
  if (t.empty()) return false;
  char* end = nullptr;
  value = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size() && std::isfinite(value);
}

std::string hemisphere(double value_deg, char positive, char negative) {
  return fmt::format("{:.5f} {}", std::abs(value_deg), value_deg >= 0 ? positive : negative);
}

std::optional<MapProjection> projection_of(const GridGeometry& geometry) {
  if (geometry.projection.is_null() || geometry.projection.empty()) return std::nullopt;
  return MapProjection::from_json(geometry.projection, "the harbour grid's projection");
}

}  // namespace

const std::vector<std::pair<std::string, std::string>>& geo_position_keys() {
  static const std::vector<std::pair<std::string, std::string>> keys = {
      {"x_m", "y_m"}, {"easting_m", "northing_m"}, {"lat", "lon"}};
  return keys;
}

GeoPosition geo_position_from_keys(const std::map<std::string, double>& keys, const std::string& subject,
                                   const std::string& entry) {
  const auto& pairs = geo_position_keys();
  std::optional<std::size_t> chosen;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const bool has_first = keys.count(pairs[i].first) > 0, has_second = keys.count(pairs[i].second) > 0;
    if (has_first != has_second)
      throw Error(subject,
                  fmt::format("{} gives {} without {}", entry, has_first ? pairs[i].first : pairs[i].second,
                              has_first ? pairs[i].second : pairs[i].first),
                  fmt::format("give both {} and {}", pairs[i].first, pairs[i].second));
    if (!has_first) continue;
    if (chosen)
      throw Error(subject,
                  fmt::format("{} gives its position twice ({} and {}, {} and {})", entry, pairs[*chosen].first,
                              pairs[*chosen].second, pairs[i].first, pairs[i].second),
                  "keep one pair: " + key_list());
    chosen = i;
  }
  for (const auto& item : keys) {
    // Not a structured binding: clang (the fuzz build) cannot capture one in the lambda below.
    const std::string& key = item.first;
    const double value = item.second;
    const bool known = std::any_of(pairs.begin(), pairs.end(), [&](const auto& p) { return p.first == key || p.second == key; });
    if (!known) throw Error(subject, fmt::format("{} has `{}`, which is not a position key", entry, key), "give " + key_list());
    if (!std::isfinite(value)) throw Error(subject, fmt::format("{}: {} = {} is not a number", entry, key, value), "give a finite number");
  }
  if (!chosen) throw Error(subject, entry + " has no position", "give " + key_list());
  GeoPosition position;
  position.frame = static_cast<GeoPosition::Frame>(*chosen);
  position.first = keys.at(pairs[*chosen].first);
  position.second = keys.at(pairs[*chosen].second);
  if (position.frame == GeoPosition::Frame::kLatLon) {
    if (!(std::abs(position.first) <= 90.0))
      throw Error(subject, fmt::format("{}: lat = {} is not a latitude", entry, position.first),
                  "give lat in degrees north (-90..90) and lon in degrees east (west negative), e.g. lat = 47.2706, "
                  "lon = -122.4345");
    if (!(std::abs(position.second) <= 360.0))
      throw Error(subject, fmt::format("{}: lon = {} is not a longitude", entry, position.second),
                  "give lon in degrees east, -180..180 (or 0..360), west negative");
    if (position.second > 180.0) position.second -= 360.0;  // 0..360, as NOAA grids give it
  }
  return position;
}

GeoPosition parse_geo_position(const std::string& text, const std::string& subject, const std::vector<std::string>& extra_keys,
                               std::map<std::string, double>* extras) {
  std::vector<std::string> fields;
  std::stringstream stream(text);
  for (std::string field; std::getline(stream, field, ',');) fields.push_back(trimmed(field));
  const std::string form = fmt::format("X,Y{} in metres from the grid's south-west corner, or KEY=VALUE pairs: {}{}",
                                       extra_keys.empty() ? std::string() : fmt::format(",{}", fmt::join(extra_keys, ",")), key_list(),
                                       extra_keys.empty() ? "" : fmt::format(" (and {})", fmt::join(extra_keys, ", ")));
  std::map<std::string, double> keys;
  std::size_t plain = 0;
  for (const std::string& field : fields) {
    double value = 0.0;
    const auto equals = field.find('=');
    if (equals == std::string::npos) {
      if (!parse_number(field, value)) throw Error(subject, fmt::format("\"{}\": `{}` is not a number", text, field), "write " + form);
      const std::vector<std::string> positional = [&] {
        std::vector<std::string> names = {"x_m", "y_m"};
        names.insert(names.end(), extra_keys.begin(), extra_keys.end());
        return names;
      }();
      if (plain >= positional.size())
        throw Error(subject, fmt::format("\"{}\" has {} numbers, more than {}", text, fields.size(), positional.size()), "write " + form);
      keys[positional[plain++]] = value;
      continue;
    }
    const std::string key = trimmed(field.substr(0, equals));
    if (!parse_number(field.substr(equals + 1), value))
      throw Error(subject, fmt::format("\"{}\": the value of `{}` is not a number", text, key), "write " + form);
    if (keys.count(key)) throw Error(subject, fmt::format("\"{}\" gives `{}` twice", text, key), "write " + form);
    keys[key] = value;
  }
  if (plain > 0 && plain < 2) throw Error(subject, fmt::format("\"{}\" has one number where X,Y needs two", text), "write " + form);
  std::map<std::string, double> position_keys;
  for (const auto& [key, value] : keys) {
    if (std::find(extra_keys.begin(), extra_keys.end(), key) != extra_keys.end()) {
      if (extras) (*extras)[key] = value;
    } else {
      position_keys[key] = value;
    }
  }
  try {
    return geo_position_from_keys(position_keys, subject, "\"" + text + "\"");
  } catch (const Error& error) {
    throw Error(error.subject(), error.problem(), error.fix() + "; the text form is " + form);
  }
}

std::string describe_grid_extent(const GridGeometry& geometry) {
  const std::optional<MapProjection> projection = projection_of(geometry);
  if (!projection)
    return fmt::format("x 0..{:.1f} m, y 0..{:.1f} m from the south-west corner", geometry.width_m(), geometry.height_m());
  // The four corners: a projected rectangle is not a lat/lon rectangle, so the box holding all four.
  double lat_low = 90, lat_high = -90, lon_low = 180, lon_high = -180;
  for (const double x : {0.0, geometry.width_m()})
    for (const double y : {0.0, geometry.height_m()}) {
      const LonLat corner = projection->reverse({geometry.origin_x_m + x, geometry.origin_y_m + y});
      lat_low = std::min(lat_low, corner.latitude_deg), lat_high = std::max(lat_high, corner.latitude_deg);
      lon_low = std::min(lon_low, corner.longitude_deg), lon_high = std::max(lon_high, corner.longitude_deg);
    }
  return fmt::format("lat {:.5f}..{:.5f}, lon {:.5f}..{:.5f} (easting {:.1f}..{:.1f} m, northing {:.1f}..{:.1f} m, {})",
                     lat_low, lat_high, lon_low, lon_high, geometry.origin_x_m, geometry.origin_x_m + geometry.width_m(),
                     geometry.origin_y_m, geometry.origin_y_m + geometry.height_m(), projection->describe());
}

std::string describe_grid_point(const GridGeometry& geometry, ProjectedPoint point) {
  std::string text = fmt::format("x {:.1f} m, y {:.1f} m from the south-west corner", point.x_m - geometry.origin_x_m,
                                 point.y_m - geometry.origin_y_m);
  if (const std::optional<MapProjection> projection = projection_of(geometry)) {
    const LonLat place = projection->reverse(point);
    text += fmt::format(" ({}, {})", hemisphere(place.latitude_deg, 'N', 'S'), hemisphere(place.longitude_deg, 'E', 'W'));
  }
  return text;
}

ProjectedPoint place_in_grid(const GeoPosition& position, const GridGeometry& geometry, const std::string& subject,
                             const std::string& entry, bool inside_only) {
  ProjectedPoint point;
  std::string given;
  switch (position.frame) {
    case GeoPosition::Frame::kFromSouthWestCorner:
      point = {geometry.origin_x_m + position.first, geometry.origin_y_m + position.second};
      given = fmt::format("x_m = {}, y_m = {}", position.first, position.second);
      break;
    case GeoPosition::Frame::kGridCrs:
      point = {position.first, position.second};
      given = fmt::format("easting_m = {}, northing_m = {}", position.first, position.second);
      break;
    case GeoPosition::Frame::kLatLon: {
      const std::optional<MapProjection> projection = projection_of(geometry);
      given = fmt::format("lat = {}, lon = {}", position.first, position.second);
      if (!projection)
        throw Error(subject,
                    fmt::format("{} gives {}, but the grid is in local metres with no map projection", entry, given),
                    "give x_m and y_m (metres from the grid's south-west corner), or grid the chart with `nearshore bathy` "
                    "so that it has a projection");
      point = projection->forward({position.second, position.first});
      break;
    }
  }
  const double x = point.x_m - geometry.origin_x_m, y = point.y_m - geometry.origin_y_m;
  if (inside_only && !(x >= 0.0 && x <= geometry.width_m() && y >= 0.0 && y <= geometry.height_m()))
    throw Error(subject,
                fmt::format("{} at {} lies outside the grid ({} from its south-west corner); the grid covers {}", entry,
                            given, fmt::format("x {:.1f} m, y {:.1f} m", x, y), describe_grid_extent(geometry)),
                "give a position inside the grid, or grid a larger area (BathyRequest::bbox_lon_lat)");
  return point;
}

std::optional<std::string> land_warning(const HarbourGrid& grid, ProjectedPoint point, const std::string& subject,
                                        const std::string& entry) {
  const GridGeometry& g = grid.geometry;
  if (grid.land.empty()) return std::nullopt;
  const double x = point.x_m - g.origin_x_m, y = point.y_m - g.origin_y_m;
  if (!(x >= 0.0 && x <= g.width_m() && y >= 0.0 && y <= g.height_m())) return std::nullopt;  // beyond the grid: not known
  const int column = std::clamp(static_cast<int>(std::floor((point.x_m - g.origin_x_m) / g.spacing_x_m())), 0, g.columns - 1);
  const int row = std::clamp(static_cast<int>(std::floor((point.y_m - g.origin_y_m) / g.spacing_y_m())), 0, g.rows - 1);
  const std::uint8_t land = grid.land(column, row);
  if (land == kWaterCell) return std::nullopt;
  const float depth_m = grid.still_water_depth_m(column, row);
  const std::string where = describe_grid_point(g, point);
  if (land == kOutsideChartCell)
    return fmt::format("{}: {} at {} lies outside the chart's coverage (cell column {}, row {}: no data, depth {:.2f} m as "
                       "stored); move it inside the charted water",
                       subject, entry, where, column, row, depth_m);
  return fmt::format("{}: {} at {} lies on land (cell column {}, row {}: depth {:.2f} m, {:.2f} m above still water); "
                     "move it onto the water (the preview.png of `nearshore bathy` shows where that is)",
                     subject, entry, where, column, row, depth_m, -depth_m);
}

}  // namespace nearshore
