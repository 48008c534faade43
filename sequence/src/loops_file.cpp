#include "nearshore/sequence/loops_file.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <limits>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "field_reader.hpp"

namespace nearshore::sequence {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr long long kLeastInt = std::numeric_limits<int>::min();
// The manifest's own bound on frame_count (sequence_format.cpp).
constexpr long long kMostFrames = 10'000'000;

// The columns of a "transitions" row, in order (version 1).
constexpr const char* kTransitionColumns[] = {
    "from", "to", "probability", "cost", "future_cost", "crossfade_frames", "seam_ratio", "seam_ratio_after"};
constexpr std::size_t kTransitionColumnCount = std::size(kTransitionColumns);

// ---- writing ------------------------------------------------------------------------------------

json loop_to_json(const LoopsFile::Loop& loop) {
  json seams = json::array();
  for (const LoopsFile::Seam& s : loop.seams)
    seams.push_back({{"from", s.from},
                     {"to", s.to},
                     {"crossfade_frames", s.crossfade_frames},
                     {"run_before_frames", s.run_before_frames},
                     {"seam_ratio_before", s.seam_ratio_before},
                     {"seam_ratio_after", s.seam_ratio_after},
                     {"volume_jump_m3", s.volume_jump_m3},
                     {"volume_jump_after_m3", s.volume_jump_after_m3},
                     {"energy_jump_fraction", s.energy_jump_fraction},
                     {"energy_dip_fraction", s.energy_dip_fraction}});
  return {{"kind", loop.kind},
          {"start_frame", loop.start_frame},
          {"length_frames", loop.length_frames},
          {"length_s", loop.length_s},
          {"cost", loop.cost},
          {"worst_seam_ratio_before", loop.worst_seam_ratio_before},
          {"worst_seam_ratio_after", loop.worst_seam_ratio_after},
          {"seams", seams}};
}

json optional_loop_to_json(const std::optional<LoopsFile::Loop>& loop) {
  return loop ? loop_to_json(*loop) : json();
}

// ---- reading ------------------------------------------------------------------------------------

LoopsFile::Loop parse_loop(const FieldReader& r, const json& value, const std::string& path,
                           int frame_count) {
  LoopsFile::Loop loop;
  loop.kind = r.text(value, path, "kind");
  loop.start_frame = r.frame(value, path, "start_frame", frame_count);
  loop.length_frames = r.integer(value, path, "length_frames", 1);
  loop.length_s = r.number(value, path, "length_s");
  loop.cost = r.number(value, path, "cost");
  loop.worst_seam_ratio_before = r.number(value, path, "worst_seam_ratio_before");
  loop.worst_seam_ratio_after = r.number(value, path, "worst_seam_ratio_after");
  const json& seams = r.array(value, path, "seams");
  if (seams.empty())
    r.fail(fmt::format("\"{}\" is empty: a loop jumps at least once", FieldReader::name(path, "seams")));
  loop.seams.reserve(seams.size());
  for (std::size_t k = 0; k < seams.size(); ++k) {
    const std::string at = fmt::format("{}.seams[{}]", path, k);
    const json& s = seams[k];
    if (!s.is_object()) r.wrong_type(s, path, fmt::format("seams[{}]", k), "an object");
    LoopsFile::Seam seam;
    seam.from = r.frame(s, at, "from", frame_count);
    seam.to = r.frame(s, at, "to", frame_count);
    seam.crossfade_frames =
        r.crossfade_value(r.member(s, at, "crossfade_frames"), at, "crossfade_frames", seam.from, seam.to);
    seam.run_before_frames = r.integer(s, at, "run_before_frames");
    seam.seam_ratio_before = r.number(s, at, "seam_ratio_before");
    seam.seam_ratio_after = r.number(s, at, "seam_ratio_after");
    seam.volume_jump_m3 = r.number(s, at, "volume_jump_m3");
    seam.volume_jump_after_m3 = r.number(s, at, "volume_jump_after_m3");
    seam.energy_jump_fraction = r.number(s, at, "energy_jump_fraction");
    seam.energy_dip_fraction = r.number(s, at, "energy_dip_fraction");
    loop.seams.push_back(seam);
  }
  // A player (schedule_loop) starts where the last jump lands and runs forward to each jump in
  // turn; a loop that does not close that way would walk off its plan, past the bake's last frame.
  if (loop.start_frame != loop.seams.back().to)
    r.fail(
        fmt::format("\"{}\" is {} but the loop's last jump lands on frame {}; a cycle starts where it lands",
                    FieldReader::name(path, "start_frame"), loop.start_frame, loop.seams.back().to));
  long long shown = 0;
  int landed = loop.start_frame;
  for (std::size_t k = 0; k < loop.seams.size(); ++k) {
    if (loop.seams[k].from < landed)
      r.fail(fmt::format(
          "\"{}.seams[{}].from\" is {}, before frame {} where the previous jump lands; runs go forward", path,
          k, loop.seams[k].from, landed));
    shown += loop.seams[k].from - landed + 1;
    landed = loop.seams[k].to;
  }
  if (shown != loop.length_frames)
    r.fail(fmt::format("\"{}\" is {} but its runs between jumps show {} frames",
                       FieldReader::name(path, "length_frames"), loop.length_frames, shown));
  return loop;
}

std::optional<LoopsFile::Loop> parse_optional_loop(const FieldReader& r, const json& parent, const char* key,
                                                   int frame_count) {
  const json& value = r.member(parent, "", key);
  if (value.is_null()) return std::nullopt;
  if (!value.is_object()) r.wrong_type(value, "", key, "an object or null");
  return parse_loop(r, value, key, frame_count);
}

LoopsFile::Report parse_report(const FieldReader& r, const json& root) {
  LoopsFile::Report report;
  report.sequence = r.text(root, "", "sequence");
  report.frame_count = r.integer(root, "", "frame_count", 1, kMostFrames);
  const int n = report.frame_count;
  report.frame_interval_s = r.number(root, "", "frame_interval_s");
  if (!(report.frame_interval_s > 0) || report.frame_interval_s == kInfinity)
    r.fail(
        fmt::format("\"frame_interval_s\" is {} but must be a finite number > 0", report.frame_interval_s));
  report.loop_period_s = r.number(root, "", "loop_period_s");

  const json& p = r.object(root, "", "parameters");
  const std::string at = "parameters";
  LoopsFile::Parameters& parameters = report.parameters;
  parameters.motion_weight_delta = r.number(p, at, "motion_weight_delta");
  // The options as given, whatever they were: none indexes frames, so any int is read.
  parameters.filter_half_width_frames = r.integer(p, at, "filter_half_width_frames", kLeastInt);
  parameters.sigma = r.number(p, at, "sigma");
  parameters.sigma_factor = r.number(p, at, "sigma_factor");
  parameters.future_discount_alpha = r.number(p, at, "future_discount_alpha");
  parameters.cost_exponent_p = r.number(p, at, "cost_exponent_p");
  parameters.candidates_per_frame = r.integer(p, at, "candidates_per_frame", kLeastInt);
  parameters.min_jump_frames = r.integer(p, at, "min_jump_frames", kLeastInt);
  parameters.min_probability = r.number(p, at, "min_probability");
  parameters.max_crossfade_frames = r.integer(p, at, "max_crossfade_frames", kLeastInt);
  parameters.period_crossfade_frames = r.integer(p, at, "period_crossfade_frames", kLeastInt);

  report.height_scale_m = r.number(root, "", "height_scale_m");
  report.motion_scale_m2_s = r.number(root, "", "motion_scale_m2_s");
  report.median_step = r.number(root, "", "median_step");
  report.median_volume_step_m3 = r.number(root, "", "median_volume_step_m3");

  const json& g = r.object(root, "", "graph");
  report.graph.candidate_jumps = r.integer(g, "graph", "candidate_jumps");
  report.graph.usable_jumps = r.integer(g, "graph", "usable_jumps");
  report.graph.dead_end_count = r.integer(g, "graph", "dead_ends", 0, n, "(a count of the bake's frames)");
  report.graph.reachable_dead_end_count =
      r.integer(g, "graph", "reachable_dead_ends", 0, n, "(a count of the bake's frames)");
  report.graph.first_playable_frame = r.frame(g, "graph", "first_playable_frame", n, /*none_allowed=*/true);

  const json& d = r.object(root, "", "detected_period");
  report.detected_period.found = r.boolean(d, "detected_period", "found");
  report.detected_period.lag_frames =
      r.integer(d, "detected_period", "lag_frames", 0, n - 1, "(a lag within the bake)");
  report.detected_period.lag_s = r.number(d, "detected_period", "lag_s");
  report.detected_period.seam_ratio = r.number(d, "detected_period", "seam_ratio");
  report.detected_period.matched_frame = r.frame(d, "detected_period", "matched_frame", n);

  report.period_loop = parse_optional_loop(r, root, "period_loop", n);
  report.requested_loop_s = r.number(root, "", "requested_loop_s");
  report.requested_loop = parse_optional_loop(r, root, "requested_loop", n);
  const json& loops = r.array(root, "", "best_loops_by_length");
  report.best_loops_by_length.reserve(loops.size());
  for (std::size_t k = 0; k < loops.size(); ++k) {
    if (!loops[k].is_object())
      r.wrong_type(loops[k], "", fmt::format("best_loops_by_length[{}]", k), "an object");
    report.best_loops_by_length.push_back(
        parse_loop(r, loops[k], fmt::format("best_loops_by_length[{}]", k), n));
  }
  report.worst_seam_ratio_after = r.number(root, "", "worst_seam_ratio_after");
  report.gram_reused = r.boolean(root, "", "gram_reused");
  report.distance_seconds = r.number(root, "", "distance_seconds");
  report.table_seconds = r.number(root, "", "table_seconds");
  return report;
}

void parse_transitions(const FieldReader& r, const json& root, LoopsFile& file) {
  const json& columns = r.array(root, "", "transition_columns");
  bool same = columns.size() == kTransitionColumnCount;
  for (std::size_t c = 0; same && c < kTransitionColumnCount; ++c) same = columns[c] == kTransitionColumns[c];
  if (!same) {
    std::string expected;
    for (const char* column : kTransitionColumns)
      expected += fmt::format("{}\"{}\"", expected.empty() ? "" : ", ", column);
    r.fail(fmt::format("\"transition_columns\" are not version {}'s {}", kLoopsFileVersion, expected));
  }
  const json& rows = r.array(root, "", "transitions");
  const int n = file.report.frame_count;
  file.transitions.reserve(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const json& row = rows[k];
    const std::string at = fmt::format("transitions[{}]", k);
    if (!row.is_array() || row.size() != kTransitionColumnCount)
      r.fail(fmt::format("\"{}\" is {}, not a row of {} values (\"transition_columns\")", at,
                         row.is_array() ? fmt::format("a row of {} values", row.size()) : describe(row),
                         kTransitionColumnCount));
    LoopsFile::Transition t;
    t.from = r.frame_value(row[0], at, kTransitionColumns[0], n);
    t.to = r.frame_value(row[1], at, kTransitionColumns[1], n);
    t.probability = r.number_value(row[2], at, kTransitionColumns[2]);
    t.cost = r.number_value(row[3], at, kTransitionColumns[3]);
    t.future_cost = r.number_value(row[4], at, kTransitionColumns[4]);
    t.crossfade_frames = r.crossfade_value(row[5], at, kTransitionColumns[5], t.from, t.to);
    t.seam_ratio = r.number_value(row[6], at, kTransitionColumns[6]);
    t.seam_ratio_after = r.number_value(row[7], at, kTransitionColumns[7]);
    file.transitions.push_back(t);
  }
}

// `command` is the `nearshore loops` call that rewrites the file, for the messages.
LoopsFile parse_loops(std::string_view text, const std::string& source, const std::string& command) {
  const FieldReader r(source, fmt::format("run `{}` again to rewrite it", command));
  try {
    // 1. Format and version first: a newer file is refused as such, not for a key it renamed.
    const json root = r.versioned_root(
        text, kLoopsFileFormat, "a loops table", kLoopsFileVersion,
        fmt::format("play it with the nearshore release that wrote it, or run `{}` to rewrite it for this one", command),
        fmt::format("remove it, or run `{}` to write one", command));

    // 2. The report, then what ties the table to its bake, then the table.
    LoopsFile file;
    file.report = parse_report(r, root);
    file.sequence_manifest_checksum = r.text(root, "", "sequence_manifest_checksum");
    file.gram_file = r.text(root, "", "gram_file");
    file.gram_checksum = r.text(root, "", "gram_checksum");
    const json& walk = r.object(root, "", "random_walk");
    file.random_walk.start_frame = r.frame(walk, "random_walk", "start_frame", file.report.frame_count, true);
    const json& seed = r.member(walk, "random_walk", "seed");
    if (!seed.is_number_unsigned()) r.wrong_type(seed, "random_walk", "seed", "an integer >= 0");
    file.random_walk.seed = seed.get<std::uint64_t>();
    parse_transitions(r, root, file);
    return file;
  } catch (const json::exception& e) {
    // Every access above is type-checked first; this is the guard that keeps the promise anyway.
    throw Error(source, std::string("is malformed: ") + e.what(), r.fix());
  }
}

}  // namespace

json loops_report_to_json(const LoopsFile::Report& report) {
  json loops = json::array();
  for (const LoopsFile::Loop& loop : report.best_loops_by_length) loops.push_back(loop_to_json(loop));
  const LoopsFile::Parameters& p = report.parameters;
  const LoopsFile::Graph& g = report.graph;
  const LoopsFile::DetectedPeriod& d = report.detected_period;
  return {{"sequence", report.sequence},
          {"frame_count", report.frame_count},
          {"frame_interval_s", report.frame_interval_s},
          {"loop_period_s", report.loop_period_s},
          {"parameters",
           {{"motion_weight_delta", p.motion_weight_delta},
            {"filter_half_width_frames", p.filter_half_width_frames},
            {"sigma", p.sigma},
            {"sigma_factor", p.sigma_factor},
            {"future_discount_alpha", p.future_discount_alpha},
            {"cost_exponent_p", p.cost_exponent_p},
            {"candidates_per_frame", p.candidates_per_frame},
            {"min_jump_frames", p.min_jump_frames},
            {"min_probability", p.min_probability},
            {"max_crossfade_frames", p.max_crossfade_frames},
            {"period_crossfade_frames", p.period_crossfade_frames}}},
          {"height_scale_m", report.height_scale_m},
          {"motion_scale_m2_s", report.motion_scale_m2_s},
          {"median_step", report.median_step},
          {"median_volume_step_m3", report.median_volume_step_m3},
          {"graph",
           {{"candidate_jumps", g.candidate_jumps},
            {"usable_jumps", g.usable_jumps},
            {"dead_ends", g.dead_end_count},
            {"reachable_dead_ends", g.reachable_dead_end_count},
            {"first_playable_frame", g.first_playable_frame}}},
          {"detected_period",
           {{"found", d.found},
            {"lag_frames", d.lag_frames},
            {"lag_s", d.lag_s},
            {"seam_ratio", d.seam_ratio},
            {"matched_frame", d.matched_frame}}},
          {"period_loop", optional_loop_to_json(report.period_loop)},
          {"requested_loop_s", report.requested_loop_s},
          {"requested_loop", optional_loop_to_json(report.requested_loop)},
          {"best_loops_by_length", loops},
          {"worst_seam_ratio_after", report.worst_seam_ratio_after},
          {"gram_reused", report.gram_reused},
          {"distance_seconds", report.distance_seconds},
          {"table_seconds", report.table_seconds}};
}

json loops_file_to_json(const LoopsFile& file) {
  json tables = loops_report_to_json(file.report);
  tables["format"] = kLoopsFileFormat;
  tables["version"] = kLoopsFileVersion;
  tables["sequence_manifest_checksum"] = file.sequence_manifest_checksum;
  tables["gram_file"] = file.gram_file;
  tables["gram_checksum"] = file.gram_checksum;
  tables["random_walk"] = {{"start_frame", file.random_walk.start_frame}, {"seed", file.random_walk.seed}};
  json columns = json::array();
  for (const char* column : kTransitionColumns) columns.push_back(column);
  tables["transition_columns"] = std::move(columns);
  json rows = json::array();
  for (const LoopsFile::Transition& t : file.transitions)
    rows.push_back({t.from, t.to, t.probability, t.cost, t.future_cost, t.crossfade_frames, t.seam_ratio,
                    t.seam_ratio_after});
  tables["transitions"] = std::move(rows);
  return tables;
}

void write_loops_file(const fs::path& folder, const LoopsFile& file) {
  const fs::path path = folder / kLoopsFileName;
  std::string text;
  try {
    text = loops_file_to_json(file).dump(1);
  } catch (const json::exception& e) {  // a string that is not UTF-8, e.g. the folder's name
    throw Error(path.string(), std::string("cannot be written: ") + e.what(),
                "give the sequence folder by a path that is valid UTF-8");
  }
  write_text_atomically(path, text);
}

LoopsFile parse_loops_file(std::string_view text, const std::string& source) {
  return parse_loops(text, source, "nearshore loops SEQUENCE_FOLDER");
}

LoopsFile read_loops_file(const fs::path& folder) {
  const fs::path path = folder / kLoopsFileName;
  const std::string command = "nearshore loops " + folder.string();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw Error(path.string(), fs::exists(path, ec) ? "is not a regular file" : "does not exist",
                fmt::format("run `{}` to write it", command));
  return parse_loops(read_file_bytes(path), path.string(), command);
}

}  // namespace nearshore::sequence
