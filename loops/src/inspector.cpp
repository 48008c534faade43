#include "nearshore/loops/inspector.hpp"

#include <unistd.h>

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/folder_lock.hpp"
#include "nearshore/core/statistics.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "nearshore/sequence/loops_file.hpp"

namespace nearshore::loops {
namespace fs = std::filesystem;
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string file_checksum(const fs::path& path) {
  const std::string bytes = sequence::read_file_bytes(path);
  return sequence::checksum_text(std::as_bytes(std::span(bytes.data(), bytes.size())));
}

// Seam of jump i -> j with its crossfade limited by the run before it (blends must not reach
// back across the previous jump).
SeamReport analyse_seam(const LoopsReport& report, Transition jump, int run_before_frames,
                        int max_crossfade_frames) {
  const Eigen::MatrixXd& d = report.distances.combined;
  const Eigen::MatrixXd& g = report.gram.elevation;
  const std::vector<double>& volume = report.gram.volume_m3;
  const int i = jump.from, j = jump.to, next = jump.from + 1;
  const double scale = report.median_step > 0 ? report.median_step : 1.0;
  SeamReport seam;
  seam.run_before_frames = run_before_frames;
  const int longest = std::max(0, std::min(max_crossfade_frames, run_before_frames - 1));
  const CrossfadeChoice fade = choose_crossfade(d, report.median_step, i, j, longest);
  jump.crossfade_frames = fade.frames;
  jump.seam_ratio = d(j, next) / scale;
  jump.seam_ratio_after = fade.seam_ratio_after;
  seam.transition = jump;
  seam.seam_ratio_before = jump.seam_ratio;
  seam.seam_ratio_after = jump.seam_ratio_after;
  const int c = fade.frames;
  seam.volume_jump_m3 = volume[static_cast<std::size_t>(j)] - volume[static_cast<std::size_t>(next)];
  for (int k = 0; k <= c; ++k)
    seam.volume_jump_after_m3 =
        std::max(seam.volume_jump_after_m3, std::abs(volume[static_cast<std::size_t>(j - c + k)] -
                                                     volume[static_cast<std::size_t>(next - c + k)]) /
                                                (c + 1));
  // Potential energy 1/2 rho g sum eta^2 dA is proportional to the Gram diagonal; the common
  // factor cancels in the fractions.
  const double mean_energy = g.diagonal().mean();
  if (mean_energy > 0) {
    seam.energy_jump_fraction = (g(j, j) - g(next, next)) / mean_energy;
    for (int k = 1; k <= c; ++k) {
      const double alpha = static_cast<double>(k) / (c + 1);
      const int a = i - c + k, b = j - 1 - c + k;
      const double blended =
          (1 - alpha) * (1 - alpha) * g(a, a) + 2 * alpha * (1 - alpha) * g(a, b) + alpha * alpha * g(b, b);
      const double linear = (1 - alpha) * g(a, a) + alpha * g(b, b);
      if (linear > 0) seam.energy_dip_fraction = std::min(seam.energy_dip_fraction, blended / linear - 1);
    }
  }
  return seam;
}

LoopReport analyse_plan(const LoopsReport& report, const LoopPlan& plan, int max_crossfade_frames) {
  LoopReport loop;
  loop.plan = plan;
  loop.length_s = plan.length_frames * report.frame_interval_s;
  const std::size_t count = plan.jumps.size();
  for (std::size_t k = 0; k < count; ++k) {
    const Transition& previous = plan.jumps[(k + count - 1) % count];
    const int run = plan.jumps[k].from - previous.to + 1;
    loop.seams.push_back(analyse_seam(report, plan.jumps[k], run, max_crossfade_frames));
    loop.plan.jumps[k] = loop.seams.back().transition;
    loop.worst_seam_ratio_before =
        std::max(loop.worst_seam_ratio_before, loop.seams.back().seam_ratio_before);
    loop.worst_seam_ratio_after = std::max(loop.worst_seam_ratio_after, loop.seams.back().seam_ratio_after);
  }
  return loop;
}

sequence::LoopsFile::Loop stored_loop(const LoopReport& loop) {
  sequence::LoopsFile::Loop stored;
  stored.kind = loop.plan.kind;
  stored.start_frame = loop.plan.start_frame;
  stored.length_frames = loop.plan.length_frames;
  stored.length_s = loop.length_s;
  stored.cost = loop.plan.cost;
  stored.worst_seam_ratio_before = loop.worst_seam_ratio_before;
  stored.worst_seam_ratio_after = loop.worst_seam_ratio_after;
  for (const SeamReport& s : loop.seams)
    stored.seams.push_back({.from = s.transition.from,
                            .to = s.transition.to,
                            .crossfade_frames = s.transition.crossfade_frames,
                            .run_before_frames = s.run_before_frames,
                            .seam_ratio_before = s.seam_ratio_before,
                            .seam_ratio_after = s.seam_ratio_after,
                            .volume_jump_m3 = s.volume_jump_m3,
                            .volume_jump_after_m3 = s.volume_jump_after_m3,
                            .energy_jump_fraction = s.energy_jump_fraction,
                            .energy_dip_fraction = s.energy_dip_fraction});
  return stored;
}

std::optional<sequence::LoopsFile::Loop> stored_loop(const std::optional<LoopReport>& loop) {
  if (!loop) return std::nullopt;
  return stored_loop(*loop);
}

// The report as loops.json (and `nearshore loops --json`) carries it.
sequence::LoopsFile::Report stored_report(const LoopsReport& report) {
  sequence::LoopsFile::Report stored;
  stored.sequence = report.folder.string();
  stored.frame_count = report.frame_count;
  stored.frame_interval_s = report.frame_interval_s;
  stored.loop_period_s = report.loop_period_s;
  const TransitionOptions& options = report.table.options;
  stored.parameters = {.motion_weight_delta = options.motion_weight,
                       .filter_half_width_frames = options.filter_half_width,
                       .sigma = report.sigma,
                       .sigma_factor = options.sigma_factor,
                       .future_discount_alpha = options.future_discount,
                       .cost_exponent_p = options.cost_exponent,
                       .candidates_per_frame = options.candidates_per_frame,
                       .min_jump_frames = options.min_jump_frames,
                       .min_probability = options.min_probability,
                       .max_crossfade_frames = options.max_crossfade_frames,
                       .period_crossfade_frames = report.period_crossfade_frames};
  stored.height_scale_m = report.height_scale_m;
  stored.motion_scale_m2_s = report.motion_scale_m2_s;
  stored.median_step = report.median_step;
  stored.median_volume_step_m3 = report.median_volume_step_m3;
  stored.graph = {.candidate_jumps = report.candidate_jumps,
                  .usable_jumps = report.usable_jumps,
                  .dead_end_count = static_cast<int>(report.dead_ends.size()),
                  .reachable_dead_end_count = static_cast<int>(report.reachable_dead_ends.size()),
                  .first_playable_frame = report.first_playable_frame};
  stored.detected_period = {.found = report.detected_period.found,
                            .lag_frames = report.detected_period.lag_frames,
                            .lag_s = report.detected_period.lag_s,
                            .seam_ratio = report.detected_period.seam_ratio,
                            .matched_frame = report.detected_period.matched_frame};
  stored.period_loop = stored_loop(report.period);
  stored.requested_loop_s = report.requested_loop_s;
  stored.requested_loop = stored_loop(report.requested);
  for (const LoopReport& loop : report.best_by_length)
    stored.best_loops_by_length.push_back(stored_loop(loop));
  stored.worst_seam_ratio_after = report.worst_seam_ratio_after();
  stored.gram_reused = report.gram_reused;
  stored.distance_seconds = report.distance_seconds;
  stored.table_seconds = report.table_seconds;
  return stored;
}

// Every LoopsOptions field in the range where it means something (NaN fails each test): a loop is
// at least one frame long. A length that rounds to no frame, or to minus one, would index the
// plans by length outside their vector (the crash of `--lengths-s -1`, issue 13). The transition
// and Gram options are checked where they are used (build_transition_table, compute_gram_matrices).
void check_options(const LoopsOptions& options, double frame_interval_s) {
  const std::string one_frame = fmt::format("one frame ({} s in this sequence)", frame_interval_s);
  for (double length_s : options.report_lengths_s)
    if (!(std::isfinite(length_s) && length_s >= frame_interval_s))
      throw Error(fmt::format("LoopsOptions::report_lengths_s holds {} s", length_s),
                  "but a loop length must be at least " + one_frame,
                  "give LoopsOptions::report_lengths_s loop lengths in seconds of at least " + one_frame);
  if (!(std::isfinite(options.requested_loop_s) &&
        (options.requested_loop_s == 0 || options.requested_loop_s >= frame_interval_s)))
    throw Error(fmt::format("LoopsOptions::requested_loop_s = {} s", options.requested_loop_s),
                "is neither 0 (no requested loop) nor a loop length of at least " + one_frame,
                "give LoopsOptions::requested_loop_s 0 or a length in seconds of at least " + one_frame);
  if (!(std::isfinite(options.max_crossfade_s) && options.max_crossfade_s >= 0))
    throw Error(fmt::format("LoopsOptions::max_crossfade_s = {} s", options.max_crossfade_s),
                "is not a duration (a finite number of seconds >= 0)",
                "give LoopsOptions::max_crossfade_s a value in [0, inf), e.g. 2");
  if (!(std::isfinite(options.period_crossfade_s) && options.period_crossfade_s >= 0))
    throw Error(fmt::format("LoopsOptions::period_crossfade_s = {} s", options.period_crossfade_s),
                "is not a duration (a finite number of seconds >= 0)",
                "give LoopsOptions::period_crossfade_s a value in [0, inf), e.g. 10");
}

}  // namespace

DetectedPeriod detect_period(const Eigen::MatrixXd& distances, double median_step, double frame_interval_s,
                             double min_lag_s) {
  DetectedPeriod best;
  const int count = static_cast<int>(distances.rows());
  const double scale = median_step > 0 ? median_step : 1.0;
  const int min_lag = std::max(2, static_cast<int>(std::lround(min_lag_s / frame_interval_s)));
  best.seam_ratio = std::numeric_limits<double>::infinity();
  for (int lag = min_lag; lag < count; ++lag)
    for (int k = 0; k + lag < count; ++k)
      if (distances(k, k + lag) / scale < best.seam_ratio) {
        best.seam_ratio = distances(k, k + lag) / scale;
        best.lag_frames = lag;
        best.matched_frame = k;
      }
  best.lag_s = best.lag_frames * frame_interval_s;
  best.found = best.seam_ratio <= 1.0;
  return best;
}

double LoopsReport::worst_seam_ratio_after() const {
  double worst = 0;
  if (period) worst = std::max(worst, period->worst_seam_ratio_after);
  if (requested) worst = std::max(worst, requested->worst_seam_ratio_after);
  // Of the loops by length, the gate is on the best one offered (a player would use that one).
  if (!period && !requested && !best_by_length.empty()) {
    double best = std::numeric_limits<double>::infinity();
    for (const LoopReport& loop : best_by_length) best = std::min(best, loop.worst_seam_ratio_after);
    worst = std::max(worst, best);
  }
  return worst;
}

nlohmann::json LoopsReport::to_json() const {
  return sequence::loops_report_to_json(stored_report(*this));
}

LoopsReport analyse_loops(const fs::path& sequence_folder, const LoopsOptions& options) {
  // One writer per folder (folder_lock.hpp), for the whole run: a bake rewriting the frames
  // meanwhile would leave loop tables that vouch for frames they were not computed from. A run
  // that writes nothing may read a folder it cannot write (a sequence on read-only media); a folder
  // that is not there is the reader's to report.
  std::optional<FolderLock> lock;
  std::error_code not_a_folder;
  if (fs::is_directory(sequence_folder, not_a_folder) &&
      (options.write_tables || ::access(sequence_folder.c_str(), W_OK) == 0))
    lock.emplace(sequence_folder, "analysing its loops");
  // A loops run killed while writing its tables left loops_gram.bin.tmp-PID (12 MB, issue 44) that
  // its rerun kept: under the lock no other writer of this folder is alive, so any temporary file
  // here is a dead writer's.
  if (lock) remove_stale_temporary_files(sequence_folder);
  const sequence::SequenceReader reader(sequence_folder);
  if (options.verify) reader.verify_checksums();
  LoopsReport report;
  report.folder = sequence_folder;
  report.frame_count = reader.frame_count();
  report.frame_interval_s = reader.frame_interval_s();
  check_options(options, report.frame_interval_s);
  report.loop_period_s = reader.manifest().loop_period_s;
  const fs::path manifest_path = sequence_folder / std::string(sequence::kManifestFile);
  const fs::path loops_path = sequence_folder / kLoopsFile, gram_path = sequence_folder / kGramFile;
  const std::string manifest_checksum = file_checksum(manifest_path);

  // 1. Gram matrices: reuse the stored ones when they belong to this very manifest.
  auto start = std::chrono::steady_clock::now();
  std::error_code ec;
  if (!options.recompute && fs::exists(loops_path, ec) && fs::exists(gram_path, ec)) {
    // A stored table that cannot be read (corrupt, another version) is simply recomputed and
    // overwritten below.
    std::optional<sequence::LoopsFile> stored;
    try {
      stored = sequence::read_loops_file(sequence_folder);
    } catch (const Error&) {
    }
    if (stored && stored->sequence_manifest_checksum == manifest_checksum &&
        stored->gram_checksum == file_checksum(gram_path)) {
      report.gram = read_gram(gram_path, report.frame_count);
      report.gram_reused = true;
    }
  }
  // Stored Gram matrices vouch for the frames as they were: a frame deleted or damaged since would
  // go unseen (the run exited 0 on a sequence missing a frame, issue 44), so reusing them costs one
  // checksum pass over the frames (hashing, far cheaper than the decoding it saves).
  if (report.gram_reused && !options.verify) reader.verify_checksums();
  if (!report.gram_reused) report.gram = compute_gram_matrices(reader, options.gram);
  report.distance_seconds = seconds_since(start);

  // 2. Distances (eq. 8-10) and the transition table (eq. 11 + Schödl).
  start = std::chrono::steady_clock::now();
  report.distances = distances_from_gram(report.gram, options.transitions.motion_weight);
  TransitionOptions transition_options = options.transitions;
  if (options.max_crossfade_s > 0)
    transition_options.max_crossfade_frames =
        std::max(1, static_cast<int>(std::lround(options.max_crossfade_s / report.frame_interval_s)));
  report.table = build_transition_table(report.distances, transition_options);
  report.sigma = report.table.sigma;
  report.median_step = report.table.median_step;
  report.height_scale_m = report.distances.height_scale;
  report.motion_scale_m2_s = report.distances.motion_scale;
  std::vector<double> volume_steps;
  for (int k = 0; k + 1 < report.frame_count; ++k)
    volume_steps.push_back(std::abs(report.gram.volume_m3[static_cast<std::size_t>(k + 1)] -
                                    report.gram.volume_m3[static_cast<std::size_t>(k)]));
  report.median_volume_step_m3 = median_of(volume_steps);
  report.candidate_jumps = report.table.candidate_jump_count();
  report.usable_jumps = report.table.usable_jump_count();
  report.dead_ends = report.table.dead_ends();
  report.first_playable_frame = report.table.first_playable_frame();
  if (report.first_playable_frame >= 0)
    report.reachable_dead_ends = report.table.reachable_dead_ends(report.first_playable_frame);

  // 3. Plans: (c) the exact period, the best loops by length, (b) a requested length.
  report.detected_period = detect_period(report.distances.combined, report.median_step, report.frame_interval_s);
  const int jump_crossfade_frames = report.table.options.max_crossfade_frames;
  if (report.loop_period_s > 0) {
    // Across the exact-period jump both timelines are in phase for every forced component, so a
    // long crossfade blends two nearly equal fields (no ghost crests); it only has to hide what
    // the forcing does not fix: the slow, chaotic part (wave-driven eddies at breaking zones and
    // breakwater heads), which drifts apart over a period. Hence its own, longer limit.
    report.period_crossfade_frames =
        std::max(0, static_cast<int>(std::lround(options.period_crossfade_s / report.frame_interval_s)));
    report.period = analyse_plan(
        report,
        period_loop(report.table, report.distances.combined, report.loop_period_s, report.frame_interval_s),
        std::max(jump_crossfade_frames, report.period_crossfade_frames));
  }
  int longest = 0;
  for (double length_s : options.report_lengths_s)
    longest = std::max(longest, static_cast<int>(std::lround(1.25 * length_s / report.frame_interval_s)));
  longest = std::min(longest, report.frame_count);
  std::vector<char> wanted(static_cast<std::size_t>(longest) + 1, 0);
  for (double length_s : options.report_lengths_s)
    for (long length = std::lround(length_s / report.frame_interval_s);
         length <= std::min<long>(longest, std::lround(1.25 * length_s / report.frame_interval_s)); ++length)
      if (length >= 0) wanted[static_cast<std::size_t>(length)] = 1;
  const std::vector<std::optional<LoopPlan>> by_length = best_loops_for_lengths(report.table, wanted);
  for (double length_s : options.report_lengths_s) {
    const int low = static_cast<int>(std::lround(length_s / report.frame_interval_s));
    const int high =
        std::min(longest, static_cast<int>(std::lround(1.25 * length_s / report.frame_interval_s)));
    std::optional<LoopReport> best;
    for (int length = low; length <= high; ++length) {
      const std::optional<LoopPlan>& plan = by_length[static_cast<std::size_t>(length)];
      // A plan that replays a stretch of frames within one cycle (in the worst case a shorter
      // loop several times over) shows the viewer a shorter repeat than its length: it does not
      // count as a loop of this length.
      if (!plan || !plan->shows_each_frame_once()) continue;
      LoopReport loop = analyse_plan(report, *plan, jump_crossfade_frames);
      if (!best || loop.worst_seam_ratio_after < best->worst_seam_ratio_after - 1e-12) best = std::move(loop);
    }
    if (best) report.best_by_length.push_back(std::move(*best));
  }
  report.requested_loop_s = options.requested_loop_s;
  if (options.requested_loop_s > 0) {
    const int length = static_cast<int>(std::lround(options.requested_loop_s / report.frame_interval_s));
    std::optional<LoopPlan> plan = optimal_loop(report.table, length);
    // The cheapest closed walk of exactly that length may replay a shorter loop (a 12 s loop played
    // five times for a 60 s request): the viewer would see a 12 s repeat. Such a plan is not the
    // requested loop. Instead, among the plans within the reporting buckets' tolerance (-20 % ..
    // +25 %) that show every frame once (the best plan per length, and every single-jump loop,
    // which is a plain forward run and so never repeats), take the nearest length, then the cheapest.
    if (plan && !plan->shows_each_frame_once()) {
      const int low = std::max(1, static_cast<int>(std::lround(0.8 * length)));
      const int high = std::min(report.frame_count, static_cast<int>(std::lround(1.25 * length)));
      std::vector<LoopPlan> candidates;
      std::vector<char> wanted(static_cast<std::size_t>(std::max(high, 0)) + 1, 0);
      for (int candidate = low; candidate <= high; ++candidate) wanted[static_cast<std::size_t>(candidate)] = 1;
      for (std::optional<LoopPlan>& best : best_loops_for_lengths(report.table, wanted))
        if (best && best->shows_each_frame_once()) candidates.push_back(std::move(*best));
      for (const Transition& jump : report.table.transitions) {
        const int run = jump.from - jump.to + 1;
        if (jump.natural() || !std::isfinite(jump.cost) || run < low || run > high) continue;
        LoopPlan single;
        single.kind = "optimal";
        single.start_frame = jump.to;
        single.length_frames = run;
        single.cost = std::pow(jump.cost, report.table.options.cost_exponent);
        single.jumps = {jump};
        candidates.push_back(std::move(single));
      }
      const auto nearer = [length](const LoopPlan& a, const LoopPlan& b) {
        return std::pair(std::abs(a.length_frames - length), a.cost) < std::pair(std::abs(b.length_frames - length), b.cost);
      };
      const auto chosen = std::min_element(candidates.begin(), candidates.end(), nearer);
      plan = chosen == candidates.end() ? std::nullopt : std::optional<LoopPlan>(*chosen);
    }
    if (plan) report.requested = analyse_plan(report, *plan, jump_crossfade_frames);
  }
  report.table_seconds = seconds_since(start);

  // 4. The tables, beside the frames: gram first, loops.json (which vouches for it) last.
  if (options.write_tables) {
    if (!report.gram_reused) write_gram(gram_path, report.gram);
    sequence::LoopsFile tables;
    tables.report = stored_report(report);
    tables.sequence_manifest_checksum = manifest_checksum;
    tables.gram_file = kGramFile;
    tables.gram_checksum = file_checksum(gram_path);
    tables.random_walk = {.start_frame = report.first_playable_frame, .seed = options.random_walk_seed};
    tables.transitions.reserve(report.table.transitions.size());
    for (const Transition& t : report.table.transitions)
      tables.transitions.push_back({.from = t.from,
                                    .to = t.to,
                                    .probability = t.probability,
                                    .cost = t.cost,
                                    .future_cost = t.future_cost,
                                    .crossfade_frames = t.crossfade_frames,
                                    .seam_ratio = t.seam_ratio,
                                    .seam_ratio_after = t.seam_ratio_after});
    sequence::write_loops_file(sequence_folder, tables);
  }
  return report;
}

}  // namespace nearshore::loops
