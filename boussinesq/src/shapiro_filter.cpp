// The Shapiro (1970) filter of the face fluxes (shapiro_filter.hpp, docs/solver.md).
#include "shapiro_filter.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
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

// Corrections of one slow line of a [slow][fast] array: out = (all filterable) * sum_k w_k u_{s+k}.
// sources[k + p]: the line that stencil point k reads (a ghost's mirrored line), signs[k + p] its
// sign; oks[k + p]: its filterable flags, or null for a ghost (filterable).
__attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4"))) void slow_line_correction(
    const double* const* sources, const double* signs, const unsigned char* const* oks, int fast_count, const double* w,
    int p, double* __restrict out, double* __restrict ok_line) {
  for (int f = 0; f < fast_count; ++f) {
    out[f] = 0.0;
    ok_line[f] = 1.0;
  }
  for (int k = -p; k <= p; ++k) {
    const double weight = w[k + p] * signs[k + p];
    const double* __restrict source = sources[k + p];
    if (weight != 0.0)
      for (int f = 0; f < fast_count; ++f) out[f] += weight * source[f];
    if (const unsigned char* __restrict ok = oks[k + p])
      for (int f = 0; f < fast_count; ++f) ok_line[f] *= static_cast<double>(ok[f]);
  }
  for (int f = 0; f < fast_count; ++f) out[f] *= ok_line[f];
}

// One line filtered along itself: `line` and `ok` hold it with p ghosts on each side.
__attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4"))) void fast_line_filter(
    double* __restrict row, const double* __restrict line, const unsigned char* __restrict ok, int fast_count,
    const double* w, int p, double* __restrict sum, double* __restrict all_filterable) {
  for (int f = 0; f < fast_count; ++f) {
    sum[f] = 0.0;
    all_filterable[f] = 1.0;
  }
  for (int k = -p; k <= p; ++k) {
    const double weight = w[k + p];
    const double* __restrict shifted = line + p + k;
    const unsigned char* __restrict shifted_ok = ok + p + k;
    for (int f = 0; f < fast_count; ++f) {
      sum[f] += weight * shifted[f];
      all_filterable[f] *= static_cast<double>(shifted_ok[f]);
    }
  }
  for (int f = 0; f < fast_count; ++f) row[f] -= all_filterable[f] * sum[f];
}

}  // namespace

void ShapiroFilter::along_slow(double* values, const unsigned char* filterable, int slow_count, int fast_count,
                               bool wall_normal) const {
  const int p = half_order_;
  if (p <= 0) return;
  const double* w = weights_.data();
  // Each line's correction reads the ORIGINAL values of the 2p lines around it. The lines are
  // filtered in blocks of kSlowBlockLines: a block computes all its corrections (into a per-thread
  // buffer of the block's size) before it writes its own lines, and reads the lines of its
  // neighbours from copies taken before any block wrote (the p lines on each side of each block).
  // So the extra memory is 2p / kSlowBlockLines of the array, not a copy of it (docs/solver.md, "Memory").
  constexpr int kSlowBlockLines = 128;
  const int blocks = (slow_count + kSlowBlockLines - 1) / kSlowBlockLines;
  const std::size_t line_size = static_cast<std::size_t>(fast_count);
  auto line_of = [&](int s) { return values + static_cast<std::size_t>(s) * line_size; };
  // halo[b]: copies of lines [begin - p, begin) and [end, end + p) of block b (inside the array).
  std::vector<std::vector<double>> halo(static_cast<std::size_t>(blocks));
  auto halo_range = [&](int b) {
    const int begin = b * kSlowBlockLines, end = std::min(slow_count, begin + kSlowBlockLines);
    return std::array<int, 4>{std::max(0, begin - p), begin, end, std::min(slow_count, end + p)};
  };
  if (blocks > 1)
    tbb::parallel_for(0, blocks, [&](int b) {
      const auto [before, begin, end, after] = halo_range(b);
      std::vector<double>& copy = halo[static_cast<std::size_t>(b)];
      copy.resize(static_cast<std::size_t>((begin - before) + (after - end)) * line_size);
      std::copy(line_of(before), line_of(begin), copy.begin());
      std::copy(line_of(end), line_of(after), copy.begin() + static_cast<std::ptrdiff_t>((begin - before) * line_size));
    });
  tbb::parallel_for(0, blocks, [&](int b) {
    const auto [before, begin, end, after] = halo_range(b);
    const double* copy = halo[static_cast<std::size_t>(b)].data();
    // The original values of line s as this block sees them: its own lines in place, others copied.
    auto original = [&](int s) -> const double* {
      if (s >= begin && s < end) return line_of(s);
      if (s < begin) return copy + static_cast<std::size_t>(s - before) * line_size;
      return copy + static_cast<std::size_t>((begin - before) + (s - end)) * line_size;
    };
    thread_local std::vector<double> corrections, ok_line;
    thread_local std::vector<const double*> sources;
    thread_local std::vector<const unsigned char*> oks;
    thread_local std::vector<double> signs;
    corrections.resize(static_cast<std::size_t>(end - begin) * line_size);
    ok_line.resize(line_size);
    sources.resize(static_cast<std::size_t>(2 * p + 1));
    oks.resize(sources.size());
    signs.resize(sources.size());
    for (int s = begin; s < end; ++s) {
      for (int k = -p; k <= p; ++k) {
        const Ghost g = ghost(s + k, slow_count, wall_normal);
        sources[static_cast<std::size_t>(k + p)] = g.sign != 0.0 ? original(g.source) : values;  // sign 0: not read
        signs[static_cast<std::size_t>(k + p)] = g.sign;
        oks[static_cast<std::size_t>(k + p)] =
            s + k >= 0 && s + k < slow_count ? filterable + static_cast<std::size_t>(s + k) * line_size : nullptr;
      }
      slow_line_correction(sources.data(), signs.data(), oks.data(), fast_count, w, p,
                           corrections.data() + static_cast<std::size_t>(s - begin) * line_size, ok_line.data());
    }
    double* first = line_of(begin);
    const std::size_t count = static_cast<std::size_t>(end - begin) * line_size;
    for (std::size_t i = 0; i < count; ++i) first[i] -= corrections[i];
  });
}

void ShapiroFilter::along_fast(double* values, const unsigned char* filterable, int slow_count, int fast_count,
                               bool wall_normal) const {
  const int p = half_order_;
  if (p <= 0) return;
  const double* w = weights_.data();
  tbb::parallel_for(0, slow_count, [&](int s) {
    // The line with p ghosts on each side and its filterable flags (ghosts 1).
    thread_local std::vector<double> line, sum, all_filterable;
    thread_local std::vector<unsigned char> ok;
    const int n = fast_count + 2 * p;
    line.resize(n);
    ok.resize(n);
    sum.resize(fast_count);
    all_filterable.resize(fast_count);
    double* row = values + static_cast<std::size_t>(s) * fast_count;
    const unsigned char* row_ok = filterable + static_cast<std::size_t>(s) * fast_count;
    std::copy(row, row + fast_count, line.begin() + p);
    std::copy(row_ok, row_ok + fast_count, ok.begin() + p);
    for (int j = 1; j <= p; ++j)
      for (const int i : {-j, fast_count - 1 + j}) {
        const Ghost g = ghost(i, fast_count, wall_normal);
        line[i + p] = g.sign * row[g.source];
        ok[i + p] = 1;
      }
    fast_line_filter(row, line.data(), ok.data(), fast_count, w, p, sum.data(), all_filterable.data());
  });
}

}  // namespace nearshore::boussinesq::detail
