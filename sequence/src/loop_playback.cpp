#include "nearshore/sequence/loop_playback.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <span>

#include "nearshore/core/error.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "nearshore/sequence/loops_file.hpp"
#include "nearshore/sequence/sequence_format.hpp"

namespace nearshore::sequence {

double crossfade_weight(int k, int crossfade_frames) {
  return static_cast<double>(k) / (crossfade_frames + 1);
}

bool crossfade_blend(int from, int to, int crossfade_frames, int frames_before_jump, BlendSource& blend) {
  if (frames_before_jump < 1 || frames_before_jump > crossfade_frames) return false;
  const int k = crossfade_frames + 1 - frames_before_jump;  // 1 .. c
  blend.source_frame = from - crossfade_frames + k;
  blend.target_frame = to - 1 - crossfade_frames + k;
  blend.target_weight = crossfade_weight(k, crossfade_frames);
  return true;
}

void blend_frames(const Frame& a, const Frame& b, double alpha, Frame& out) {
  const float wa = static_cast<float>(1.0 - alpha), wb = static_cast<float>(alpha);
  auto blend = [&](const Raster<float>& x, const Raster<float>& y, Raster<float>& z, const char* name) {
    if (x.empty() || y.empty()) {
      z = Raster<float>();
      return;
    }
    if (x.columns() != y.columns() || x.rows() != y.rows())
      throw Error(fmt::format("crossfade of frames {} and {}", a.index, b.index),
                  fmt::format("{} is {} x {} in one and {} x {} in the other", name, x.columns(), x.rows(),
                              y.columns(), y.rows()),
                  "blend frames of the same sequence");
    if (z.columns() != x.columns() || z.rows() != x.rows()) z = Raster<float>(x.columns(), x.rows());
    const float* px = x.data();
    const float* py = y.data();
    float* pz = z.data();
    for (std::size_t k = 0; k < x.size(); ++k) pz[k] = wa * px[k] + wb * py[k];
  };
  blend(a.surface_elevation_m, b.surface_elevation_m, out.surface_elevation_m, "surface_elevation");
  blend(a.flux_x_m2_s, b.flux_x_m2_s, out.flux_x_m2_s, "flux_x");
  blend(a.flux_y_m2_s, b.flux_y_m2_s, out.flux_y_m2_s, "flux_y");
  blend(a.breaking, b.breaking, out.breaking, "breaking");
  out.index = -1;
  out.time_s = (1.0 - alpha) * a.time_s + alpha * b.time_s;
}

std::vector<int> LoopSchedule::frames() const {
  std::vector<int> order;
  order.reserve(shown.size());
  for (const BlendSource& step : shown) order.push_back(step.source_frame);
  return order;
}

LoopSchedule schedule_loop(int start_frame, int length_frames, const std::vector<PlannedJump>& jumps) {
  // A loop is at least one frame long and made of frames that exist; anything else is a plan that
  // was never made (e.g. of a length that rounds to no frame) and would index outside the bake.
  const std::string subject = fmt::format("loop of {} frames from frame {}", length_frames, start_frame);
  const std::string fix = "plan loops of at least one frame (nearshore::loops::optimal_loop, period_loop)";
  if (length_frames < 1) throw Error(subject, "is shorter than one frame", fix);
  if (start_frame < 0) throw Error(subject, "starts before frame 0", fix);
  for (const PlannedJump& jump : jumps)
    if (jump.from < 0 || jump.to < 0 || jump.crossfade_frames < 0)
      throw Error(subject, fmt::format("has a jump {} -> {} with a crossfade of {} frames", jump.from, jump.to,
                                       jump.crossfade_frames),
                  fix);
  LoopSchedule schedule;
  schedule.shown.reserve(static_cast<std::size_t>(length_frames));
  std::size_t next_jump = 0;
  int frame = start_frame;
  for (int step = 0; step < length_frames; ++step) {
    BlendSource shown{frame, frame, 0.0};
    if (!jumps.empty()) {
      const PlannedJump& jump = jumps[next_jump];
      // Frames of the run that ends at jump.from: the last crossfade_frames of them are blends.
      if (frame <= jump.from)
        crossfade_blend(jump.from, jump.to, jump.crossfade_frames, jump.from - frame + 1, shown);
    }
    schedule.shown.push_back(shown);
    if (!jumps.empty() && frame == jumps[next_jump].from) {
      frame = jumps[next_jump].to;
      next_jump = (next_jump + 1) % jumps.size();
    } else {
      ++frame;
    }
  }
  return schedule;
}

LoopSchedule schedule_of(const LoopsFile::Loop& loop) {
  std::vector<PlannedJump> jumps;
  jumps.reserve(loop.seams.size());
  for (const LoopsFile::Seam& seam : loop.seams) jumps.push_back({seam.from, seam.to, seam.crossfade_frames});
  LoopSchedule schedule = schedule_loop(loop.start_frame, loop.length_frames, jumps);
  schedule.kind = loop.kind;
  schedule.length_s = loop.length_s;
  return schedule;
}

// The exact period of a periodic bake, else the requested loop, else the longest reported loop
// whose seams are no larger than an ordinary step after crossfade (R <= 1); nullptr if none.
const LoopsFile::Loop* loop_to_play(const LoopsFile& tables) {
  if (tables.report.period_loop) return &*tables.report.period_loop;
  if (tables.report.requested_loop) return &*tables.report.requested_loop;
  const LoopsFile::Loop* longest = nullptr;
  for (const LoopsFile::Loop& loop : tables.report.best_loops_by_length)
    if (loop.worst_seam_ratio_after <= 1.0 && (!longest || loop.length_s > longest->length_s))
      longest = &loop;
  return longest;
}

LoopsFile read_loops_for_playback(const std::filesystem::path& folder) {
  const std::filesystem::path path = folder / kLoopsFileName;
  LoopsFile tables = read_loops_file(folder);
  const std::filesystem::path manifest_path = folder / kManifestFile;
  const std::string manifest = read_file_bytes(manifest_path);
  const std::string rerun = fmt::format("run `nearshore loops {}` again", folder.string());
  if (tables.sequence_manifest_checksum !=
      checksum_text(std::as_bytes(std::span(manifest.data(), manifest.size()))))
    throw Error(path.string(), "was made for another bake of this folder (its manifest checksum differs)",
                rerun);
  // The same manifest means the same frames; a count that differs means the table itself is
  // corrupt, and its frame indices (checked against its own count) might lie outside the bake.
  const int frame_count = parse_manifest(manifest, manifest_path.string()).frame_count;
  if (tables.report.frame_count != frame_count)
    throw Error(path.string(),
                fmt::format("counts {} frames but {} lists {}", tables.report.frame_count,
                            manifest_path.string(), frame_count),
                rerun);
  return tables;
}

std::optional<LoopSchedule> read_loop_schedule(const std::filesystem::path& folder) {
  std::error_code ec;
  if (!std::filesystem::exists(folder / kLoopsFileName, ec)) return std::nullopt;
  const LoopsFile tables = read_loops_for_playback(folder);
  const LoopsFile::Loop* loop = loop_to_play(tables);
  if (!loop) return std::nullopt;
  return schedule_of(*loop);
}

TransitionWalk::TransitionWalk(int frame_count, std::vector<WalkTransition> transitions)
    : frame_count_(frame_count) {
  for (const WalkTransition& t : transitions)
    if (t.from < 0 || t.from >= frame_count || t.to < 0 || t.to >= frame_count || !(t.probability >= 0.0) ||
        t.crossfade_frames < 0)
      throw Error("transition table", fmt::format("has a transition {} -> {} (probability {}, {} crossfade frames) outside "
                                                  "frames 0..{} or with a negative value",
                                                  t.from, t.to, t.probability, t.crossfade_frames, frame_count - 1),
                  "rebuild the transition table with `nearshore loops`");
  // Group by `from`, keeping each row's order (stable): which entry a draw picks depends on it.
  std::stable_sort(transitions.begin(), transitions.end(),
                   [](const WalkTransition& a, const WalkTransition& b) { return a.from < b.from; });
  transitions_ = std::move(transitions);
  row_start_.assign(static_cast<std::size_t>(std::max(frame_count, 0)) + 1, 0);
  std::size_t next = 0;
  for (int frame = 0; frame < frame_count; ++frame) {
    row_start_[static_cast<std::size_t>(frame)] = next;
    while (next < transitions_.size() && transitions_[next].from == frame) ++next;
  }
  row_start_[static_cast<std::size_t>(std::max(frame_count, 0))] = next;
}

TransitionWalk TransitionWalk::from_loops_file(const LoopsFile& tables) {
  std::vector<WalkTransition> rows;
  rows.reserve(tables.transitions.size());
  for (const LoopsFile::Transition& t : tables.transitions)
    rows.push_back({t.from, t.to, t.probability, t.crossfade_frames});
  return TransitionWalk(tables.report.frame_count, std::move(rows));
}

std::span<const WalkTransition> TransitionWalk::row(int frame) const {
  if (frame < 0 || frame >= frame_count_) return {};
  const std::size_t begin = row_start_[static_cast<std::size_t>(frame)];
  const std::size_t end = row_start_[static_cast<std::size_t>(frame) + 1];
  return std::span(transitions_).subspan(begin, end - begin);
}

const WalkTransition* TransitionWalk::choose(int frame, double u) const {
  const WalkTransition* chosen = nullptr;
  double total = 0.0;
  for (const WalkTransition& t : row(frame)) {
    if (t.probability <= 0.0) continue;
    total += t.probability;
    chosen = &t;
    if (u < total) break;
  }
  return chosen;
}

double uniform_from_draw(std::uint64_t draw) { return static_cast<double>(draw >> 11) * 0x1.0p-53; }

RandomWalker::RandomWalker(const TransitionWalk& walk, int start_frame, std::uint64_t seed)
    : walk_(&walk), frame_(start_frame), random_(seed) {}

const WalkTransition* RandomWalker::step() {
  const WalkTransition* taken = walk_->choose(frame_, uniform_from_draw(random_()));
  if (taken) frame_ = taken->to;
  return taken;
}

std::vector<int> random_walk(const TransitionWalk& walk, int start, int steps, std::uint64_t seed) {
  RandomWalker walker(walk, start, seed);
  std::vector<int> frames{start};
  frames.reserve(static_cast<std::size_t>(std::max(steps, 1)));
  for (int step = 1; step < steps; ++step) {
    if (!walker.step())
      throw Error(fmt::format("random walk at frame {}", walker.frame()), "reached a dead end",
                  "the transition table is inconsistent; rebuild it with `nearshore loops`");
    frames.push_back(walker.frame());
  }
  return frames;
}

}  // namespace nearshore::sequence
