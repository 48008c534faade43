#include "nearshore/runtime/playback_plan.hpp"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::runtime {

std::string_view plan_kind_name(PlanKind kind) {
  switch (kind) {
    case PlanKind::kExactPeriod: return "exact period";
    case PlanKind::kOptimalLoop: return "optimal loop";
    case PlanKind::kRandomWalk: return "random walk";
    case PlanKind::kFrameOrder: return "frame order";
  }
  return "frame order";
}

std::optional<PlanKind> parse_plan_kind(std::string_view name) {
  for (PlanKind kind : {PlanKind::kExactPeriod, PlanKind::kOptimalLoop, PlanKind::kRandomWalk, PlanKind::kFrameOrder})
    if (name == plan_kind_name(kind)) return kind;
  if (name == "period") return PlanKind::kExactPeriod;
  if (name == "loop") return PlanKind::kOptimalLoop;
  if (name == "random") return PlanKind::kRandomWalk;
  if (name == "order") return PlanKind::kFrameOrder;
  return std::nullopt;
}

PlaybackPlan PlaybackPlan::frame_order(int frame_count) {
  if (frame_count < 1)
    throw Error("frame-order plan", fmt::format("has {} frames to play", frame_count), "bake at least one frame");
  PlaybackPlan plan;
  plan.kind_ = PlanKind::kFrameOrder;
  plan.frame_count_ = frame_count;
  std::vector<int> frames(static_cast<std::size_t>(frame_count));
  for (int i = 0; i < frame_count; ++i) frames[static_cast<std::size_t>(i)] = i;
  // A hard cut n - 1 -> 0 (no table says how to blend it).
  plan.set_cycle(std::move(frames), {});
  plan.description_ = fmt::format("frame order 0..{} repeated (hard cut back to frame 0)", frame_count - 1);
  return plan;
}

PlaybackPlan::PlaybackPlan(const sequence::LoopsFile::Loop& loop, int frame_count, PlanKind kind) {
  kind_ = kind;
  frame_count_ = frame_count;
  const sequence::LoopSchedule schedule = sequence::schedule_of(loop);
  std::vector<int> crossfade;
  for (const sequence::LoopsFile::Seam& seam : loop.seams) {
    if (seam.from < 0 || seam.from >= frame_count || seam.to < 0 || seam.to >= frame_count)
      throw Error(fmt::format("{} loop", loop.kind), fmt::format("jumps {} -> {} outside frames 0..{}", seam.from,
                                                                 seam.to, frame_count - 1),
                  "run `nearshore loops` again for this bake");
  }
  std::vector<int> frames = schedule.frames();
  const std::size_t length = frames.size();
  crossfade.assign(length, -1);
  for (std::size_t i = 0; i < length; ++i) {
    const int here = frames[i], next = frames[(i + 1) % length];
    if (next == here + 1) continue;
    crossfade[i] = 0;
    for (const sequence::LoopsFile::Seam& seam : loop.seams)
      if (seam.from == here && seam.to == next) crossfade[i] = seam.crossfade_frames;
  }
  set_cycle(std::move(frames), std::move(crossfade));
  description_ = fmt::format("{} of {} frames ({:.1f} s) from frame {} with {} jump{} per cycle",
                             plan_kind_name(kind), loop.length_frames, loop.length_s, loop.start_frame, cycle_jumps_,
                             cycle_jumps_ == 1 ? "" : "s");
}

PlaybackPlan::PlaybackPlan(sequence::TransitionWalk walk, int start_frame, std::uint64_t seed) {
  kind_ = PlanKind::kRandomWalk;
  seed_ = seed;
  frame_count_ = walk.frame_count();
  if (start_frame < 0 || start_frame >= frame_count_)
    throw Error("random-walk plan", fmt::format("starts at frame {} outside frames 0..{}", start_frame, frame_count_ - 1),
                "run `nearshore loops` again for this bake");
  walk_start_ = start_frame;
  for (int frame = 0; frame < frame_count_; ++frame)
    for (const sequence::WalkTransition& t : walk.row(frame)) {
      if (!(t.probability > 0.0) || t.to == t.from + 1) continue;
      // The blends of a crossfade must be frames of the bake (docs/formats/sequence.md).
      if (t.crossfade_frames > std::min(t.to, t.from + 1))
        throw Error("random-walk plan", fmt::format("jump {} -> {} has {} crossfade frames, more than the bake has before it",
                                                    t.from, t.to, t.crossfade_frames),
                    "run `nearshore loops` again for this bake");
      max_crossfade_ = std::max(max_crossfade_, t.crossfade_frames);
    }
  walk_ = std::move(walk);
  description_ = fmt::format("random walk from frame {}, seed {}", start_frame, seed);
  restart_walk();
}

PlaybackPlan::PlaybackPlan(const std::filesystem::path& folder, PlanKind kind, std::optional<std::uint64_t> seed) {
  const sequence::SequenceReader reader(folder);  // the manifest: throws for a newer or unreadable one
  if (kind == PlanKind::kFrameOrder) {
    *this = frame_order(reader.frame_count());
    return;
  }
  std::error_code ec;
  const std::filesystem::path tables_path = folder / sequence::kLoopsFileName;
  if (!std::filesystem::exists(tables_path, ec))
    throw Error(tables_path.string(), fmt::format("does not exist, so there is no {} to play", plan_kind_name(kind)),
                fmt::format("run `nearshore loops {}` (until then the frames play in order)", folder.string()));
  const sequence::LoopsFile tables = sequence::read_loops_for_playback(folder);
  switch (kind) {
    case PlanKind::kExactPeriod:
      if (!tables.report.period_loop)
        throw Error(tables_path.string(), "has no period loop (the bake is not time-periodic)",
                    "play the optimal loop or the random walk instead");
      *this = PlaybackPlan(*tables.report.period_loop, reader.frame_count(), kind);
      return;
    case PlanKind::kOptimalLoop: {
      const sequence::LoopsFile::Loop* loop = sequence::loop_to_play(tables);
      if (!loop)
        throw Error(tables_path.string(), "offers no loop whose seams are no larger than a step (R <= 1)",
                    "play the random walk instead, or run `nearshore loops` with a longer loop");
      *this = PlaybackPlan(*loop, reader.frame_count(), kind);
      return;
    }
    case PlanKind::kRandomWalk: {
      int start = tables.random_walk.start_frame;
      if (start < 0) start = tables.report.graph.first_playable_frame;
      if (start < 0)
        throw Error(tables_path.string(), "has no playable frame to start a random walk from (every frame leads to a dead end)",
                    "play the optimal loop instead, or bake a longer sequence");
      *this = PlaybackPlan(sequence::TransitionWalk::from_loops_file(tables), start,
                           seed.value_or(tables.random_walk.seed));
      return;
    }
    case PlanKind::kFrameOrder: break;
  }
}

void PlaybackPlan::set_cycle(std::vector<int> frames, std::vector<int> jump_crossfade) {
  const std::size_t length = frames.size();
  if (jump_crossfade.size() != length) {
    jump_crossfade.assign(length, -1);
    for (std::size_t i = 0; i < length; ++i)
      if (frames[(i + 1) % length] != frames[i] + 1) jump_crossfade[i] = 0;
  }
  cycle_landed_.assign(length, 0);
  long long landed = 0;
  for (std::size_t i = 0; i < length; ++i) {
    cycle_landed_[i] = landed;  // jumps after positions 0..i-1
    if (jump_crossfade[i] >= 0) {
      ++landed;
      max_crossfade_ = std::max(max_crossfade_, jump_crossfade[i]);
    }
  }
  cycle_jumps_ = landed;
  cycle_ = std::move(frames);
  cycle_jump_crossfade_ = std::move(jump_crossfade);
}

void PlaybackPlan::restart_walk() {
  random_.seed(seed_);
  walk_window_.clear();
  walk_window_.push_back({walk_start_, -1, false, 0});
  walk_base_ = 0;
}

void PlaybackPlan::extend_walk_to(long long p) {
  if (p < walk_base_) restart_walk();
  while (walk_base_ + static_cast<long long>(walk_window_.size()) - 1 < p) {
    WalkPosition& last = walk_window_.back();
    const sequence::WalkTransition* taken = walk_->choose(last.frame, sequence::uniform_from_draw(random_()));
    WalkPosition next;
    if (taken) {
      next.frame = taken->to;
      last.jump_crossfade_after = taken->to == last.frame + 1 ? -1 : taken->crossfade_frames;
    } else {
      // A dead end (loops.json promises none is reachable): restart at the walk's start with a
      // hard cut, and say so in the step.
      next.frame = walk_start_;
      next.restarted = true;
      last.jump_crossfade_after = walk_start_ == last.frame + 1 ? -1 : 0;
    }
    next.landed = last.landed + (last.jump_crossfade_after >= 0 ? 1 : 0);
    walk_window_.push_back(next);
  }
}

int PlaybackPlan::timeline_frame(long long p) {
  if (!walk_) return cycle_[static_cast<std::size_t>(p % static_cast<long long>(cycle_.size()))];
  extend_walk_to(p);
  return walk_window_[static_cast<std::size_t>(p - walk_base_)].frame;
}

int PlaybackPlan::jump_crossfade_after(long long p) {
  if (!walk_) return cycle_jump_crossfade_[static_cast<std::size_t>(p % static_cast<long long>(cycle_.size()))];
  extend_walk_to(p + 1);  // the draw after p decides it
  return walk_window_[static_cast<std::size_t>(p - walk_base_)].jump_crossfade_after;
}

long long PlaybackPlan::landed_by(long long p) {
  if (!walk_) {
    const long long length = static_cast<long long>(cycle_.size());
    return (p / length) * cycle_jumps_ + cycle_landed_[static_cast<std::size_t>(p % length)];
  }
  extend_walk_to(p);
  return walk_window_[static_cast<std::size_t>(p - walk_base_)].landed;
}

PlanStep PlaybackPlan::step(long long k) {
  if (k < 0) k = 0;
  if (walk_) {
    if (k < walk_base_) restart_walk();
    // Keep the window from k on: memory stays bounded by the longest crossfade.
    extend_walk_to(k);
    while (walk_base_ < k) {
      walk_window_.pop_front();
      ++walk_base_;
    }
  }
  PlanStep s;
  s.step = k;
  s.frame = timeline_frame(k);
  s.shown = {s.frame, s.frame, 0.0};
  s.transitions_taken = landed_by(k);
  if (walk_) s.restarted_at_dead_end = walk_window_.front().restarted;
  // The next jump of the timeline within reach of a crossfade (loop_playback.hpp's rule).
  const long long reach = std::max(max_crossfade_, 1);
  for (long long p = k; p < k + reach; ++p) {
    const int crossfade = jump_crossfade_after(p);
    if (crossfade < 0) continue;
    const int from = timeline_frame(p), to = timeline_frame(p + 1);
    const int before = static_cast<int>(p - k + 1);
    if (sequence::crossfade_blend(from, to, crossfade, before, s.shown)) s.in_crossfade = true;
    if (s.in_crossfade || p == k) {
      s.jump_from = from;
      s.jump_to = to;
      s.jump_crossfade_frames = crossfade;
      s.jump_after_this_step = p == k;
    }
    break;
  }
  return s;
}

}  // namespace nearshore::runtime
