#include "nearshore/boussinesq/incident_reflected.hpp"

#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore::boussinesq {

std::complex<double> harmonic_amplitude(const std::vector<double>& elevation_m, double start_time_s,
                                        double sample_interval_s, double angular_frequency_rad_s) {
  const double period_s = 2.0 * std::numbers::pi / angular_frequency_rad_s;
  const double span_s = sample_interval_s * static_cast<double>(elevation_m.size());
  const double whole_periods = std::floor(span_s / period_s);
  if (whole_periods < 1.0)
    throw Error("harmonic_amplitude", fmt::format("the record ({:.3g} s) is shorter than one period ({:.3g} s)", span_s, period_s),
                "record at least one whole period");
  // Samples spanning whole periods; exact only when the period is a whole number of samples, and
  // within O(dt / record) otherwise (the caller picks dt = T / integer where it can).
  const auto count = static_cast<std::size_t>(std::lround(whole_periods * period_s / sample_interval_s));
  std::complex<double> sum = 0.0;
  for (std::size_t n = 0; n < count; ++n) {
    const double t = start_time_s + sample_interval_s * static_cast<double>(n);
    sum += elevation_m[n] * std::polar(1.0, angular_frequency_rad_s * t);
  }
  return 2.0 * sum / static_cast<double>(count);
}

IncidentReflected separate_incident_reflected(const std::vector<double>& position_m,
                                              const std::vector<std::complex<double>>& amplitude, double wavenumber_rad_m) {
  if (position_m.size() < 2 || position_m.size() != amplitude.size())
    throw Error("separate_incident_reflected", "needs at least two gauges, one amplitude each", "add gauges");
  const double n = static_cast<double>(position_m.size());
  std::complex<double> s = 0.0, right_incident = 0.0, right_reflected = 0.0;
  for (std::size_t p = 0; p < position_m.size(); ++p) {
    const std::complex<double> e = std::polar(1.0, wavenumber_rad_m * position_m[p]);
    s += e * e;
    right_incident += amplitude[p] * std::conj(e);
    right_reflected += amplitude[p] * e;
  }
  const std::complex<double> determinant = n * n - std::norm(s);
  // |S| -> N: the gauges cannot tell the two waves apart (spacings at multiples of L/2).
  if (std::abs(determinant) < 1e-3 * n * n)
    throw Error("separate_incident_reflected",
                fmt::format("gauge spacings are (near) multiples of half a wavelength (k = {} rad/m)", wavenumber_rad_m),
                "move a gauge (Mansard & Funke: x12 ~ L/10, L/6 < x13 < L/3)");
  return {(n * right_incident - std::conj(s) * right_reflected) / determinant,
          (n * right_reflected - s * right_incident) / determinant};
}

}  // namespace nearshore::boussinesq
