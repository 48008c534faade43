// The case file's text: TOML or JSON -> one JSON document; the grid-side names every section uses.
#include <cctype>
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

std::string shortened_numbers(const std::string& text) {
  constexpr std::size_t kLongest = 24, kKept = 12;
  std::string out;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = at;
    while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
    if (end == at) {
      out += text[at++];
      continue;
    }
    if (end - at > kLongest)
      out += text.substr(at, kKept) + fmt::format("... ({} digits)", end - at);
    else
      out += text.substr(at, end - at);
    at = end;
  }
  return out;
}

std::string shown(const json& value) {
  std::string text = shortened_numbers(value.dump());
  if (text.size() > 80) text = text.substr(0, 77) + "...";
  return text;
}

// ---- JSON, depth-limited and without duplicate keys ---------------------------------------------
// nlohmann's parser is iterative, but what the document meets next (copies, the readers) recurses
// once per level: 150 000 nested arrays overflowed the stack (issue 44). A case is 4 levels deep at
// most (a gauge's position: [[gauges]] -> table -> [x, y]); a library's sweep a few more. Anything
// deeper than kMaxCaseDepth is no case file, and is refused while it is read, before a deep
// document exists. TOML refuses a key given twice; JSON's grammar allows it and nlohmann keeps the
// last, silently: one of two values the author wrote would be ignored, so it is refused as in TOML.
constexpr int kMaxCaseDepth = 64;

class CaseJsonChecks {
 public:
  explicit CaseJsonChecks(const std::string& source) : source_(source) {}
  bool operator()(int depth, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        if (depth >= kMaxCaseDepth)
          throw Error(source_,
                      fmt::format("nests objects and arrays more than {} levels deep (at {}): no case or library file is deeper "
                                  "than a few levels, and a deeper document is refused before it is built",
                                  kMaxCaseDepth, place()),
                      "fix the file's brackets; it is not a case file as written");
        scopes_.push_back({event == json::parse_event_t::object_start, {}, {}});
        break;
      case json::parse_event_t::key:
        if (!scopes_.empty()) {
          Scope& scope = scopes_.back();
          scope.current_key = parsed.get<std::string>();
          if (!scope.keys.insert(scope.current_key).second)
            throw Error(source_, fmt::format("the key `{}` is given twice", place()),
                        "keep one of the two values (JSON allows a repeated key but would silently keep the last; TOML "
                        "refuses it too)");
        }
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        if (!scopes_.empty()) scopes_.pop_back();
        break;
      case json::parse_event_t::value:
        break;
    }
    return true;
  }

 private:
  struct Scope {
    bool object;
    std::set<std::string> keys;
    std::string current_key;
  };
  // "wave_maker.height_m": the keys of the objects around the current place.
  std::string place() const {
    std::string path;
    for (const Scope& scope : scopes_)
      if (scope.object && !scope.current_key.empty()) path += (path.empty() ? "" : ".") + scope.current_key;
    return path.empty() ? std::string("the top level") : path;
  }
  std::string source_;
  std::vector<Scope> scopes_;
};

json parse_case_text(const std::string& text, CaseSyntax syntax, const std::string& source) {
  if (syntax == CaseSyntax::kJson) {
    try {
      return json::parse(text, CaseJsonChecks(source));
    } catch (const json::exception& error) {  // parse_error, and out_of_range for a number such as 1e400
      throw Error(source, fmt::format("is not valid JSON ({})", shortened_numbers(error.what())),
                  "fix the syntax at the byte offset given");
    }
  }
  try {
    return to_json_value(toml::parse(text, source));
  } catch (const toml::parse_error& error) {
    throw Error(source,
                fmt::format("is not valid TOML at line {}, column {}: {}", error.source().begin.line,
                            error.source().begin.column, shortened_numbers(std::string(error.description()))),
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
