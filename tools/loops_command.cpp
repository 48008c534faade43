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
                report.loop_period_s <= 0 ? ""
                : std::abs(detected.lag_s - report.loop_period_s) < 0.5 * report.frame_interval_s
                    ? ", as the manifest says"
                    : ", NOT the manifest's period: the bake has not settled into its forcing");
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
    std::printf("requested loop: none of exactly %.1f s can be made from the table's jumps\n",
                report.requested_loop_s);
  }
  std::printf("best loops by length:\n");
  if (report.best_by_length.empty())
    std::printf("  (none: no candidate jumps give loops of the reported lengths)\n");
  for (const loops::LoopReport& loop : report.best_by_length) print_loop(loop);
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
  command->add_option("sequence", options->sequence, "The sequence folder written by `nearshore bake -o DIR`")
      ->required()
      ->check(CLI::ExistingDirectory);
  command->add_option("--png", options->png,
                      "Write distance_matrix.png, seam_ratios.png, worst_seam_gauge.png here");
  command->add_option("--vdb", options->vdb,
                      "Also export the sequence as an OpenVDB volume (x, y, frame) for Houdini or Blender");
  command->add_flag("--json", options->json, "Print the report as JSON (for scripts) instead of text");
  command->add_option(
      "--max-seam", options->max_seam,
      "Exit with status 2 if the planned loop's worst seam ratio after crossfade exceeds this");
  command->add_option("--loop-s", options->loop_s,
                      "Also plan the optimal loop of exactly this length (seconds)");
  command
      ->add_option("--lengths-s", options->lengths_s,
                   "Report the best loop with length in [L, 1.25 L] for each L")
      ->delimiter(',');
  command->add_option("--delta", options->transitions.motion_weight,
                      "delta of eq. 10: weight of the flux distance");
  command->add_option("--sigma", options->transitions.sigma,
                      "sigma of eq. 11 (default: 0.1 x mean jump cost)");
  command->add_option("--filter-width", options->transitions.filter_half_width,
                      "Half-width m of the dynamics-preserving filter, frames");
  command->add_option("--alpha", options->transitions.future_discount,
                      "Future-cost discount (Schödl's alpha)");
  command->add_option("--candidates", options->transitions.candidates_per_frame,
                      "Jumps kept per frame before pruning");
  command->add_option("--min-probability", options->transitions.min_probability,
                      "Prune transitions below this");
  command->add_option("--max-crossfade-s", options->max_crossfade_s, "Longest crossfade of a jump, seconds");
  command->add_option(
      "--period-crossfade-s", options->period_crossfade_s,
      "Longest crossfade across the exact-period jump of a periodic bake (in phase), seconds");
  command->add_option("--memory-mb", options->memory_mb,
                      "Memory for one stripe of all frames (distance pass)");
  command->add_option("--threads", options->threads, "Threads for decoding and matrix products");
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
    analysis.period_crossfade_s = options->period_crossfade_s;
    analysis.gram.memory_budget_bytes =
        static_cast<std::size_t>(std::max(16.0, options->memory_mb) * (1 << 20));
    analysis.gram.threads = options->threads;
    if (!options->vdb.empty()) loops::export_sequence_vdb(options->sequence, options->vdb);
    const loops::LoopsReport report = loops::analyse_loops(options->sequence, analysis);
    if (!options->png.empty()) loops::write_loops_pictures(report, options->png);
    if (options->json)
      std::printf("%s\n", report.to_json().dump(2).c_str());
    else
      print_report(report);
    const double worst = report.worst_seam_ratio_after();
    if (worst > options->max_seam) {
      std::fprintf(stderr, "nearshore loops: worst seam ratio after crossfade %.3f exceeds --max-seam %.3f\n",
                   worst, options->max_seam);
      throw ExitStatus{2};
    }
  }));
}

}  // namespace nearshore::tools
