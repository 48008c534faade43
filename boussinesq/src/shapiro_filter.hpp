#pragma once
// The Shapiro (1970) low-pass filter of order 2p that the Boussinesq solver applies to its face
// fluxes every step (docs/solver.md, "Grid-scale filter"):
//   u <- u - (-delta^2 / 4)^p u,   response 1 - sin^{2p}(k dx / 2)
// so 2 dx waves are removed and resolved waves are left all but untouched. (-delta^2)^p u is the
// (2p+1)-point stencil sum_k (-1)^k C(2p, p+k) u_{i+k}, k = -p..p.
//
// The arrays are [slow][fast]: value (s, f) at s * fast_count + f. Filtering runs along one index;
// beyond the array's ends ghost values follow a wall: odd about the end faces when the flux crosses
// the wall (`wall_normal`: faces 0 and count-1 are the walls and hold 0), even about the half-way
// points beyond the ends when the flux runs along it. A value is changed only where every value of
// its stencil inside the array has filterable = 1 (ghosts count as filterable).
#include <vector>

namespace nearshore::boussinesq::detail {

class ShapiroFilter {
 public:
  /// Order 2 * half_order (half_order = p >= 0; 0 = no filter). The stencil is built here, once.
  explicit ShapiroFilter(int half_order = 4);
  int half_order() const { return half_order_; }
  /// Along the slow index: all fast lanes in lock-step (contiguous, vectorised).
  void along_slow(double* values, const unsigned char* filterable, int slow_count, int fast_count,
                  bool wall_normal) const;
  /// Along the fast index, each slow line on its own.
  void along_fast(double* values, const unsigned char* filterable, int slow_count, int fast_count,
                  bool wall_normal) const;
  /// The stencil (-delta^2)^p / 4^p with the filter's sign: u_new = u - sum_k weight_k u_{i+k}.
  const std::vector<double>& weights() const { return weights_; }

 private:
  int half_order_ = 4;
  std::vector<double> weights_;
};

}  // namespace nearshore::boussinesq::detail
