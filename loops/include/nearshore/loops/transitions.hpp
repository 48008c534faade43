#pragma once
// Markov transition tables over the frames of a sequence: seed 003 eq. (11) with the refinements of
// Schödl, Szeliski, Salesin & Essa (2000), "Video Textures" (SIGGRAPH), section 3:
//   D'_ij  = sum_{k=-m}^{m-1} w_k D_{i+k, j+k}       dynamics-preserving diagonal filter, binomial w (eq. 3)
//   C_ij   = D'_{i+1, j}                              cost of showing j after i (seed 003: "D_{i+1,j}")
//   D''_ij = C_ij^p + alpha min_k D''_jk              future cost, so a walk never runs into a dead end (eq. 5)
//   T_ij   ~ exp(-D''_ij / sigma), sum_j T_ij = 1     seed 003 eq. (11), Schödl eq. (2)
// Pruning keeps, per frame, the natural successor and the few jumps that are local minima of C
// along the row (Schödl section 3.4), then drops probabilities below a threshold.
#include <span>
#include <vector>

#include <Eigen/Core>

#include "nearshore/loops/distance.hpp"

namespace nearshore::loops {

struct TransitionOptions {
  double motion_weight = 1.0;      ///< delta of eq. (10): weight of the flux distance
  int filter_half_width = 2;       ///< m of the diagonal filter (2m taps, binomial); 0 = no filter
  double sigma = 0;                ///< sigma of eq. (11); 0 = sigma_factor * mean candidate jump cost
  double sigma_factor = 0.1;       ///< Schödl: "a small multiple of the average" cost
  double future_discount = 0.995;  ///< alpha of the future cost (Schödl uses 0.99 .. 0.999)
  double cost_exponent = 2;        ///< p of the future cost
  int candidates_per_frame = 4;    ///< local-minimum jumps kept per frame before probabilities
  int min_jump_frames = 3;         ///< |j - (i+1)| below this is not a jump (it is a stutter or skip)
  double min_probability = 0.01;   ///< pruning threshold for random playback
  int max_crossfade_frames = 12;   ///< longest crossfade considered
};

/// One transition i -> j: after frame `from` the player shows frame `to`.
struct Transition {
  int from = 0, to = 0;
  double cost = 0;         ///< C_ij = D'_{i+1, j} (0 for the natural successor)
  double future_cost = 0;  ///< D''_ij
  double probability = 0;  ///< T_ij after pruning (0: kept for loop planning, never taken at random)
  int crossfade_frames = 0;       ///< c: the last c frames before the jump are blends (sequence/loop_playback.hpp crossfade_blend)
  double seam_ratio = 0;          ///< R = |f(j) - f(i+1)| / median_k |f(k+1) - f(k)|, no crossfade
  double seam_ratio_after = 0;    ///< the same across the crossfade (choose_crossfade)
  bool natural() const { return to == from + 1; }
};

struct TransitionTable {
  TransitionOptions options;
  double sigma = 0;              ///< the sigma used
  double median_step = 0;        ///< median_k D(k, k+1), the denominator of R
  int frame_count = 0;
  std::vector<Transition> transitions;  ///< grouped by `from`, natural first, then by probability
  std::vector<int> row_start;           ///< transitions of frame i: [row_start[i], row_start[i+1])
  std::vector<double> future_value;     ///< min_k D''_ik per frame (infinity: a dead end)

  std::span<const Transition> from(int frame) const {
    return std::span(transitions).subspan(row_start[frame], row_start[frame + 1] - row_start[frame]);
  }
  int usable_jump_count() const;  ///< jumps with probability > 0
  int candidate_jump_count() const;
  std::vector<int> dead_ends() const;  ///< frames with no transition of probability > 0
  /// Dead ends a random walk from `start` can reach (must be none).
  std::vector<int> reachable_dead_ends(int start) const;
  int first_playable_frame() const;  ///< the first frame with a finite future
};

/// The diagonal filter; entries without full filter support are +infinity.
Eigen::MatrixXd filter_distances(const Eigen::MatrixXd& distances, int half_width);

/// The seam ratio after a crossfade of c frames, and the c in [0, max] that minimises it.
struct CrossfadeChoice {
  int frames = 0;
  double seam_ratio_after = 0;
};
CrossfadeChoice choose_crossfade(const Eigen::MatrixXd& distances, double median_step, int from, int to,
                                 int max_crossfade_frames);

TransitionTable build_transition_table(const DistanceMatrices& distances, const TransitionOptions& options);

}  // namespace nearshore::loops
