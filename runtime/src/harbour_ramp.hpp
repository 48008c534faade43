#pragma once
// The sin^2 ramp of the harbour's weight (surface_snapshot.hpp harbour_weight), inline for its two
// readers: surface_snapshot.cpp (the weight of any site point) and surface_sampler.cpp (the
// displaced queries' Newton steps in the blending zone, where the call was a fifth of the time).
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace nearshore::runtime::detail {

// sin^2 ramp from 0 at s = 0 to 1 at s = width (the bake's blending record's rule), and its
// derivative d/ds. Flat parts return without a sine: most query points lie there.
struct Ramp {
  double value = 0.0, slope = 0.0;
};
// sin^2(pi u / 2) on u in [0, 1] and its derivative (pi / 2) sin(pi u) at 257 nodes, read by a cubic
// Hermite in each interval (value and slope exact at the nodes, so the ramp stays C1): within
// 3e-11 of sin^2 and 1.5e-8 of its largest slope (the interpolation bounds h^4 / 384 max |f^(4)|
// and sqrt(3) h^3 / 216 max |f^(4)|, h = 1/256, f^(4) at most pi^4 / 2; measured 2.95e-11 and
// 1.48e-8 over 2e6 points). A displaced query in the blending zone takes the weight at every
// Newton step: libm's sin and sincos were a fifth of its time (perf); the table is a few
// multiply-adds (the zone's hull points 4.6 -> 6.3 M/s).
struct RampTable {
  static constexpr int kIntervals = 256;
  std::array<double, kIntervals + 1> value, slope_per_u;
};
inline const RampTable kRampTable = [] {
  RampTable t;
  for (int i = 0; i <= RampTable::kIntervals; ++i) {
    const double u = static_cast<double>(i) / RampTable::kIntervals;
    const double r = std::sin(0.5 * std::numbers::pi * u);
    t.value[i] = r * r;
    t.slope_per_u[i] = 0.5 * std::numbers::pi * std::sin(std::numbers::pi * u);
  }
  t.value[RampTable::kIntervals] = 1.0;
  return t;
}();

inline Ramp sin2_ramp(double s, double width, bool with_slope) {
  if (width <= 0.0) return {s > 0.0 ? 1.0 : 0.0, 0.0};
  // Written so that a NaN argument or width returns a flat part: the table index below must be in
  // range whatever a host passes.
  if (!(s > 0.0)) return {0.0, 0.0};
  if (!(s < width)) return {1.0, 0.0};
  constexpr double h = 1.0 / RampTable::kIntervals;
  const double per_width = RampTable::kIntervals / width;  // off the chain that s starts
  const double x = s * per_width;
  const int i = std::min(static_cast<int>(x), RampTable::kIntervals - 1);
  const double t = x - i, t2 = t * t, t3 = t2 * t;
  const double p0 = kRampTable.value[i], p1 = kRampTable.value[i + 1];
  const double m0 = h * kRampTable.slope_per_u[i], m1 = h * kRampTable.slope_per_u[i + 1];
  const double value = (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + t) * m0 + (3 * t2 - 2 * t3) * p1 + (t3 - t2) * m1;
  if (!with_slope) return {value, 0.0};
  const double d_dt = (6 * t2 - 6 * t) * (p0 - p1) + (3 * t2 - 4 * t + 1) * m0 + (3 * t2 - 2 * t) * m1;
  return {value, d_dt * per_width};
}

}  // namespace nearshore::runtime::detail
