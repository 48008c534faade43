#pragma once
// Test data for the natural-neighbour tests: jittered samples of a surface, and a square grid.
#include <random>
#include <vector>

#include "nearshore/bathymetry/natural_neighbour.hpp"

namespace nearshore::bathymetry::testing {

// Jittered points at spacing h over [0, L]^2 (+ one spacing outside so the hull covers the square).
template <class Surface>
std::vector<ScatteredDepth> jittered_samples(double h, double length_m, Surface&& f, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.35 * h, 0.35 * h);
  std::vector<ScatteredDepth> points;
  for (double y = -h; y <= length_m + h + 1e-9; y += h)
    for (double x = -h; x <= length_m + h + 1e-9; x += h) {
      const double px = x + jitter(random), py = y + jitter(random);
      points.push_back({px, py, f(px, py)});
    }
  return points;
}

inline nearshore::GridGeometry square_grid(double length_m, double spacing_m) {
  nearshore::GridGeometry g;
  g.columns = g.rows = static_cast<int>(length_m / spacing_m);
  g.spacing_m = spacing_m;
  return g;
}

}  // namespace nearshore::bathymetry::testing

