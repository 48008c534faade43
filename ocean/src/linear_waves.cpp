#include "nearshore/ocean/linear_waves.hpp"

#include <cmath>
#include <limits>

namespace nearshore::ocean {
namespace {
bool is_deep(double depth_m) { return !(depth_m > 0.0) || std::isinf(depth_m); }
}  // namespace

double wavenumber_from_frequency(double w, double depth_m) {
  if (w <= 0.0) return 0.0;
  const double deep_k = w * w / kGravity_m_s2;
  if (is_deep(depth_m) || deep_k * depth_m > 20.0) return deep_k;  // tanh(kd) = 1 to 1e-17
  // Start from Fenton & McKee (1990): k d ~ k0 d / tanh((k0 d)^(3/4))^(2/3), then Newton on
  // f(k) = g k tanh(k d) - w^2.
  const double k0d = deep_k * depth_m;
  double k = k0d / std::pow(std::tanh(std::pow(k0d, 0.75)), 2.0 / 3.0) / depth_m;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const double t = std::tanh(k * depth_m);
    const double f = kGravity_m_s2 * k * t - w * w;
    const double df = kGravity_m_s2 * (t + k * depth_m * (1.0 - t * t));
    const double step = f / df;
    k -= step;
    if (std::abs(step) < 1e-12 * k) break;
  }
  return k;
}

double frequency_from_wavenumber(double k, double depth_m) {
  if (k <= 0.0) return 0.0;
  const double t = is_deep(depth_m) ? 1.0 : std::tanh(k * depth_m);
  return std::sqrt(kGravity_m_s2 * k * t);
}

double phase_speed_m_s(double k, double depth_m) {
  if (k <= 0.0) return is_deep(depth_m) ? std::numeric_limits<double>::infinity() : std::sqrt(kGravity_m_s2 * depth_m);
  return frequency_from_wavenumber(k, depth_m) / k;
}

double group_speed_m_s(double k, double depth_m) {
  const double c = phase_speed_m_s(k, depth_m);
  if (is_deep(depth_m)) return 0.5 * c;
  const double kd = k * depth_m;
  const double n = kd > 20.0 ? 0.5 : 0.5 * (1.0 + 2.0 * kd / std::sinh(2.0 * kd));
  return n * c;
}

double wavenumber_in_current(double w, double U, const std::function<double(double)>& sigma) {
  if (w <= 0.0) return 0.0;
  // f(k) = sigma(k) + k U - w is -w at k = 0 and grows while the group speed in the current,
  // sigma'(k) + U, is positive; against the current it peaks where that speed vanishes (the
  // blocking point) and falls beyond. Walk k up by 5 % until f > 0 (bracketed) or f falls (blocked).
  auto f = [&](double k) { return sigma(k) + k * U - w; };
  double low = 0.0, high = 1e-6 * w;
  double f_high = f(high), f_low = -w;
  while (f_high <= 0.0) {
    const double next = high * 1.05, f_next = f(next);
    if (f_next < f_high) return 0.0;  // past the blocking point without reaching w
    low = high;
    f_low = f_high;
    high = next;
    f_high = f_next;
    if (high > 1e9) return 0.0;
  }
  (void)f_low;
  for (int iteration = 0; iteration < 200 && high - low > 1e-14 * high; ++iteration) {
    const double middle = 0.5 * (low + high);
    (f(middle) > 0.0 ? high : low) = middle;
  }
  return 0.5 * (low + high);
}

double wavenumber_in_current(double w, double depth_m, double U) {
  return wavenumber_in_current(w, U, [depth_m](double k) { return frequency_from_wavenumber(k, depth_m); });
}

}  // namespace nearshore::ocean
