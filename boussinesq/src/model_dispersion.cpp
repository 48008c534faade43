#include "nearshore/boussinesq/model_dispersion.hpp"

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

}  // namespace nearshore::boussinesq
