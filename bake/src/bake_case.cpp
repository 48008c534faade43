// The case file: TOML or JSON -> one JSON document -> BakeCase. Every key is read through a
// TableReader that remembers what it consumed, so unknown keys (typos) are reported, and every
// message names the case file, the full key and the fix.
#include "nearshore/bake/bake_case.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>

#include <fmt/core.h>
#include <toml++/toml.h>

#include "nearshore/bake/bake_bathymetry.hpp"
#include "nearshore/bake/bake_time_series.hpp"
#include "nearshore/bake/deep_water_coupling.hpp"
#include "nearshore/bake/sea_state_beaufort.hpp"
#include "nearshore/bake/sea_state_builder.hpp"
#include "nearshore/bake/spectrum.hpp"
#include "nearshore/bake/spectrum_wavenumber.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bake {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

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

json parse_document(const fs::path& case_file) {
  require_readable_file(case_file, "a bake case file (.toml or .json, docs/commands/bake.md)");
  const std::string extension = case_file.extension().string();
  std::ifstream in(case_file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (extension == ".json") {
    try {
      return json::parse(text.str());
    } catch (const json::parse_error& error) {
      throw Error(case_file.string(), fmt::format("is not valid JSON ({})", error.what()),
                  "fix the syntax at the byte offset given");
    }
  }
  if (extension != ".toml")
    throw Error(case_file.string(), "has neither a .toml nor a .json extension", "rename it to CASE.toml or CASE.json");
  try {
    return to_json_value(toml::parse(text.str(), case_file.string()));
  } catch (const toml::parse_error& error) {
    throw Error(case_file.string(),
                fmt::format("is not valid TOML at line {}, column {}: {}", error.source().begin.line,
                            error.source().begin.column, error.description()),
                "fix the syntax there");
  }
}

// ---- TableReader ---------------------------------------------------------------------------------
class TableReader {
 public:
  TableReader(const json& table, std::string prefix, std::string subject)
      : table_(table), prefix_(std::move(prefix)), subject_(std::move(subject)) {
    if (!table_.is_object())
      throw Error(subject_, (prefix_.empty() ? std::string("the document") : "key `" + trimmed_prefix() + "`") + " is not a table",
                  "write it as a [table] (TOML) or an object (JSON)");
  }

  bool has(const std::string& key) const { return table_.contains(key); }

  /// A number; `minimum`/`maximum` are inclusive bounds unless `exclusive_minimum`.
  double number(const std::string& key, std::optional<double> fallback, double minimum, double maximum,
                bool exclusive_minimum, const std::string& meaning) {
    const json* value = find(key);
    if (!value) {
      if (fallback) return *fallback;
      fail(full(key), "is missing", "add " + full(key) + " = <" + meaning + ">");
    }
    if (!value->is_number())
      fail(full(key), fmt::format("is {} but must be a number", value->dump()), "write " + meaning + " as a number");
    const double x = value->get<double>();
    const bool below = exclusive_minimum ? !(x > minimum) : !(x >= minimum);
    if (!std::isfinite(x) || below || x > maximum)
      fail(full(key), fmt::format("= {} is out of range", x),
           fmt::format("give {} {} {}{}", meaning, exclusive_minimum ? ">" : ">=", minimum,
                       std::isfinite(maximum) ? fmt::format(" and <= {}", maximum) : std::string()));
    return x;
  }
  double positive(const std::string& key, std::optional<double> fallback, const std::string& meaning) {
    return number(key, fallback, 0.0, kInfinity, true, meaning);
  }
  double non_negative(const std::string& key, std::optional<double> fallback, const std::string& meaning) {
    return number(key, fallback, 0.0, kInfinity, false, meaning);
  }
  int integer(const std::string& key, std::optional<int> fallback, int minimum, int maximum, const std::string& meaning) {
    const json* value = find(key);
    if (!value) {
      if (fallback) return *fallback;
      fail(full(key), "is missing", "add " + full(key) + " = <" + meaning + ">");
    }
    if (!value->is_number_integer())
      fail(full(key), fmt::format("is {} but must be a whole number", value->dump()), "write " + meaning + " as an integer");
    const auto x = value->get<long long>();
    if (x < minimum || x > maximum)
      fail(full(key), fmt::format("= {} is out of range", x), fmt::format("give {} from {} to {}", meaning, minimum, maximum));
    return static_cast<int>(x);
  }
  std::uint64_t unsigned_integer(const std::string& key, std::uint64_t fallback, const std::string& meaning) {
    const json* value = find(key);
    if (!value) return fallback;
    if (!value->is_number_integer() || value->get<long long>() < 0)
      fail(full(key), fmt::format("is {} but must be a whole number >= 0", value->dump()), "write " + meaning + " as an integer");
    return value->get<std::uint64_t>();
  }
  bool boolean(const std::string& key, bool fallback) {
    const json* value = find(key);
    if (!value) return fallback;
    if (!value->is_boolean()) fail(full(key), fmt::format("is {} but must be true or false", value->dump()), "write true or false");
    return value->get<bool>();
  }
  std::string string(const std::string& key, std::optional<std::string> fallback, const std::string& meaning) {
    const json* value = find(key);
    if (!value) {
      if (fallback) return *fallback;
      fail(full(key), "is missing", "add " + full(key) + " = \"<" + meaning + ">\"");
    }
    if (!value->is_string()) fail(full(key), fmt::format("is {} but must be a string", value->dump()), "write it in quotes");
    return value->get<std::string>();
  }
  /// One of `choices`, returned as its index.
  std::size_t choice(const std::string& key, std::optional<std::string> fallback, const std::vector<std::string>& choices) {
    const std::string value = string(key, fallback, "one of " + list(choices));
    const auto found = std::find(choices.begin(), choices.end(), value);
    if (found == choices.end())
      fail(full(key), fmt::format("= \"{}\" is not known", value), "use one of " + list(choices));
    return static_cast<std::size_t>(found - choices.begin());
  }
  /// An array of exactly `count` numbers (count 0 = any length >= 1).
  std::vector<double> numbers(const std::string& key, std::size_t count, const std::string& meaning) {
    const json* value = find(key);
    if (!value) fail(full(key), "is missing", "add " + full(key) + " = " + meaning);
    if (!value->is_array() || (count && value->size() != count) || value->empty())
      fail(full(key), fmt::format("is {} but must be {}", value->dump().substr(0, 80), meaning), "write it as " + meaning);
    std::vector<double> out;
    for (const json& item : *value) {
      if (!item.is_number() || !std::isfinite(item.get<double>()))
        fail(full(key), fmt::format("holds {}, not a number", item.dump()), "write it as " + meaning);
      out.push_back(item.get<double>());
    }
    return out;
  }
  /// An array of [a, b] pairs (a 1-D table).
  std::vector<std::pair<double, double>> pairs(const std::string& key, const std::string& meaning) {
    const json* value = find(key);
    if (!value) fail(full(key), "is missing", "add " + full(key) + " = " + meaning);
    std::vector<std::pair<double, double>> out;
    if (!value->is_array() || value->empty()) fail(full(key), "is not a list of pairs", "write it as " + meaning);
    for (const json& item : *value) {
      if (!item.is_array() || item.size() != 2 || !item[0].is_number() || !item[1].is_number())
        fail(full(key), fmt::format("holds {}, not a pair of numbers", item.dump()), "write it as " + meaning);
      out.emplace_back(item[0].get<double>(), item[1].get<double>());
    }
    return out;
  }
  const std::string& subject() const { return subject_; }
  /// A sub-table; the returned reader checks its own keys.
  TableReader table(const std::string& key) {
    const json* value = find(key);
    static const json kEmpty = json::object();
    return TableReader(value ? *value : kEmpty, prefix_ + key + ".", subject_);
  }
  /// An array of tables ([[key]] in TOML).
  std::vector<TableReader> tables(const std::string& key) {
    std::vector<TableReader> out;
    const json* value = find(key);
    if (!value) return out;
    if (!value->is_array())
      fail(full(key), "is not an array of tables", "write each entry as [[" + full(key) + "]] (TOML) or an array of objects");
    for (std::size_t i = 0; i < value->size(); ++i)
      out.emplace_back((*value)[i], fmt::format("{}{}[{}].", prefix_, key, i), subject_);
    return out;
  }
  /// A path, relative to the case file's folder.
  fs::path path(const std::string& key, const fs::path& base) {
    const fs::path relative = string(key, std::nullopt, "path");
    return relative.is_absolute() ? relative : (base / relative).lexically_normal();
  }
  /// Runs `read` (which reads the file named by `key`); a nearshore::Error from it is re-thrown
  /// naming the case file and the key as well.
  template <class Read>
  auto reading_file(const std::string& key, Read&& read) -> decltype(read()) {
    try {
      return read();
    } catch (const Error& error) {
      fail(full(key), "names a file that cannot be used: " + error.problem() + " (" + error.subject() + ")", error.fix());
    }
  }
  /// Throws for any key of this table that was never asked for.
  void finish() const {
    for (const auto& [key, value] : table_.items())
      if (!used_.count(key))
        fail(full(key), "is not a known key here",
             "check its spelling against docs/commands/bake.md (known here: " + list(asked_) + ")");
  }
  [[noreturn]] void fail(const std::string& what, const std::string& problem, const std::string& fix) const {
    throw Error(subject_, "key `" + what + "` " + problem, fix);
  }
  std::string full(const std::string& key) const { return prefix_ + key; }

 private:
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const json* find(const std::string& key) {
    asked_.push_back(key);
    if (!table_.contains(key)) return nullptr;
    used_.insert(key);
    return &table_.at(key);
  }
  std::string trimmed_prefix() const { return prefix_.empty() ? prefix_ : prefix_.substr(0, prefix_.size() - 1); }
  static std::string list(const std::vector<std::string>& items) {
    std::string out;
    std::set<std::string> seen;
    for (const auto& item : items)
      if (seen.insert(item).second) out += (out.empty() ? "" : ", ") + item;
    return out;
  }

  const json& table_;
  std::string prefix_, subject_;
  std::set<std::string> used_;
  std::vector<std::string> asked_;
};

const std::vector<std::string> kSideNames = {"west", "east", "south", "north"};
Side side_from_index(std::size_t index) { return static_cast<Side>(index); }
std::string side_name(Side side) { return kSideNames[static_cast<std::size_t>(side)]; }

// Direction of travel (radians, counter-clockwise from +x) of waves coming from `facing`.
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

// ---- bathymetry ----------------------------------------------------------------------------------
HarbourGrid read_bathymetry(TableReader& bathymetry, const fs::path& base) {
  const std::size_t kind = bathymetry.choice("kind", std::nullopt, {"harbour_grid", "profile", "berkhoff_shoal"});
  HarbourGrid grid;
  if (kind == 0) {
    const fs::path file = bathymetry.path("file", base);
    grid = bathymetry.reading_file("file", [&] { return read_harbour_grid(file); });
    if (bathymetry.has("spacing_m"))
      grid = resample_harbour_grid(grid, bathymetry.positive("spacing_m", std::nullopt, "cell size in metres"));
  } else {
    const double length_m = bathymetry.positive("length_m", std::nullopt, "flume length along x in metres");
    const double width_m = bathymetry.positive("width_m", std::nullopt, "flume width along y in metres");
    const double spacing_m = bathymetry.positive("spacing_m", std::nullopt, "cell size in metres");
    if (length_m / spacing_m > 20000 || width_m / spacing_m > 20000)
      bathymetry.fail(bathymetry.full("spacing_m"), "makes more than 20000 cells along a side",
                      "use a larger spacing_m (cells of at least 1/20000 of the flume)");
    if (kind == 1) {
      grid = flume_from_profile(length_m, width_m, spacing_m,
                                bathymetry.pairs("profile", "[[x_m, depth_m], ...] with increasing x"),
                                bathymetry.subject() + ": key `" + bathymetry.full("profile") + "`");
      return grid;
    }
    BerkhoffShoal shoal;
    const std::vector<double> centre = bathymetry.numbers("centre_m", 2, "[x_m, y_m]");
    shoal.centre_x_m = centre[0];
    shoal.centre_y_m = centre[1];
    shoal.rotation_deg = bathymetry.number("rotation_deg", 20.0, -90.0, 90.0, false, "contour angle in degrees");
    shoal.deep_depth_m = bathymetry.positive("deep_depth_m", 0.45, "depth before the slope in metres");
    shoal.slope = bathymetry.non_negative("slope", 0.02, "bed slope (rise over run)");
    shoal.slope_start_m = bathymetry.number("slope_start_m", 5.84, -1e6, 1e6, false, "distance up-wave of the shoal centre where the slope starts, metres");
    shoal.minimum_depth_m = bathymetry.positive("minimum_depth_m", 0.07, "depth where the slope is clipped, metres");
    grid = berkhoff_shoal_grid(length_m, width_m, spacing_m, shoal);
  }
  return grid;
}

// Rectangles of porous structure (rubble mounds) or walls laid over any bathymetry.
void apply_porous_blocks(std::vector<TableReader> blocks, HarbourGrid& grid) {
  for (TableReader& block : blocks) {
    const std::vector<double> x_range = block.numbers("x_range_m", 2, "[x_min_m, x_max_m]");
    const std::vector<double> y_range = block.numbers("y_range_m", 2, "[y_min_m, y_max_m]");
    const double porosity = block.number("porosity", std::nullopt, 0.0, 1.0, false, "porosity n (0 wall .. 1 open water)");
    block.finish();
    if (!(x_range[1] > x_range[0]) || !(y_range[1] > y_range[0]))
      block.fail(block.full("x_range_m"), "or y_range_m is empty (max <= min)", "give [min, max] with max > min");
    int cells = 0;
    for (int row = 0; row < grid.geometry.rows; ++row)
      for (int column = 0; column < grid.geometry.columns; ++column) {
        const double x = grid.geometry.cell_centre_x_m(column) - grid.geometry.origin_x_m;  // local frame
        const double y = grid.geometry.cell_centre_y_m(row) - grid.geometry.origin_y_m;
        if (x >= x_range[0] && x <= x_range[1] && y >= y_range[0] && y <= y_range[1]) {
          grid.porosity(column, row) = static_cast<float>(porosity);
          ++cells;
        }
      }
    if (cells == 0)
      block.fail(block.full("x_range_m"), "and y_range_m contain no cell centre of the grid",
                 "widen the rectangle to at least one cell, inside the grid");
  }
}

struct TimeRequest {
  double time_step_s = 0.0, courant_number = 0.5;
};

TimeRequest read_timing(TableReader& time, BakeTiming& timing) {
  timing.duration_s = time.positive("duration_s", std::nullopt, "simulated duration in seconds");
  timing.spin_up_s = time.non_negative("spin_up_s", 0.0, "spin-up in seconds");
  timing.output_interval_s = time.positive("output_interval_s", std::nullopt, "simulated seconds between frames");
  timing.checkpoint_interval_s = time.non_negative("checkpoint_interval_s", 0.0, "simulated seconds between checkpoints (0 = none)");
  timing.gauge_interval_s = time.non_negative("gauge_interval_s", 0.0, "simulated seconds between gauge samples (0 = every step)");
  TimeRequest request;
  if (time.has("time_step_s") && time.has("courant_number"))
    time.fail(time.full("time_step_s"), "and time.courant_number are both given", "give one of them");
  request.time_step_s = time.non_negative("time_step_s", 0.0, "time step in seconds");
  request.courant_number = time.number("courant_number", 0.5, 0.0, 10.0, true, "Courant number sqrt(g d_max) dt / dx");
  if (timing.spin_up_s >= timing.duration_s)
    time.fail(time.full("spin_up_s"), fmt::format("= {} s is not shorter than time.duration_s = {} s", timing.spin_up_s, timing.duration_s),
              "make the duration longer than the spin-up, or shorten the spin-up");
  if (timing.output_interval_s > timing.duration_s - timing.spin_up_s)
    time.fail(time.full("output_interval_s"), "is longer than the time after spin-up", "give a shorter output interval or a longer duration");
  return request;
}

// Waves of the regular and `components` kinds as linear components; checks the loop period.
void check_loop_period(TableReader& maker, const std::string& key, double loop_period_s, double period_s) {
  const long cycles = whole_steps(loop_period_s, period_s);
  if (cycles < 1)
    maker.fail(maker.full(key), fmt::format("= {} s does not repeat in wave_maker.loop_period_s = {} s ({:.4f} cycles)",
                                            period_s, loop_period_s, loop_period_s / period_s),
               fmt::format("make every period divide the loop period, e.g. loop_period_s = {} s",
                           period_s * std::max(1.0, std::round(loop_period_s / period_s))));
}

// The grid can carry a component only if it is long enough: at the deepest still water, k d <= 3
// (the range where the B = 1/15 equations hold linear dispersion within 2 %, Madsen & Sorensen 1992)
// and at least `cells_per_wavelength` cells per wavelength. Shorter waves are not waves the bake can
// make: they alias, or blow up at the source line. Returns that highest frequency (rad/s).
double highest_carried_frequency_rad_s(const HarbourGrid& grid, int cells_per_wavelength) {
  const double deepest_m = deepest_still_water_m(grid);
  const double k_max = std::min(3.0 / std::max(deepest_m, 1e-3),
                                2 * std::numbers::pi / (cells_per_wavelength * grid.geometry.spacing_m));
  return frequency_from_wavenumber(k_max, deepest_m);
}

std::string carried_band_reason(const HarbourGrid& grid, int cells_per_wavelength) {
  return fmt::format("k d <= 3 at the deepest {:.2f} m and {} cells of {} m per wavelength",
                     deepest_still_water_m(grid), cells_per_wavelength, grid.geometry.spacing_m);
}

// An irregular maker whose components the grid cannot carry is refused with the band to give.
void check_resolvable(TableReader& maker, const SeaState& sea, const HarbourGrid& grid,
                      int cells_per_wavelength) {
  const double w_max = highest_carried_frequency_rad_s(grid, cells_per_wavelength);
  double highest = 0, lowest = std::numeric_limits<double>::infinity();
  for (const WaveComponent& component : sea.components)
    highest = std::max(highest, component.angular_frequency_rad_s), lowest = std::min(lowest, component.angular_frequency_rad_s);
  if (highest > w_max * (1 + 1e-9))
    maker.fail("wave_maker",
               fmt::format("(irregular) has components up to {:.3f} Hz, but the grid carries waves only up "
                           "to {:.3f} Hz ({})",
                           highest / (2 * std::numbers::pi), w_max / (2 * std::numbers::pi),
                           carried_band_reason(grid, cells_per_wavelength)),
               fmt::format("give the band explicitly, e.g. min_frequency_hz = {:.3f} and max_frequency_hz = "
                           "{:.3f}, or use a finer grid",
                           lowest / (2 * std::numbers::pi), w_max / (2 * std::numbers::pi)));
}

WaveComponent component_from(TableReader& reader, const std::string& amplitude_key, double amplitude_factor,
                             double default_direction_rad) {
  WaveComponent component;
  component.amplitude_m = amplitude_factor * reader.positive(amplitude_key, std::nullopt,
                                                             amplitude_key == "height_m" ? "wave height in metres" : "amplitude in metres");
  component.angular_frequency_rad_s = 2.0 * std::numbers::pi / reader.positive("period_s", std::nullopt, "wave period in seconds");
  component.direction_rad = reader.number("direction_deg", default_direction_rad / kDegree, -360.0, 360.0, false,
                                          "direction of travel in degrees counter-clockwise from +x (east)") * kDegree;
  component.phase_rad = reader.number("phase_deg", 0.0, -360.0, 360.0, false, "phase in degrees") * kDegree;
  return component;
}

// A frequency spectrum of `spectrum` kind 0 "jonswap", 1 "pierson_moskowitz" or 2 "tma" from
// its keys: what the irregular maker and [deep_water] both read, with the same keys.
std::shared_ptr<const FrequencySpectrum> read_frequency_spectrum(TableReader& table, std::size_t spectrum) {
  const double hs_m =
      table.positive("significant_height_m", std::nullopt, "significant wave height Hs in metres");
  const double tp_s = table.positive("peak_period_s", std::nullopt, "peak period Tp in seconds");
  const double gamma =
      table.number("peak_enhancement", 3.3, 1.0, 20.0, false, "JONSWAP gamma (1 = Pierson-Moskowitz)");
  std::shared_ptr<const FrequencySpectrum> deep;
  if (spectrum == 1)
    deep = std::make_shared<PiersonMoskowitzSpectrum>(hs_m, tp_s);
  else
    deep = std::make_shared<JonswapSpectrum>(hs_m, tp_s, gamma);
  if (spectrum == 2)
    deep = std::make_shared<TmaSpectrum>(
        deep, table.positive("tma_depth_m", std::nullopt, "depth of the TMA transformation in metres"));
  return deep;
}

// What the [wave_maker] table asks of the sea beyond the single maker: the irregular maker's spectrum
// and spreading (which [deep_water] shares), or for kind "deep_water" the band of the field it makes.
struct MakerRequest {
  bool from_deep_water = false;  // kind = "deep_water": the components come from [deep_water]
  std::shared_ptr<const FrequencySpectrum> spectrum;      // irregular
  std::shared_ptr<const DirectionalSpreading> spreading;  // irregular
  bool long_crested = false;                              // irregular with spreading_s = 0
  WaveMakerBand band;                                     // deep_water
};

WaveMaker read_wave_maker(TableReader& maker, const HarbourGrid& grid, const fs::path& base,
                          MakerRequest& request) {
  WaveMaker wave_maker;
  const std::size_t kind =
      maker.choice("kind", std::nullopt,
                   {"none", "regular", "components", "time_series", "solitary", "irregular", "deep_water"});
  if (kind == 0) return wave_maker;
  wave_maker.facing = side_from_index(maker.choice("facing", std::nullopt, kSideNames));
  const bool along_x = wave_maker.facing == Side::kWest || wave_maker.facing == Side::kEast;
  const double extent_m = along_x ? grid.geometry.width_m() : grid.geometry.height_m();
  const double origin_m = along_x ? grid.geometry.origin_x_m : grid.geometry.origin_y_m;
  const std::string where = kind == 4 ? "crest_position_m" : "source_line_m";
  // Case positions are metres from the grid's south-west corner; the solver's frame includes the origin.
  const double position_m = origin_m + maker.number(where, std::nullopt, 0.0, extent_m, false,
                                                    fmt::format("position along {} from the south-west corner, inside the grid, metres",
                                                                along_x ? "x" : "y"));
  wave_maker.source_line_m = position_m;
  wave_maker.ramp_time_s = maker.non_negative("ramp_time_s", 0.0, "smooth start in seconds");
  const double default_direction_rad = direction_away_from(wave_maker.facing);
  SeaState& sea = wave_maker.sea_state;
  if (kind == 1) {
    wave_maker.kind = WaveMaker::Kind::kComponents;
    const double height_m = maker.positive("height_m", std::nullopt, "wave height (crest to trough) in metres");
    const double period_s = maker.positive("period_s", std::nullopt, "wave period in seconds");
    const double direction_rad = kDegree * maker.number("direction_deg", default_direction_rad / kDegree, -360.0, 360.0, false,
                                                        "direction of travel in degrees counter-clockwise from +x (east)");
    const double phase_rad = kDegree * maker.number("phase_deg", 0.0, -360.0, 360.0, false, "phase in degrees");
    sea = regular_wave_sea_state(height_m, period_s, direction_rad, phase_rad);
    sea.loop_period_s = maker.non_negative("loop_period_s", 0.0, "loop period in seconds (0 = not periodic)");
    if (sea.loop_period_s > 0) check_loop_period(maker, "period_s", sea.loop_period_s, period_s);
  } else if (kind == 5) {
    wave_maker.kind = WaveMaker::Kind::kComponents;
    DirectionalSeaSpecification specification;
    specification.spectrum = read_frequency_spectrum(
        maker, maker.choice("spectrum", "jonswap", {"jonswap", "pierson_moskowitz", "tma"}));
    const double mean_direction_rad = kDegree * maker.number("mean_direction_deg", default_direction_rad / kDegree, -360.0, 360.0,
                                                             false, "mean direction of travel in degrees counter-clockwise from +x");
    const double spreading_s = maker.non_negative("spreading_s", 0.0, "cos^2s exponent s (0 = long-crested)");
    specification.spreading = std::make_shared<CosineSquaredSpreading>(mean_direction_rad, std::max(spreading_s, 1.0));
    specification.frequency_count = maker.integer("frequency_count", 64, 1, 100000, "number of frequency components");
    specification.direction_count = maker.integer("direction_count", spreading_s > 0 ? 16 : 1, 1, 10000, "number of directions");
    if (spreading_s == 0 && specification.direction_count != 1)
      maker.fail(maker.full("direction_count"), "is above 1 for a long-crested sea (spreading_s = 0)", "set spreading_s > 0 or direction_count = 1");
    specification.loop_period_s = maker.non_negative("loop_period_s", 0.0, "loop period in seconds (0 = not periodic)");
    specification.seed = maker.unsigned_integer("seed", 1, "phase seed");
    if (maker.has("min_frequency_hz") || maker.has("max_frequency_hz")) {
      specification.min_frequency_rad_s = 2 * std::numbers::pi * maker.positive("min_frequency_hz", std::nullopt, "lowest frequency in Hz");
      specification.max_frequency_rad_s = 2 * std::numbers::pi * maker.positive("max_frequency_hz", std::nullopt, "highest frequency in Hz");
    }
    request.spectrum = specification.spectrum;
    request.spreading = specification.spreading;
    request.long_crested = spreading_s == 0;
    const int cells_per_wavelength = maker.integer("min_cells_per_wavelength", 8, 2, 1000, "cells per wavelength the grid must give every component");
    try {
      sea = build_sea_state(specification);
    } catch (const Error& error) {
      maker.fail("wave_maker", "(irregular) cannot be built: " + error.problem(), error.fix());
    }
    check_resolvable(maker, sea, grid, cells_per_wavelength);
  } else if (kind == 6) {
    // The components are the [deep_water] field's (read_deep_water, couple_wave_maker): here only
    // the loop period both share and the band of the field the grid carries.
    wave_maker.kind = WaveMaker::Kind::kComponents;
    request.from_deep_water = true;
    sea.loop_period_s = maker.non_negative("loop_period_s", 0.0, "loop period in seconds (0 = not periodic)");
    const int cells_per_wavelength = maker.integer("min_cells_per_wavelength", 8, 2, 1000,
                                                   "cells per wavelength the grid must give every component");
    const double carried_rad_s = highest_carried_frequency_rad_s(grid, cells_per_wavelength);
    request.band.min_frequency_rad_s =
        2 * std::numbers::pi * maker.non_negative("min_frequency_hz", 0.0, "lowest frequency in Hz");
    request.band.max_frequency_rad_s =
        2 * std::numbers::pi *
        maker.positive("max_frequency_hz", carried_rad_s / (2 * std::numbers::pi), "highest frequency in Hz");
    if (request.band.max_frequency_rad_s > carried_rad_s * (1 + 1e-9))
      maker.fail(maker.full("max_frequency_hz"),
                 fmt::format("= {:.4f} Hz is above what the grid carries ({:.4f} Hz: {})",
                             request.band.max_frequency_rad_s / (2 * std::numbers::pi),
                             carried_rad_s / (2 * std::numbers::pi),
                             carried_band_reason(grid, cells_per_wavelength)),
                 "leave max_frequency_hz out (the grid's limit is the default), or use a finer grid");
    if (!(request.band.max_frequency_rad_s > request.band.min_frequency_rad_s))
      maker.fail(maker.full("min_frequency_hz"), "is not below the highest frequency the maker makes",
                 "lower min_frequency_hz");
    // A narrower fan than the source line's 78 degrees, e.g. 0 in a flume whose side walls would
    // reflect oblique waves.
    const double max_angle_rad =
        kDegree * maker.number("max_angle_from_normal_deg", 78.0, 0.0, 78.0, false,
                               "largest angle between a made wave and the source line's normal, degrees");
    request.band.min_normal_fraction = std::max(request.band.min_normal_fraction, std::cos(max_angle_rad));
    if (maker.has("seed"))
      maker.fail(maker.full("seed"), "is the deep-water field's when kind = \"deep_water\"",
                 "move seed into [deep_water]");
  } else if (kind == 2) {
    wave_maker.kind = WaveMaker::Kind::kComponents;
    sea.loop_period_s = maker.non_negative("loop_period_s", 0.0, "loop period in seconds (0 = not periodic)");
    auto components = maker.tables("components");
    if (components.empty())
      maker.fail(maker.full("components"), "is missing or empty", "add [[wave_maker.components]] tables with amplitude_m and period_s");
    for (TableReader& entry : components) {
      sea.components.push_back(component_from(entry, "amplitude_m", 1.0, default_direction_rad));
      if (sea.loop_period_s > 0) check_loop_period(entry, "period_s", sea.loop_period_s, 2 * std::numbers::pi / sea.components.back().angular_frequency_rad_s);
      entry.finish();
    }
  } else if (kind == 3) {
    wave_maker.kind = WaveMaker::Kind::kTimeSeries;
    TimeSeriesLayout layout;
    const fs::path file = maker.path("file", base);
    layout.time_column = maker.integer("time_column", 0, 0, 1000, "1-based time column (0 = none)");
    layout.elevation_column = maker.integer("elevation_column", layout.time_column > 0 ? 2 : 1, 1, 1000, "1-based elevation column");
    layout.sample_interval_s = maker.non_negative("sample_interval_s", 0.0, "sample spacing in seconds");
    layout.elevation_scale_to_m = maker.positive("elevation_scale_to_m", 1.0, "factor to metres (0.01 for cm)");
    layout.remove_mean = maker.boolean("remove_mean", true);
    if (layout.time_column == 0 && layout.sample_interval_s <= 0.0)
      maker.fail(maker.full("sample_interval_s"), "is missing and there is no time_column", "give sample_interval_s > 0 or time_column");
    TimeSeries series = maker.reading_file("file", [&] { return read_time_series(file, layout); });
    wave_maker.series_time_s = std::move(series.time_s);
    wave_maker.series_elevation_m = std::move(series.elevation_m);
  } else if (kind == 4) {
    wave_maker.kind = WaveMaker::Kind::kSolitary;
    wave_maker.solitary_height_m = maker.positive("height_m", std::nullopt, "solitary wave height above still water, metres");
    wave_maker.solitary_crest_position_m = position_m;
  }
  if (kind != 5 && kind != 6)
    sea.seed = maker.unsigned_integer("seed", 0, "phase seed (recorded; used by irregular seas)");
  return wave_maker;
}

SolverParameters read_solver(TableReader& solver) {
  SolverParameters p;
  p.dispersion_coefficient = solver.number("dispersion_coefficient", p.dispersion_coefficient, 0.0, 1.0, false, "B (1/15 in Madsen & Sorensen 1992)");
  p.dispersion_cutoff_depth_m = solver.non_negative("dispersion_cutoff_depth_m", p.dispersion_cutoff_depth_m, "depth in metres below which dispersion is off");
  p.dispersion_cutoff_kh = solver.non_negative("dispersion_cutoff_kh", p.dispersion_cutoff_kh, "k h below which dispersion is off");
  p.dry_depth_m = solver.positive("dry_depth_m", p.dry_depth_m, "wet/dry threshold in metres");
  p.chezy_coefficient = solver.non_negative("chezy_coefficient", p.chezy_coefficient, "Chezy C in m^0.5/s (0 = no friction)");
  p.nonlinear_iterations = solver.integer("nonlinear_iterations", p.nonlinear_iterations, 1, 20, "iterations per half step");
  p.adi_passes = solver.integer("adi_passes", p.adi_passes, 1, 4, "x + y sweep pairs per step");
  p.alternate_sweep_order = solver.boolean("alternate_sweep_order", p.alternate_sweep_order);
  p.shapiro_filter_order = solver.integer("shapiro_filter_order", p.shapiro_filter_order, 0, 16, "order of the grid-scale flux filter (even, 0 = off)");
  if (p.shapiro_filter_order % 2 != 0)
    solver.fail(solver.full("shapiro_filter_order"), "is odd", "give an even order: 8 (the default), or 0 to turn the filter off");
  p.blowup_elevation_depth_ratio = solver.positive("blowup_elevation_depth_ratio", p.blowup_elevation_depth_ratio, "|eta| / depth ratio that stops the run");
  TableReader breaking = solver.table("breaking");
  p.breaking.enabled = breaking.boolean("enabled", p.breaking.enabled);
  p.breaking.onset_celerity_fraction = breaking.positive("onset_celerity_fraction", p.breaking.onset_celerity_fraction, "fraction of sqrt(g h)");
  p.breaking.stop_celerity_fraction = breaking.positive("stop_celerity_fraction", p.breaking.stop_celerity_fraction, "fraction of sqrt(g h)");
  p.breaking.transition_time_factor = breaking.positive("transition_time_factor", p.breaking.transition_time_factor, "T* in units of sqrt(h/g)");
  p.breaking.mixing_length_coefficient = breaking.positive("mixing_length_coefficient", p.breaking.mixing_length_coefficient, "delta");
  if (p.breaking.stop_celerity_fraction > p.breaking.onset_celerity_fraction)
    breaking.fail(breaking.full("stop_celerity_fraction"), "is larger than onset_celerity_fraction", "make the stop threshold smaller than the onset threshold");
  breaking.finish();
  TableReader porous = solver.table("porous");
  p.porous.laminar_alpha = porous.non_negative("laminar_alpha", p.porous.laminar_alpha, "alpha (dimensionless)");
  p.porous.turbulent_beta = porous.non_negative("turbulent_beta", p.porous.turbulent_beta, "beta (dimensionless)");
  p.porous.stone_diameter_m = porous.positive("stone_diameter_m", p.porous.stone_diameter_m, "stone diameter in metres");
  porous.finish();
  return p;
}

json solver_record(const SolverParameters& p) {
  json sponges = json::array();
  for (const SpongeLayer& sponge : p.sponges) sponges.push_back({{"side", side_name(sponge.side)}, {"width_m", sponge.width_m}});
  return {{"time_step_s", p.time_step_s},
          {"dispersion_coefficient", p.dispersion_coefficient},
          {"dispersion_cutoff_depth_m", p.dispersion_cutoff_depth_m},
          {"dispersion_cutoff_kh", p.dispersion_cutoff_kh},
          {"dry_depth_m", p.dry_depth_m},
          {"chezy_coefficient", p.chezy_coefficient},
          {"nonlinear_iterations", p.nonlinear_iterations},
          {"adi_passes", p.adi_passes},
          {"shapiro_filter_order", p.shapiro_filter_order},
          {"alternate_sweep_order", p.alternate_sweep_order},
          {"blowup_elevation_depth_ratio", p.blowup_elevation_depth_ratio},
          {"breaking",
           {{"enabled", p.breaking.enabled},
            {"onset_celerity_fraction", p.breaking.onset_celerity_fraction},
            {"stop_celerity_fraction", p.breaking.stop_celerity_fraction},
            {"transition_time_factor", p.breaking.transition_time_factor},
            {"mixing_length_coefficient", p.breaking.mixing_length_coefficient}}},
          {"porous",
           {{"laminar_alpha", p.porous.laminar_alpha},
            {"turbulent_beta", p.porous.turbulent_beta},
            {"stone_diameter_m", p.porous.stone_diameter_m}}},
          {"sponges", sponges}};
}

json wave_record(const WaveMaker& maker, const json& as_written) {
  json components = json::array();
  for (const WaveComponent& c : maker.sea_state.components)
    components.push_back({{"amplitude_m", c.amplitude_m},
                          {"angular_frequency_rad_s", c.angular_frequency_rad_s},
                          {"direction_rad", c.direction_rad},
                          {"phase_rad", c.phase_rad}});
  json record = {{"case", as_written}, {"components", components}, {"seed", maker.sea_state.seed},
                 {"loop_period_s", maker.sea_state.loop_period_s}};
  if (maker.kind == WaveMaker::Kind::kTimeSeries) record["series_samples"] = maker.series_time_s.size();
  return record;
}

}  // namespace

long whole_steps(double interval_s, double step_s) {
  if (!(step_s > 0.0) || !(interval_s > 0.0)) return -1;
  const double ratio = interval_s / step_s;
  const long n = std::lround(ratio);
  return (n >= 1 && std::abs(ratio - static_cast<double>(n)) <= 1e-9 * std::max(1.0, ratio)) ? n : -1;
}

double resolve_time_step(double requested_time_step_s, double courant_number, const HarbourGrid& harbour,
                         double output_interval_s) {
  double step_s = requested_time_step_s;
  if (!(step_s > 0.0)) {
    float deepest_m = 0.f;
    for (float depth : harbour.still_water_depth_m.values()) deepest_m = std::max(deepest_m, depth);
    // Courant number of the shallow-water celerity in the deepest water: sqrt(g d_max) dt / dx.
    step_s = courant_number * harbour.geometry.spacing_m / std::sqrt(kGravity_m_s2 * std::max(deepest_m, 0.01f));
  }
  const double steps_per_output = std::ceil(output_interval_s / step_s * (1.0 - 1e-12));
  return output_interval_s / std::max(1.0, steps_per_output);
}

namespace {

// [deep_water] spectrum (docs/commands/bake.md) when the field defines the sea (wave_maker.kind =
// "deep_water"): a frequency spectrum with cos^2s spreading (as the irregular maker's, converted to
// wavenumbers at `depth_m`), a wind spectrum, or a Beaufort preset (seed 000 table 3.1). Wind and
// mean directions default to away from the maker's side.
std::shared_ptr<const WavenumberSpectrum> read_deep_water_spectrum(TableReader& deep,
                                                                   double default_direction_rad,
                                                                   double depth_m) {
  // The keys are checked here; a spectrum that still cannot be built says why under deep_water.spectrum.
  const auto built = [&deep](auto&& make) -> std::shared_ptr<const WavenumberSpectrum> {
    try {
      return make();
    } catch (const Error& error) {
      deep.fail(deep.full("spectrum"), "cannot be built: " + error.problem(), error.fix());
    }
  };
  const std::size_t kind =
      deep.choice("spectrum", std::nullopt,
                  {"jonswap", "pierson_moskowitz", "tma", "phillips", "unified", "pm_ittc", "beaufort"});
  const auto direction_rad = [&](const std::string& key) {
    return kDegree * deep.number(key, default_direction_rad / kDegree, -360.0, 360.0, false,
                                 "direction of travel in degrees counter-clockwise from +x (east)");
  };
  if (kind <= 2) {
    std::shared_ptr<const FrequencySpectrum> spectrum = read_frequency_spectrum(deep, kind);
    const double mean_direction_rad = direction_rad("mean_direction_deg");
    const double spreading_s =
        deep.number("spreading_s", 20.0, 1.0, 1000.0, false, "cos^2s exponent s (10-25 wind sea, 75 swell)");
    return built([&] {
      return std::make_shared<DirectionalWavenumberSpectrum>(
          spectrum, std::make_shared<CosineSquaredSpreading>(mean_direction_rad, spreading_s), depth_m);
    });
  }
  if (kind == 3) {
    const double wind_m_s =
        deep.positive("wind_speed_m_s", std::nullopt, "wind speed U of Lw = U^2 / g in m/s");
    const double hs_m =
        deep.positive("significant_height_m", std::nullopt, "significant wave height Hs in metres (sets A)");
    const double wind_direction_rad = direction_rad("wind_direction_deg");
    return built([&] {
      return std::make_shared<PhillipsSpectrum>(
          PhillipsSpectrum::amplitude_for_significant_wave_height(hs_m, wind_m_s), wind_m_s,
          wind_direction_rad);
    });
  }
  if (kind == 4) {
    const double wind_m_s =
        deep.positive("wind_speed_10_m_s", std::nullopt, "wind speed 10 m above the sea in m/s");
    if (deep.has("inverse_wave_age") && deep.has("fetch_m"))
      deep.fail(deep.full("inverse_wave_age"), "and deep_water.fetch_m are both given",
                "give one of them (the fetch sets the inverse wave age)");
    const double fetch_m = deep.positive("fetch_m", 0.0, "fetch in metres");
    const double given_age = deep.number("inverse_wave_age", 0.84, 0.84, 5.0, false,
                                         "Omega_c = U10 / c_p (0.84 fully developed .. 5 young)");
    const double wind_direction_rad = direction_rad("wind_direction_deg");
    return built([&] {
      const double inverse_wave_age =
          fetch_m > 0 ? UnifiedSpectrum::inverse_wave_age_from_fetch(wind_m_s, fetch_m) : given_age;
      return std::make_shared<UnifiedSpectrum>(wind_m_s, inverse_wave_age, wind_direction_rad);
    });
  }
  if (kind == 5) {
    const double wind_m_s =
        deep.positive("wind_speed_10_m_s", std::nullopt, "wind speed 10 m above the sea in m/s");
    const double wind_direction_rad = direction_rad("wind_direction_deg");
    return built([&] { return std::make_shared<PmIttcSpectrum>(wind_m_s, wind_direction_rad); });
  }
  const int force = deep.integer("beaufort_force", std::nullopt, 1, 12,
                                 "Beaufort force (1 light air .. 12 hurricane; 0 is a flat sea)");
  const std::size_t choice = deep.choice("beaufort_spectrum", "seed", {"seed", "phillips", "unified"});
  const double wind_direction_rad = direction_rad("wind_direction_deg");
  return built([&] {
    return beaufort_preset(force, wind_direction_rad, static_cast<BeaufortSpectrum>(choice)).spectrum;
  });
}

// Whether the deep-water field gives the wave maker its components, and in which band.
struct DeepWaterDrive {
  bool drives_wave_maker = false;
  WaveMakerBand band;
};

// [deep_water] (docs/commands/bake.md): the FFT field beyond the harbour. With an irregular wave
// maker it is made from the maker's spectrum and spreading (DirectionalWavenumberSpectrum at the
// source line's depth), loop period and seed, so both sides describe one sea; with
// wave_maker.kind = "deep_water" it has its own spectrum and seed and gives the maker its waves.
DeepWaterSpecification read_deep_water(TableReader& deep, const WaveMaker& maker, const MakerRequest& request,
                                       const HarbourGrid& grid, DeepWaterDrive& drive, BakeCase& bake_case) {
  if (!request.spectrum && !request.from_deep_water)
    deep.fail("deep_water",
              "needs a wave maker that makes the same sea: an irregular one (whose spectrum, spreading, loop "
              "period and "
              "seed the field shares) or one made from the field",
              "set wave_maker.kind = \"irregular\" or \"deep_water\", or remove [deep_water]");
  if (request.long_crested)
    deep.fail("deep_water",
              "cannot share a long-crested irregular wave maker's sea (wave_maker.spreading_s = 0): the FFT "
              "lattice needs "
              "a directional spread",
              "set wave_maker.spreading_s (e.g. 75 for a swell, 20 for a wind sea)");
  if (request.spectrum)
    for (const char* key : {"spectrum", "seed"})
      if (deep.has(key))
        deep.fail(deep.full(key), "is the irregular wave maker's, which the field shares",
                  "set it in [wave_maker], or use wave_maker.kind = \"deep_water\" for a field with its own "
                  "spectrum");
  DeepWaterSpecification specification;
  specification.grid_size = deep.integer("grid_size", 256, 8, 4096, "samples per tile side, a power of two");
  if ((specification.grid_size & (specification.grid_size - 1)) != 0)
    deep.fail(deep.full("grid_size"), fmt::format("= {} is not a power of two", specification.grid_size), "use 64, 128, 256 or 512");
  const bool explicit_tiles = deep.has("tile_lengths_m");
  if (explicit_tiles && (deep.has("cascade_count") || deep.has("shortest_wavelength_m")))
    deep.fail(deep.full("tile_lengths_m"), "is given with cascade_count or shortest_wavelength_m",
              "give either the tile lengths or the cascade count and shortest wavelength (which lay the "
              "tiles out)");
  if (explicit_tiles) {
    specification.tile_lengths_m =
        deep.numbers("tile_lengths_m", 0, "[L_0, L_1, ...] in metres, strictly decreasing");
    for (std::size_t i = 0; i < specification.tile_lengths_m.size(); ++i)
      if (!(specification.tile_lengths_m[i] > 0.0) ||
          (i > 0 && !(specification.tile_lengths_m[i] < specification.tile_lengths_m[i - 1])))
        deep.fail(deep.full("tile_lengths_m"),
                  fmt::format("has {} m at position {}, not positive and below the one before",
                              specification.tile_lengths_m[i], i),
                  "list the tile lengths in metres from the largest down, e.g. [1000.0, 270.0, 73.0]");
    if (specification.tile_lengths_m.size() > 8)
      deep.fail(deep.full("tile_lengths_m"), fmt::format("has {} tiles", specification.tile_lengths_m.size()),
                "use at most 8 cascades");
  }
  const int cascade_count = explicit_tiles ? static_cast<int>(specification.tile_lengths_m.size())
                                           : deep.integer("cascade_count", 3, 1, 8,
                                                          "number of cascades (tiles of decreasing length)");
  const double shortest_wavelength_m =
      explicit_tiles ? 0.0
                     : deep.positive("shortest_wavelength_m", 0.5,
                                     "shortest wavelength the last cascade resolves, metres");
  specification.choppiness = deep.number("choppiness", 1.0, 0.0, 2.0, false, "lambda of the choppy displacement (0 = none)");
  drive.drives_wave_maker = request.from_deep_water || deep.boolean("drive_wave_maker", false);
  if (request.from_deep_water && !deep.boolean("drive_wave_maker", true))
    deep.fail(deep.full("drive_wave_maker"),
              "= false, but wave_maker.kind = \"deep_water\" takes its waves from the field",
              "remove drive_wave_maker, or give the wave maker its own kind");
  const double default_depth_m = source_line_depth_m(maker, grid);
  if (drive.drives_wave_maker && deep.has("depth_m"))
    deep.fail(
        deep.full("depth_m"),
        fmt::format(
            "is given, but a field that drives the wave maker must use the source line's depth ({:.3f} m)",
            default_depth_m),
        "remove depth_m: the field and the baked waves then share one dispersion relation at the offshore "
        "edge");
  specification.still_water_depth_m =
      deep.non_negative("depth_m", default_depth_m, "still-water depth of the dispersion relation, metres (0 = deep water)");
  specification.loop_period_s = maker.sea_state.loop_period_s;
  specification.seed =
      request.from_deep_water ? deep.unsigned_integer("seed", 1, "phase seed") : maker.sea_state.seed;
  bake_case.deep_water_tile_set_frame_interval_s =
      deep.non_negative("tile_set_frame_interval_s", 0.0, "frame interval of the baked tile set in seconds (0 = none)");
  bake_case.deep_water_tile_set_cascade = deep.integer("tile_set_cascade", 0, 0, cascade_count - 1, "the cascade the tile set bakes");
  if (bake_case.deep_water_tile_set_frame_interval_s > 0) {
    const double loop_s = specification.loop_period_s;
    const double frames = loop_s / bake_case.deep_water_tile_set_frame_interval_s;
    if (loop_s <= 0 || std::abs(frames - std::round(frames)) > 1e-9 * frames || frames < 2)
      deep.fail(deep.full("tile_set_frame_interval_s"),
                fmt::format("= {} s must divide wave_maker.loop_period_s = {} s into 2 or more frames (a tile set is one loop)",
                            bake_case.deep_water_tile_set_frame_interval_s, loop_s),
                "set wave_maker.loop_period_s and a frame interval that divides it, or remove tile_set_frame_interval_s");
  }
  specification.spectrum = request.from_deep_water
                               ? read_deep_water_spectrum(deep, direction_away_from(maker.facing),
                                                          specification.still_water_depth_m)
                               : std::make_shared<DirectionalWavenumberSpectrum>(
                                     request.spectrum, request.spreading, specification.still_water_depth_m);
  try {
    if (!explicit_tiles)
      specification.tile_lengths_m = cascade_tile_lengths_for_m(
          *specification.spectrum, specification.grid_size, cascade_count, shortest_wavelength_m);
  } catch (const Error& error) {
    deep.fail("deep_water", "cannot be laid out: " + error.problem(), error.fix());
  }
  // The band of the field the maker makes: kind "deep_water" says it; an irregular maker driven by
  // the field keeps the band its own discretisation chose (what the grid carries, checked above).
  drive.band = request.band;
  if (!request.from_deep_water && !maker.sea_state.components.empty()) {
    const auto [lowest, highest] =
        std::minmax_element(maker.sea_state.components.begin(), maker.sea_state.components.end(),
                            [](const WaveComponent& a, const WaveComponent& b) {
                              return a.angular_frequency_rad_s < b.angular_frequency_rad_s;
                            });
    drive.band.min_frequency_rad_s = lowest->angular_frequency_rad_s * (1 - 1e-9);
    drive.band.max_frequency_rad_s = highest->angular_frequency_rad_s * (1 + 1e-9);
  }
  return specification;
}

}  // namespace

BakeCase parse_bake_case(const json& document, const fs::path& case_file) {
  const std::string subject = case_file.string();
  const fs::path base = case_file.parent_path();
  TableReader root(document, "", subject);
  BakeCase bake_case;
  bake_case.case_file = case_file;
  bake_case.source = document;
  (void)root.string("title", "", "a title for the record");

  TableReader bathymetry = root.table("bathymetry");
  if (!root.has("bathymetry")) root.fail("bathymetry", "is missing", "add a [bathymetry] table (docs/commands/bake.md)");
  bake_case.harbour = read_bathymetry(bathymetry, base);
  bathymetry.finish();
  apply_porous_blocks(root.tables("porous_blocks"), bake_case.harbour);
  const GridGeometry& geometry = bake_case.harbour.geometry;

  if (!root.has("time")) root.fail("time", "is missing", "add a [time] table with duration_s and output_interval_s");
  TableReader time = root.table("time");
  const TimeRequest request = read_timing(time, bake_case.timing);
  time.finish();

  TableReader solver = root.table("solver");
  bake_case.solver = read_solver(solver);
  solver.finish();
  for (TableReader& entry : root.tables("sponges")) {
    SpongeLayer sponge;
    sponge.side = side_from_index(entry.choice("side", std::nullopt, kSideNames));
    const bool across_x = sponge.side == Side::kWest || sponge.side == Side::kEast;
    const double extent_m = across_x ? geometry.width_m() : geometry.height_m();
    sponge.width_m = entry.number("width_m", std::nullopt, 0.0, 0.5 * extent_m, true, "sponge width in metres, at most half the grid");
    entry.finish();
    bake_case.solver.sponges.push_back(sponge);
  }
  bake_case.solver.courant_number = request.courant_number;
  // The step divides the shorter of the output and gauge intervals, and that divides the longer, so
  // frames and gauge samples fall exactly on steps.
  const BakeTiming& timing = bake_case.timing;
  double divided_interval_s = timing.output_interval_s;
  if (timing.gauge_interval_s > 0) {
    divided_interval_s = std::min(timing.output_interval_s, timing.gauge_interval_s);
    if (whole_steps(std::max(timing.output_interval_s, timing.gauge_interval_s), divided_interval_s) < 1)
      time.fail(time.full("gauge_interval_s"), fmt::format("= {} s neither divides time.output_interval_s = {} s nor is a multiple of it",
                                                           timing.gauge_interval_s, timing.output_interval_s),
                "choose a gauge interval such as output_interval_s / 10");
  }
  bake_case.solver.time_step_s =
      resolve_time_step(request.time_step_s, request.courant_number, bake_case.harbour, divided_interval_s);

  if (!root.has("wave_maker")) root.fail("wave_maker", "is missing", "add a [wave_maker] table (kind = \"none\" for a basin at rest)");
  TableReader maker = root.table("wave_maker");
  MakerRequest maker_request;
  bake_case.wave_maker = read_wave_maker(maker, bake_case.harbour, base, maker_request);
  maker.finish();
  if (maker_request.from_deep_water && !root.has("deep_water"))
    root.fail("deep_water", "is missing, but wave_maker.kind = \"deep_water\" takes its waves from it",
              "add a [deep_water] table with a spectrum (docs/commands/bake.md), or give the wave maker "
              "another kind");
  if (root.has("deep_water")) {
    TableReader deep = root.table("deep_water");
    DeepWaterDrive drive;
    bake_case.deep_water =
        read_deep_water(deep, bake_case.wave_maker, maker_request, bake_case.harbour, drive, bake_case);
    deep.finish();
    if (drive.drives_wave_maker) {
      // The maker makes the field's own waves, phases moved to the solver's frame
      // (deep_water_coupling.hpp): at the offshore edge both are the same waves to linear order.
      try {
        const DeepWaterField field(*bake_case.deep_water);
        bake_case.deep_water_maker =
            couple_wave_maker(field, bake_case.wave_maker, bake_case.harbour, bake_case.solver, drive.band);
      } catch (const Error& error) {
        deep.fail("deep_water", "cannot be built: " + error.problem(), error.fix());
      }
      bake_case.wave_maker.sea_state = bake_case.deep_water_maker->sea_state;
      if (bake_case.wave_maker.sea_state.components.empty())
        deep.fail("deep_water",
                  "leaves the wave maker no component (none inside its band travelling into the domain "
                  "within 78 degrees)",
                  "turn the waves towards the domain (wave_maker.facing, the spectrum's direction), widen "
                  "the maker's frequency band, "
                  "or use a larger deep_water tile (finer lattice cells)");
    }
  }
  const double loop_period_s = bake_case.wave_maker.sea_state.loop_period_s;
  if (loop_period_s > 0 && whole_steps(loop_period_s, bake_case.timing.output_interval_s) < 1)
    time.fail(time.full("output_interval_s"), fmt::format("= {} s does not divide wave_maker.loop_period_s = {} s",
                                                          bake_case.timing.output_interval_s, loop_period_s),
              "choose an output interval that divides the loop period into whole frames");

  for (TableReader& entry : root.tables("gauges")) {
    GaugeSpec gauge;
    gauge.name = entry.string("name", std::nullopt, "gauge name");
    gauge.x_m = geometry.origin_x_m + entry.number("x_m", std::nullopt, 0.0, geometry.width_m(), false, "x from the south-west corner, inside the grid, metres");
    gauge.y_m = geometry.origin_y_m + entry.number("y_m", std::nullopt, 0.0, geometry.height_m(), false, "y from the south-west corner, inside the grid, metres");
    entry.finish();
    if (gauge.name.empty() || gauge.name.find_first_of(",\"\n") != std::string::npos)
      entry.fail(entry.full("name"), fmt::format("= \"{}\" is empty or holds a comma, quote or newline", gauge.name),
                 "name gauges with letters, digits, '_' or '-' (they become gauges.csv column names)");
    for (const GaugeSpec& other : bake_case.gauges)
      if (other.name == gauge.name)
        entry.fail(entry.full("name"), fmt::format("= \"{}\" is used by another gauge", gauge.name), "give every gauge its own name");
    bake_case.gauges.push_back(gauge);
  }
  root.finish();

  bake_case.wave_conditions = wave_record(bake_case.wave_maker, document.value("wave_maker", json::object()));
  if (bake_case.deep_water_maker) {
    bake_case.wave_conditions["driven_by_deep_water"] = true;
    bake_case.wave_conditions["deep_water_variance_fraction"] =
        bake_case.deep_water_maker->variance_fraction();
  }
  bake_case.solver_record = solver_record(bake_case.solver);
  return bake_case;
}

json read_case_document(const fs::path& case_file) { return parse_document(case_file); }

BakeCase read_bake_case(const fs::path& case_file) { return parse_bake_case(parse_document(case_file), case_file); }

}  // namespace nearshore::bake
