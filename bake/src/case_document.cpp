// The case file's text: TOML or JSON -> one JSON document; the grid-side names every section uses.
#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "case_reader.hpp"

namespace nearshore::bake::detail {

using namespace nearshore::ocean;       // spectra, sea states, the deep-water field
using namespace nearshore::boussinesq;  // the solver and its parameters

// ---- TOML -> JSON, keeping integers and floats apart -------------------------------------------
json to_json_value(const toml::node& node) {
  if (const auto* table = node.as_table()) {
    json out = json::object();
    for (const auto& [key, value] : *table) out[std::string(key.str())] = to_json_value(value);
    return out;
  }
  if (const auto* array = node.as_array()) {
    json out = json::array();
    for (const auto& value : *array) out.push_back(to_json_value(value));
    return out;
  }
  if (const auto* value = node.as_integer()) return value->get();
  if (const auto* value = node.as_floating_point()) return value->get();
  if (const auto* value = node.as_boolean()) return value->get();
  if (const auto* value = node.as_string()) return value->get();
  return json();  // dates and times: no key takes one, so the key reader will reject the type
}

json parse_case_text(const std::string& text, CaseSyntax syntax, const std::string& source) {
  if (syntax == CaseSyntax::kJson) {
    try {
      return json::parse(text);
    } catch (const json::exception& error) {  // parse_error, and out_of_range for a number such as 1e400
      throw Error(source, fmt::format("is not valid JSON ({})", error.what()), "fix the syntax at the byte offset given");
    }
  }
  try {
    return to_json_value(toml::parse(text, source));
  } catch (const toml::parse_error& error) {
    throw Error(source,
                fmt::format("is not valid TOML at line {}, column {}: {}", error.source().begin.line,
                            error.source().begin.column, error.description()),
                "fix the syntax there");
  }
}

json parse_case_document(const fs::path& case_file) {
  require_readable_file(case_file, "a bake case file (.toml or .json, docs/commands/bake.md)");
  const std::string extension = case_file.extension().string();
  if (extension != ".json" && extension != ".toml")
    throw Error(case_file.string(), "has neither a .toml nor a .json extension", "rename it to CASE.toml or CASE.json");
  std::ifstream in(case_file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return parse_case_text(text.str(), extension == ".json" ? CaseSyntax::kJson : CaseSyntax::kToml, case_file.string());
}

const std::vector<std::string> kSideNames = {"west", "east", "south", "north"};
Side side_from_index(std::size_t index) { return static_cast<Side>(index); }
std::string side_name(Side side) { return kSideNames[static_cast<std::size_t>(side)]; }

double direction_away_from(Side facing) {
  switch (facing) {
    case Side::kWest: return 0.0;
    case Side::kSouth: return 0.5 * std::numbers::pi;
    case Side::kEast: return std::numbers::pi;
    case Side::kNorth: return 1.5 * std::numbers::pi;
  }
  return 0.0;
}

double deepest_still_water_m(const HarbourGrid& grid) {
  float deepest_m = 0.f;
  for (float depth : grid.still_water_depth_m.values()) deepest_m = std::max(deepest_m, depth);
  return deepest_m;
}


}  // namespace nearshore::bake::detail
