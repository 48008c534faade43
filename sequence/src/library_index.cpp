#include "nearshore/sequence/library_index.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <set>

#include "field_reader.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/sequence/checksum.hpp"

namespace nearshore::sequence {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr const char* kQuantityNames[] = {"direction_deg", "height_m",       "period_s",          "spectrum",
                                          "tide_m",        "wind_speed_m_s", "wind_direction_deg"};
constexpr const char* kStatusNames[] = {"pending", "baked", "failed"};
constexpr const char* kRunActions[] = {"", "reused", "loops", "resumed", "baked"};
// More states than any sweep a cluster bakes (hundreds): a larger count is a corrupt file.
constexpr std::size_t kMostStates = 1'000'000;

double wrap_degrees(double angle_deg) {
  const double wrapped = std::fmod(angle_deg, 360.0);
  return wrapped < 0 ? wrapped + 360.0 : wrapped;
}

// ---- writing ------------------------------------------------------------------------------------

json conditions_to_json(const SeaConditions& conditions) {
  json object = json::object();
  for (SeaQuantity quantity : kSeaQuantities) {
    if (quantity == SeaQuantity::kSpectrum) {
      if (conditions.spectrum) object[std::string(sea_quantity_name(quantity))] = *conditions.spectrum;
    } else if (const std::optional<double> value = conditions.number(quantity)) {
      object[std::string(sea_quantity_name(quantity))] = *value;
    }
  }
  return object;
}

// ---- reading ------------------------------------------------------------------------------------

// A file name or a relative path inside the library's folder: a reader joins it to that folder, so
// an absolute path or a ".." would make the index point outside it.
std::string relative_path(const FieldReader& r, const json& parent, const std::string& path, const char* key) {
  const std::string text = r.text(parent, path, key);
  const fs::path as_path(text);
  bool escapes = text.empty() || as_path.is_absolute();
  for (const fs::path& part : as_path) escapes = escapes || part == "..";
  if (escapes)
    r.fail(fmt::format("\"{}\" is \"{}\", not a relative path inside the library's folder",
                       FieldReader::name(path, key), text));
  return text;
}

// Letters, digits and . _ + -: a folder name on every file system, never "." or "..".
bool is_state_id(const std::string& id) {
  if (id.empty() || id == "." || id == ".." || id.size() > 200) return false;
  return std::all_of(id.begin(), id.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
           c == '+' || c == '-';
  });
}

bool is_checksum(const std::string& text) {
  if (text.size() != 22 || text.rfind("xxh64:", 0) != 0) return false;
  return std::all_of(text.begin() + 6, text.end(), [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

LibraryIndex::Axis parse_axis(const FieldReader& r, const json& value, const std::string& at) {
  if (!value.is_object()) r.wrong_type(value, "", at, "an object");
  LibraryIndex::Axis axis;
  const std::string name = r.text(value, at, "quantity");
  const std::optional<SeaQuantity> quantity = sea_quantity_from_name(name);
  if (!quantity) {
    std::string known;
    for (const char* n : kQuantityNames) known += fmt::format("{}\"{}\"", known.empty() ? "" : ", ", n);
    r.fail(fmt::format("\"{}.quantity\" is \"{}\", not one of {}", at, name, known));
  }
  axis.quantity = *quantity;
  const json& values = r.array(value, at, "values");
  for (std::size_t k = 0; k < values.size(); ++k) {
    const std::string key = fmt::format("values[{}]", k);
    if (axis.quantity == SeaQuantity::kSpectrum) {
      if (!values[k].is_string()) r.wrong_type(values[k], at, key, "a spectrum's name");
      axis.labels.push_back(values[k].get<std::string>());
    } else {
      const double number = r.number_value(values[k], at, key);
      if (!std::isfinite(number)) r.fail(fmt::format("\"{}.{}\" is not a finite number", at, key));
      axis.values.push_back(number);
    }
  }
  if (const std::string problem = library_axis_problem(axis); !problem.empty())
    r.fail(fmt::format("\"{}\" ({}) {}", at, name, problem));
  return axis;
}

LibraryIndex::Run parse_run(const FieldReader& r, const json& state, const std::string& at) {
  const json& value = r.object(state, at, "run");
  const std::string path = at + ".run";
  LibraryIndex::Run run;
  run.action = r.text(value, path, "action");
  if (std::find(std::begin(kRunActions), std::end(kRunActions), run.action) == std::end(kRunActions))
    r.fail(fmt::format("\"{}.action\" is \"{}\", not \"reused\", \"loops\", \"resumed\", \"baked\" or \"\"", path,
                       run.action));
  run.rank = r.integer(value, path, "rank", -1);
  run.wall_time_s = r.number(value, path, "wall_time_s");
  if (!(run.wall_time_s >= 0) || !std::isfinite(run.wall_time_s))
    r.fail(fmt::format("\"{}.wall_time_s\" is {}, not a finite number >= 0", path, run.wall_time_s));
  return run;
}

// The state's conditions: exactly one value of every axis (other known quantities are refused, so
// a state never claims a condition the sweep did not vary); `cell` receives the value indices.
SeaConditions parse_conditions(const FieldReader& r, const json& state, const std::string& at,
                               const std::vector<LibraryIndex::Axis>& axes, std::vector<int>& cell) {
  const json& value = r.object(state, at, "conditions");
  const std::string path = at + ".conditions";
  SeaConditions conditions;
  cell.assign(axes.size(), -1);
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const LibraryIndex::Axis& axis = axes[a];
    const std::string name(sea_quantity_name(axis.quantity));
    const json& entry = r.member(value, path, name.c_str());
    if (axis.quantity == SeaQuantity::kSpectrum) {
      if (!entry.is_string()) r.wrong_type(entry, path, name, "a spectrum's name");
      const auto it = std::find(axis.labels.begin(), axis.labels.end(), entry.get<std::string>());
      if (it == axis.labels.end())
        r.fail(fmt::format("\"{}.{}\" is {}, not a value of the axis", path, name, describe(entry)));
      conditions.spectrum = *it;
      cell[a] = static_cast<int>(it - axis.labels.begin());
    } else {
      const double number = r.number_value(entry, path, name);
      const auto it = std::find(axis.values.begin(), axis.values.end(), number);
      if (it == axis.values.end())
        r.fail(fmt::format("\"{}.{}\" is {}, not a value of the axis", path, name, describe(entry)));
      conditions.set_number(axis.quantity, number);
      cell[a] = static_cast<int>(it - axis.values.begin());
    }
  }
  for (const char* name : kQuantityNames)
    if (value.contains(name) &&
        std::none_of(axes.begin(), axes.end(), [&](const LibraryIndex::Axis& axis) { return sea_quantity_name(axis.quantity) == name; }))
      r.fail(fmt::format("\"{}.{}\" is given but the library has no {} axis", path, name, name));
  return conditions;
}

LibraryIndex::State parse_state(const FieldReader& r, const json& value, const std::string& at,
                                const std::vector<LibraryIndex::Axis>& axes, std::vector<int>& cell) {
  if (!value.is_object()) r.wrong_type(value, "", at, "an object");
  LibraryIndex::State state;
  state.id = r.text(value, at, "id");
  if (!is_state_id(state.id))
    r.fail(fmt::format("\"{}.id\" is {}, not a folder name of letters, digits, '.', '_', '+' and '-'", at,
                       describe(value["id"])));
  state.conditions = parse_conditions(r, value, at, axes, cell);
  const std::string status = r.text(value, at, "status");
  const auto it = std::find(std::begin(kStatusNames), std::end(kStatusNames), status);
  if (it == std::end(kStatusNames))
    r.fail(fmt::format("\"{}.status\" is \"{}\", not \"pending\", \"baked\" or \"failed\"", at, status));
  state.status = static_cast<LibraryStateStatus>(it - std::begin(kStatusNames));
  state.sequence = relative_path(r, value, at, "sequence");
  state.case_file = relative_path(r, value, at, "case_file");
  state.manifest_checksum = r.text(value, at, "manifest_checksum");
  state.loops_checksum = r.text(value, at, "loops_checksum");
  state.cost_cell_steps = r.number(value, at, "cost_cell_steps");
  if (!(state.cost_cell_steps >= 0) || !std::isfinite(state.cost_cell_steps))
    r.fail(fmt::format("\"{}.cost_cell_steps\" is {}, not a finite number >= 0", at, state.cost_cell_steps));
  state.error = r.text(value, at, "error");
  // What a runtime relies on: a baked state names the files it was verified against; a failed
  // state says why.
  if (state.status == LibraryStateStatus::kBaked) {
    if (!is_checksum(state.manifest_checksum) || !is_checksum(state.loops_checksum))
      r.fail(fmt::format("\"{}\" is baked but its manifest_checksum and loops_checksum are not both "
                         "\"xxh64:<16 hex digits>\"",
                         at));
  }
  if (state.status == LibraryStateStatus::kFailed && state.error.empty())
    r.fail(fmt::format("\"{}\" failed but its \"error\" is empty", at));
  state.run = parse_run(r, value, at);
  return state;
}

LibraryIndex parse_index(std::string_view text, const std::string& source, const std::string& command) {
  const FieldReader r(source, fmt::format("run `{}` again to rewrite it", command));
  try {
    // 1. Format and version first: a newer file is refused as such, not for a key it renamed.
    const json root = r.versioned_root(
        text, kLibraryIndexFormat, "a sea-state library index", kLibraryIndexVersion,
        fmt::format("read it with the nearshore release that wrote it, or run `{}` to rewrite it for this one (finished "
                    "states are kept)",
                    command),
        fmt::format("remove it, or run `{}` to write one", command));

    // 2. The sweep, then its states: every combination of the axes' values exactly once.
    LibraryIndex index;
    index.title = r.text(root, "", "title");
    index.library_file = r.text(root, "", "library_file");
    index.base_case = r.text(root, "", "base_case");
    const json& axes = r.array(root, "", "axes");
    std::set<SeaQuantity> swept;
    std::size_t combinations = 1;
    for (std::size_t a = 0; a < axes.size(); ++a) {
      const std::string at = fmt::format("axes[{}]", a);
      index.axes.push_back(parse_axis(r, axes[a], at));
      if (!swept.insert(index.axes.back().quantity).second)
        r.fail(fmt::format("\"{}\" sweeps {} a second time", at, sea_quantity_name(index.axes.back().quantity)));
      combinations *= index.axes.back().size();
      if (combinations > kMostStates)
        r.fail(fmt::format("\"axes\" make more than {} states, more than any library holds", kMostStates));
    }
    const json& states = r.array(root, "", "states");
    if (states.size() != combinations)
      r.fail(fmt::format("\"states\" holds {} states but the axes make {} combinations", states.size(), combinations));
    std::set<std::string> ids;
    std::set<std::vector<int>> cells;
    std::vector<int> cell;
    index.states.reserve(states.size());
    for (std::size_t k = 0; k < states.size(); ++k) {
      const std::string at = fmt::format("states[{}]", k);
      index.states.push_back(parse_state(r, states[k], at, index.axes, cell));
      if (!ids.insert(index.states.back().id).second)
        r.fail(fmt::format("\"{}.id\" is \"{}\", the id of an earlier state", at, index.states.back().id));
      if (!cells.insert(cell).second)
        r.fail(fmt::format("\"{}.conditions\" are those of an earlier state", at));
    }
    return index;
  } catch (const json::exception& e) {
    // Every access above is type-checked first; this is the guard that keeps the promise anyway.
    throw Error(source, std::string("is malformed: ") + e.what(), r.fix());
  }
}

// ---- choosing -----------------------------------------------------------------------------------

// One axis's share of a request: one or two of its value indices with weights adding up to 1.
struct AxisBracket {
  int lower = 0, upper = 0;
  double upper_weight = 0.0;  ///< t; the lower value weighs 1 - t
};

AxisBracket bracket_linear(const std::vector<double>& values, double x) {
  std::vector<int> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return values[a] < values[b]; });
  if (x <= values[order.front()]) return {order.front(), order.front(), 0.0};
  if (x >= values[order.back()]) return {order.back(), order.back(), 0.0};
  for (std::size_t k = 0; k + 1 < order.size(); ++k) {
    const double a = values[order[k]], b = values[order[k + 1]];
    if (x >= a && x <= b) return {order[k], order[k + 1], (x - a) / (b - a)};
  }
  return {order.back(), order.back(), 0.0};  // not reached: x is finite and inside
}

AxisBracket bracket_circular(const std::vector<double>& values, double x_deg) {
  const std::size_t n = values.size();
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return wrap_degrees(values[a]) < wrap_degrees(values[b]); });
  // gap k runs counter-clockwise from order[k] to order[k + 1] (the last one across 360).
  std::vector<double> gaps(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double from = wrap_degrees(values[order[k]]), to = wrap_degrees(values[order[(k + 1) % n]]);
    gaps[k] = k + 1 < n ? to - from : to + 360.0 - from;
  }
  const std::size_t widest = static_cast<std::size_t>(std::max_element(gaps.begin(), gaps.end()) - gaps.begin());
  const double x = wrap_degrees(x_deg);
  for (std::size_t k = 0; k < n; ++k) {
    const double along = wrap_degrees(x - wrap_degrees(values[order[k]]));
    if (along >= gaps[k]) continue;
    const int lower = order[k], upper = order[(k + 1) % n];
    if (k == widest && gaps[k] > 180.0) {  // outside the sector the sweep covers: the nearer end
      const int end = along <= gaps[k] - along ? lower : upper;
      return {end, end, 0.0};
    }
    return {lower, upper, along / gaps[k]};
  }
  return {order.front(), order.front(), 0.0};  // not reached
}

// The smallest spacing between an axis's values (on the circle for angles): one "step".
double axis_step(const LibraryIndex::Axis& axis) {
  std::vector<double> sorted;
  for (double v : axis.values) sorted.push_back(is_direction(axis.quantity) ? wrap_degrees(v) : v);
  std::sort(sorted.begin(), sorted.end());
  double step = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < sorted.size(); ++k) step = std::min(step, sorted[k + 1] - sorted[k]);
  if (is_direction(axis.quantity) && sorted.size() > 1) step = std::min(step, sorted.front() + 360.0 - sorted.back());
  return step;
}

double axis_difference(const LibraryIndex::Axis& axis, double a, double b) {
  if (!is_direction(axis.quantity)) return a - b;
  const double d = wrap_degrees(a - b);
  return d > 180.0 ? d - 360.0 : d;
}

// The axis value a request asks for: its own, or the axis's first when unset (rule 1 and 2).
int requested_label(const LibraryIndex::Axis& axis, const SeaConditions& requested) {
  if (requested.spectrum) {
    const auto it = std::find(axis.labels.begin(), axis.labels.end(), *requested.spectrum);
    if (it != axis.labels.end()) return static_cast<int>(it - axis.labels.begin());
  }
  return 0;
}

// The value index of a state on each axis (the parser guarantees one).
std::vector<int> state_cell(const LibraryIndex& index, const LibraryIndex::State& state) {
  std::vector<int> cell;
  for (const LibraryIndex::Axis& axis : index.axes) {
    int found = -1;
    if (axis.quantity == SeaQuantity::kSpectrum) {
      for (std::size_t k = 0; k < axis.labels.size(); ++k)
        if (state.conditions.spectrum == axis.labels[k]) found = static_cast<int>(k);
    } else {
      const std::optional<double> value = state.conditions.number(axis.quantity);
      for (std::size_t k = 0; k < axis.values.size(); ++k)
        if (value == axis.values[k]) found = static_cast<int>(k);
    }
    cell.push_back(found);
  }
  return cell;
}

}  // namespace

std::string_view sea_quantity_name(SeaQuantity quantity) { return kQuantityNames[static_cast<int>(quantity)]; }

std::optional<SeaQuantity> sea_quantity_from_name(std::string_view name) {
  for (SeaQuantity quantity : kSeaQuantities)
    if (sea_quantity_name(quantity) == name) return quantity;
  return std::nullopt;
}

bool is_direction(SeaQuantity quantity) {
  return quantity == SeaQuantity::kDirection || quantity == SeaQuantity::kWindDirection;
}

std::string_view library_state_status_name(LibraryStateStatus status) { return kStatusNames[static_cast<int>(status)]; }

std::optional<double> SeaConditions::number(SeaQuantity quantity) const {
  switch (quantity) {
    case SeaQuantity::kDirection: return direction_deg;
    case SeaQuantity::kHeight: return height_m;
    case SeaQuantity::kPeriod: return period_s;
    case SeaQuantity::kTide: return tide_m;
    case SeaQuantity::kWindSpeed: return wind_speed_m_s;
    case SeaQuantity::kWindDirection: return wind_direction_deg;
    case SeaQuantity::kSpectrum: break;
  }
  return std::nullopt;
}

void SeaConditions::set_number(SeaQuantity quantity, double value) {
  switch (quantity) {
    case SeaQuantity::kDirection: direction_deg = value; break;
    case SeaQuantity::kHeight: height_m = value; break;
    case SeaQuantity::kPeriod: period_s = value; break;
    case SeaQuantity::kTide: tide_m = value; break;
    case SeaQuantity::kWindSpeed: wind_speed_m_s = value; break;
    case SeaQuantity::kWindDirection: wind_direction_deg = value; break;
    case SeaQuantity::kSpectrum: break;
  }
}

std::string library_axis_problem(const LibraryIndex::Axis& axis) {
  if (axis.size() == 0) return "has no values";
  if (axis.quantity == SeaQuantity::kSpectrum) {
    if (!axis.values.empty()) return "holds numbers, not spectrum names";
    for (std::size_t k = 0; k < axis.labels.size(); ++k)
      for (std::size_t j = 0; j < k; ++j)
        if (axis.labels[j] == axis.labels[k]) return fmt::format("has \"{}\" twice", axis.labels[k]);
    return "";
  }
  if (!axis.labels.empty()) return "holds names, not numbers";
  for (std::size_t k = 0; k < axis.values.size(); ++k) {
    if (!std::isfinite(axis.values[k])) return fmt::format("has the value {}, not a finite number", axis.values[k]);
    for (std::size_t j = 0; j < k; ++j) {
      const bool same = is_direction(axis.quantity) ? wrap_degrees(axis.values[j]) == wrap_degrees(axis.values[k])
                                                    : axis.values[j] == axis.values[k];
      if (same)
        return fmt::format("has {} and {}, the same {}", axis.values[j], axis.values[k],
                           is_direction(axis.quantity) ? "direction (modulo 360 degrees)" : "value");
    }
  }
  return "";
}

int LibraryIndex::count(LibraryStateStatus status) const {
  return static_cast<int>(std::count_if(states.begin(), states.end(), [&](const State& s) { return s.status == status; }));
}

json library_index_to_json(const LibraryIndex& index) {
  json axes = json::array();
  for (const LibraryIndex::Axis& axis : index.axes) {
    json values = axis.quantity == SeaQuantity::kSpectrum ? json(axis.labels) : json(axis.values);
    axes.push_back({{"quantity", sea_quantity_name(axis.quantity)}, {"values", std::move(values)}});
  }
  json states = json::array();
  for (const LibraryIndex::State& state : index.states)
    states.push_back({{"id", state.id},
                      {"conditions", conditions_to_json(state.conditions)},
                      {"status", library_state_status_name(state.status)},
                      {"sequence", state.sequence},
                      {"case_file", state.case_file},
                      {"manifest_checksum", state.manifest_checksum},
                      {"loops_checksum", state.loops_checksum},
                      {"cost_cell_steps", state.cost_cell_steps},
                      {"error", state.error},
                      {"run",
                       {{"action", state.run.action},
                        {"rank", state.run.rank},
                        {"wall_time_s", state.run.wall_time_s}}}});
  return {{"format", kLibraryIndexFormat},
          {"version", kLibraryIndexVersion},
          {"title", index.title},
          {"library_file", index.library_file},
          {"base_case", index.base_case},
          {"axes", std::move(axes)},
          {"states", std::move(states)}};
}

void write_library_index(const fs::path& folder, const LibraryIndex& index) {
  const fs::path path = folder / kLibraryIndexFileName;
  std::string text;
  try {
    text = library_index_to_json(index).dump(1);
  } catch (const json::exception& e) {  // a string that is not UTF-8 (an error message naming a path)
    throw Error(path.string(), std::string("cannot be written: ") + e.what(),
                "give the library's files by paths that are valid UTF-8");
  }
  write_text_atomically(path, text);
}

LibraryIndex parse_library_index(std::string_view text, const std::string& source) {
  return parse_index(text, source, "nearshore library LIBRARY.toml -o LIBRARY_FOLDER");
}

LibraryIndex read_library_index(const fs::path& folder) {
  const fs::path path = folder / kLibraryIndexFileName;
  const std::string command = "nearshore library LIBRARY.toml -o " + folder.string();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw Error(path.string(), fs::exists(path, ec) ? "is not a regular file" : "does not exist",
                fmt::format("run `{}` to write it", command));
  return parse_index(read_file_bytes(path), path.string(), command);
}

LibrarySelection select_library_states(const LibraryIndex& index, const SeaConditions& requested) {
  LibrarySelection selection;
  std::map<std::vector<int>, int> state_at;
  std::vector<std::vector<int>> cells;
  for (std::size_t s = 0; s < index.states.size(); ++s) {
    cells.push_back(state_cell(index, index.states[s]));
    state_at[cells.back()] = static_cast<int>(s);
  }

  // Rules 1 and 2: each axis's bracket.
  std::vector<AxisBracket> brackets;
  for (const LibraryIndex::Axis& axis : index.axes) {
    if (axis.quantity == SeaQuantity::kSpectrum) {
      const int label = requested_label(axis, requested);
      brackets.push_back({label, label, 0.0});
      continue;
    }
    const std::optional<double> x = requested.number(axis.quantity);
    if (!x || !std::isfinite(*x) || axis.values.size() < 2) {
      brackets.push_back({0, 0, 0.0});
      continue;
    }
    brackets.push_back(is_direction(axis.quantity) ? bracket_circular(axis.values, *x) : bracket_linear(axis.values, *x));
  }

  // The nearest baked state (in axis steps), preferring the spectrum asked for.
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < index.states.size(); ++s) {
    if (index.states[s].status != LibraryStateStatus::kBaked) continue;
    double distance = 0.0;
    for (std::size_t a = 0; a < index.axes.size(); ++a) {
      const LibraryIndex::Axis& axis = index.axes[a];
      if (axis.quantity == SeaQuantity::kSpectrum) {
        if (cells[s][a] != brackets[a].lower) distance += 1e12;
        continue;
      }
      if (axis.values.size() < 2) continue;
      const std::optional<double> asked = requested.number(axis.quantity);
      const double x = asked && std::isfinite(*asked) ? *asked : axis.values.front();
      const double steps = axis_difference(axis, x, axis.values[cells[s][a]]) / axis_step(axis);
      distance += steps * steps;
    }
    if (distance < best) {
      best = distance;
      selection.nearest = static_cast<int>(s);
    }
  }
  if (selection.nearest < 0) return selection;

  // Rule 3: the corners of the bracketing cell.
  const std::size_t axes = index.axes.size();
  std::vector<int> corner(axes);
  double total = 0.0;
  for (std::uint64_t bits = 0; bits < (std::uint64_t{1} << axes); ++bits) {
    double weight = 1.0;
    bool duplicate = false;
    for (std::size_t a = 0; a < axes; ++a) {
      const bool upper = (bits >> a) & 1u;
      const AxisBracket& b = brackets[a];
      if (upper && b.upper == b.lower) duplicate = true;  // a held axis has one corner
      corner[a] = upper ? b.upper : b.lower;
      weight *= upper ? b.upper_weight : 1.0 - b.upper_weight;
    }
    if (duplicate || !(weight > 0.0)) continue;
    const auto it = state_at.find(corner);
    if (it == state_at.end() || index.states[it->second].status != LibraryStateStatus::kBaked) continue;
    selection.blend.push_back({it->second, weight});
    total += weight;
  }
  // Rule 4, and the renormalisation of rule 3.
  if (selection.blend.empty()) {
    selection.blend = {{selection.nearest, 1.0}};
    return selection;
  }
  for (LibraryStateWeight& w : selection.blend) w.weight /= total;
  std::stable_sort(selection.blend.begin(), selection.blend.end(),
                   [](const LibraryStateWeight& a, const LibraryStateWeight& b) { return a.weight > b.weight; });
  return selection;
}

SeaConditions parse_sea_conditions(std::string_view text, const std::string& subject) {
  SeaConditions conditions;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string item(text.substr(start, end - start));
    start = end + 1;
    if (item.empty()) continue;
    const std::size_t equals = item.find('=');
    const std::optional<SeaQuantity> quantity =
        equals == std::string::npos ? std::nullopt : sea_quantity_from_name(item.substr(0, equals));
    if (!quantity)
      throw Error(subject, "'" + item + "' is not KEY=VALUE with a quantity a library sweeps",
                  "use direction_deg, height_m, period_s, spectrum, tide_m, wind_speed_m_s or wind_direction_deg");
    const std::string value = item.substr(equals + 1);
    if (*quantity == SeaQuantity::kSpectrum) {
      conditions.spectrum = value;
      continue;
    }
    std::size_t used = 0;
    double number = std::numeric_limits<double>::quiet_NaN();
    try {
      number = std::stod(value, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != value.size() || !std::isfinite(number))
      throw Error(subject, "'" + value + "' in '" + item + "' is not a finite number", "give KEY=NUMBER, e.g. tide_m=1.5");
    conditions.set_number(*quantity, number);
  }
  return conditions;
}

}  // namespace nearshore::sequence
