// Linear dispersion of the DISCRETE scheme against Airy theory (issue 4). A standing wave
// cos(k x) in a closed basin is an exact eigenmode of the staggered scheme (wall faces, mirror
// ghost cells), so the period of its oscillation is the scheme's own dispersion relation, with
// every discretisation error (space, time, the iterated dispersive terms) included.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "boussinesq_test_support.hpp"
#include "nearshore/plot/plot.hpp"

namespace nearshore::boussinesq {

using namespace nearshore::ocean;
namespace {


// Madsen & Sorensen (1992) phase speed of the continuous equations with coefficient B.
double continuous_phase_speed(double kh, double depth_m, double B) {
  return std::sqrt(kGravity_m_s2 * depth_m * (1.0 + B * kh * kh) / (1.0 + (B + 1.0 / 3.0) * kh * kh));
}

struct DispersionPoint {
  double kh = 0, airy_m_s = 0, scheme_m_s = 0, continuous_m_s = 0;
  double scheme_error() const { return scheme_m_s / airy_m_s - 1.0; }
  double continuous_error() const { return continuous_m_s / airy_m_s - 1.0; }
};

// Phase speed of the scheme for a wave of k h at `points_per_wavelength` cells per wavelength and
// Courant number `courant` (sqrt(g d) dt / dx), from the zero crossings of the wall cell.
DispersionPoint measure(double kh, int points_per_wavelength, double courant) {
  const double wavelength_m = 10.0, k = 2.0 * std::numbers::pi / wavelength_m, depth_m = kh / k;
  const HarbourGrid harbour = testing::flume(2 * points_per_wavelength, 1, wavelength_m / points_per_wavelength, depth_m);
  BoussinesqSolver solver(harbour, testing::inviscid_parameters(courant), WaveMaker{});
  const double amplitude_m = 1e-5 * depth_m;  // linear: nonlinearity a/d = 1e-5
  solver.set_surface_elevation([&](double x, double) { return amplitude_m * std::cos(k * x); });
  const double period_s = testing::standing_mode_period_s(solver);
  DispersionPoint point;
  point.kh = kh;
  point.airy_m_s = phase_speed_m_s(k, depth_m);
  point.scheme_m_s = 2.0 * std::numbers::pi / period_s / k;
  point.continuous_m_s = continuous_phase_speed(kh, depth_m, 1.0 / 15.0);
  return point;
}

TEST(BoussinesqDispersion, PhaseSpeedAgainstAiryAt20PointsPerWavelength) {
  std::vector<DispersionPoint> points;
  for (double kh = 0.1; kh < 3.0 + 1e-9; kh += 0.1) points.push_back(measure(kh, 20, 0.5));
  LinePlot plot;
  plot.title = "Phase speed / Airy, 20 cells per wavelength, Courant 0.5";
  plot.x_label = "k h";
  plot.y_label = "c / c_Airy";
  PlotSeries scheme{"scheme, measured", {}, {}, {0.84f, 0.15f, 0.16f}, true};
  PlotSeries continuous{"M&S B=1/15, continuous", {}, {}, {0.12f, 0.47f, 0.71f}, false};
  PlotSeries unity{"Airy", {}, {}, {0.3f, 0.3f, 0.3f}, false};
  std::printf("   kh   c_scheme/c_airy   c_MS/c_airy\n");
  for (const DispersionPoint& p : points) {
    std::printf("%5.2f   %+8.3f %%        %+8.3f %%\n", p.kh, 100 * p.scheme_error(), 100 * p.continuous_error());
    scheme.x.push_back(p.kh); scheme.y.push_back(p.scheme_m_s / p.airy_m_s);
    continuous.x.push_back(p.kh); continuous.y.push_back(p.continuous_m_s / p.airy_m_s);
    unity.x.push_back(p.kh); unity.y.push_back(1.0);
  }
  plot.series = {unity, continuous, scheme};
  write_png(render_line_plot(plot), testing::plot_folder() / "dispersion.png");
  for (const DispersionPoint& p : points) {
    // The bound, 2 % of Airy at 20 points per wavelength, holds up to kh = 2.9. At kh = 3
    // the continuous B = 1/15 equations themselves are 2.40 % fast; the scheme (2.08 % measured)
    // must not add to that error.
    if (p.kh < 2.95) EXPECT_LT(std::abs(p.scheme_error()), 0.02) << "kh = " << p.kh;
    else EXPECT_LT(std::abs(p.scheme_error()), std::abs(p.continuous_error())) << "kh = " << p.kh;
    // The discretisation adds little to the continuous equations: the staggered differences change
    // k^2 by sinc^2(pi/20) = 0.9918 (-0.41 % in c) and Crank-Nicolson lags the phase by
    // (w dt)^2/12 <= 0.21 % at Courant 0.5, so the two may differ by at most 0.7 %.
    EXPECT_LT(std::abs(p.scheme_m_s / p.continuous_m_s - 1.0), 0.007) << "kh = " << p.kh;
  }
}


// The same in two dimensions: the mode cos(kx x) cos(ky y) with kx = ky (waves at 45 degrees) is an
// eigenmode of the closed basin; its period tests the cross-derivative dispersive terms
// (Q_xyt, eta_xyy) and the ADI splitting, which a 1-D wave never sees.
TEST(BoussinesqDispersion, ObliqueStandingWaveAgainstAiry) {
  for (double kh : {0.5, 1.5, 2.5}) {
    const double wavelength_m = 10.0, k = 2.0 * std::numbers::pi / wavelength_m, depth_m = kh / k;
    const double k_axis = k / std::sqrt(2.0);
    const int cells = 28;  // per axis wavelength 2 pi / k_axis = sqrt(2) L: 19.8 cells per wavelength
    const double spacing_m = 2.0 * std::numbers::pi / k_axis / cells;
    const HarbourGrid harbour = testing::flume(cells, cells, spacing_m, depth_m);
    BoussinesqSolver solver(harbour, testing::inviscid_parameters(0.5), WaveMaker{});
    const double amplitude_m = 1e-5 * depth_m;
    solver.set_surface_elevation([&](double x, double y) { return amplitude_m * std::cos(k_axis * x) * std::cos(k_axis * y); });
    const double period_s = testing::standing_mode_period_s(solver);
    const double error = 2.0 * std::numbers::pi / period_s / k / phase_speed_m_s(k, depth_m) - 1.0;
    std::printf("45 deg, kh = %.1f: c/c_Airy - 1 = %+.3f %%\n", kh, 100 * error);
    EXPECT_LT(std::abs(error), 0.02) << "kh = " << kh;  // the bound, as along an axis
  }
}

}  // namespace
}  // namespace nearshore::boussinesq
