#pragma once
// Playback plans: the endless, deterministic order in which the runtime shows a baked sequence's
// frames (seed 003 section 2: "loop playback" of the optimal loop, and "random playback" by the
// transition matrix T; Schodl et al. 2000). A plan is a function of (kind, seed, step k): step k
// shows one frame, or the crossfade blend (1 - w) f(source) + w f(target) of loop_playback.hpp.
//
// Every kind is a TIMELINE f_0, f_1, ... of frames plus, for each jump f_m -> f_{m+1} (f_{m+1} !=
// f_m + 1), its crossfade length c. Step k shows, if the next jump of the timeline at or after k
// is at position m with m - k + 1 <= c, the blend crossfade_blend(f_m, f_{m+1}, c, m - k + 1);
// else f_k alone. This is exactly what sequence::schedule_loop does for one cycle of a planned
// loop (tested), and for the random walk it means the walk decides each jump c frames before it
// is shown (the plan draws ahead by the longest crossfade of the table).
//
//   kExactPeriod   loops.json period_loop: the exact period of a periodic bake
//   kOptimalLoop   loops.json's planned loop as read_loop_schedule chooses it (period, else the
//                  requested loop, else the longest one with seams no larger than a step)
//   kRandomWalk    a random walk on loops.json's transition table (probability > 0 only), from
//                  random_walk.start_frame, seeded by random_walk.seed or the seed given
//   kFrameOrder    0, 1, ..., n - 1, 0, ... with a hard cut n - 1 -> 0: the fallback without
//                  loops.json (the viewer says so)
#include <cstdint>
#include <deque>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "nearshore/sequence/loop_playback.hpp"

namespace nearshore::runtime {

enum class PlanKind { kExactPeriod, kOptimalLoop, kRandomWalk, kFrameOrder };

/// "exact period", "optimal loop", "random walk", "frame order".
std::string_view plan_kind_name(PlanKind kind);
/// The inverse ("period", "loop", "random", "order" are accepted too); nullopt if unknown.
std::optional<PlanKind> parse_plan_kind(std::string_view name);

/// What step k of a plan shows, and where it is in the plan.
struct PlanStep {
  long long step = 0;            ///< k
  int frame = 0;                 ///< f_k: the timeline's frame (= shown.source_frame)
  sequence::BlendSource shown;   ///< f_k alone (target_weight 0) or the planned crossfade blend
  bool in_crossfade = false;     ///< shown.target_weight > 0
  /// The jump this step belongs to when in_crossfade, or that follows right after it
  /// (jump_after_this_step): from -> to with its crossfade length; -1 when none is that near.
  int jump_from = -1, jump_to = -1, jump_crossfade_frames = 0;
  bool jump_after_this_step = false;  ///< step k + 1 shows jump_to's timeline (f_{k+1} = jump_to)
  long long transitions_taken = 0;    ///< jumps landed at steps 1..k (the frame order's wrap counts)
  bool restarted_at_dead_end = false; ///< random walk only: f_k is the start frame after a dead end
};

class PlaybackPlan {
 public:
  /// The plan of `kind` for the sequence in `folder` (its manifest.json and loops.json). `seed`
  /// replaces loops.json's random_walk.seed (random walk only). Throws nearshore::Error naming
  /// the file and the fix, the message a viewer shows: no loops.json (kinds other than frame
  /// order), one of a newer version, malformed, or made for another bake (its manifest checksum
  /// differs), no period loop (a bake that is not periodic) or no planned loop, an unreadable
  /// manifest.
  PlaybackPlan(const std::filesystem::path& folder, PlanKind kind, std::optional<std::uint64_t> seed = {});
  /// Frame order over `frame_count` frames: no files needed.
  static PlaybackPlan frame_order(int frame_count);
  /// A random walk on `walk` from `start_frame` (for tests and hosts with their own tables).
  PlaybackPlan(sequence::TransitionWalk walk, int start_frame, std::uint64_t seed);
  /// A planned loop's cycle (its frames repeated, each jump with its crossfade).
  PlaybackPlan(const sequence::LoopsFile::Loop& loop, int frame_count, PlanKind kind);

  PlanKind kind() const { return kind_; }
  std::uint64_t seed() const { return seed_; }
  int frame_count() const { return frame_count_; }
  /// One line for people: "random walk from frame 12, seed 7, 40 transitions", "optimal loop of
  /// 240 frames (24.0 s) with 2 jumps", ...
  const std::string& description() const { return description_; }
  /// The longest crossfade of any jump the plan can take (the walk draws this far ahead).
  int max_crossfade_frames() const { return max_crossfade_; }
  /// Loops and frame order: the steps of one cycle (the plan repeats with it); random walk: 0.
  long long cycle_length_steps() const { return static_cast<long long>(cycle_.size()); }

  /// Step k >= 0. O(1) for the cyclic kinds; for the random walk O(1) amortised while k grows
  /// (the engine asks for 0, 1, 2, ...), and a k behind the last one asked replays the walk from
  /// its start (O(k)). Not thread-safe: each thread keeps its own copy of the plan.
  PlanStep step(long long k);

 private:
  PlaybackPlan() = default;
  void set_cycle(std::vector<int> frames, std::vector<int> jump_crossfade);
  // The timeline at position p and the crossfade of the jump after p (-1: no jump after p).
  int timeline_frame(long long p);
  int jump_crossfade_after(long long p);
  long long landed_by(long long p);
  void extend_walk_to(long long p);
  void restart_walk();

  PlanKind kind_ = PlanKind::kFrameOrder;
  std::uint64_t seed_ = 0;
  int frame_count_ = 0;
  int max_crossfade_ = 0;
  std::string description_;
  // Cyclic kinds: the frames of one cycle, the crossfade of the jump after each position (-1: the
  // next position is the natural successor), and the jumps landed up to each position.
  std::vector<int> cycle_;
  std::vector<int> cycle_jump_crossfade_;
  std::vector<long long> cycle_landed_;
  long long cycle_jumps_ = 0;
  // Random walk: the table, its start, and a window [walk_base_, walk_base_ + size) of the timeline.
  std::optional<sequence::TransitionWalk> walk_;
  int walk_start_ = 0;
  std::mt19937_64 random_;  // the walk's draws (sequence::uniform_from_draw), copied with the plan
  struct WalkPosition {
    int frame = 0;
    int jump_crossfade_after = -1;  ///< -1 until the next position is drawn, or no jump
    bool restarted = false;
    long long landed = 0;           ///< jumps landed at positions 1..p
  };
  std::deque<WalkPosition> walk_window_;
  long long walk_base_ = 0;
};

}  // namespace nearshore::runtime
