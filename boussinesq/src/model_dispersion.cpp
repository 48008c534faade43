#include "nearshore/boussinesq/model_dispersion.hpp"

#include <algorithm>
#include <cmath>

#include "nearshore/ocean/linear_waves.hpp"

namespace nearshore::boussinesq {

double boussinesq_wavenumber(double w, double d, double B) {
  if (w <= 0.0 || d <= 0.0) return 0.0;
  // Newton on f(k) = g d k^2 (1 + B k^2 d^2) - w^2 (1 + (B+1/3) k^2 d^2), from the Airy wavenumber.
  const double g = ocean::kGravity_m_s2, B3 = B + 1.0 / 3.0;
  double k = ocean::wavenumber_from_frequency(w, d);
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double k2 = k * k, d2 = d * d;
    const double f = g * d * k2 * (1.0 + B * k2 * d2) - w * w * (1.0 + B3 * k2 * d2);
    const double df = g * d * (2.0 * k + 4.0 * B * k2 * k * d2) - w * w * 2.0 * B3 * k * d2;
    const double step = f / df;
    k -= step;
    if (std::abs(step) < 1e-13 * k) break;
  }
  return k;
}

double boussinesq_wavenumber_in_current(double w, double d, double B, double U) {
  if (w <= 0.0 || d <= 0.0) return 0.0;
  const double g = ocean::kGravity_m_s2, B3 = B + 1.0 / 3.0, d2 = d * d;
  // The intrinsic frequency of the still-water equations, sigma(k) = k sqrt(G / M).
  return ocean::wavenumber_in_current(w, U, [&](double k) {
    const double s = k * k;
    return k * std::sqrt(g * d * (1.0 + B * d2 * s) / (1.0 + B3 * d2 * s));
  });
}

double phase_speed_error(double w, double model_depth_m, double true_depth_m, double B) {
  // Same frequency, so the ratio of phase speeds w/k is the inverse ratio of the wavenumbers.
  return ocean::wavenumber_from_frequency(w, true_depth_m) / boussinesq_wavenumber(w, model_depth_m, B) - 1.0;
}

double carried_phase_speed_tolerance(double B) {
  // Any depth: the error depends on k d alone. The wave of Airy k d = 3 over 1 m.
  const double w = ocean::frequency_from_wavenumber(kLargestCarriedKd, 1.0);
  return std::abs(phase_speed_error(w, 1.0, 1.0, B));
}

double effective_depth_limit_m(double w) {
  // Airy: w^2 = g k tanh(k d) with k d = K fixed gives d = K tanh(K) g / w^2.
  return kLargestCarriedKd * std::tanh(kLargestCarriedKd) * ocean::kGravity_m_s2 / (w * w);
}

double highest_frequency_over_effective_depth_rad_s(double lowest_w, double deepest_m, double B) {
  const double without_limit = ocean::frequency_from_wavenumber(kLargestCarriedKd / deepest_m, deepest_m);
  if (!(lowest_w > 0.0)) return without_limit;
  // The longest wave slows down over a limited depth (it feels the false bottom): the error is
  // monotone in the limit, so bisect for the shallowest limit that keeps it within tolerance.
  const double tolerance = carried_phase_speed_tolerance(B);
  double feels_m = 0.0, fine_m = deepest_m;
  if (phase_speed_error(lowest_w, fine_m, deepest_m, B) < -tolerance) return without_limit;
  for (int iteration = 0; iteration < 100 && fine_m - feels_m > 1e-6 * deepest_m; ++iteration) {
    const double middle_m = 0.5 * (feels_m + fine_m);
    (phase_speed_error(lowest_w, middle_m, deepest_m, B) < -tolerance ? feels_m : fine_m) = middle_m;
  }
  // The band may reach the wave of k d = 3 over that limit, and never less than without one.
  return std::max(without_limit, ocean::frequency_from_wavenumber(kLargestCarriedKd / fine_m, fine_m));
}

}  // namespace nearshore::boussinesq
