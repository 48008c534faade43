#pragma once
// Playing a planned loop: the contract between `nearshore loops` (which writes loops.json into the
// sequence folder: loops_file.hpp, docs/formats/sequence.md) and any player (runtime/StreamingEngine,
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
#include <cstdint>
#include <filesystem>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "nearshore/sequence/loops_file.hpp"
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

/// `folder`/loops.json, read and checked against the folder's manifest.json as every player must:
/// its sequence_manifest_checksum must be the manifest's (else it was made for another bake) and
/// its frame count the manifest's. Throws nearshore::Error naming loops.json and the fix (run
/// `nearshore loops` again) for those, a missing file, and everything read_loops_file refuses.
LoopsFile read_loops_for_playback(const std::filesystem::path& folder);
/// The loop read_loop_schedule plays from those tables (period, else requested, else the longest
/// with R <= 1); nullptr if they offer none.
const LoopsFile::Loop* loop_to_play(const LoopsFile& tables);
/// A loops.json plan expanded into its steps (schedule_loop of its start, length and seams).
LoopSchedule schedule_of(const LoopsFile::Loop& loop);

// Random playback (seed 003 section 2: "random playback decides the next height field by the
// probability matrix T"; Schodl et al. 2000): after frame `from`, a player picks one of the
// transitions of probability > 0 by its probability. One implementation, used by the runtime's
// endless plans and by loops/ (nearshore::loops::random_walk).

/// One transition as a walk sees it: after `from` the player shows `to`; the last
/// `crossfade_frames` frames before a jump (to != from + 1) are blends (crossfade_blend).
struct WalkTransition {
  int from = 0, to = 0;
  double probability = 0;  ///< T_ij; 0: never taken at random
  int crossfade_frames = 0;
};

/// A transition table indexed by frame. Rows keep the order given (loops.json: natural successor
/// first), which fixes which transition a draw picks.
class TransitionWalk {
 public:
  /// `transitions` in any order of `from` (each row keeps the given order). Throws
  /// nearshore::Error if a frame index lies outside [0, frame_count) or a probability is negative.
  TransitionWalk(int frame_count, std::vector<WalkTransition> transitions);
  /// The table of loops.json.
  static TransitionWalk from_loops_file(const LoopsFile& tables);
  int frame_count() const { return frame_count_; }
  /// The transitions after `frame` (empty outside the table).
  std::span<const WalkTransition> row(int frame) const;
  /// The transition taken after `frame` for a uniform draw u in [0, 1): the first row entry of
  /// probability > 0 whose running sum of probabilities exceeds u (the last such entry when
  /// rounding leaves the sum at or below u). nullptr at a dead end (no entry of probability > 0).
  const WalkTransition* choose(int frame, double u) const;

 private:
  int frame_count_ = 0;
  std::vector<WalkTransition> transitions_;
  std::vector<std::size_t> row_start_;
};

/// u in [0, 1) from one raw std::mt19937_64 draw: its 53 high bits times 2^-53, the same on every
/// standard library (std::uniform_real_distribution is not specified bit for bit).
double uniform_from_draw(std::uint64_t draw);

/// A walk one frame at a time: one std::mt19937_64(seed) draw per step (uniform_from_draw).
class RandomWalker {
 public:
  RandomWalker(const TransitionWalk& walk, int start_frame, std::uint64_t seed);
  int frame() const { return frame_; }
  /// Moves to the next frame and returns the transition taken; nullptr at a dead end (the frame
  /// does not change; a player decides what to do, e.g. restart).
  const WalkTransition* step();

 private:
  const TransitionWalk* walk_;
  int frame_;
  std::mt19937_64 random_;
};

/// `steps` frames of a random walk from `start` (the first is `start`), reproducible from `seed`.
/// Throws nearshore::Error at a dead end (the table is inconsistent).
std::vector<int> random_walk(const TransitionWalk& walk, int start, int steps, std::uint64_t seed);

}  // namespace nearshore::sequence
