#include "nearshore/ships/scenario.hpp"

#include <cmath>
#include <optional>
#include <set>
#include <string>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "nearshore/core/error.hpp"
#include "nearshore/ships/generic_hulls.hpp"
#include "nearshore/ships/hull_file.hpp"

namespace nearshore::ships {
namespace {

namespace fs = std::filesystem;

// Reads one [[ship]] table, naming the file, the ship and the key in every error.
class ShipTable {
 public:
  ShipTable(const fs::path& file, const toml::table& table, int number)
      : file_(file), table_(table), subject_(fmt::format("ship #{}", number)) {
    if (auto name = table_["name"].value<std::string>()) subject_ = fmt::format("ship #{} '{}'", number, *name);
  }
  const std::string& subject() const { return subject_; }

  [[noreturn]] void fail(const std::string& key, const std::string& problem, const std::string& fix) const {
    throw Error(file_.string(), fmt::format("{}: {} {}", subject_, key, problem), fix);
  }
  std::optional<double> number(const std::string& key) const {
    const toml::node* node = table_.get(key);
    if (node == nullptr) return std::nullopt;
    const std::optional<double> value = node->value<double>();
    if (!value || !std::isfinite(*value)) fail(key, "must be a number", fmt::format("write e.g. {} = 1.0", key));
    return value;
  }
  double positive(const std::string& key, double fallback) const {
    const double value = number(key).value_or(fallback);
    if (!(value > 0.0)) fail(key, fmt::format("= {} must be positive", value), "give a positive value");
    return value;
  }
  std::optional<std::string> text(const std::string& key) const {
    const toml::node* node = table_.get(key);
    if (node == nullptr) return std::nullopt;
    const auto value = node->value<std::string>();
    if (!value) fail(key, "must be a string", fmt::format("write e.g. {} = \"...\"", key));
    return value;
  }
  std::optional<Eigen::Vector2d> point(const toml::node* node, const std::string& key) const {
    const toml::array* a = node != nullptr ? node->as_array() : nullptr;
    if (a == nullptr || a->size() != 2) fail(key, "must be a pair of numbers [east_m, north_m]", "write e.g. [820.0, 260.0]");
    const auto x = (*a)[0].value<double>(), y = (*a)[1].value<double>();
    if (!x || !y || !std::isfinite(*x) || !std::isfinite(*y))
      fail(key, "must be a pair of numbers [east_m, north_m]", "write e.g. [820.0, 260.0]");
    return Eigen::Vector2d(*x, *y);
  }
  const toml::table& table() const { return table_; }

 private:
  fs::path file_;
  const toml::table& table_;
  std::string subject_;
};

const std::set<std::string> kKeys = {"name",      "hull",        "length_m",          "beam_m",
                                     "depth_m",   "draft_m",     "mass_kg",           "centre_of_gravity_height_m",
                                     "position_m", "heading_deg", "speed_m_s",        "speed_kn",
                                     "engine_order", "initial_speed_m_s", "route",    "hull_points",
                                     "bow_wave",  "bow_wave_cells", "service_speed_m_s", "dispersive_wake",
                                     "restricted_water"};

ShipDefinition read_ship(const fs::path& file, const toml::table& table, int number) {
  ShipTable t(file, table, number);
  for (const auto& [key, value] : table)
    if (!kKeys.contains(std::string(key.str())))
      t.fail(std::string(key.str()), "is not a key of a ship", "see docs/ships.md for the keys of [[ship]]");
  ShipDefinition d;
  d.name = t.text("name").value_or(fmt::format("ship {}", number));

  // Hull: a generic one by name, else a mesh file relative to the scenario.
  const std::string hull = t.text("hull").value_or("");
  if (hull.empty()) t.fail("hull", "is missing", "give hull = \"tug\", \"wigley\", \"box_barge\" or a mesh file");
  try {
    GenericHullDimensions dimensions;
    auto given = [&](const char* key) { return t.number(key) ? t.positive(key, 0.0) : 0.0; };
    dimensions.length_m = given("length_m");
    dimensions.beam_m = given("beam_m");
    dimensions.depth_m = given("depth_m");
    dimensions.draft_m = given("draft_m");
    if (std::optional<HullMesh> generic = generic_hull(hull, dimensions)) {
      d.hull = std::move(*generic);
    } else {
      fs::path mesh = hull;
      if (mesh.is_relative()) mesh = file.parent_path() / mesh;
      d.hull = load_hull_mesh(mesh);
    }
  } catch (const Error& e) {
    if (e.subject() == file.string()) throw;
    throw Error(file.string(), fmt::format("{}: hull: {}: {}", t.subject(), e.subject(), e.problem()), e.fix());
  }

  const auto mass = t.number("mass_kg");
  const auto draft = t.number("draft_m");
  if (mass) d.loading.mass_kg = t.positive("mass_kg", 0.0);
  if (!mass) {
    if (!draft) t.fail("mass_kg", "and draft_m are both missing", "give the displacement mass_kg or the draft_m");
    d.loading.draft_m = t.positive("draft_m", 0.0);
  }
  d.loading.centre_of_gravity_height_m = t.number("centre_of_gravity_height_m");
  if (auto service = t.number("service_speed_m_s")) d.loading.service_speed_m_s = t.positive("service_speed_m_s", 0.0);

  const toml::node* position = table.get("position_m");
  if (position == nullptr) t.fail("position_m", "is missing", "give position_m = [east_m, north_m] in site metres");
  const Eigen::Vector2d p = *t.point(position, "position_m");
  d.x_m = p.x();
  d.y_m = p.y();
  d.heading_deg = t.number("heading_deg").value_or(0.0);
  d.initial_speed_m_s = t.number("initial_speed_m_s").value_or(0.0);

  const auto engine = t.number("engine_order");
  auto speed = t.number("speed_m_s");
  if (const auto knots = t.number("speed_kn")) {
    if (speed) t.fail("speed_kn", "and speed_m_s are both given", "give one of them");
    speed = *knots * 1852.0 / 3600.0;
  }
  if (engine && speed) t.fail("engine_order", "and a speed are both given", "give an engine order or a speed, not both");
  if (engine && !(*engine >= -1.0 && *engine <= 1.0))
    t.fail("engine_order", fmt::format("= {} is outside [-1, 1]", *engine), "use -1 (full astern) to 1 (full ahead)");
  if (speed && !(*speed >= 0.0)) t.fail("speed", fmt::format("= {} m/s is negative", *speed), "give a speed ahead");
  d.orders.engine_order = engine;
  d.orders.speed_m_s = speed;
  if (const toml::node* route = table.get("route")) {
    const toml::array* a = route->as_array();
    if (a == nullptr) t.fail("route", "must be an array of [east_m, north_m] pairs", "write e.g. [[820.0, 700.0]]");
    for (const toml::node& waypoint : *a) d.orders.route_m.push_back(*t.point(&waypoint, "route"));
  }
  if (const auto points = t.number("hull_points")) {
    if (!(*points >= 16 && *points <= 1e6)) t.fail("hull_points", fmt::format("= {} is outside [16, 1e6]", *points), "use 500-5000");
    d.hull_points = static_cast<int>(*points);
  }
  if (const toml::node* bow = table.get("bow_wave")) {
    const auto on = bow->value_exact<bool>();  // not value<bool>(), which takes 1 for true
    if (!on) t.fail("bow_wave", "must be true or false", "write bow_wave = true");
    d.bow_wave = *on;
  }
  if (const toml::node* dispersive = table.get("dispersive_wake")) {
    const auto on = dispersive->value_exact<bool>();
    if (!on) t.fail("dispersive_wake", "must be true or false", "write dispersive_wake = true");
    d.dispersive_wake = *on;  // the Kelvin layer (dispersive_wake.hpp), chosen by Fr_d (ship_fleet.hpp)
  }
  if (const toml::node* restricted = table.get("restricted_water")) {
    const auto on = restricted->value_exact<bool>();  // not value<bool>(), which takes 1 for true
    if (!on) t.fail("restricted_water", "must be true or false", "write restricted_water = false");
    d.restricted_water = *on;  // squat and shallow-water resistance (restricted_water.hpp)
  }
  if (const auto cells = t.number("bow_wave_cells")) {
    if (!(*cells >= 16 && *cells <= 1024)) t.fail("bow_wave_cells", fmt::format("= {} is outside [16, 1024]", *cells), "use 64-256");
    d.bow_wave_options.cells = static_cast<int>(*cells);
  }
  return d;
}

}  // namespace

std::vector<ShipDefinition> read_scenario(const fs::path& scenario_toml) {
  require_readable_file(scenario_toml, "a ship scenario (TOML with [[ship]] tables)");
  toml::table document;
  try {
    document = toml::parse_file(scenario_toml.string());
  } catch (const toml::parse_error& e) {
    throw Error(scenario_toml.string(),
                fmt::format("is not valid TOML at line {}, column {}: {}", e.source().begin.line,
                            e.source().begin.column, e.description()),
                "fix the TOML syntax there");
  }
  const toml::node* ships = document.get("ship");
  const toml::array* list = ships != nullptr ? ships->as_array() : nullptr;
  if (list == nullptr || list->empty())
    throw Error(scenario_toml.string(), "has no [[ship]] tables", "add one [[ship]] table per ship (docs/ships.md)");
  std::vector<ShipDefinition> out;
  int number = 0;
  for (const toml::node& node : *list) {
    ++number;
    const toml::table* table = node.as_table();
    if (table == nullptr)
      throw Error(scenario_toml.string(), fmt::format("ship #{} is not a table", number), "write each ship as [[ship]]");
    out.push_back(read_ship(scenario_toml, *table, number));
  }
  return out;
}

std::size_t load_scenario(const fs::path& scenario_toml, ShipFleet& fleet) {
  const std::vector<ShipDefinition> definitions = read_scenario(scenario_toml);
  const std::size_t first = fleet.size();
  for (std::size_t k = 0; k < definitions.size(); ++k) {
    try {
      fleet.add_ship(definitions[k]);
    } catch (const Error& e) {
      while (fleet.size() > first) fleet.remove_ship(fleet.size() - 1);
      throw Error(scenario_toml.string(), fmt::format("ship #{}: {} {}", k + 1, e.subject(), e.problem()), e.fix());
    }
  }
  return definitions.size();
}

}  // namespace nearshore::ships
