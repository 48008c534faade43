// LIBRARY.toml: the sweep of a sea-state library over a base case (library_definition.hpp).
#include "nearshore/library/library_definition.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::library {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;
using sequence::LibraryIndex;
using sequence::SeaQuantity;

/// At most this many states in one library (see the check in read_library_definition).
constexpr double kMaxLibraryStates = 10000;
constexpr const char* kSweepFix = "give each quantity of [sweep] a list of values (docs/library.md)";

// Spectra whose waves the wind makes (ocean/spectrum_registry.hpp): their direction is the wind's.
bool is_wind_spectrum(const std::string& spectrum) {
  return spectrum == "phillips" || spectrum == "unified" || spectrum == "pm_ittc" || spectrum == "beaufort";
}

// The case key that means `quantity` for a wave maker of `maker_kind` whose (deep-water) spectrum
// is `spectrum`: {table, key}, or nullopt when that maker has none (library_definition.hpp).
std::optional<std::pair<std::string, std::string>> case_key(SeaQuantity quantity, const std::string& maker_kind,
                                                             const std::string& spectrum) {
  using Key = std::pair<std::string, std::string>;
  if (quantity == SeaQuantity::kTide) return Key{"bathymetry", "still_water_level_m"};
  if (maker_kind == "regular") {
    if (quantity == SeaQuantity::kDirection) return Key{"wave_maker", "direction_deg"};
    if (quantity == SeaQuantity::kHeight) return Key{"wave_maker", "height_m"};
    if (quantity == SeaQuantity::kPeriod) return Key{"wave_maker", "period_s"};
    return std::nullopt;
  }
  if (maker_kind == "irregular") {
    if (quantity == SeaQuantity::kDirection) return Key{"wave_maker", "mean_direction_deg"};
    if (quantity == SeaQuantity::kHeight) return Key{"wave_maker", "significant_height_m"};
    if (quantity == SeaQuantity::kPeriod) return Key{"wave_maker", "peak_period_s"};
    if (quantity == SeaQuantity::kSpectrum) return Key{"wave_maker", "spectrum"};
    return std::nullopt;
  }
  if (maker_kind == "deep_water") {
    const bool wind = is_wind_spectrum(spectrum);
    if (quantity == SeaQuantity::kSpectrum) return Key{"deep_water", "spectrum"};
    if (quantity == SeaQuantity::kDirection)
      return Key{"deep_water", wind ? "wind_direction_deg" : "mean_direction_deg"};
    if (quantity == SeaQuantity::kWindDirection && wind) return Key{"deep_water", "wind_direction_deg"};
    if (quantity == SeaQuantity::kHeight && (!wind || spectrum == "phillips"))
      return Key{"deep_water", "significant_height_m"};
    if (quantity == SeaQuantity::kPeriod && !wind) return Key{"deep_water", "peak_period_s"};
    if (quantity == SeaQuantity::kWindSpeed && spectrum == "phillips") return Key{"deep_water", "wind_speed_m_s"};
    if (quantity == SeaQuantity::kWindSpeed && (spectrum == "unified" || spectrum == "pm_ittc"))
      return Key{"deep_water", "wind_speed_10_m_s"};
  }
  return std::nullopt;
}

// "dir90", "h1.5", "t12", "jonswap", "tide+0.5", "wind15", "winddir80": a state id's parts.
std::string id_part(SeaQuantity quantity, double value) {
  switch (quantity) {
    case SeaQuantity::kDirection: return fmt::format("dir{:g}", value);
    case SeaQuantity::kHeight: return fmt::format("h{:g}", value);
    case SeaQuantity::kPeriod: return fmt::format("t{:g}", value);
    case SeaQuantity::kTide: return fmt::format("tide{:+g}", value);
    case SeaQuantity::kWindSpeed: return fmt::format("wind{:g}", value);
    case SeaQuantity::kWindDirection: return fmt::format("winddir{:g}", value);
    case SeaQuantity::kSpectrum: break;
  }
  return "";
}

std::string text_of(const json& document, const char* table, const char* key) {
  const auto t = document.find(table);
  if (t == document.end() || !t->is_object()) return "";
  const auto k = t->find(key);
  return k != t->end() && k->is_string() ? k->get<std::string>() : "";
}

// A relative file path of the case, made absolute against the base case's folder.
void make_path_absolute(json& document, const char* table, const fs::path& base_folder) {
  const auto t = document.find(table);
  if (t == document.end() || !t->is_object()) return;
  const auto file = t->find("file");
  if (file == t->end() || !file->is_string()) return;
  const fs::path path(file->get<std::string>());
  if (path.is_relative()) *file = fs::absolute(base_folder / path).lexically_normal().string();
}

}  // namespace

LibraryDefinition read_library_definition(const fs::path& library_file) {
  require_readable_file(library_file, "a sea-state library file (LIBRARY.toml, docs/library.md)");
  const json document = bake::read_case_document(library_file);
  const std::string subject = library_file.string();
  LibraryDefinition definition;
  definition.library_file = library_file;
  for (const auto& [key, value] : document.items())
    if (key != "title" && key != "base_case" && key != "sweep")
      throw Error(subject, fmt::format("key `{}` is not a key of a library file", key),
                  "remove it; a library file has title, base_case and [sweep] (docs/library.md)");
  if (const auto title = document.find("title"); title != document.end()) {
    if (!title->is_string()) throw Error(subject, "key `title` is not a string", "write the title in quotes");
    definition.title = title->get<std::string>();
  }
  const auto base = document.find("base_case");
  if (base == document.end() || !base->is_string())
    throw Error(subject, "key `base_case` is missing or not a string",
                "add base_case = \"CASE.toml\": the case file every state starts from, relative to this file");
  definition.base_case_as_written = base->get<std::string>();
  definition.base_case = library_file.parent_path() / definition.base_case_as_written;
  try {
    definition.base_document = bake::read_case_document(definition.base_case);
  } catch (const Error& error) {
    throw Error(subject, fmt::format("key `base_case` names a case that cannot be read: {}", error.what()),
                "name a case file that `nearshore bake` reads, relative to this file");
  }

  const auto sweep = document.find("sweep");
  if (sweep == document.end()) return definition;  // one state: the base case itself
  if (!sweep->is_object())
    throw Error(subject, "key `sweep` is not a table", kSweepFix);
  for (const auto& [key, value] : sweep->items())
    if (!sequence::sea_quantity_from_name(key)) {
      std::string known;
      for (SeaQuantity q : sequence::kSeaQuantities) known += fmt::format("{}{}", known.empty() ? "" : ", ", sequence::sea_quantity_name(q));
      throw Error(subject, fmt::format("key `sweep.{}` is not a quantity a library sweeps", key),
                  fmt::format("use one of {}", known));
    }
  for (SeaQuantity quantity : sequence::kSeaQuantities) {
    const std::string name(sequence::sea_quantity_name(quantity));
    const auto values = sweep->find(name);
    if (values == sweep->end()) continue;
    const std::string key = "sweep." + name;
    if (!values->is_array() || values->empty())
      throw Error(subject, fmt::format("key `{}` is not a list of values", key),
                  fmt::format("write {} = [value, value, ...]", key));
    LibraryIndex::Axis axis;
    axis.quantity = quantity;
    for (const json& value : *values) {
      if (quantity == SeaQuantity::kSpectrum) {
        if (!value.is_string())
          throw Error(subject, fmt::format("key `{}` holds {}, not a spectrum's name", key, value.dump()),
                      "write the names in quotes, e.g. [\"jonswap\", \"pierson_moskowitz\"]");
        axis.labels.push_back(value.get<std::string>());
      } else {
        if (!value.is_number() || !std::isfinite(value.get<double>()))
          throw Error(subject, fmt::format("key `{}` holds {}, not a number", key, value.dump()),
                      fmt::format("write {} as numbers", key));
        axis.values.push_back(value.get<double>());
      }
    }
    if (const std::string problem = sequence::library_axis_problem(axis); !problem.empty())
      throw Error(subject, fmt::format("key `{}` {}", key, problem), "give each value once");
    definition.axes.push_back(std::move(axis));
  }
  // The count before anything is expanded or planned (issue 44: a sweep of 300 000 states planned
  // silently for over an hour at ~15 ms a state). Each state is a whole bake with its loop tables,
  // minutes to hours of one machine: kMaxLibraryStates bakes of even a minute are a week, and
  // reading their cases alone takes minutes. More is a sweep list mistyped or multiplied by mistake.
  double states = 1.0;
  std::string sizes;
  for (const LibraryIndex::Axis& axis : definition.axes) {
    states *= static_cast<double>(axis.size());
    sizes += fmt::format("{}{} {}", sizes.empty() ? "" : " x ", axis.size(), sequence::sea_quantity_name(axis.quantity));
  }
  if (states > kMaxLibraryStates)
    throw Error(subject,
                fmt::format("[sweep] makes {:.0f} states ({}), more than a library takes ({:.0f}): each state is a whole "
                            "bake with its loop tables (minutes to hours each), so {:.0f} bakes of even a minute are a week "
                            "of one machine, and planning them reads every case (~15 ms each)",
                            states, sizes, kMaxLibraryStates, kMaxLibraryStates),
                "sweep fewer values per quantity (the player crossfades between neighbouring states, docs/library.md), "
                "or split the sweep into several libraries");
  return definition;
}

std::vector<LibraryStateCase> expand_library_states(const LibraryDefinition& definition) {
  const std::string subject = definition.library_file.string();
  const std::string maker_kind = text_of(definition.base_document, "wave_maker", "kind");
  const fs::path base_folder = definition.base_case.parent_path();
  std::size_t count = 1;
  for (const LibraryIndex::Axis& axis : definition.axes) count *= axis.size();

  std::vector<LibraryStateCase> states;
  std::set<std::string> ids;
  for (std::size_t combination = 0; combination < count; ++combination) {
    // The axis value indices of this combination, the last axis varying fastest.
    std::vector<std::size_t> at(definition.axes.size());
    std::size_t rest = combination;
    for (std::size_t a = definition.axes.size(); a-- > 0;) {
      at[a] = rest % definition.axes[a].size();
      rest /= definition.axes[a].size();
    }
    LibraryStateCase state;
    state.case_document = definition.base_document;
    make_path_absolute(state.case_document, "bathymetry", base_folder);
    make_path_absolute(state.case_document, "wave_maker", base_folder);
    // The spectrum first: the keys of the other quantities may depend on it.
    std::string spectrum = text_of(definition.base_document, maker_kind == "deep_water" ? "deep_water" : "wave_maker", "spectrum");
    for (std::size_t a = 0; a < definition.axes.size(); ++a)
      if (definition.axes[a].quantity == SeaQuantity::kSpectrum) spectrum = definition.axes[a].labels[at[a]];
    std::vector<std::string> parts;
    std::set<std::string> keys_set;
    for (std::size_t a = 0; a < definition.axes.size(); ++a) {
      const LibraryIndex::Axis& axis = definition.axes[a];
      const std::string name(sequence::sea_quantity_name(axis.quantity));
      const auto key = case_key(axis.quantity, maker_kind, spectrum);
      if (!key)
        throw Error(subject,
                    fmt::format("key `sweep.{}` has no key to set in the base case {} (wave_maker.kind = \"{}\"{})", name,
                                definition.base_case.string(), maker_kind,
                                spectrum.empty() ? "" : fmt::format(", spectrum \"{}\"", spectrum)),
                    "sweep only what the base case's wave maker has (docs/library.md lists each maker's keys), or "
                    "use a base case with another wave maker");
      if (!keys_set.insert(key->first + "." + key->second).second)
        throw Error(subject, fmt::format("key `sweep.{}` sets {}.{}, which another swept quantity sets too", name, key->first, key->second),
                    "sweep only one of them (for a wind spectrum the waves' direction is the wind's)");
      json& table = state.case_document[key->first];
      if (axis.quantity == SeaQuantity::kSpectrum) {
        table[key->second] = axis.labels[at[a]];
        state.conditions.spectrum = axis.labels[at[a]];
        parts.push_back(axis.labels[at[a]]);
        continue;
      }
      double value = axis.values[at[a]];
      state.conditions.set_number(axis.quantity, value);
      parts.push_back(id_part(axis.quantity, value));
      if (axis.quantity == SeaQuantity::kTide) {  // above the base case's own level
        const auto level = table.find(key->second);
        if (level != table.end() && level->is_number()) value += level->get<double>();
      }
      table[key->second] = value;
    }
    for (std::string& part : parts)  // a spectrum name may hold anything; ids are folder names
      for (char& c : part)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '+' && c != '-') c = '-';
    for (const std::string& part : parts) state.id += (state.id.empty() ? "" : "_") + part;
    if (state.id.empty()) state.id = "base";
    if (!ids.insert(state.id).second)
      throw Error(subject, fmt::format("two states would both be named {} (values that differ beyond 6 digits)", state.id),
                  "make the values of each [sweep] list differ in their first 6 significant digits");
    states.push_back(std::move(state));
  }
  return states;
}

}  // namespace nearshore::library
