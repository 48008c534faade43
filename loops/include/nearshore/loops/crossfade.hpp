#pragma once
// Crossfading across a transition i -> j with c blend frames. The last c frames shown before the
// jump are blends of the source timeline and the target timeline, aligned so that target frame j
// replaces source frame i + 1:
//   shown_k = (1 - alpha_k) f(i - c + k) + alpha_k f(j - 1 - c + k),  alpha_k = k / (c + 1),  k = 1..c
// then f(j), f(j + 1), ... The discontinuity f(j) - f(i + 1) is spread over c + 1 steps.
// eta, P and Q (and breaking) are blended with the SAME weights, which sum to 1: the blended water
// volume sum(eta) dA is exactly (1 - alpha) V_source + alpha V_target (no mass is made or lost by
// the blend itself) and the blended fluxes stay the fluxes that carry that volume. The price is an
// energy dip where the two fields are uncorrelated (reported per seam by the inspector).
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::loops {

/// alpha_k = k / (c + 1): the target's weight in blend k = 1..c.
double crossfade_weight(int k, int crossfade_frames);

/// The frame pair and weight shown `frames_before_jump` frames before the jump i -> j
/// (1 = the last frame before the jump, which is blend k = c). Returns false outside the crossfade.
struct BlendSource {
  int source_frame = 0, target_frame = 0;
  double target_weight = 0;
};
bool crossfade_blend(int from, int to, int crossfade_frames, int frames_before_jump, BlendSource& blend);

/// out = (1 - alpha) a + alpha b for every channel present in both; `out` may alias neither.
void blend_frames(const sequence::Frame& a, const sequence::Frame& b, double alpha, sequence::Frame& out);

}  // namespace nearshore::loops
