#pragma once
// Numerical integration shared by the spectra and the sea-state builder: composite Gauss-Legendre
// quadrature. Wave spectra are smooth but steep (exp(-5/4 (wp/w)^4) below the peak, a power-law
// tail above), so the integrals that matter (cell energies, zeroth moments) are done on panels
// small enough that the 8-point rule is exact to far below the 3 % the tests ask for.
#include <array>
#include <cmath>

namespace nearshore::ocean {

/// Integral of f over [a, b] with `panels` equal panels of 8-point Gauss-Legendre (exact for
/// polynomials of degree 15 on each panel).
template <class Function>
double integrate_gauss_legendre(const Function& f, double a, double b, int panels = 8) {
  // Nodes and weights on [-1, 1] (Abramowitz & Stegun table 25.4, n = 8).
  static constexpr std::array<double, 4> node = {0.1834346424956498, 0.5255324099163290,
                                                 0.7966664774136267, 0.9602898564975363};
  static constexpr std::array<double, 4> weight = {0.3626837833783620, 0.3137066458778873,
                                                   0.2223810344533745, 0.1012285362903763};
  if (!(b > a) || panels < 1) return 0.0;
  const double panel_width = (b - a) / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double centre = a + (p + 0.5) * panel_width;
    const double half = 0.5 * panel_width;
    for (std::size_t i = 0; i < node.size(); ++i)
      sum += weight[i] * half * (f(centre - half * node[i]) + f(centre + half * node[i]));
  }
  return sum;
}

/// Integral of f over [a, b] (0 < a < b) on panels equally spaced in log(x): the right spacing
/// for spectra that span decades of frequency or wavenumber.
template <class Function>
double integrate_log_panels(const Function& f, double a, double b, int panels = 400) {
  if (!(b > a) || !(a > 0.0)) return 0.0;
  const double ratio = std::pow(b / a, 1.0 / panels);
  double sum = 0.0, lower = a;
  for (int p = 0; p < panels; ++p) {
    const double upper = p + 1 == panels ? b : lower * ratio;
    sum += integrate_gauss_legendre(f, lower, upper, 1);
    lower = upper;
  }
  return sum;
}

}  // namespace nearshore::ocean
