// Sibson gridding accuracy on dense grids: exact on planes (linear precision) and O(h^2) on a
// smooth surface. Kept out of the ASan run (CGAL in a Debug + ASan build takes minutes here).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "nearshore/bathymetry/natural_neighbour.hpp"
#include "scattered_samples.hpp"

namespace nb = nearshore::bathymetry;
using nb::testing::jittered_samples;
using nb::testing::square_grid;

TEST(NaturalNeighbour, ReproducesAPlaneExactly) {
  auto plane = [](double x, double y) { return 12.0 + 0.013 * x - 0.021 * y; };
  const auto points = jittered_samples(40.0, 1000.0, plane, 1);
  const nb::NaturalNeighbourSurface surface(points);
  const auto g = square_grid(1000.0, 7.0);
  const auto depth = surface.sample(g);
  double worst = 0;
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.columns; ++c) worst = std::max(worst, std::abs(depth(c, r) - plane(g.cell_centre_x_m(c), g.cell_centre_y_m(r))));
  // Sibson coordinates have linear precision (Sibson 1981): the only error is rounding, in double
  // for the coordinates and float for the stored depth (~1e-6 relative of ~20 m = 2e-5 m).
  EXPECT_LT(worst, 5e-5);
  EXPECT_NEAR(surface.depth_at(500.5, 333.3), plane(500.5, 333.3), 1e-9);
}

TEST(NaturalNeighbour, ConvergesAtSecondOrderOnASmoothSurface) {
  const double length_m = 1000.0, k = 2.0 * std::numbers::pi / 500.0;
  auto surface_depth = [&](double x, double y) { return 20.0 + 6.0 * std::sin(k * x) * std::cos(k * y); };
  const auto g = square_grid(length_m, 5.0);
  std::vector<double> rms;
  for (double h : {40.0, 20.0, 10.0}) {
    const nb::NaturalNeighbourSurface surface(jittered_samples(h, length_m, surface_depth, 3));
    const auto depth = surface.sample(g);
    double sum = 0;
    for (int r = 0; r < g.rows; ++r)
      for (int c = 0; c < g.columns; ++c) {
        const double e = depth(c, r) - surface_depth(g.cell_centre_x_m(c), g.cell_centre_y_m(r));
        sum += e * e;
      }
    rms.push_back(std::sqrt(sum / g.cell_count()));
  }
  // Linear precision gives O(h^2) (Sibson's C1 interpolant); jittered data make the ratio noisy,
  // so we require an observed order of at least 1.7 per halving (2^1.7 = 3.2) and a small error.
  for (std::size_t i = 0; i + 1 < rms.size(); ++i) {
    const double order = std::log2(rms[i] / rms[i + 1]);
    EXPECT_GT(order, 1.7) << "h=" << 40.0 / (1 << i) << " rms " << rms[i] << " -> " << rms[i + 1];
    RecordProperty("order_" + std::to_string(i), std::to_string(order));
  }
  EXPECT_LT(rms.back(), 0.05);  // 6 m amplitude, 500 m wavelength, 10 m data: < 1 % of the amplitude
}

