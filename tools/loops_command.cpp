// nearshore loops SEQ: loop-transition tables and seam quality of a baked sequence
// (docs/commands/loops.md). Thin: parse options, call nearshore::loops::analyse_loops, print.
#include <fmt/core.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "command_support.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/loops/inspector.hpp"
#include "nearshore/loops/sequence_vdb.hpp"

namespace nearshore::tools {
namespace {

void print_loop(const loops::LoopReport& loop) {
  std::printf("  %7.1f s  %6d frames  %2zu jump%s  R %6.2f -> %5.2f", loop.length_s, loop.plan.length_frames,
              loop.seams.size(), loop.seams.size() == 1 ? " " : "s", loop.worst_seam_ratio_before,
              loop.worst_seam_ratio_after);
  for (const loops::SeamReport& seam : loop.seams)
    std::printf("  [%d->%d fade %d, dV %+.3g m3, dE %+.1f%%, dip %.1f%%]", seam.transition.from,
                seam.transition.to, seam.transition.crossfade_frames, seam.volume_jump_m3,
                100 * seam.energy_jump_fraction, 100 * seam.energy_dip_fraction);
  std::printf("\n");
}

// How the period found in the frames stands to the manifest's loop period T. Frames that repeat
// every T also repeat every 2T, 3T, ...; and a bake whose loop period holds several wave periods
// (T = 2 x 10 s) has frames that repeat every wave period, a divisor of T. Both agree with the
// manifest; only a lag that neither divides T nor is a multiple of it says the bake has not
// settled into its forcing. Compared in whole frames (the lag is one; period_loop requires T to be).
std::string period_agreement(const loops::DetectedPeriod& detected, double loop_period_s, double frame_interval_s) {
  if (!(loop_period_s > 0)) return "";
  const long period_frames = std::lround(loop_period_s / frame_interval_s);
  const long lag_frames = detected.lag_frames;
  if (lag_frames == period_frames) return ", as the manifest says";
  if (lag_frames > 0 && period_frames > 0 && period_frames % lag_frames == 0)
    return fmt::format(": the frames repeat every {:g} s, which divides the manifest's {:g} s loop period ({} "
                       "repeats per period), as a periodic bake should",
                       detected.lag_s, loop_period_s, period_frames / lag_frames);
  if (lag_frames > 0 && period_frames > 0 && lag_frames % period_frames == 0)
    return fmt::format(": {} of the manifest's {:g} s loop periods, as a periodic bake should (the search "
                       "starts at 10 s)",
                       lag_frames / period_frames, loop_period_s);
  return fmt::format(", NOT the manifest's {:g} s loop period (nor a divisor or multiple of it): the bake has not "
                     "settled into its forcing",
                     loop_period_s);
}

void print_report(const loops::LoopsReport& report) {
  std::printf("sequence %s: %d frames every %g s (%.1f s)%s\n", report.folder.c_str(), report.frame_count,
              report.frame_interval_s, report.frame_count * report.frame_interval_s,
              report.loop_period_s > 0
                  ? fmt::format(", periodic bake, period {} s", report.loop_period_s).c_str()
                  : "");
  std::printf(
      "distances (eq. 8-10): %s in %.1f s; height scale %.4g m, motion scale %.4g m^2/s, median step %.4g\n",
      report.gram_reused ? "reused loops_gram.bin" : "computed", report.distance_seconds,
      report.height_scale_m, report.motion_scale_m2_s, report.median_step);
  std::printf(
      "transition graph: %d usable jumps (of %d candidates), sigma %.4g; %zu dead ends, %zu reachable from "
      "frame %d\n",
      report.usable_jumps, report.candidate_jumps, report.sigma, report.dead_ends.size(),
      report.reachable_dead_ends.size(), report.first_playable_frame);
  std::printf(
      "seam ratio R = |f(j) - f(i+1)| / median step, before -> after crossfade; dV volume jump, dE energy "
      "jump\n");
  const loops::DetectedPeriod& detected = report.detected_period;
  if (detected.found)
    std::printf("period found in the frames: %.1f s (%d frames; frame %d matches frame %d with R %.2f)%s\n",
                detected.lag_s, detected.lag_frames, detected.matched_frame,
                detected.matched_frame + detected.lag_frames, detected.seam_ratio,
                period_agreement(detected, report.loop_period_s, report.frame_interval_s).c_str());
  else
    std::printf("no period in the frames: the best repeat, after %.1f s, is %.2f steps away%s\n", detected.lag_s,
                detected.seam_ratio, report.loop_period_s > 0 ? " (the manifest claims one: spin-up too short?)" : "");
  if (report.period) {
    std::printf("exact period loop:\n");
    print_loop(*report.period);
  }
  if (report.requested) {
    std::printf("requested loop:\n");
    print_loop(*report.requested);
  } else if (report.requested_loop_s > 0) {
    std::printf("requested loop: none of about %.1f s (-20 %% .. +25 %%) that shows every frame once can be made "
                "from the table's jumps\n",
                report.requested_loop_s);
  }
  std::printf("best loops by length:\n");
  if (report.best_by_length.empty())
    std::printf("  (none: no candidate jumps give loops of the reported lengths)\n");
  for (const loops::LoopReport& loop : report.best_by_length) print_loop(loop);
}

// Why the --max-seam gate has no loop to judge, or "" when it has one: a --loop-s loop that cannot be
// made (the user asked for that one), or no loop at all (no period in the manifest, no --loop-s,
// and no loop in any --lengths-s bucket).
std::string loop_missing_for_gate(const loops::LoopsReport& report) {
  if (report.requested_loop_s > 0 && !report.requested)
    return fmt::format("no loop of exactly {:g} s (--loop-s) can be made from the table's jumps",
                       report.requested_loop_s);
  if (!report.period && !report.requested && report.best_by_length.empty())
    return "no loop was planned (the manifest has no loop period, no --loop-s was given, and no --lengths-s "
           "bucket holds a loop)";
  return "";
}

// The flag of each parameter that library errors may name (command_support.hpp), as the options
// below set them, and the bake's own, which the user of this command gives to `nearshore bake`.
FlagTable loops_flags() {
  return {{"LoopsOptions::recompute", "--recompute"},
          {"LoopsOptions::verify", "--verify"},
          {"SequenceReader::verify_checksums", "--verify"},
          {"LoopsOptions::report_lengths_s", "--lengths-s"},
          {"LoopsOptions::requested_loop_s", "--loop-s"},
          {"LoopsOptions::max_crossfade_s", "--max-crossfade-s"},
          {"LoopsOptions::period_crossfade_s", "--period-crossfade-s"},
          {"TransitionOptions::motion_weight", "--delta"},
          {"TransitionOptions::sigma", "--sigma"},
          {"TransitionOptions::filter_half_width", "--filter-width"},
          {"TransitionOptions::future_discount", "--alpha"},
          {"TransitionOptions::candidates_per_frame", "--candidates"},
          {"TransitionOptions::min_probability", "--min-probability"},
          {"TransitionOptions::max_crossfade_frames", "--max-crossfade-s"},
          {"GramOptions::memory_budget_bytes", "--memory-mb"},
          {"GramOptions::threads", "--threads"},
          {"BakeOptions::output_folder", "nearshore bake -o"},
          {"BakeOptions::resume", "nearshore bake --resume"}};
}

}  // namespace

void add_loops_command(CLI::App& app) {
  struct Options {
    std::string sequence, png, vdb;
    bool json = false, recompute = false, verify = false, no_write = false;
    double max_seam = std::numeric_limits<double>::infinity();
    double loop_s = 0, max_crossfade_s = 2.0, period_crossfade_s = 10.0, memory_mb = 1024;
    std::vector<double> lengths_s = {10, 20, 30, 60, 120, 300};
    loops::TransitionOptions transitions;
    int threads = 2;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "loops", "Build loop-transition tables for a baked sequence and report seam quality");
  // A folder that is not there is the sequence reader's to name (exit 1, as for any bad input),
  // not a CLI11 check's (exit 105).
  command->add_option("sequence", options->sequence, "The sequence folder written by `nearshore bake -o DIR`")
      ->required();
  command->add_option("--png", options->png,
                      "Write distance_matrix.png, seam_ratios.png, worst_seam_gauge.png here");
  command->add_option("--vdb", options->vdb,
                      "Also export the sequence as an OpenVDB volume (x, y, frame) for Houdini or Blender");
  command->add_flag("--json", options->json, "Print the report as JSON (for scripts) instead of text");
  command
      ->add_option("--max-seam", options->max_seam,
                   "Exit with status 2 if the planned loop's worst seam ratio after crossfade exceeds this, or if "
                   "there is no loop to judge")
      ->check(number_in(at_least(0), unbounded()));
  command->add_option("--loop-s", options->loop_s, "Also plan the optimal loop of exactly this length (seconds)")
      ->check(number_in(above(0), unbounded()));
  command
      ->add_option("--lengths-s", options->lengths_s,
                   "Report the best loop with length in [L, 1.25 L] for each L (seconds, at least one frame)")
      ->delimiter(',')
      ->check(number_in(above(0), unbounded()));
  command->add_option("--delta", options->transitions.motion_weight, "delta of eq. 10: weight of the flux distance")
      ->check(number_in(at_least(0), unbounded()));
  command->add_option("--sigma", options->transitions.sigma, "sigma of eq. 11 (default, or 0: 0.1 x mean jump cost)")
      ->check(number_in(at_least(0), unbounded()));
  command
      ->add_option("--filter-width", options->transitions.filter_half_width,
                   "Half-width m of the dynamics-preserving filter, frames (0: no filter)")
      ->check(number_in(at_least(0), at_most(1000)));
  command->add_option("--alpha", options->transitions.future_discount, "Future-cost discount (Schödl's alpha)")
      ->check(number_in(at_least(0), below(1)));
  command->add_option("--candidates", options->transitions.candidates_per_frame, "Jumps kept per frame before pruning")
      ->check(number_in(at_least(1), at_most(1000)));
  command->add_option("--min-probability", options->transitions.min_probability, "Prune transitions below this")
      ->check(number_in(at_least(0), below(1)));
  command
      ->add_option("--max-crossfade-s", options->max_crossfade_s,
                   "Longest crossfade of a jump, seconds (0: hard cuts)")
      ->check(number_in(at_least(0), unbounded()));
  command
      ->add_option("--period-crossfade-s", options->period_crossfade_s,
                   "Longest crossfade across the exact-period jump of a periodic bake (in phase), seconds")
      ->check(number_in(at_least(0), unbounded()));
  command->add_option("--memory-mb", options->memory_mb, "Memory for one stripe of all frames (distance pass)")
      ->check(number_in(at_least(16), at_most(1 << 20)));
  command->add_option("--threads", options->threads, "Threads for decoding and matrix products")
      ->check(number_in(at_least(1), at_most(1024)));
  command->add_flag("--recompute", options->recompute,
                    "Recompute the distances even if loops_gram.bin is current");
  command->add_flag("--verify", options->verify, "Verify every file's checksum first");
  command->add_flag("--no-write", options->no_write, "Do not write loops.json / loops_gram.bin");
  set_example(*command, "nearshore loops out/bake --png out/loops --max-seam 1.0");
  command->callback(naming_flags_in_errors(loops_flags(), [options]() {
    if (options->json) ProgressBar::set_quiet(true);
    loops::LoopsOptions analysis;
    analysis.transitions = options->transitions;
    analysis.recompute = options->recompute;
    analysis.verify = options->verify;
    analysis.write_tables = !options->no_write;
    analysis.report_lengths_s = options->lengths_s;
    analysis.requested_loop_s = options->loop_s;
    analysis.max_crossfade_s = options->max_crossfade_s;
    // The library reads max_crossfade_s = 0 as "keep transitions.max_crossfade_frames"; on the
    // command line 0 means what it says.
    if (options->max_crossfade_s == 0) analysis.transitions.max_crossfade_frames = 0;
    analysis.period_crossfade_s = options->period_crossfade_s;
    analysis.gram.memory_budget_bytes =
        static_cast<std::size_t>(options->memory_mb * (1 << 20));
    analysis.gram.threads = options->threads;
    if (!options->vdb.empty()) loops::export_sequence_vdb(options->sequence, options->vdb);
    const loops::LoopsReport report = loops::analyse_loops(options->sequence, analysis);
    if (!options->png.empty()) loops::write_loops_pictures(report, options->png);
    if (options->json)
      std::printf("%s\n", report.to_json().dump(2).c_str());
    else
      print_report(report);
    if (!std::isfinite(options->max_seam)) return;  // no gate asked for
    // The gate judges the loop a player would use (docs/commands/loops.md); with none, there is
    // nothing that passes it.
    if (const std::string missing = loop_missing_for_gate(report); !missing.empty()) {
      std::fprintf(stderr, "nearshore loops: --max-seam %g fails: %s, so there is no seam to judge\n",
                   options->max_seam, missing.c_str());
      throw ExitStatus{2};
    }
    const double worst = report.worst_seam_ratio_after();
    if (worst > options->max_seam) {
      std::fprintf(stderr, "nearshore loops: worst seam ratio after crossfade %.3f exceeds --max-seam %.3f\n",
                   worst, options->max_seam);
      throw ExitStatus{2};
    }
  }));
}

}  // namespace nearshore::tools
