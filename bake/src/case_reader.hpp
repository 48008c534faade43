#pragma once
// The case file's reader, shared by the files that read its sections (case_document.cpp,
// case_bathymetry.cpp, case_wave_maker.cpp, case_sea_state.cpp, case_solver.cpp; bake_case.cpp
// assembles them). Private to bake/. Every key is read through a TableReader that remembers what it
// consumed, so unknown keys (typos) are reported, and every message names the case file, the full
// key and the fix.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/deep_water_coupling.hpp"
#include "nearshore/boussinesq/initial_conditions.hpp"
#include "nearshore/boussinesq/solver_parameters.hpp"  // kMaxCourantNumber, Side, WaveMaker, SolverParameters
#include "nearshore/core/error.hpp"
#include "nearshore/core/map_projection.hpp"
#include "nearshore/ocean/spectrum_registry.hpp"

namespace nearshore::bake::detail {

namespace fs = std::filesystem;
using nlohmann::json;

inline constexpr double kDegree = std::numbers::pi / 180.0;

// ---- physical plausibility bounds of a case (docs/commands/bake.md, "Bounds") ---------------------
/// No water on Earth is deeper than the Challenger Deep (10 935 m): a deeper cell is a fill value,
/// a wrong unit or a wrong sign (bathymetry/ refuses such inputs with the same bound).
inline constexpr double kDeepestPlausibleDepth_m = 11000.0;
/// The solver's stability limit, checked here first so that the message names the case file's key.
using boussinesq::kMaxCourantNumber;
/// At most this many solver steps: 1e7 steps of a 300 x 300 grid are about a day on one core at
/// the solver's ~1e7 cell updates per second (docs/solver.md); more is a mistyped time or grid.
inline constexpr double kMaxSolverSteps = 1e7;
/// At most this many frames, one file each: a million frames of 1 s are 11.6 days of simulated sea,
/// where a looping sea needs one loop period (minutes).
inline constexpr double kMaxFrames = 1e6;

/// TOML or JSON -> one JSON document, integers kept apart from floats (case_document.cpp).
json parse_case_document(const fs::path& case_file);
/// The same from the case file's text; `source` names it in messages (the case-file fuzzer's entry).
enum class CaseSyntax { kToml, kJson };
json parse_case_text(const std::string& text, CaseSyntax syntax, const std::string& source);

/// `text` with every run of more than 24 digits cut to its first 12 and a count ("123456789012...
/// (309 digits)"): a parser's message or a value echoed back must not reprint a 309-digit number
/// (issue 44); the count says what was wrong with it.
std::string shortened_numbers(const std::string& text);
/// A value as the messages show it: its JSON text, numbers shortened, at most 80 characters.
std::string shown(const json& value);

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
  /// Whether `key` is present and a table (for keys that take a value or a table of values).
  bool has_table(const std::string& key) const { return table_.contains(key) && table_.at(key).is_object(); }

  /// A number; `minimum`/`maximum` are inclusive bounds unless `exclusive_minimum`.
  double number(const std::string& key, std::optional<double> fallback, double minimum, double maximum,
                bool exclusive_minimum, const std::string& meaning) {
    const json* value = find(key);
    if (!value) {
      if (fallback) return *fallback;
      fail(full(key), "is missing", "add " + full(key) + " = <" + meaning + ">");
    }
    if (!value->is_number())
      fail(full(key), fmt::format("is {} but must be a number", shown(*value)), "write " + meaning + " as a number");
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
      fail(full(key), fmt::format("is {} but must be a whole number", shown(*value)), "write " + meaning + " as an integer");
    const auto x = value->get<long long>();
    if (x < minimum || x > maximum)
      fail(full(key), fmt::format("= {} is out of range", x), fmt::format("give {} from {} to {}", meaning, minimum, maximum));
    return static_cast<int>(x);
  }
  std::uint64_t unsigned_integer(const std::string& key, std::uint64_t fallback, const std::string& meaning) {
    const json* value = find(key);
    if (!value) return fallback;
    if (!value->is_number_integer() || value->get<long long>() < 0)
      fail(full(key), fmt::format("is {} but must be a whole number >= 0", shown(*value)), "write " + meaning + " as an integer");
    return value->get<std::uint64_t>();
  }
  bool boolean(const std::string& key, bool fallback) {
    const json* value = find(key);
    if (!value) return fallback;
    if (!value->is_boolean()) fail(full(key), fmt::format("is {} but must be true or false", shown(*value)), "write true or false");
    return value->get<bool>();
  }
  std::string string(const std::string& key, std::optional<std::string> fallback, const std::string& meaning) {
    const json* value = find(key);
    if (!value) {
      if (fallback) return *fallback;
      fail(full(key), "is missing", "add " + full(key) + " = \"<" + meaning + ">\"");
    }
    if (!value->is_string()) fail(full(key), fmt::format("is {} but must be a string", shown(*value)), "write it in quotes");
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
  /// A cell size in metres: one positive number (square cells) or two, [dx, dy] (rectangular
  /// cells along x and y, issue 15). Returns {dx, dy}.
  std::pair<double, double> cell_size(const std::string& key) {
    const json* value = find(key);
    if (value && value->is_array()) {
      const std::vector<double> sizes = numbers(key, 2, "[dx_m, dy_m], the cell size along x and along y in metres");
      if (!(sizes[0] > 0.0) || !(sizes[1] > 0.0))
        fail(full(key), fmt::format("= [{}, {}] is not a cell size", sizes[0], sizes[1]), "give two sizes > 0 in metres");
      return {sizes[0], sizes[1]};
    }
    const double size = positive(key, std::nullopt, "cell size in metres, or [dx_m, dy_m] for rectangular cells");
    return {size, size};
  }
  std::vector<double> numbers(const std::string& key, std::size_t count, const std::string& meaning) {
    const json* value = find(key);
    if (!value) fail(full(key), "is missing", "add " + full(key) + " = " + meaning);
    if (!value->is_array() || (count && value->size() != count) || value->empty())
      fail(full(key), fmt::format("is {} but must be {}", shown(*value), meaning), "write it as " + meaning);
    std::vector<double> out;
    for (const json& item : *value) {
      if (!item.is_number() || !std::isfinite(item.get<double>()))
        fail(full(key), fmt::format("holds {}, not a number", shown(item)), "write it as " + meaning);
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
        fail(full(key), fmt::format("holds {}, not a pair of numbers", shown(item)), "write it as " + meaning);
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

// ---- grid sides ----------------------------------------------------------------------------------
extern const std::vector<std::string> kSideNames;  ///< "west", "east", "south", "north": Side order
boussinesq::Side side_from_index(std::size_t index);
std::string side_name(boussinesq::Side side);
/// Direction of travel (radians, counter-clockwise from +x) of waves coming from `facing`.
double direction_away_from(boussinesq::Side facing);
double deepest_still_water_m(const HarbourGrid& grid);

// ---- sections ------------------------------------------------------------------------------------
/// [bathymetry] (case_bathymetry.cpp). Refuses a grid with a non-finite depth or one deeper than
/// kDeepestPlausibleDepth_m, naming the key the grid came from.
HarbourGrid read_bathymetry(TableReader& bathymetry, const fs::path& base, const CaseReadOptions& options);
/// [[porous_blocks]]: rectangles of porous structure (rubble mounds) or walls over any bathymetry.
void apply_porous_blocks(std::vector<TableReader> blocks, HarbourGrid& grid);
/// A position given in `table` by one pair of geo_position_keys() (x_m/y_m from the
/// south-west corner, easting_m/northing_m in the grid's CRS, or lat/lon; case_bathymetry.cpp): the
/// point in the solver's frame (GridGeometry origin included). Outside the grid it fails naming
/// `entry` and the grid's extent; on land or outside the chart it appends a warning naming `entry`
/// and the cell's depth (docs/commands/bake.md, "Positions").
ProjectedPoint read_case_position(TableReader& table, const HarbourGrid& grid, const std::string& entry,
                                  std::vector<std::string>& warnings);

/// The spectrum named by `key` (the registry's names; `fallback` when absent, required when
/// nullopt) built from the table's keys (ocean/spectrum_registry.hpp; case_sea_state.cpp).
std::shared_ptr<const ocean::FrequencySpectrum> read_frequency_spectrum(TableReader& table, const std::string& key,
                                                                        std::optional<std::string> fallback);
std::shared_ptr<const ocean::WavenumberSpectrum> read_wavenumber_spectrum(TableReader& table, const std::string& key,
                                                                          const ocean::SpectrumDefaults& defaults);

/// The wave-maker kinds of the case file, in the order of kMakerKindNames.
enum class MakerKind { kNone, kRegular, kComponents, kTimeSeries, kSolitary, kIrregular, kDeepWater };
inline const std::vector<std::string> kMakerKindNames = {"none",     "regular",   "components", "time_series",
                                                         "solitary", "irregular", "deep_water"};

// What the [wave_maker] table asks of the sea beyond the single maker: the irregular maker's spectrum
// and spreading (which [deep_water] shares), or for kind "deep_water" the band of the field it makes.
/// An irregular sea split between the bake and the FFT deep-water layer (docs/commands/bake.md,
/// "The spectrum is split"): the bake keeps the components its grid carries, the deep-water layer
/// draws the rest; Hs_total^2 = Hs_bake^2 + Hs_left^2 (variances add).
struct SpectrumSplit {
  double min_frequency_hz = 0.0, max_frequency_hz = 0.0;  // the bake's band (its components' range)
  double left_min_frequency_hz = 0.0;  // the lowest left component's frequency (the edge lies half-way)
  double bake_significant_height_m = 0.0, left_significant_height_m = 0.0, total_significant_height_m = 0.0;
  int bake_components = 0, left_components = 0;
  std::string reason;  // why the band ends there (carried_band_reason)
};

struct MakerRequest {
  bool from_deep_water = false;  // kind = "deep_water": the components come from [deep_water]
  std::optional<SpectrumSplit> split;                     // irregular: components the grid does not carry
  std::shared_ptr<const ocean::FrequencySpectrum> spectrum;      // irregular
  std::shared_ptr<const ocean::DirectionalSpreading> spreading;  // irregular
  bool long_crested = false;                              // irregular with spreading_s = 0
  WaveMakerBand band;                                     // deep_water
  std::optional<boussinesq::SolitaryWave> solitary_wave;  // solitary: the initial condition
  std::vector<std::string> warnings;                      // a source line on land (BakeCase::warnings)
};

/// What bounds the band the bake carries besides the grid: the solver's B and its effective-depth
/// limit, given in [solver] (`given`) or derived from the band (docs/solver.md, "Effective depth").
struct DispersionBound {
  double dispersion_coefficient = 1.0 / 15.0;
  bool effective_depth_limit_given = false;
  double effective_depth_limit_m = 0.0;  // when given; 0 = none
};

/// [wave_maker] (case_wave_maker.cpp). `sponges`: the case's [[sponges]], behind which a source along
/// an open boundary (`boundary = "north"`) is placed.
boussinesq::WaveMaker read_wave_maker(TableReader& maker, const HarbourGrid& grid, const fs::path& base,
                                      const DispersionBound& bound, const std::vector<boussinesq::SpongeLayer>& sponges,
                                      MakerRequest& request);
/// The wave maker as recorded in the sequence's wave_conditions.
json wave_record(const boussinesq::WaveMaker& maker, const json& as_written);
/// The highest frequency (rad/s) the grid carries in a band starting at `lowest_rad_s` (0 when not
/// known): `cells_per_wavelength` cells per wavelength and k d <= 3 over the deepest water the
/// solver sees, which an effective-depth limit may make shallower as long as the band's longest wave
/// stays within boussinesq::carried_phase_speed_tolerance() of Airy over the true deepest
/// (docs/solver.md, "Effective depth"); and that rule in words.
double highest_carried_frequency_rad_s(const HarbourGrid& grid, int cells_per_wavelength, double lowest_rad_s,
                                       const DispersionBound& bound);
std::string carried_band_reason(const HarbourGrid& grid, int cells_per_wavelength, double lowest_rad_s,
                                const DispersionBound& bound);
/// The effective-depth limit a band whose highest frequency is `highest_rad_s` needs: the depth
/// where that wave has k d = 3 (boussinesq::effective_depth_limit_m), or 0 where the grid is not
/// that deep (the limit is then inactive and the solver sees the grid unchanged).
double automatic_effective_depth_limit_m(const HarbourGrid& grid, double highest_rad_s);

// Whether the deep-water field gives the wave maker its components, and in which band.
struct DeepWaterDrive {
  bool drives_wave_maker = false;
  WaveMakerBand band;
};

/// [deep_water] (case_sea_state.cpp).
ocean::DeepWaterSpecification read_deep_water(TableReader& deep, const boussinesq::WaveMaker& maker,
                                              const MakerRequest& request, const HarbourGrid& grid,
                                              DeepWaterDrive& drive, BakeCase& bake_case);

/// [output] (case_output.cpp): frame codec and precision, the wave-statistics maps.
BakeOutput read_output(TableReader& output);

/// [solver] and its record (case_solver.cpp).
boussinesq::SolverParameters read_solver(TableReader& solver);
json solver_record(const boussinesq::SolverParameters& p);

}  // namespace nearshore::bake::detail
