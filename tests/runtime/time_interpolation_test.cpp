// The harbour in time (issue 40, runtime/surface_snapshot.hpp): each keyframe's d eta / dt is the
// bake's mass equation applied to its fluxes, and the keyframes are joined by a cubic Hermite, so
// a host's heave sees heights that are C1 in time, a vertical velocity, and an acceleration of the
// wave's own size instead of a spike at every keyframe. Checked against a linear wave, whose
// d eta / dt = a w sin(k x - w t) and max |d2 eta / dt2| = a w^2 nobody here chose.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/runtime/surface_sampler.hpp"
#include "runtime_test_support.hpp"

namespace nearshore::runtime {
namespace {
using namespace testing;

// A 30 m wave travelling east, period 6 s, 0.3 m amplitude: keyframes 0.5 s apart (the demo's
// output interval) put 12 on a period.
constexpr double kAmplitude_m = 0.3, kWavelength_m = 30.0, kPeriod_s = 6.0, kFrameInterval_s = 0.5;
const double kWavenumber = 2.0 * std::numbers::pi / kWavelength_m, kOmega = 2.0 * std::numbers::pi / kPeriod_s;

TEST(TimeInterpolation, TheRateIsTheMassEquationOfTheFluxesTheSolverWrites) {
  // Cell averages of face fluxes P = (w / k) eta (BoussinesqSolver::flux_x_m2_s), 2 m cells.
  GridGeometry geometry;
  geometry.columns = 64;
  geometry.rows = 6;
  geometry.spacing_m = 2.0;
  HarbourGrid grid = HarbourGrid::open_water(geometry, 5.0f);
  const double t = 0.7;
  auto flux_at = [&](double x) { return kOmega / kWavenumber * kAmplitude_m * std::cos(kWavenumber * x - kOmega * t); };
  Raster<float> p(geometry.columns, geometry.rows), q(geometry.columns, geometry.rows, 0.0f);
  for (int r = 0; r < geometry.rows; ++r)
    for (int c = 0; c < geometry.columns; ++c) p(c, r) = static_cast<float>(0.5 * (flux_at(c * 2.0) + flux_at((c + 1) * 2.0)));
  const Raster<float> rate = surface_elevation_rate(grid, p, q);
  // Against the solver's own divergence -(P_{i+1/2} - P_{i-1/2}) / dx the [1 2 1] undoing leaves
  // sin^4(k dx / 2) (0.19 % at 15 cells a wavelength, k dx = 0.42); that divergence is itself
  // sin(k dx / 2) / (k dx / 2) of the true one (0.73 %): within 0.3 % and 1.2 % of a w.
  double worst_discrete = 0.0, worst_true = 0.0;
  for (int c = 2; c < geometry.columns - 2; ++c) {
    const double x = (c + 0.5) * 2.0;
    const double discrete = -(flux_at((c + 1) * 2.0) - flux_at(c * 2.0)) / 2.0;
    worst_discrete = std::max(worst_discrete, std::abs(rate(c, 3) - discrete));
    worst_true = std::max(worst_true, std::abs(rate(c, 3) - kAmplitude_m * kOmega * std::sin(kWavenumber * x - kOmega * t)));
  }
  EXPECT_LT(worst_discrete, 0.003 * kAmplitude_m * kOmega);
  EXPECT_LT(worst_true, 0.012 * kAmplitude_m * kOmega);

  // Land and walls hold no water to rise; a porous cell rises by the divergence over its porosity.
  grid.land(10, 3) = kLandCell;
  grid.porosity(20, 3) = 0.0f;
  grid.porosity(30, 3) = 0.4f;
  const Raster<float> with_structures = surface_elevation_rate(grid, p, q);
  EXPECT_EQ(with_structures(10, 3), 0.0f);
  EXPECT_EQ(with_structures(20, 3), 0.0f);
  EXPECT_NEAR(with_structures(30, 3), rate(30, 3) / 0.4, 1e-6);
}

TEST(TimeInterpolation, TheHermiteBasisJoinsValuesAndRates) {
  for (double f : {0.0, 0.25, 0.5, 1.0}) {
    const HermiteWeights h = hermite_weights(f);
    EXPECT_NEAR(h.from + h.to, 1.0, 1e-15);  // a constant stays constant
    // A straight line eta = f (rates 1 per interval) is reproduced with its slope.
    EXPECT_NEAR(h.to + h.from_rate + h.to_rate, f, 1e-15);
    EXPECT_NEAR(h.d_to + h.d_from_rate + h.d_to_rate, 1.0, 1e-15);
  }
  EXPECT_EQ(hermite_weights(0.0).from, 1.0);
  EXPECT_EQ(hermite_weights(1.0).to, 1.0);
  EXPECT_EQ(hermite_weights(0.0).d_from_rate, 1.0);
  EXPECT_EQ(hermite_weights(1.0).d_to_rate, 1.0);
}

// Heights a host reads at 120 Hz in lockstep from a real sequence (the sequence writer's half
// floats, the engine's decode): their vertical acceleration against the wave's a w^2.
struct HostSeries {
  double largest_acceleration_m_s2 = 0.0;  // max |second difference| / dt^2
  double largest_velocity_error_m_s = 0.0; // max |vertical velocity - a w sin(k x - w t)|
};

HostSeries host_series(const fs::path& folder, bool without_rates) {
  StreamingOptions options;
  options.plan = PlanKind::kFrameOrder;
  options.deep_water = DeepWaterChoice::kNone;
  options.lockstep = true;
  StreamingEngine engine(folder, options);
  const double x = 41.0, y = 21.0, dt = 1.0 / 120.0;
  std::vector<double> heights;
  HostSeries series;
  for (int n = 0; n <= 8 * 120; ++n) {
    const double t = n * dt;
    engine.advance_to(t);
    SurfaceSnapshot snapshot = engine.snapshot();
    if (without_rates) {
      // The same keyframes without their rates: the straight lines the runtime drew before.
      for (auto* keyframe : {&snapshot.harbour_from, &snapshot.harbour_to}) {
        auto copy = std::make_shared<HarbourKeyframe>(**keyframe);
        copy->surface_elevation_rate_m_s = Raster<float>();
        *keyframe = copy;
      }
    }
    const SurfaceSampler sampler(snapshot);
    const SurfaceState state = sampler.state(x, y);
    heights.push_back(state.surface_elevation_m);
    series.largest_velocity_error_m_s = std::max(
        series.largest_velocity_error_m_s,
        std::abs(state.vertical_velocity_m_s - kAmplitude_m * kOmega * std::sin(kWavenumber * x - kOmega * t)));
  }
  for (std::size_t i = 1; i + 1 < heights.size(); ++i)
    series.largest_acceleration_m_s2 =
        std::max(series.largest_acceleration_m_s2, std::abs(heights[i + 1] - 2.0 * heights[i] + heights[i - 1]) / (dt * dt));
  return series;
}

TEST(TimeInterpolation, AHostSeesTheWavesAccelerationNotASpikeAtEveryKeyframe) {
  const fs::path folder = scratch_folder();
  const std::vector<PlaneWave> wave = {{kAmplitude_m, kWavenumber, 0.0, kOmega, 0.0}};
  write_wave_sequence(folder, wave_geometry(40, 20, 2.0), wave, 24, kFrameInterval_s);
  const double wave_acceleration = kAmplitude_m * kOmega * kOmega;  // 0.33 m/s^2

  const HostSeries hermite = host_series(folder, false);
  // The cubic's second derivative is linear within an interval and jumps at the keyframes by
  // O((w T)^2 / 12) of a w^2 (2 % at 12 keyframes a period); a quarter leaves room for the rates'
  // half-float fluxes. Linear joins put the change of slope in one 1/120 s step instead.
  EXPECT_LT(hermite.largest_acceleration_m_s2, 1.25 * wave_acceleration);
  EXPECT_GT(hermite.largest_acceleration_m_s2, 0.75 * wave_acceleration);
  // The vertical velocity is the wave's (within 5 % of a w: the divergence of half floats).
  EXPECT_LT(hermite.largest_velocity_error_m_s, 0.05 * kAmplitude_m * kOmega);

  const HostSeries linear = host_series(folder, true);
  EXPECT_GT(linear.largest_acceleration_m_s2, 10.0 * wave_acceleration) << "the test must see what linear joins do";
  std::printf("max |d2 eta/dt2| at 120 Hz: Hermite %.3f m/s^2, linear %.3f m/s^2, the wave's a w^2 %.3f m/s^2\n",
              hermite.largest_acceleration_m_s2, linear.largest_acceleration_m_s2, wave_acceleration);
}

}  // namespace
}  // namespace nearshore::runtime
