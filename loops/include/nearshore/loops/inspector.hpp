#pragma once
// The loop inspector behind `nearshore loops SEQ` (and `nearshore demo`): distances, transition
// table, plans, and for every planned transition the seam ratio
//   R = |f(j) - f(i+1)| / median_k |f(k+1) - f(k)|     (|.| the metric of eq. 10)
// before and after its crossfade, with the water volume and wave energy change across the seam.
// Writes loops.json (through sequence/loops_file.hpp, the one type of that file) + loops_gram.bin
// into the sequence folder; optional PNG pictures.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "nearshore/loops/distance.hpp"
#include "nearshore/loops/plans.hpp"
#include "nearshore/loops/transitions.hpp"
#include "nearshore/sequence/loops_file.hpp"

namespace nearshore::loops {

inline constexpr const char* kLoopsFile = sequence::kLoopsFileName;
inline constexpr const char* kGramFile = sequence::kLoopsGramFileName;

struct LoopsOptions {
  TransitionOptions transitions;
  GramOptions gram;
  bool recompute = false;    ///< ignore a stored loops_gram.bin
  bool verify = false;       ///< verify every file's checksum first
  bool write_tables = true;  ///< write loops.json / loops_gram.bin into the sequence folder
  std::vector<double> report_lengths_s = {10, 20,  30,
                                          60, 120, 300};  ///< loops reported with length in [L, 1.25 L]
  double requested_loop_s = 0;   ///< plan (b): the optimal loop of exactly this length (0: none)
  double max_crossfade_s = 2.0;  ///< longest crossfade; sets transitions.max_crossfade_frames (0: keep that)
  /// Longest crossfade across the exact-period jump of a periodic bake (plan c). Both sides of that
  /// jump are in phase, so it may be much longer than a jump between unrelated frames; the bake must
  /// hold this many frames beyond one period for it (docs/commands/loops.md).
  double period_crossfade_s = 10.0;
  std::uint64_t random_walk_seed = 1;
};

/// One planned transition across which the player jumps.
struct SeamReport {
  Transition transition;
  int run_before_frames = 0;        ///< frames shown since the previous jump landed
  double seam_ratio_before = 0;     ///< R without crossfade
  double seam_ratio_after = 0;      ///< R across the crossfade (sequence/loop_playback.hpp crossfade_blend)
  double volume_jump_m3 = 0;        ///< V(j) - V(i+1): volume discontinuity without crossfade
  double volume_jump_after_m3 = 0;  ///< the largest per-step volume deviation across the crossfade
  double energy_jump_fraction = 0;  ///< (E(j) - E(i+1)) / mean E, E = 1/2 rho g sum eta^2 dA
  double energy_dip_fraction = 0;   ///< min over blends of E(blend) / E(linear interpolation) - 1
};

/// The period read off the frames themselves (independent of the manifest): the lag L (frames)
/// whose best match min_k D(k, k + L) is smallest, searched from `min_lag_s` to the whole bake. A
/// lag counts as a period when that match is no larger than an ordinary step (ratio <= 1).
struct DetectedPeriod {
  bool found = false;
  int lag_frames = 0;     ///< the best lag (also reported when not found)
  double lag_s = 0;
  double seam_ratio = 0;  ///< min_k D(k, k + lag) / median step
  int matched_frame = 0;  ///< the k of that minimum
};
DetectedPeriod detect_period(const Eigen::MatrixXd& distances, double median_step, double frame_interval_s,
                             double min_lag_s = 10.0);

struct LoopReport {
  LoopPlan plan;
  double length_s = 0;
  std::vector<SeamReport> seams;
  double worst_seam_ratio_before = 0, worst_seam_ratio_after = 0;
};

struct LoopsReport {
  std::filesystem::path folder;
  int frame_count = 0;
  double frame_interval_s = 0;
  double loop_period_s = 0;
  int period_crossfade_frames = 0;  ///< the crossfade limit used for plan (c)
  double sigma = 0, median_step = 0, height_scale_m = 0, motion_scale_m2_s = 0;
  double median_volume_step_m3 = 0;
  int candidate_jumps = 0, usable_jumps = 0, first_playable_frame = 0;
  std::vector<int> dead_ends, reachable_dead_ends;
  DetectedPeriod detected_period;            ///< the period found in the frames (cross-checks the manifest)
  std::optional<LoopReport> period;          ///< plan (c), periodic bakes
  std::vector<LoopReport> best_by_length;  ///< one per report length that has a loop
  std::optional<LoopReport> requested;     ///< plan (b) for requested_loop_s
  double requested_loop_s = 0;             ///< what was asked for (0: nothing)
  bool gram_reused = false;
  double distance_seconds = 0, table_seconds = 0;
  // The matrices behind the report (for pictures and further analysis).
  GramMatrices gram;
  DistanceMatrices distances;
  TransitionTable table;

  /// The largest R after crossfade over all reported plans (the --max-seam gate).
  double worst_seam_ratio_after() const;
  /// The report as `nearshore loops --json` prints it (sequence::loops_report_to_json).
  nlohmann::json to_json() const;
};

/// Runs the whole analysis on a sequence folder. Throws nearshore::Error on bad input.
LoopsReport analyse_loops(const std::filesystem::path& sequence_folder, const LoopsOptions& options = {});

/// Writes distance_matrix.png, seam_ratios.png and worst_seam_gauge.png into `png_folder`.
void write_loops_pictures(const LoopsReport& report, const std::filesystem::path& png_folder);

}  // namespace nearshore::loops
