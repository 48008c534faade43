// The rigid body against hydrostatics and linear wave theory: numbers from physics, not from the code.
#include <cmath>
#include <complex>
#include <numbers>

#include <gtest/gtest.h>

#include "nearshore/ships/generic_hulls.hpp"
#include "nearshore/ships/ship_body.hpp"
#include "ships_test_support.hpp"

namespace nearshore::ships {
namespace {

constexpr double kRho = 1025.0;
using testing::kG;
// The test barge: 20 m x 8 m x 4 m, floating at 1.5 m.
constexpr double kL = 20.0, kB = 8.0, kD = 4.0, kDraft = 1.5;

struct Box {
  ShipBody body;
  ShipParticulars particulars;
};

Box floating_box(bool damped, int points = 2000) {
  const HullMesh box = box_barge(kL, kB, kD);
  HullSamples samples = sample_hull(box, points);
  HullLoading loading;
  loading.mass_kg = kRho * kL * kB * kDraft;
  ShipParticulars p = particulars_for_hull("test barge", box, samples, loading);
  if (!damped) {
    p.linear_damping_N_s_m.setZero();
    p.linear_damping_N_m_s.setZero();
    p.quadratic_drag_N_s2_m2.setZero();
    p.quadratic_drag_N_m_s2.setZero();
  }
  ShipState state;
  state.position_m = {0.0, 0.0, p.centre_of_gravity_m.z() - kDraft};  // keel at -draft
  return {ShipBody(std::move(samples), p, state), p};
}

// Mean period (s) of the upward crossings of x(t) through its mean over the record.
double mean_period_s(const std::vector<double>& t, const std::vector<double>& x) {
  double mean = 0.0;
  for (double v : x) mean += v / static_cast<double>(x.size());
  std::vector<double> crossings;
  for (std::size_t k = 1; k < x.size(); ++k)
    if (x[k - 1] < mean && x[k] >= mean)
      crossings.push_back(t[k - 1] + (mean - x[k - 1]) / (x[k] - x[k - 1]) * (t[k] - t[k - 1]));
  if (crossings.size() < 2) return 0.0;
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

TEST(ShipBody, ABoxSettlesAtTheDraftOfArchimedes) {
  Box box = floating_box(true);
  ShipState s = box.body.state();
  s.position_m.z() += 0.3;  // dropped 0.3 m high
  box.body.set_state(s);
  ShipEnvironment still;
  const double frame = 1.0 / 30.0;
  for (int k = 0; k < 90 * 30; ++k) box.body.step(still, {}, {}, frame);
  const double draft = box.particulars.centre_of_gravity_m.z() - box.body.state().position_m.z();
  const double archimedes = box.particulars.mass_kg / (kRho * kL * kB);  // m / (rho L B)
  EXPECT_NEAR(draft, archimedes, 0.01 * archimedes);
  EXPECT_NEAR(box.particulars.design_draft_m, archimedes, 0.01 * archimedes);
  std::printf("box barge draft %.5f m (Archimedes %.5f m)\n", draft, archimedes);
}

TEST(ShipBody, HeaveAndRollPeriodsFollowFromTheWaterplaneAndTheMetacentricHeight) {
  // Heave: T = 2 pi sqrt((m + a33) / (rho g L B)). Roll about G: T = 2 pi sqrt((I_xx + a44) / (m g GM)),
  // GM = KB + BM - KG = T/2 + B^2 / (12 T) - KG for a box (KG = D/2, the solid's centroid).
  Box heave = floating_box(false, 4000);
  const ShipParticulars& p = heave.particulars;
  ShipState s = heave.body.state();
  s.position_m.z() += 0.1;
  heave.body.set_state(s);
  std::vector<double> t, z;
  ShipEnvironment still;
  const double frame = 1.0 / 60.0;
  for (int k = 0; k < 20 * 60; ++k) {
    heave.body.step(still, {}, {}, frame);
    t.push_back((k + 1) * frame);
    z.push_back(heave.body.state().position_m.z());
  }
  const double heave_period = 2 * std::numbers::pi * std::sqrt((p.mass_kg + p.added_mass_kg.z()) / (kRho * kG * kL * kB));
  const double measured_heave = mean_period_s(t, z);
  EXPECT_NEAR(measured_heave, heave_period, 0.05 * heave_period);

  Box roll = floating_box(false, 4000);
  s = roll.body.state();
  s.orientation = orientation_from_euler(0.0, 0.0, 3.0 * std::numbers::pi / 180.0);
  roll.body.set_state(s);
  std::vector<double> t2, phi;
  for (int k = 0; k < 30 * 60; ++k) {
    roll.body.step(still, {}, {}, frame);
    t2.push_back((k + 1) * frame);
    phi.push_back(roll.body.state().roll_rad());
  }
  const double gm = kDraft / 2 + kB * kB / (12 * kDraft) - kD / 2;
  const double ixx = p.mass_kg * (kB * kB + kD * kD) / 12.0;
  EXPECT_NEAR(p.inertia_kg_m2(0, 0), ixx, 1e-6 * ixx);
  const double roll_period = 2 * std::numbers::pi * std::sqrt((ixx + p.added_inertia_kg_m2.x()) / (p.mass_kg * kG * gm));
  const double measured_roll = mean_period_s(t2, phi);
  EXPECT_NEAR(measured_roll, roll_period, 0.05 * roll_period);
  std::printf("heave period %.4f s (analytic %.4f s), roll period %.4f s (analytic %.4f s, GM %.3f m)\n",
              measured_heave, heave_period, measured_roll, roll_period, gm);
}

// Heave amplitude / wave amplitude of the floating barge in head seas of wavelength lambda,
// measured over the last two wave periods of a 90 s run.
double heave_response(double wavelength_m, double amplitude_m, ShipParticulars* used = nullptr) {
  testing::RegularWave wave(amplitude_m, wavelength_m);
  Box box = floating_box(true);
  if (used) *used = box.particulars;
  const double frame = 1.0 / 30.0;
  const double period = 2 * std::numbers::pi / wave.angular_frequency_rad_s();
  const double end = 90.0;
  double low = 1e9, high = -1e9;
  for (int k = 0; k < static_cast<int>(end / frame); ++k) {
    const double time = k * frame;
    const runtime::SurfaceSampler water(wave.snapshot(time));
    ShipEnvironment environment;
    environment.water = &water;
    box.body.step(environment, {}, {}, frame);
    if (time > end - 2 * period) {
      low = std::min(low, box.body.state().position_m.z());
      high = std::max(high, box.body.state().position_m.z());
    }
  }
  return 0.5 * (high - low) / amplitude_m;
}

TEST(ShipBody, HeaveFollowsLongWavesAndFiltersShortOnes) {
  // The Froude-Krylov heave force on a box in head seas, pressure rho g eta under the local
  // surface integrated over the bottom: F = rho g B a integral cos(k x) dx = rho g B L a sinc(k L/2).
  // The heave response of the mass-spring-damper (m + a33, rho g L B, 5 % of critical):
  //   RAO = |sinc(k L / 2)| / |1 - r^2 + 2 i zeta r|, r = omega / omega_n.
  ShipParticulars p;
  const double long_wave = 10 * kL, short_wave = 0.4 * kL;
  const double measured_long = heave_response(long_wave, 0.5, &p);
  const double measured_short = heave_response(short_wave, 0.1);
  auto analytic = [&](double wavelength) {
    const double k = 2 * std::numbers::pi / wavelength, omega2 = kG * k;
    const double omega_n2 = kRho * kG * kL * kB / (p.mass_kg + p.added_mass_kg.z());
    const double r = std::sqrt(omega2 / omega_n2);
    const double sinc = std::sin(k * kL / 2) / (k * kL / 2);
    return std::abs(sinc) / std::abs(std::complex<double>(1 - r * r, 2 * 0.05 * r));
  };
  std::printf("heave RAO: lambda = 10 L: %.3f (analytic %.3f); lambda = 0.4 L: %.3f (analytic %.3f)\n", measured_long,
              analytic(long_wave), measured_short, analytic(short_wave));
  EXPECT_NEAR(measured_long, analytic(long_wave), 0.05 * analytic(long_wave));
  EXPECT_GT(measured_long, 0.8);  // "follows the surface"
  EXPECT_LT(measured_long, 1.25);
  EXPECT_LT(measured_short, 0.2);  // "filters them out"
}

}  // namespace
}  // namespace nearshore::ships
