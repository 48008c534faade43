// Operability of berths over a library and an occurrence table (operability.hpp).
#include "nearshore/library/operability.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <fmt/core.h>

#include "nearshore/core/csv_fields.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::library {
namespace {

namespace fs = std::filesystem;

double wrapped_deg(double degrees) {
  const double wrapped = std::fmod(degrees, 360.0);
  return wrapped < 0.0 ? wrapped + 360.0 : wrapped;
}

// What a state gives every berth: its incident Hs and the agitation coefficient there.
struct StateAgitation {
  double incident_significant_wave_height_m = 0.0;
  std::vector<double> coefficients;
};

StateAgitation read_state_agitation(const fs::path& library_folder, const sequence::LibraryIndex::State& state,
                                    const fs::path& berths_file, std::vector<exports::Berth>& berths) {
  const sequence::SequenceReader reader(library_folder / state.sequence);
  const HarbourGrid harbour = reader.read_harbour_grid();
  if (berths.empty()) berths = exports::read_berths(berths_file, harbour.geometry);
  const std::optional<double> incident =
      exports::recorded_incident_significant_wave_height_m(reader.manifest().wave_conditions);
  if (!incident || !(*incident > 0.0))
    throw Error((library_folder / state.sequence / "manifest.json").string(),
                fmt::format("state '{}': wave_conditions record no wave maker height, so its agitation coefficient is unknown",
                            state.id),
                "bake the library's states with a regular, components, irregular or deep-water wave maker");
  const exports::SignificantWaveHeight hs =
      exports::sequence_significant_wave_height(reader, harbour, 0, reader.frame_count());
  StateAgitation agitation;
  agitation.incident_significant_wave_height_m = *incident;
  try {
    for (const exports::BerthValue& value : exports::berth_values(berths, hs.significant_wave_height_m, *incident, harbour))
      agitation.coefficients.push_back(value.agitation_coefficient);
  } catch (const Error& error) {
    throw Error(error.subject(), fmt::format("in state '{}' of {}: {}", state.id, library_folder.string(), error.problem()),
                error.fix());
  }
  return agitation;
}

// The axis of the index that a condition's direction sets: the waves' direction, else (a wind-sea
// library) the wind's, along which the waves travel.
std::optional<sequence::SeaQuantity> direction_axis(const sequence::LibraryIndex& index) {
  for (sequence::SeaQuantity quantity : {sequence::SeaQuantity::kDirection, sequence::SeaQuantity::kWindDirection})
    for (const auto& axis : index.axes)
      if (axis.quantity == quantity) return quantity;
  return std::nullopt;
}

const sequence::LibraryIndex::Axis* axis_of(const sequence::LibraryIndex& index, sequence::SeaQuantity quantity) {
  for (const auto& axis : index.axes)
    if (axis.quantity == quantity) return &axis;
  return nullptr;
}

// The smallest spacing between an axis's values (0 for an axis of one value): half of it is how
// far a condition may lie from its state before the library is said not to cover it.
double axis_step(const sequence::LibraryIndex::Axis& axis, bool circular) {
  double step = 0.0;
  for (std::size_t a = 0; a < axis.values.size(); ++a)
    for (std::size_t b = a + 1; b < axis.values.size(); ++b) {
      double gap = std::abs(axis.values[a] - axis.values[b]);
      if (circular) gap = std::min(wrapped_deg(gap), 360.0 - wrapped_deg(gap));
      if (gap > 0.0 && (step == 0.0 || gap < step)) step = gap;
    }
  return step;
}

std::string csv_condition_columns() { return "line,hs_m,tp_s,direction_deg,probability,state,state_incident_hs_m,scale"; }

}  // namespace

std::vector<OccurrenceCondition> read_occurrence_table(const fs::path& file) {
  require_readable_file(file, "an occurrence table: CSV hs_m,tp_s,direction_deg,probability");
  std::ifstream in(file);
  const std::string subject = file.string();
  const std::string header_fix =
      "start the file with hs_m,tp_s,direction_deg,probability (direction the waves travel toward, degrees "
      "counter-clockwise from east) or hs_m,tp_s,direction_from_deg,probability (the direction they come from, degrees "
      "clockwise from north)";
  bool header_read = false, from_north = false;
  std::vector<OccurrenceCondition> conditions;
  std::string line;
  int number = 0;
  double sum = 0.0;
  while (std::getline(in, line)) {
    ++number;
    const std::string text = trimmed(line);
    if (text.empty() || text.front() == '#') continue;
    const std::vector<std::string> fields = csv_fields(text);
    if (!header_read) {
      if (fields == std::vector<std::string>{"hs_m", "tp_s", "direction_deg", "probability"})
        from_north = false;
      else if (fields == std::vector<std::string>{"hs_m", "tp_s", "direction_from_deg", "probability"})
        from_north = true;
      else
        throw Error(subject, fmt::format("line {}: the header is '{}', not an occurrence table's", number, text), header_fix);
      header_read = true;
      continue;
    }
    if (fields.size() != 4)
      throw Error(subject, fmt::format("line {}: '{}' has {} fields", number, text, fields.size()),
                  "write hs_m,tp_s,direction,probability: four numbers separated by commas");
    static const char* const kNames[] = {"hs_m", "tp_s", "direction", "probability"};
    double values[4];
    for (int f = 0; f < 4; ++f) {
      const std::optional<double> value = finite_number(fields[f]);
      if (!value)
        throw Error(subject, fmt::format("line {}: {} = '{}' is not a number", number, kNames[f], fields[f]),
                    "give plain decimal numbers (a probability as a fraction, 0.125, not 12.5 %)");
      values[f] = *value;
    }
    if (!(values[0] > 0.0) || !(values[1] > 0.0))
      throw Error(subject, fmt::format("line {}: Hs = {} m, Tp = {} s: both must be > 0", number, values[0], values[1]),
                  "give the significant wave height in metres and the peak period in seconds");
    if (!(values[3] >= 0.0 && values[3] <= 1.0))
      throw Error(subject, fmt::format("line {}: probability = {} is outside 0 .. 1", number, values[3]),
                  "give the probability as a fraction of time (percent / 100)");
    OccurrenceCondition condition;
    condition.significant_wave_height_m = values[0];
    condition.peak_period_s = values[1];
    // From (nautical, clockwise from north) to toward (counter-clockwise from east): waves from the
    // north (0) travel south (270), from the west (270) travel east (0).
    condition.direction_deg = from_north ? wrapped_deg(270.0 - values[2]) : values[2];
    condition.probability = values[3];
    condition.place = fmt::format("{}:{}", file.filename().string(), number);
    sum += values[3];
    conditions.push_back(condition);
  }
  if (!header_read) throw Error(subject, "is empty", header_fix + ", then one condition a line");
  if (conditions.empty()) throw Error(subject, "has a header but no condition", "add one condition a line");
  if (std::abs(sum - 1.0) > kProbabilitySumTolerance)
    throw Error(subject,
                fmt::format("the probabilities of its {} conditions add up to {:.4f}, not 1 (within {})", conditions.size(), sum,
                            kProbabilitySumTolerance),
                "give every condition's fraction of time, all of them together 1 (a missing or repeated bin shows as this)");
  return conditions;
}

double exceedance_percent(const std::vector<double>& hs_m, const std::vector<double>& probability, double limit_m) {
  double exceeded = 0.0;
  for (std::size_t i = 0; i < hs_m.size() && i < probability.size(); ++i)
    if (hs_m[i] > limit_m) exceeded += probability[i];
  return 100.0 * exceeded;
}

OperabilityResult compute_operability(const OperabilityRequest& request) {
  if (!(request.limit_significant_wave_height_m > 0.0 && std::isfinite(request.limit_significant_wave_height_m)))
    throw Error("OperabilityRequest::limit_significant_wave_height_m",
                fmt::format("= {} m is not a wave height", request.limit_significant_wave_height_m),
                "give the Hs above which a berth is not workable, in metres (e.g. 0.5 for small craft)");
  const sequence::LibraryIndex index = sequence::read_library_index(request.library_folder);
  const std::vector<OccurrenceCondition> table = read_occurrence_table(request.occurrence_file);
  if (index.count(sequence::LibraryStateStatus::kBaked) == 0)
    throw Error((request.library_folder / sequence::kLibraryIndexFileName).string(), "has no baked state",
                "bake the library first (its failed states' errors are in the index)");
  const std::optional<sequence::SeaQuantity> direction = direction_axis(index);
  const auto* period_axis = axis_of(index, sequence::SeaQuantity::kPeriod);
  const auto* height_axis = axis_of(index, sequence::SeaQuantity::kHeight);
  const auto* direction_axis_values = direction ? axis_of(index, *direction) : nullptr;

  OperabilityResult result;
  result.library_folder = request.library_folder;
  result.limit_significant_wave_height_m = request.limit_significant_wave_height_m;
  std::vector<exports::Berth> berths;
  std::map<int, StateAgitation> states;  // read once each, as the conditions first need them
  double uncovered_probability = 0.0;
  int uncovered = 0;
  for (const OccurrenceCondition& condition : table) {
    sequence::SeaConditions requested = request.held;
    if (direction) requested.set_number(*direction, condition.direction_deg);
    if (period_axis) requested.period_s = condition.peak_period_s;
    if (height_axis) requested.height_m = condition.significant_wave_height_m;
    const int chosen = sequence::select_library_states(index, requested).nearest;
    const sequence::LibraryIndex::State& state = index.states[static_cast<std::size_t>(chosen)];
    auto found = states.find(chosen);
    if (found == states.end())
      found = states.emplace(chosen, read_state_agitation(request.library_folder, state, request.berths_file, berths)).first;
    const StateAgitation& agitation = found->second;
    // A condition more than half an axis step from its state's direction or period (or outside an
    // axis of one value) is not one the library covers: say how much of the time that is.
    bool covered = true;
    if (direction_axis_values) {
      const double step = axis_step(*direction_axis_values, true);
      const double gap = wrapped_deg(condition.direction_deg - *state.conditions.number(*direction));
      const double distance = std::min(gap, 360.0 - gap);
      covered = covered && distance <= (step > 0.0 ? 0.5 * step : 0.0) + 1e-9;
    }
    if (period_axis) {
      const double step = axis_step(*period_axis, false);
      covered = covered && std::abs(condition.peak_period_s - *state.conditions.period_s) <= (step > 0.0 ? 0.5 * step : 0.0) + 1e-9;
    }
    if (!covered) {
      ++uncovered;
      uncovered_probability += condition.probability;
    }
    OperabilityCondition mapped;
    mapped.condition = condition;
    mapped.state_id = state.id;
    mapped.state_conditions = state.conditions;
    mapped.state_incident_significant_wave_height_m = agitation.incident_significant_wave_height_m;
    mapped.scale = condition.significant_wave_height_m / agitation.incident_significant_wave_height_m;
    for (double coefficient : agitation.coefficients)
      mapped.berth_significant_wave_height_m.push_back(coefficient * condition.significant_wave_height_m);  // (1)
    result.conditions.push_back(std::move(mapped));
  }
  if (uncovered > 0)
    result.notes.push_back(fmt::format(
        "{} condition{} ({:.1f} % of the time) {} more than half an axis step from {} state's direction or period: the "
        "library does not cover {} and {} berths' Hs are the nearest state's; add states there",
        uncovered, uncovered == 1 ? "" : "s", 100.0 * uncovered_probability, uncovered == 1 ? "lies" : "lie",
        uncovered == 1 ? "its" : "their", uncovered == 1 ? "it" : "them", uncovered == 1 ? "its" : "their"));
  if (!direction) result.notes.push_back("the library sweeps no direction: every condition takes the base case's");
  if (!period_axis) result.notes.push_back("the library sweeps no period: every condition takes the base case's");

  std::vector<double> probability;
  for (const OperabilityCondition& mapped : result.conditions) probability.push_back(mapped.condition.probability);
  for (std::size_t b = 0; b < berths.size(); ++b) {
    std::vector<double> hs;
    for (const OperabilityCondition& mapped : result.conditions) hs.push_back(mapped.berth_significant_wave_height_m[b]);
    OperabilityBerth berth;
    berth.berth = berths[b];
    berth.exceedance_percent = exceedance_percent(hs, probability, request.limit_significant_wave_height_m);
    berth.largest_significant_wave_height_m = *std::max_element(hs.begin(), hs.end());
    result.berths.push_back(berth);
  }
  return result;
}

nlohmann::json OperabilityResult::to_json() const {
  nlohmann::json berth_json = nlohmann::json::array();
  for (const OperabilityBerth& berth : berths)
    berth_json.push_back({{"name", berth.berth.name},
                          {"x_m", berth.berth.x_m},
                          {"y_m", berth.berth.y_m},
                          {"exceedance_percent", berth.exceedance_percent},
                          {"operability_percent", 100.0 - berth.exceedance_percent},
                          {"largest_significant_wave_height_m", berth.largest_significant_wave_height_m}});
  nlohmann::json condition_json = nlohmann::json::array();
  for (const OperabilityCondition& mapped : conditions)
    condition_json.push_back({{"place", mapped.condition.place},
                              {"hs_m", mapped.condition.significant_wave_height_m},
                              {"tp_s", mapped.condition.peak_period_s},
                              {"direction_deg", mapped.condition.direction_deg},
                              {"probability", mapped.condition.probability},
                              {"state", mapped.state_id},
                              {"state_incident_hs_m", mapped.state_incident_significant_wave_height_m},
                              {"scale", mapped.scale},
                              {"berth_hs_m", mapped.berth_significant_wave_height_m}});
  return {{"library", library_folder.string()},
          {"limit_significant_wave_height_m", limit_significant_wave_height_m},
          {"berths", berth_json},
          {"conditions", condition_json},
          {"notes", notes}};
}

std::string operability_berths_csv(const OperabilityResult& result) {
  std::ostringstream csv;
  csv << "name,x_m,y_m,limit_hs_m,exceedance_percent,operability_percent,largest_hs_m\n";
  for (const OperabilityBerth& berth : result.berths)
    csv << berth.berth.name
        << fmt::format(",{:.2f},{:.2f},{:.3f},{:.3f},{:.3f},{:.4f}\n", berth.berth.x_m, berth.berth.y_m,
                       result.limit_significant_wave_height_m, berth.exceedance_percent, 100.0 - berth.exceedance_percent,
                       berth.largest_significant_wave_height_m);
  return csv.str();
}

std::string operability_conditions_csv(const OperabilityResult& result) {
  std::ostringstream csv;
  csv << csv_condition_columns();
  for (const OperabilityBerth& berth : result.berths) csv << ",hs_m_" << berth.berth.name;
  csv << '\n';
  for (const OperabilityCondition& mapped : result.conditions) {
    const std::string line = mapped.condition.place.substr(mapped.condition.place.rfind(':') + 1);
    csv << fmt::format("{},{},{},{},{},{},{:.4f},{:.4f}", line, mapped.condition.significant_wave_height_m,
                       mapped.condition.peak_period_s, mapped.condition.direction_deg, mapped.condition.probability,
                       mapped.state_id, mapped.state_incident_significant_wave_height_m, mapped.scale);
    for (double hs : mapped.berth_significant_wave_height_m) csv << fmt::format(",{:.4f}", hs);
    csv << '\n';
  }
  return csv.str();
}

}  // namespace nearshore::library
