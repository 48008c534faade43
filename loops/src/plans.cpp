#include "nearshore/loops/plans.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "nearshore/core/error.hpp"

namespace nearshore::loops {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The jumps loops may use: all candidate jumps, the best 3 per diagonal (same loop length, spread
// along the sequence), then the cheapest `max_jumps` overall.
std::vector<Transition> loop_jumps(const TransitionTable& table, int max_jumps) {
  std::map<int, std::vector<Transition>> by_diagonal;
  for (const Transition& t : table.transitions)
    if (!t.natural() && std::isfinite(t.cost)) by_diagonal[t.to - t.from].push_back(t);
  std::vector<Transition> jumps;
  for (auto& [offset, diagonal] : by_diagonal) {
    std::sort(diagonal.begin(), diagonal.end(),
              [](const Transition& a, const Transition& b) { return a.cost < b.cost; });
    std::vector<Transition> kept;
    for (const Transition& t : diagonal) {
      // Neighbours on a diagonal are nearly the same jump; keep ones at least 8 frames apart.
      if (std::all_of(kept.begin(), kept.end(),
                      [&](const Transition& k) { return std::abs(k.from - t.from) >= 8; }))
        kept.push_back(t);
      if (kept.size() == 3) break;
    }
    jumps.insert(jumps.end(), kept.begin(), kept.end());
  }
  std::sort(jumps.begin(), jumps.end(),
            [](const Transition& a, const Transition& b) { return a.cost < b.cost; });
  if (static_cast<int>(jumps.size()) > max_jumps) jumps.resize(static_cast<std::size_t>(max_jumps));
  return jumps;
}

// Dynamic programme over (step, frame) from one start frame s: value_t(f) = least jump cost of a
// walk of t frames from s to f. A forward step shifts every value by one frame, so values are
// stored in a ring indexed by (frame - step) and the shift costs nothing; only jumps do work.
// Returns best[L] = value_L(s) (a closed walk of L frames) for L <= max_length; with `choices`,
// records which jump reached each target at each step, for backtracking.
class LoopProgramme {
 public:
  // Each jump also costs kJumpPenalty, so of two loops with the same jump cost (e.g. both exact)
  // the one with fewer jumps wins; reported costs leave it out.
  static constexpr double kJumpPenalty = 1e-9;
  LoopProgramme(int frame_count, const std::vector<Transition>& jumps, const std::vector<double>& jump_cost)
      : n_(frame_count), jumps_(jumps), cost_(jump_cost) {
    for (double& c : cost_) c += kJumpPenalty;
  }

  std::vector<double> run(int start, int max_length, std::vector<std::vector<int>>* choices) {
    ring_.assign(static_cast<std::size_t>(n_), kInfinity);
    step_ = 0;
    at(start) = 0;
    std::vector<double> closed(static_cast<std::size_t>(max_length) + 1, kInfinity), arriving(jumps_.size());
    if (choices) choices->assign(static_cast<std::size_t>(max_length) + 1, {});
    for (int length = 1; length <= max_length; ++length) {
      for (std::size_t k = 0; k < jumps_.size(); ++k) arriving[k] = at(jumps_[k].from) + cost_[k];
      ++step_;
      at(0) = kInfinity;  // the slot of frame 0 held frame n-1, which has no successor
      std::vector<int>* record = choices ? &(*choices)[static_cast<std::size_t>(length)] : nullptr;
      if (record) record->clear();
      for (std::size_t k = 0; k < jumps_.size(); ++k) {
        double& target = at(jumps_[k].to);
        if (arriving[k] < target) {
          target = arriving[k];
          if (record) record->push_back(static_cast<int>(k));  // later entries override earlier ones
        }
      }
      closed[static_cast<std::size_t>(length)] = at(start);
    }
    return closed;
  }

 private:
  double& at(int frame) {
    const long slot = ((static_cast<long>(frame) - step_) % n_ + n_) % n_;
    return ring_[static_cast<std::size_t>(slot)];
  }
  int n_;
  long step_ = 0;
  const std::vector<Transition>& jumps_;
  std::vector<double> cost_;
  std::vector<double> ring_;
};

LoopPlan backtrack(const TransitionTable& table, const std::vector<Transition>& jumps,
                   const std::vector<double>& cost, int start, int length) {
  LoopProgramme programme(table.frame_count, jumps, cost);
  std::vector<std::vector<int>> choices;
  programme.run(start, length, &choices);
  LoopPlan plan;
  plan.kind = "optimal";
  plan.start_frame = start;
  plan.length_frames = length;
  int frame = start;
  std::vector<Transition> reversed;
  for (int step = length; step >= 1; --step) {
    // The last recorded jump into `frame` at this step is the one that set its value.
    int chosen = -1;
    for (int k : choices[static_cast<std::size_t>(step)])
      if (jumps[static_cast<std::size_t>(k)].to == frame) chosen = k;
    if (chosen >= 0) {
      reversed.push_back(jumps[static_cast<std::size_t>(chosen)]);
      plan.cost += cost[static_cast<std::size_t>(chosen)];
      frame = jumps[static_cast<std::size_t>(chosen)].from;
    } else {
      --frame;
    }
  }
  plan.jumps.assign(reversed.rbegin(), reversed.rend());
  // Start the cycle at the target of its last jump, so it reads "play from start, jump, ...".
  if (!plan.jumps.empty()) plan.start_frame = plan.jumps.back().to;
  return plan;
}

}  // namespace

int LoopPlan::repetitions() const {
  const std::size_t count = jumps.size();
  for (std::size_t pattern = 1; pattern < count; ++pattern) {
    if (count % pattern != 0) continue;
    bool repeats = true;
    for (std::size_t k = pattern; k < count && repeats; ++k)
      repeats = jumps[k].from == jumps[k - pattern].from && jumps[k].to == jumps[k - pattern].to;
    if (repeats) return static_cast<int>(count / pattern);
  }
  return 1;
}

bool LoopPlan::shows_each_frame_once() const {
  std::vector<int> shown = frames();
  std::sort(shown.begin(), shown.end());
  return std::adjacent_find(shown.begin(), shown.end()) == shown.end();
}

std::vector<int> LoopPlan::frames() const { return schedule().frames(); }

sequence::LoopSchedule LoopPlan::schedule() const {
  std::vector<sequence::PlannedJump> planned;
  for (const Transition& jump : jumps) planned.push_back({jump.from, jump.to, jump.crossfade_frames});
  sequence::LoopSchedule shown = sequence::schedule_loop(start_frame, length_frames, planned);
  shown.kind = kind;
  return shown;
}

std::vector<std::optional<LoopPlan>> best_loops_by_length(const TransitionTable& table, int max_length_frames,
                                                          int max_jumps) {
  return best_loops_for_lengths(
      table,
      std::vector<char>(static_cast<std::size_t>(std::min(max_length_frames, table.frame_count)) + 1, 1),
      max_jumps);
}

std::vector<std::optional<LoopPlan>> best_loops_for_lengths(const TransitionTable& table,
                                                            const std::vector<char>& wanted, int max_jumps) {
  int max_length_frames = static_cast<int>(wanted.size()) - 1;
  const std::vector<Transition> jumps = loop_jumps(table, max_jumps);
  std::vector<double> cost;
  for (const Transition& t : jumps) cost.push_back(std::pow(t.cost, table.options.cost_exponent));
  std::vector<int> starts;
  for (const Transition& t : jumps) starts.push_back(t.to);
  std::sort(starts.begin(), starts.end());
  starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
  max_length_frames = std::min(max_length_frames, table.frame_count);
  std::vector<double> best(static_cast<std::size_t>(max_length_frames) + 1, kInfinity);
  std::vector<int> best_start(best.size(), -1);
  LoopProgramme programme(table.frame_count, jumps, cost);
  for (int start : starts) {
    const std::vector<double> closed = programme.run(start, max_length_frames, nullptr);
    for (std::size_t length = 1; length < closed.size(); ++length)
      if (closed[length] < best[length] - 1e-15) best[length] = closed[length], best_start[length] = start;
  }
  std::vector<std::optional<LoopPlan>> plans(best.size());
  for (std::size_t length = 1; length < best.size(); ++length)
    if (best_start[length] >= 0 && wanted[length])
      plans[length] = backtrack(table, jumps, cost, best_start[length], static_cast<int>(length));
  return plans;
}

std::optional<LoopPlan> optimal_loop(const TransitionTable& table, int length_frames, int max_jumps) {
  if (length_frames < 1 || length_frames > table.frame_count) return std::nullopt;
  const std::vector<Transition> jumps = loop_jumps(table, max_jumps);
  std::vector<double> cost;
  for (const Transition& t : jumps) cost.push_back(std::pow(t.cost, table.options.cost_exponent));
  std::vector<int> starts;
  for (const Transition& t : jumps) starts.push_back(t.to);
  std::sort(starts.begin(), starts.end());
  starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
  LoopProgramme programme(table.frame_count, jumps, cost);
  double best = kInfinity;
  int best_start = -1;
  for (int start : starts) {
    const double closed = programme.run(start, length_frames, nullptr).back();
    if (closed < best - 1e-15) best = closed, best_start = start;
  }
  if (best_start < 0) return std::nullopt;
  return backtrack(table, jumps, cost, best_start, length_frames);
}

LoopPlan period_loop(const TransitionTable& table, const Eigen::MatrixXd& distances, double loop_period_s,
                     double frame_interval_s) {
  const int n = table.frame_count;
  const double period_frames = loop_period_s / frame_interval_s;
  const long period = std::lround(period_frames);
  if (!(loop_period_s > 0) || std::abs(period_frames - period) > 1e-6 * std::max(1.0, period_frames))
    throw Error(fmt::format("loop period {} s", loop_period_s),
                fmt::format("is {:.6f} frames of {} s, not a whole number", period_frames, frame_interval_s),
                "bake with an output interval that divides the forcing period");
  if (period < 2 || period + 1 > n - 1)
    throw Error(fmt::format("loop period {} s", loop_period_s),
                fmt::format("is {} frames but the bake has {} frames after spin-up", period, n),
                "bake at least one period plus two frames");
  LoopPlan plan;
  plan.kind = "period";
  plan.length_frames = static_cast<int>(period);
  plan.start_frame = n - 1 - plan.length_frames;
  Transition jump;
  jump.from = n - 2;
  jump.to = plan.start_frame;
  jump.cost = distances(n - 1, plan.start_frame);  // the unfiltered D: the filter's support ends before n-1
  plan.cost = std::pow(jump.cost, table.options.cost_exponent);
  const double scale = table.median_step > 0 ? table.median_step : 1.0;
  jump.seam_ratio = distances(jump.to, jump.from + 1) / scale;
  const CrossfadeChoice fade =
      choose_crossfade(distances, table.median_step, jump.from, jump.to,
                       std::min(table.options.max_crossfade_frames, plan.length_frames - 1));
  jump.crossfade_frames = fade.frames;
  jump.seam_ratio_after = fade.seam_ratio_after;
  plan.jumps = {jump};
  return plan;
}

std::vector<int> random_walk(const TransitionTable& table, int start, int steps, std::uint64_t seed) {
  // The one random walk of the project (sequence/loop_playback.hpp), on this table's rows.
  std::vector<sequence::WalkTransition> rows;
  rows.reserve(table.transitions.size());
  for (const Transition& t : table.transitions) rows.push_back({t.from, t.to, t.probability, t.crossfade_frames});
  return sequence::random_walk(sequence::TransitionWalk(table.frame_count, std::move(rows)), start, steps, seed);
}

}  // namespace nearshore::loops
