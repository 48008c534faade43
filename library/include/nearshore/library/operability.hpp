#pragma once
// Operability of a harbour's berths over its wave climate (issue 39; docs/port-study.md): given a
// sea-state library (library.json, one baked sequence per state) and an occurrence table of the
// offshore conditions (Hs, Tp, direction, probability), the percentage of time each berth's
// significant wave height exceeds a limit (downtime; 100 minus it is the operability).
//
// Each condition of the table is mapped to the library's nearest baked state by the rule the
// runtime chooses states by (sequence::select_library_states: least sum over the swept axes of
// ((condition - state) / axis step)^2, directions on the circle), and that state's agitation
// coefficient at the berth, K = Hs_berth / Hs_incident (export/agitation.hpp), is scaled linearly:
//     Hs_berth(condition) = K_state(berth) * Hs_condition.                                   (1)
// Linear wave theory makes K independent of the incident height (diffraction, refraction,
// reflection and linear transmission are linear operators on the surface), so (1) holds where
// the waves inside are linear; it does not where they break (depth-limited Hs ~ 0.5-0.6 h), where
// a porous structure's quadratic (Forchheimer) resistance makes transmission fall with height, or
// where overtopping adds waves. A library that sweeps the height picks the state nearest the
// condition's Hs, so the scale stays near 1 where those effects matter.
//
// Downtime of a berth:  D = 100 * sum over conditions with Hs_berth > limit of p,          (2)
// p the condition's probability (the table's probabilities add up to 1).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nearshore/export/agitation.hpp"
#include "nearshore/sequence/library_index.hpp"

namespace nearshore::library {

/// |sum of probabilities - 1| above which an occurrence table is refused: tables rounded to 0.1 %
/// over up to ten bins stay within it; a missing or doubled bin (a few per cent) does not.
inline constexpr double kProbabilitySumTolerance = 0.005;

/// One row of an occurrence table: an offshore condition and how often it occurs.
struct OccurrenceCondition {
  double significant_wave_height_m = 0.0;  ///< Hs offshore (at the wave maker), m
  double peak_period_s = 0.0;              ///< Tp, s
  double direction_deg = 0.0;              ///< direction of travel, degrees counter-clockwise from east (the library's)
  double probability = 0.0;                ///< fraction of time, 0..1
  std::string place;                       ///< "occurrence.csv:7"
};

/// Reads a CSV occurrence table: the header `hs_m,tp_s,direction_deg,probability` (direction the
/// waves travel toward, degrees counter-clockwise from east, as the library and the case files) or
/// `hs_m,tp_s,direction_from_deg,probability` (the metocean convention: the direction the waves
/// come from, degrees clockwise from north; converted as 270 - from), then one condition a line;
/// blank lines and lines starting with '#' skipped. Throws nearshore::Error naming the file, the
/// line and the fix for another header, a field that is not a number, Hs or Tp not > 0, a
/// probability outside 0..1, no rows, or probabilities whose sum is not 1 within
/// kProbabilitySumTolerance.
std::vector<OccurrenceCondition> read_occurrence_table(const std::filesystem::path& file);

/// (2): 100 x the sum of `probability[i]` over the i with `hs_m[i]` > `limit_m` (strictly: a berth
/// at its limit is still workable), percent of time.
double exceedance_percent(const std::vector<double>& hs_m, const std::vector<double>& probability, double limit_m);

struct OperabilityRequest {
  std::filesystem::path library_folder;   ///< holds library.json and the states' sequences
  std::filesystem::path occurrence_file;  ///< read_occurrence_table
  std::filesystem::path berths_file;      ///< exports::read_berths (CSV or GeoJSON)
  double limit_significant_wave_height_m = 0.0;  ///< Hs above which a berth is not workable, m (> 0)
  /// The library's other swept quantities (tide, spectrum, wind), which the table has no column for;
  /// unset ones are held at the axis's first value, as select_library_states does.
  sequence::SeaConditions held;
};

/// A condition of the table, the state it was mapped to, and the berths' Hs under it.
struct OperabilityCondition {
  OccurrenceCondition condition;
  std::string state_id;
  sequence::SeaConditions state_conditions;
  double state_incident_significant_wave_height_m = 0.0;  ///< Hs_incident of the state's bake, m
  double scale = 0.0;                                     ///< Hs_condition / Hs_incident of the state
  std::vector<double> berth_significant_wave_height_m;    ///< (1), one per berth, in the berths file's order
};

struct OperabilityBerth {
  exports::Berth berth;
  double exceedance_percent = 0.0;  ///< (2)
  double largest_significant_wave_height_m = 0.0;
};

struct OperabilityResult {
  std::filesystem::path library_folder;
  double limit_significant_wave_height_m = 0.0;
  std::vector<OperabilityCondition> conditions;
  std::vector<OperabilityBerth> berths;
  std::vector<std::string> notes;  ///< conditions the library does not cover, a rescaled probability sum
  /// {"library", "limit_significant_wave_height_m", "berths": [{"name", "x_m", "y_m",
  /// "exceedance_percent", "operability_percent", "largest_significant_wave_height_m"}],
  /// "conditions": [{"hs_m", "tp_s", "direction_deg", "probability", "state", "state_incident_hs_m",
  /// "scale", "berth_hs_m": [...]}], "notes"}.
  nlohmann::json to_json() const;
};

/// Maps every condition to its state, reads each state used once (its Hs: the bake's statistics or
/// its frames, export/agitation.hpp), and computes (1) and (2). Throws nearshore::Error naming the
/// file at fault: the index, a state's sequence, the table, the berths (on land or outside the
/// grid in a state), OperabilityRequest::limit_significant_wave_height_m not > 0, or a library
/// with no baked state.
OperabilityResult compute_operability(const OperabilityRequest& request);

/// Writes, atomically, `folder`/operability.csv (one row per berth), operability_conditions.csv
/// (one row per condition: its state, scale and every berth's Hs) and operability.png (a bar
/// chart of the berths' exceedance, axes and the limit in its title). Returns the files written.
std::vector<std::filesystem::path> write_operability(const OperabilityResult& result, const std::filesystem::path& folder);

}  // namespace nearshore::library
