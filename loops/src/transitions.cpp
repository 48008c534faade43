#include "nearshore/loops/transitions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "nearshore/core/statistics.hpp"

namespace nearshore::loops {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Every TransitionOptions field in the range where the table means something; NaN fails each test.
void check_options(const TransitionOptions& o) {
  auto refuse = [](const char* field, double value, const char* range, const char* why) {
    throw Error(fmt::format("TransitionOptions::{} = {}", field, value), fmt::format("is outside {}: {}", range, why),
                fmt::format("give TransitionOptions::{} a value in {}", field, range));
  };
  if (!(o.motion_weight >= 0 && std::isfinite(o.motion_weight)))
    refuse("motion_weight", o.motion_weight, "[0, inf)", "delta of eq. 10 weighs a distance");
  if (o.filter_half_width < 0) refuse("filter_half_width", o.filter_half_width, "[0, inf)", "it counts frames");
  if (!(o.sigma >= 0 && std::isfinite(o.sigma)))
    refuse("sigma", o.sigma, "[0, inf)", "sigma of eq. 11 scales costs (0: from sigma_factor)");
  if (!(o.sigma_factor > 0 && std::isfinite(o.sigma_factor)))
    refuse("sigma_factor", o.sigma_factor, "(0, inf)", "it scales the mean jump cost into sigma");
  if (!(o.future_discount >= 0 && o.future_discount < 1))
    refuse("future_discount", o.future_discount, "[0, 1)",
           "alpha of the future cost; at 1 or more the future cost of a loop grows without bound");
  if (!(o.cost_exponent > 0 && std::isfinite(o.cost_exponent)))
    refuse("cost_exponent", o.cost_exponent, "(0, inf)", "p of the future cost");
  if (o.candidates_per_frame < 1)
    refuse("candidates_per_frame", o.candidates_per_frame, "[1, inf)", "with none kept there are no jumps");
  if (o.min_jump_frames < 1) refuse("min_jump_frames", o.min_jump_frames, "[1, inf)", "it counts frames");
  if (!(o.min_probability >= 0 && o.min_probability < 1))
    refuse("min_probability", o.min_probability, "[0, 1)", "at 1 every transition but a certain one is pruned");
  if (o.max_crossfade_frames < 0) refuse("max_crossfade_frames", o.max_crossfade_frames, "[0, inf)", "it counts frames");
}

}  // namespace

Eigen::MatrixXd filter_distances(const Eigen::MatrixXd& distances, int half_width) {
  const int n = static_cast<int>(distances.rows());
  if (half_width <= 0) return distances;
  // Binomial weights over the 2m taps k = -m .. m-1 (Schödl et al. 2000, eq. 3): comparing the
  // m frames before and after makes a jump respect the direction of motion, not just the shape.
  const int taps = 2 * half_width;
  std::vector<double> weights(static_cast<std::size_t>(taps));
  double binomial = 1, total = 0;
  for (int k = 0; k < taps; ++k) {
    weights[static_cast<std::size_t>(k)] = binomial;
    total += binomial;
    binomial = binomial * (taps - 1 - k) / (k + 1);
  }
  for (double& w : weights) w /= total;
  Eigen::MatrixXd filtered = Eigen::MatrixXd::Constant(n, n, kInfinity);
  const int first = half_width, last = n - half_width;  // full support: i - m >= 0, i + m - 1 <= n - 1
  for (int j = first; j <= last; ++j)
    for (int i = first; i <= last; ++i) {
      double sum = 0;
      for (int k = -half_width; k < half_width; ++k)
        sum += weights[static_cast<std::size_t>(k + half_width)] * distances(i + k, j + k);
      filtered(i, j) = sum;
    }
  return filtered;
}

CrossfadeChoice choose_crossfade(const Eigen::MatrixXd& distances, double median_step, int from, int to,
                                 int max_crossfade_frames) {
  // Blending the last c frames before the jump spreads the discontinuity f(j) - f(i+1) over c + 1
  // steps: the step into blend k deviates from the natural motion by D(j-c+k, i+1-c+k) / (c+1)
  // The target frames j-c .. j-1 must exist.
  const int next = from + 1;
  const double scale = median_step > 0 ? median_step : 1.0;
  CrossfadeChoice best{0, distances(to, next) / scale};
  const int longest = std::min({max_crossfade_frames, to, next});
  for (int c = 1; c <= longest; ++c) {
    double worst = 0;
    for (int k = 0; k <= c; ++k) worst = std::max(worst, distances(to - c + k, next - c + k));
    const double ratio = worst / (c + 1) / scale;
    if (ratio < best.seam_ratio_after - 1e-12) best = {c, ratio};
  }
  return best;
}

int TransitionTable::usable_jump_count() const {
  return static_cast<int>(
      std::count_if(transitions.begin(), transitions.end(), [](const Transition& t) { return !t.natural() && t.probability > 0; }));
}

int TransitionTable::candidate_jump_count() const {
  return static_cast<int>(
      std::count_if(transitions.begin(), transitions.end(), [](const Transition& t) { return !t.natural(); }));
}

std::vector<int> TransitionTable::dead_ends() const {
  std::vector<int> frames;
  for (int i = 0; i < frame_count; ++i) {
    const auto row = from(i);
    if (std::none_of(row.begin(), row.end(), [](const Transition& t) { return t.probability > 0; })) frames.push_back(i);
  }
  return frames;
}

std::vector<int> TransitionTable::reachable_dead_ends(int start) const {
  std::vector<char> seen(static_cast<std::size_t>(frame_count), 0);
  std::vector<int> stack{start}, dead;
  seen[static_cast<std::size_t>(start)] = 1;
  while (!stack.empty()) {
    const int frame = stack.back();
    stack.pop_back();
    bool any = false;
    for (const Transition& t : from(frame)) {
      if (t.probability <= 0) continue;
      any = true;
      if (!seen[static_cast<std::size_t>(t.to)]) {
        seen[static_cast<std::size_t>(t.to)] = 1;
        stack.push_back(t.to);
      }
    }
    if (!any) dead.push_back(frame);
  }
  std::sort(dead.begin(), dead.end());
  return dead;
}

int TransitionTable::first_playable_frame() const {
  for (int i = 0; i < frame_count; ++i)
    if (std::isfinite(future_value[static_cast<std::size_t>(i)])) return i;
  return -1;
}

TransitionTable build_transition_table(const DistanceMatrices& distances, const TransitionOptions& options) {
  check_options(options);
  const Eigen::MatrixXd& d = distances.combined;
  const int n = static_cast<int>(d.rows());
  const int m = options.filter_half_width;
  if (n < 2 * m + 3)
    throw Error(fmt::format("sequence of {} frames", n),
                fmt::format("is too short for transitions with a filter half-width of {}", m),
                "bake more frames or give a smaller TransitionOptions::filter_half_width");
  TransitionTable table;
  table.options = options;
  table.frame_count = n;
  std::vector<double> steps;
  for (int k = 0; k + 1 < n; ++k) steps.push_back(d(k, k + 1));
  table.median_step = median_of(steps);

  // 1. Dynamics-preserving filter; C_ij = D'_{i+1, j}.
  const Eigen::MatrixXd filtered = filter_distances(d, m);
  auto cost = [&](int i, int j) { return i + 1 < n ? filtered(i + 1, j) : kInfinity; };

  // 2. Candidates per row: the natural successor and the best local minima of C along the row.
  std::vector<std::vector<Transition>> rows(static_cast<std::size_t>(n));
  for (int i = 0; i + 1 < n; ++i) {
    const int next = i + 1;
    if (!std::isfinite(cost(i, next))) continue;  // outside the filter's support: a dead end
    std::vector<Transition>& row = rows[static_cast<std::size_t>(i)];
    row.push_back(Transition{i, next, 0.0});
    std::vector<Transition> jumps;
    for (int j = 0; j < n; ++j) {
      const double c = cost(i, j);
      if (!std::isfinite(c) || std::abs(j - next) < options.min_jump_frames) continue;
      // A true local minimum along the row, with both neighbours inside the filter's support (the
      // edge of the support is not a minimum, only the end of what can be compared).
      const double left = j > 0 ? cost(i, j - 1) : kInfinity, right = j + 1 < n ? cost(i, j + 1) : kInfinity;
      if (std::isfinite(left) && std::isfinite(right) && c <= left && c < right) jumps.push_back(Transition{i, j, c});
    }
    const std::size_t keep = std::min(jumps.size(), static_cast<std::size_t>(std::max(0, options.candidates_per_frame)));
    std::partial_sort(jumps.begin(), jumps.begin() + static_cast<std::ptrdiff_t>(keep), jumps.end(),
                      [](const Transition& a, const Transition& b) { return a.cost < b.cost; });
    row.insert(row.end(), jumps.begin(), jumps.begin() + static_cast<std::ptrdiff_t>(keep));
  }

  // 3. Future cost by value iteration, V_i = min_j (C_ij^p + alpha V_j), Gauss-Seidel from the
  //    last frame back (Schödl section 3.2): the end of the sequence propagates in one sweep.
  const double p = options.cost_exponent, alpha = options.future_discount;
  std::vector<double>& value = table.future_value;
  value.assign(static_cast<std::size_t>(n), kInfinity);
  for (int i = 0; i < n; ++i)
    if (!rows[static_cast<std::size_t>(i)].empty()) value[static_cast<std::size_t>(i)] = 0;
  for (auto& row : rows)
    for (Transition& t : row) t.future_cost = std::pow(t.cost, p);  // C^p, completed below
  for (int sweep = 0; sweep < 100000; ++sweep) {
    double change = 0, largest = 0;
    for (int i = n - 1; i >= 0; --i) {
      const auto& row = rows[static_cast<std::size_t>(i)];
      if (row.empty()) continue;
      double best = kInfinity;
      for (const Transition& t : row) best = std::min(best, t.future_cost + alpha * value[static_cast<std::size_t>(t.to)]);
      double& v = value[static_cast<std::size_t>(i)];
      if (std::isfinite(best)) largest = std::max(largest, best);
      change = std::max(change, std::isfinite(best) && std::isfinite(v) ? std::abs(best - v) : (best == v ? 0.0 : kInfinity));
      v = best;
    }
    if (change <= 1e-13 * (1 + largest)) break;
  }

  // 4. sigma: a small multiple of the mean candidate jump cost (Schödl section 3).
  table.sigma = options.sigma;
  if (!(table.sigma > 0)) {
    double sum = 0;
    int count = 0;
    for (const auto& row : rows)
      for (const Transition& t : row)
        if (!t.natural()) sum += t.future_cost, ++count;
    table.sigma = count && sum > 0 ? options.sigma_factor * sum / count : 1.0;
  }

  // 5. T_ij ~ exp(-D''_ij / sigma) (eq. 11), pruned and renormalised; crossfades and seam ratios.
  const double scale = table.median_step > 0 ? table.median_step : 1.0;
  table.row_start.assign(static_cast<std::size_t>(n) + 1, 0);
  for (int i = 0; i < n; ++i) {
    auto& row = rows[static_cast<std::size_t>(i)];
    double lowest = kInfinity;
    for (Transition& t : row) {
      t.future_cost += alpha * value[static_cast<std::size_t>(t.to)];
      lowest = std::min(lowest, t.future_cost);
    }
    for (int pass = 0; pass < 2; ++pass) {  // normalise, prune, normalise again
      double total = 0;
      for (Transition& t : row) {
        if (pass == 0) t.probability = std::isfinite(t.future_cost) ? std::exp(-(t.future_cost - lowest) / table.sigma) : 0.0;
        total += t.probability;
      }
      for (Transition& t : row) {
        t.probability = total > 0 ? t.probability / total : 0.0;
        if (pass == 0 && t.probability < options.min_probability) t.probability = 0;
      }
    }
    for (Transition& t : row) {
      if (t.natural()) continue;
      t.seam_ratio = d(t.to, t.from + 1) / scale;
      const CrossfadeChoice fade = choose_crossfade(d, table.median_step, t.from, t.to, options.max_crossfade_frames);
      t.crossfade_frames = fade.frames;
      t.seam_ratio_after = fade.seam_ratio_after;
    }
    std::stable_sort(row.begin() + (row.empty() ? 0 : 1), row.end(),
                     [](const Transition& a, const Transition& b) { return a.probability > b.probability; });
    table.row_start[static_cast<std::size_t>(i) + 1] = table.row_start[static_cast<std::size_t>(i)] + static_cast<int>(row.size());
    table.transitions.insert(table.transitions.end(), row.begin(), row.end());
  }
  return table;
}

}  // namespace nearshore::loops
