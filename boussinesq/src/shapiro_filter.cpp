// The Shapiro (1970) filter of the face fluxes (shapiro_filter.hpp, docs/solver.md).
#include "shapiro_filter.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace nearshore::boussinesq::detail {
namespace {

// Where the ghost at position s (outside [0, count)) takes its value, and with which sign
// (0: the ghost is 0, for arrays shorter than the stencil).
struct Ghost {
  int source = 0;
  double sign = 0.0;
};
Ghost ghost(int s, int count, bool wall_normal) {
  if (s >= 0 && s < count) return {s, 1.0};
  if (wall_normal) {  // odd about faces 0 and count-1 (the walls, which hold 0)
    const int mirrored = s < 0 ? -s : 2 * (count - 1) - s;
    return mirrored >= 0 && mirrored < count ? Ghost{mirrored, -1.0} : Ghost{0, 0.0};
  }
  const int mirrored = s < 0 ? -1 - s : 2 * count - 1 - s;  // even about -1/2 and count-1/2
  return {std::clamp(mirrored, 0, count - 1), 1.0};
}

}  // namespace

ShapiroFilter::ShapiroFilter(int half_order) : half_order_(std::max(half_order, 0)) {
  const int p = half_order_;
  weights_.resize(2 * p + 1);
  double binomial = 1.0;  // C(2p, j)
  const double scale = 1.0 / std::pow(4.0, p);
  for (int j = 0; j <= 2 * p; ++j) {
    const int k = j - p;
    weights_[j] = ((k % 2 == 0) ? 1.0 : -1.0) * binomial * scale;
    binomial = binomial * (2 * p - j) / (j + 1);
  }
}

// The per-line kernels, compiled per instruction set like the sweep (boussinesq_sweep.cpp) and
// called from inside the parallel loops (a clone's lambdas would be compiled for the generic
// target); -ffp-contract=off keeps the clones' results identical.
namespace {

// Corrections of slow line s of a [slow][fast] array: out = (all filterable) * sum_k w_k u_{s+k}.
__attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4"))) void slow_line_correction(
    const double* values, const double* filterable, int s, int slow_count, int fast_count, bool wall_normal,
    const double* w, int p, double* __restrict out, double* __restrict ok_line) {
  for (int f = 0; f < fast_count; ++f) {
    out[f] = 0.0;
    ok_line[f] = 1.0;
  }
  for (int k = -p; k <= p; ++k) {
    const Ghost g = ghost(s + k, slow_count, wall_normal);
    const double weight = w[k + p] * g.sign;
    const double* __restrict source = values + static_cast<std::size_t>(g.source) * fast_count;
    if (weight != 0.0)
      for (int f = 0; f < fast_count; ++f) out[f] += weight * source[f];
    if (s + k >= 0 && s + k < slow_count) {
      const double* __restrict ok = filterable + static_cast<std::size_t>(s + k) * fast_count;
      for (int f = 0; f < fast_count; ++f) ok_line[f] *= ok[f];
    }
  }
  for (int f = 0; f < fast_count; ++f) out[f] *= ok_line[f];
}

// One line filtered along itself: `line` and `ok` hold it with p ghosts on each side.
__attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4"))) void fast_line_filter(
    double* __restrict row, const double* __restrict line, const double* __restrict ok, int fast_count,
    const double* w, int p, double* __restrict sum, double* __restrict all_filterable) {
  for (int f = 0; f < fast_count; ++f) {
    sum[f] = 0.0;
    all_filterable[f] = 1.0;
  }
  for (int k = -p; k <= p; ++k) {
    const double weight = w[k + p];
    const double* __restrict shifted = line + p + k;
    const double* __restrict shifted_ok = ok + p + k;
    for (int f = 0; f < fast_count; ++f) {
      sum[f] += weight * shifted[f];
      all_filterable[f] *= shifted_ok[f];
    }
  }
  for (int f = 0; f < fast_count; ++f) row[f] -= all_filterable[f] * sum[f];
}

}  // namespace

void ShapiroFilter::along_slow(double* values, const double* filterable, int slow_count, int fast_count,
                               bool wall_normal) const {
  const int p = half_order_;
  if (p <= 0) return;
  const double* w = weights_.data();
  const std::size_t size = static_cast<std::size_t>(slow_count) * fast_count;
  thread_local std::vector<double> correction;  // the original values are read while corrections build
  correction.resize(size);
  double* const corrections = correction.data();  // this thread's buffer, shared with the workers
  tbb::parallel_for(0, slow_count, [&](int s) {
    thread_local std::vector<double> ok_line;
    ok_line.resize(fast_count);
    slow_line_correction(values, filterable, s, slow_count, fast_count, wall_normal, w, p,
                         corrections + static_cast<std::size_t>(s) * fast_count, ok_line.data());
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, size, 16384),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i < range.end(); ++i) values[i] -= corrections[i];
                    });
}

void ShapiroFilter::along_fast(double* values, const double* filterable, int slow_count, int fast_count,
                               bool wall_normal) const {
  const int p = half_order_;
  if (p <= 0) return;
  const double* w = weights_.data();
  tbb::parallel_for(0, slow_count, [&](int s) {
    // The line with p ghosts on each side and its filterable flags (ghosts 1).
    thread_local std::vector<double> line, ok, sum, all_filterable;
    const int n = fast_count + 2 * p;
    line.resize(n);
    ok.resize(n);
    sum.resize(fast_count);
    all_filterable.resize(fast_count);
    double* row = values + static_cast<std::size_t>(s) * fast_count;
    const double* row_ok = filterable + static_cast<std::size_t>(s) * fast_count;
    std::copy(row, row + fast_count, line.begin() + p);
    std::copy(row_ok, row_ok + fast_count, ok.begin() + p);
    for (int j = 1; j <= p; ++j)
      for (const int i : {-j, fast_count - 1 + j}) {
        const Ghost g = ghost(i, fast_count, wall_normal);
        line[i + p] = g.sign * row[g.source];
        ok[i + p] = 1.0;
      }
    fast_line_filter(row, line.data(), ok.data(), fast_count, w, p, sum.data(), all_filterable.data());
  });
}

}  // namespace nearshore::boussinesq::detail
