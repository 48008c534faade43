#pragma once
// Playing a planned loop: the contract between `nearshore loops` (which writes loops.json into the
// sequence folder: loops_file.hpp, docs/formats/sequence.md) and any player (playback/SequencePlayer,
// or an engine's own). Here because both sides need it and the playback runtime links only this
// library.
//
// Crossfading across a transition i -> j with c blend frames. The last c frames shown before the
// jump are blends of the source timeline and the target timeline, aligned so that target frame j
// replaces source frame i + 1:
//   shown_k = (1 - alpha_k) f(i - c + k) + alpha_k f(j - 1 - c + k),  alpha_k = k / (c + 1),  k = 1..c
// then f(j), f(j + 1), ... The discontinuity f(j) - f(i + 1) is spread over c + 1 steps.
// eta, P and Q (and breaking) are blended with the SAME weights, which sum to 1: the blended water
// volume sum(eta) dA is exactly (1 - alpha) V_source + alpha V_target (no mass is made or lost by
// the blend itself) and the blended fluxes stay the fluxes that carry that volume. The price is an
// energy dip where the two fields are uncorrelated (reported per seam by the inspector).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::sequence {

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
void blend_frames(const Frame& a, const Frame& b, double alpha, Frame& out);

/// One jump of a planned loop: after frame `from` the player shows `to`, the last
/// `crossfade_frames` frames before it being blends.
struct PlannedJump {
  int from = 0, to = 0, crossfade_frames = 0;
};

/// What a player shows at each step of one cycle of a loop, in order: source_frame alone
/// (target_weight 0) or the crossfade blend (1 - w) source + w target.
struct LoopSchedule {
  std::string kind;  ///< the kind of the loops.json plan it came from: "period" or "optimal"
  double length_s = 0;
  std::vector<BlendSource> shown;
  /// The source frames alone (the frames of the loop without its blends).
  std::vector<int> frames() const;
};

/// The cycle that starts at `start_frame` (where the last jump lands) and runs forward, taking
/// `jumps` in order, for `length_frames` steps.
LoopSchedule schedule_loop(int start_frame, int length_frames, const std::vector<PlannedJump>& jumps);

/// The loop a player should use from `folder`/loops.json (written by `nearshore loops`, read through
/// read_loops_file): the exact period of a periodic bake, else the requested loop (--loop-s), else
/// the longest reported loop whose seams are no larger than an ordinary step after crossfade
/// (R <= 1). nullopt if there is no loops.json or it offers none. Throws nearshore::Error if
/// loops.json is malformed, of another format version, or was made for another bake (its manifest
/// checksum differs).
std::optional<LoopSchedule> read_loop_schedule(const std::filesystem::path& folder);

}  // namespace nearshore::sequence
