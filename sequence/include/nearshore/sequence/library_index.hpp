#pragma once
// library.json: the index of a sea-state library (`nearshore library`, library/), the one file a
// runtime reads to choose among a harbour's baked sea states. One typed, versioned contract
// (docs/library.md, "The index"): the writer and the parser below are the only code that spells
// its keys, as loops_file.hpp is for loops.json.
//
// A library is a sweep: a few axes (wave direction, height, period, spectrum, tide, wind), each a
// list of values, and one state per combination. Every state is a sequence folder (with its loop
// tables, so it plays forever) beside the index, or a failure recorded with its error.
//
// Version rule: "format": "nearshore library", "version": kLibraryIndexVersion. A reader refuses any
// other format and any version it does not know (a newer one included), naming the file; keys it
// does not know are ignored. Removing, renaming or re-typing a key, or changing what a value
// means, is a new version.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace nearshore::sequence {

inline constexpr std::string_view kLibraryIndexFormat = "nearshore library";
inline constexpr int kLibraryIndexVersion = 1;
inline constexpr const char* kLibraryIndexFileName = "library.json";

/// The quantities a library may sweep, as the index and LIBRARY.toml name them. Directions are
/// degrees counter-clockwise from east, the direction the waves (or the wind) travel TOWARD, as in
/// the case files (docs/commands/bake.md).
enum class SeaQuantity {
  kDirection,      ///< "direction_deg": mean direction of travel of the waves
  kHeight,         ///< "height_m": regular waves crest to trough; irregular seas Hs
  kPeriod,         ///< "period_s": regular waves' period; irregular seas' peak period Tp
  kSpectrum,       ///< "spectrum": the frequency spectrum's name ("jonswap", ...): the one label axis
  kTide,           ///< "tide_m": still-water level above the base case's datum (moves the wet/dry line)
  kWindSpeed,      ///< "wind_speed_m_s": wind speed of a wind-sea spectrum
  kWindDirection,  ///< "wind_direction_deg": direction the wind blows toward
};
inline constexpr SeaQuantity kSeaQuantities[] = {SeaQuantity::kDirection, SeaQuantity::kHeight,
                                                 SeaQuantity::kPeriod,    SeaQuantity::kSpectrum,
                                                 SeaQuantity::kTide,      SeaQuantity::kWindSpeed,
                                                 SeaQuantity::kWindDirection};
std::string_view sea_quantity_name(SeaQuantity quantity);
/// The quantity of a name, or nullopt for a name that is none.
std::optional<SeaQuantity> sea_quantity_from_name(std::string_view name);
/// Whether the quantity is an angle (compared on the circle: 350 and 10 degrees are 20 apart).
bool is_direction(SeaQuantity quantity);

/// The conditions of one sea state: one value per quantity the library sweeps, none for the others.
struct SeaConditions {
  std::optional<double> direction_deg, height_m, period_s, tide_m, wind_speed_m_s, wind_direction_deg;
  std::optional<std::string> spectrum;

  std::optional<double> number(SeaQuantity quantity) const;  ///< nullopt for kSpectrum
  void set_number(SeaQuantity quantity, double value);       ///< not for kSpectrum
  bool operator==(const SeaConditions&) const = default;
};

enum class LibraryStateStatus {
  kPending,  ///< not (yet) baked by the run that wrote the index: it is under way, or was stopped
  kBaked,    ///< its sequence folder is complete and verified, with loop tables
  kFailed,   ///< the bake or its loop tables failed; `error` says why
};
std::string_view library_state_status_name(LibraryStateStatus status);  ///< "pending", "baked", "failed"

struct LibraryIndex {
  /// One axis of the sweep, in the order of the library file: numbers, or labels for kSpectrum.
  struct Axis {
    SeaQuantity quantity = SeaQuantity::kDirection;
    std::vector<double> values;        ///< numeric axes
    std::vector<std::string> labels;   ///< kSpectrum
    std::size_t size() const { return quantity == SeaQuantity::kSpectrum ? labels.size() : values.size(); }
    bool operator==(const Axis&) const = default;
  };
  /// What the library run that wrote the index did with a state.
  struct Run {
    /// "reused" (complete and verified before), "loops" (baked before; only its loop tables were
    /// made), "resumed" (continued from its bake's checkpoint), "baked", or "" (not taken up)
    std::string action;
    int rank = -1;             ///< the MPI rank that did it (0 when serial), -1 when not taken up
    double wall_time_s = 0.0;  ///< of that work
    bool operator==(const Run&) const = default;
  };
  struct State {
    std::string id;             ///< unique, also the folder name ("dir090_h1.5_tide+0.5")
    SeaConditions conditions;   ///< one value per axis
    LibraryStateStatus status = LibraryStateStatus::kPending;
    std::string sequence;       ///< the sequence folder, relative to the index's folder ("states/<id>")
    std::string case_file;      ///< the case it was baked from, relative ("cases/<id>.json")
    std::string manifest_checksum;  ///< XXH64 of its manifest.json when baked ("xxh64:..."), else ""
    std::string loops_checksum;     ///< XXH64 of its loops.json when baked, else ""
    double cost_cell_steps = 0.0;   ///< cells x solver steps: the schedule's size (largest first)
    std::string error;              ///< why it failed (status kFailed), else ""
    Run run;
    bool operator==(const State&) const = default;
  };

  std::string title;
  std::string library_file;  ///< LIBRARY.toml as given to the run
  std::string base_case;     ///< the base case file, as the library file names it
  std::vector<Axis> axes;
  std::vector<State> states;  ///< every combination of the axes' values, in the library file's order

  int count(LibraryStateStatus status) const;
  bool operator==(const LibraryIndex&) const = default;
};

/// What is wrong with an axis ("has 90 and 450, the same direction (modulo 360 degrees)"), or ""
/// when nothing is: no values, numbers on the spectrum axis or names on another, a value that is
/// not finite, a value twice. The index parser and the library file's reader (library/) both ask.
std::string library_axis_problem(const LibraryIndex::Axis& axis);

/// The index as JSON (what write_library_index writes).
nlohmann::json library_index_to_json(const LibraryIndex& index);

/// Writes `folder`/library.json atomically. Throws nearshore::Error naming the file if it cannot.
void write_library_index(const std::filesystem::path& folder, const LibraryIndex& index);

/// Parses and validates library.json text: not JSON, another format, an unknown or newer version, a
/// missing key, a wrong type, an unknown quantity, a state whose conditions do not name one value
/// of every axis, two states with one id, a path that leaves the library's folder, a baked state
/// without checksums or a failed one without its error: each is a nearshore::Error naming `source`,
/// the key and the fix. Never crashes and throws nothing else on malformed input (fuzzed).
LibraryIndex parse_library_index(std::string_view text, const std::string& source);

/// Reads and validates `folder`/library.json (a missing file is an Error too).
LibraryIndex read_library_index(const std::filesystem::path& folder);

// ---- choosing states by the conditions asked for (what a runtime calls) ---------------------------

/// A baked state and its weight in a blend.
struct LibraryStateWeight {
  int state = -1;       ///< index into LibraryIndex::states
  double weight = 0.0;  ///< > 0; the weights of a selection add up to 1
  bool operator==(const LibraryStateWeight&) const = default;
};

struct LibrarySelection {
  /// The baked state nearest the request: least sum over the numeric axes of
  /// ((requested - value) / axis step)^2, the axis step being the smallest spacing between its
  /// values (so one step of any axis counts the same), angles on the circle; a state of another
  /// spectrum than the one asked for only when no baked state has that one. -1: nothing is baked.
  int nearest = -1;
  /// The request blended between its neighbours on the sweep's grid (the rule below), heaviest
  /// first; {nearest, 1} when the request falls on a state or its neighbours are not baked.
  std::vector<LibraryStateWeight> blend;
};

/// Conditions written as text, "KEY=VALUE,KEY=VALUE" with the quantities' names (e.g.
/// "wind_direction_deg=30,tide_m=1.5", "spectrum=jonswap"): how a viewer's command line and a
/// host through the C API ask for a sea state. "" is no condition at all. Throws nearshore::Error
/// naming `subject` and the item for an unknown quantity or a value that is not a finite number.
SeaConditions parse_sea_conditions(std::string_view text, const std::string& subject);

/// Chooses among the index's baked states for `requested` conditions. The blend rule (multilinear
/// interpolation on the sweep's grid, docs/library.md "Choosing a state"):
///  1. every numeric axis brackets the requested value between its two neighbouring values a <= x
///     <= b and gives the far one the weight t = (x - a) / (b - a), the near one 1 - t. Outside
///     the axis the value is held at its end (t = 0): the library does not extrapolate. Directions
///     are bracketed on the circle, except across the largest gap between an axis's directions
///     when that gap exceeds 180 degrees (the sweep covers a sector, not the circle), where the
///     value is held at the nearer end. An axis of one value, and a quantity the request leaves
///     unset, is held at the axis's first value;
///  2. the spectrum axis takes the requested spectrum (the axis's first when unset or not swept);
///  3. each corner of the bracketing cell weighs the product of its axes' weights; corners of zero
///     weight are dropped, and so are corners not baked (failed, pending), the others renormalised;
///  4. when no corner is baked the blend is the nearest state alone.
/// Costs O(states x axes); call it when the conditions change, not every frame. Blending surfaces
/// of different sea states by these weights is the runtime's business (a crossfade): two
/// uncorrelated seas blended with weights w and 1 - w have (w^2 + (1 - w)^2) of their variance.
LibrarySelection select_library_states(const LibraryIndex& index, const SeaConditions& requested);

}  // namespace nearshore::sequence
