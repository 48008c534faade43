#pragma once
// Playback plans over a transition table (Schödl et al. 2000, section 4):
//   (a) a random walk by T (what an endless player does),
//   (b) the optimal loop of a requested length: the closed walk of exactly L frames, made of
//       forward runs and jumps from the table, with the least total jump cost sum C^p, found by
//       dynamic programming over (frame, step) for every start frame that is a jump target,
//   (c) for a time-periodic bake, the exact period (manifest loop_period_s).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "nearshore/loops/transitions.hpp"
#include "nearshore/sequence/loop_playback.hpp"

namespace nearshore::loops {

struct LoopPlan {
  std::string kind;               ///< "optimal" or "period"
  int start_frame = 0;            ///< a cycle starts here (the target of its last jump)
  int length_frames = 0;          ///< frames shown per cycle
  double cost = 0;                ///< sum over jumps of C^p
  std::vector<Transition> jumps;  ///< in play order; after jumps[k].from the player shows jumps[k].to

  /// The frames of one cycle, in order, starting at start_frame.
  std::vector<int> frames() const;
  /// What a player shows per step, crossfade blends included (sequence/loop_playback.hpp).
  sequence::LoopSchedule schedule() const;
  /// How many times the cycle plays one shorter loop over: the largest n such that the jump list
  /// is n copies of its first jumps.size() / n jumps (1 for a loop that does not repeat itself).
  int repetitions() const;
  /// True if no frame is shown twice in one cycle: the viewer never sees a stretch of the loop
  /// again before the whole loop has played (a compound loop of Schödl et al. may replay one).
  bool shows_each_frame_once() const;
};

/// best[L] = the cheapest loop of exactly L frames (L = 0 .. max_length_frames), if any. Loops use
/// the table's candidate jumps (probability 0 included: a loop is planned, not sampled), at most
/// `max_jumps` of them, the best few per diagonal i - j (one diagonal = one loop length).
std::vector<std::optional<LoopPlan>> best_loops_by_length(const TransitionTable& table, int max_length_frames,
                                                          int max_jumps = 256);
/// The same, but only the lengths flagged in `wanted` (index = length) are reconstructed (one
/// dynamic programme for all lengths, one backtrack per wanted length).
std::vector<std::optional<LoopPlan>> best_loops_for_lengths(const TransitionTable& table,
                                                            const std::vector<char>& wanted,
                                                            int max_jumps = 256);
/// The optimal loop of exactly `length_frames`, or nullopt if none exists.
std::optional<LoopPlan> optimal_loop(const TransitionTable& table, int length_frames, int max_jumps = 256);

/// The exact-period loop of a periodic bake: frames [N-1-P, N-2] with the jump N-2 -> N-1-P, so
/// the frame shown after the jump is the one the bake computed one period later (N-1). Throws
/// nearshore::Error if the period is not a whole number of frames or longer than the bake.
LoopPlan period_loop(const TransitionTable& table, const Eigen::MatrixXd& distances, double loop_period_s,
                     double frame_interval_s);

/// `steps` frames of a random walk by T from `start`, reproducible from `seed`.
std::vector<int> random_walk(const TransitionTable& table, int start, int steps, std::uint64_t seed);

}  // namespace nearshore::loops
