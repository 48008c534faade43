// The dispersive wake layer (dispersive_wake.hpp) against linear wave theory: free waves at the
// phase speed of the finite-depth dispersion relation, Kelvin's 19.47 deg behind a pressure patch in
// deep water, Havelock's wider cusp at depth Froude number 0.9, and the fleet's choice of layer.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nearshore/plot/plot.hpp"
#include "nearshore/ships/dispersive_wake.hpp"
#include "nearshore/ships/generic_hulls.hpp"
#include "nearshore/ships/hull_samples.hpp"
#include "nearshore/ships/ship_fleet.hpp"
#include "ships_test_support.hpp"

namespace nearshore::ships {
namespace {

using testing::kG;
constexpr double kDeg = 180.0 / std::numbers::pi;

TEST(DispersiveWake, FreeWavesKeepTheirAmplitudeAndTravelAtTheLinearPhaseSpeed) {
  // eta = a cos(k.x - w t), phi = (g a / w) sin(k.x - w t), w^2 = g k tanh(k d): a free progressive
  // wave of linear theory. The layer rotates each mode exactly, so after many steps the only error
  // is float round-off of the transforms (about 1e-7 relative per transform, four per step).
  DispersiveWakeOptions o;
  o.cells = 64;
  o.absorbing_fraction = 0.0;  // a periodic box: nothing absorbs
  o.max_depth_m = 1e4;
  const double spacing = 1.0, side = o.cells * spacing, amplitude = 0.5;
  for (const double kd : {0.3, 1.0, 3.0, 10.0}) {
    for (const auto& [mx, my] : {std::pair{4, 0}, std::pair{3, -5}}) {
      DispersiveWake wake(spacing, o);
      const double kx = 2 * std::numbers::pi * mx / side, ky = 2 * std::numbers::pi * my / side, k = std::hypot(kx, ky);
      const double depth = kd / k, omega = std::sqrt(kG * k * std::tanh(kd));
      for (int j = 0; j < o.cells; ++j)
        for (int i = 0; i < o.cells; ++i) {
          const double phase = kx * i * spacing + ky * j * spacing;
          wake.surface_elevation_m(i, j) = static_cast<float>(amplitude * std::cos(phase));
          wake.velocity_potential_m2_s(i, j) = static_cast<float>(kG * amplitude / omega * std::sin(phase));
        }
      // 40 steps of 0.3 s: several periods, and a step far beyond any explicit scheme's CFL limit.
      const int steps = 40;
      const double dt = 0.3;
      for (int s = 0; s < steps; ++s) wake.advance(dt, depth);
      const double t = steps * dt;
      double worst = 0.0;
      for (int j = 0; j < o.cells; ++j)
        for (int i = 0; i < o.cells; ++i) {
          const double exact = amplitude * std::cos(kx * i * spacing + ky * j * spacing - omega * t);
          worst = std::max(worst, std::abs(wake.surface_elevation_m(i, j) - exact));
        }
      std::printf("free wave k d = %.1f, mode (%d, %d): phase speed %.4f m/s, max error after %.0f s = %.2g m (a = %.1f m)\n",
                  kd, mx, my, omega / k, t, worst, amplitude);
      // 160 transforms of float round-off (~1e-7 relative each, growing at most linearly, measured
      // up to 4e-5 a): 1e-4 a.
      // A phase-speed error of 1e-4 would already give 1e-4 omega t a = 6e-4 a here.
      EXPECT_LT(worst, 1e-4 * amplitude) << "k d = " << kd;
    }
  }
}

// A Gaussian pressure patch zeta = h exp(-r^2 / b^2) moved at U along +x for `seconds`, the
// window following it by whole nodes (as DispersiveWake::update does for a hull). Returns the
// state of a "ship" of length 2 b centred on the patch, for the envelope measurement.
ShipState run_pressure_patch(DispersiveWake& wake, double speed_m_s, double depth_m, double radius_m,
                             double seconds) {
  const int n = wake.cells();
  const double dx = wake.spacing_m(), dt = 1.0 / 30.0;
  const double astern = wake.options().astern_fraction * n;
  double x = 0.0;
  const double y = 0.5 * dx;  // between nodes: the pattern is symmetric about the track
  for (int step = 0; step <= static_cast<int>(seconds / dt); ++step) {
    wake.move_window(std::llround(x / dx - n / 2 - astern), -n / 2);  // centre astern of the patch
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double px = (wake.origin_i() + i) * dx - x, py = (wake.origin_j() + j) * dx - y;
        wake.pressure_head_m(i, j) = static_cast<float>(0.05 * std::exp(-(px * px + py * py) / (radius_m * radius_m)));
      }
    if (step == 0) wake.rest_in_depression();
    wake.advance(dt, depth_m);
    x += speed_m_s * dt;
  }
  ShipState state;
  state.position_m = {x - speed_m_s * dt, y, 0.0};
  return state;
}

// Havelock (1908): in depth d at depth Froude number F, a steady wave whose crests make the angle
// theta with the track has U cos(theta) = c(k), c^2 = g tanh(k d) / k; its energy travels at
// n = c_g / c of the phase speed, so in the ship's frame along the ray tan(alpha) =
// n tan(theta) / (1 - n + tan^2(theta)). The cusp is the largest alpha over theta (deep water:
// n = 1/2, tan(alpha) = 1 / sqrt(8), 19.47 deg). Solved here by bisection and a scan over theta.
double havelock_cusp_angle_deg(double froude) {
  double best = 0.0;
  for (double theta = 0.0; theta < 0.5 * std::numbers::pi - 1e-3; theta += 1e-4) {
    const double f2 = std::pow(froude * std::cos(theta), 2);  // tanh(kd) / kd = F^2 cos^2(theta)
    double lo = 1e-9, hi = 200.0;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (std::tanh(mid) / mid > f2 ? lo : hi) = mid;
    }
    const double kd = 0.5 * (lo + hi);
    const double n = 0.5 * (1.0 + 2.0 * kd / std::sinh(2.0 * kd));
    const double t = std::tan(theta);
    best = std::max(best, std::atan(n * t / (1.0 - n + t * t)));
  }
  return best * kDeg;
}

// The layer's heights as a map in metres from the patch's centre (docs/ships.md shows them).
void write_picture(const DispersiveWake& wake, const ShipState& state, const std::string& title,
                   const std::string& file) {
  const BowWaveField f = wake.field();
  Raster<float> heights(f.columns, f.rows);
  double peak = 1e-9;
  // The colour scale from the wake, not the hull's depression (which is many times higher).
  for (int j = 0; j < f.rows; ++j)
    for (int i = 0; i < f.columns; ++i) heights(i, j) = (*f.heights_m)[static_cast<std::size_t>(j) * f.columns + i];
  std::vector<float> sorted(f.heights_m->begin(), f.heights_m->end());
  for (float& v : sorted) v = std::abs(v);
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() * 995 / 1000, sorted.end());
  peak = std::max(peak, static_cast<double>(sorted[sorted.size() * 995 / 1000]));
  HeatMapStyle style;
  style.title = title;
  style.value_label = "surface elevation (m)";
  style.map = ColourMap::kDiverging;
  style.low = -peak;
  style.high = peak;
  MapAxes axes;
  axes.origin_x_m = f.origin_x_m - state.position_m.x();
  axes.origin_y_m = f.origin_y_m - state.position_m.y();
  axes.cell_size_x_m = axes.cell_size_y_m = f.spacing_m;
  axes.x_label = "along the track, from the patch or hull centre (m)";
  axes.y_label = "across (m)";
  axes.north_label = "+y";
  style.map_axes = axes;
  style.max_image_size_px = 560;
  write_png(render_heat_map(heights, style), std::filesystem::path(NEARSHORE_BINARY_DIR) / "tests" / "ships" / file);
}

TEST(DispersiveWake, APressurePatchInDeepWaterMakesKelvinsCuspAt19Point47Degrees) {
  // A patch of radius 1 m at 2.2 m/s in 1000 m of water: the transverse wave 2 pi U^2 / g = 3.1 m
  // (12 nodes of 0.25 m; k d = 2000, deep), the cusp's waves 2/3 of that (8 nodes); length Froude
  // number U / sqrt(g b) = 0.7, where the largest amplitude still lies on Kelvin's cusp (it moves
  // inside it only at larger patch Froude numbers, Rabaud & Moisy 2013). 30 s: the pattern forms
  // behind the patch at 2/3 U (the cusp's energy speed relative to it), 44 m, the whole window.
  // Tolerance 1.5 deg: the maximum per station is found to half a node (0.125 m) at 3-40 m
  // behind, i.e. within atan(0.125 / 10 m) = 0.7 deg at the fit's middle, plus the slow race of the
  // cusp against the transverse waves near the patch (measured 19.36 deg).
  DispersiveWakeOptions o;
  o.max_depth_m = 1000.0;
  const double dx = 0.25;
  DispersiveWake wake(dx, o);
  const double speed = 2.2, radius = 1.0;
  const ShipState state = run_pressure_patch(wake, speed, 1000.0, radius, 30.0);
  const WakeAngle angle = measure_wake_envelope_angle(wake, state, 2 * radius, 3.0, 1.0);
  write_picture(wake, state, "Kelvin wake: pressure patch at 2.2 m/s, deep water", "dispersive_wake_kelvin.png");
  std::printf("deep water: envelope ray %.2f deg over %d stations (r^2 %.3f, wedge %s); Kelvin 19.47 deg\n",
              angle.half_angle_deg, angle.stations, angle.r_squared, angle.wedge ? "yes" : "no");
  EXPECT_TRUE(angle.wedge);
  EXPECT_NEAR(angle.half_angle_deg, std::asin(1.0 / 3.0) * kDeg, 1.5);
}

WakeAngle patch_wake_at_froude(double froude, bool picture) {
  DispersiveWakeOptions o;
  o.max_depth_m = 1000.0;
  const double dx = 0.25, depth = 1.0, radius = 1.0;
  DispersiveWake wake(dx, o);
  const double speed = froude * std::sqrt(kG * depth);
  const ShipState state = run_pressure_patch(wake, speed, depth, radius, 30.0);
  if (picture) write_picture(wake, state, "Pressure patch at Fr_d = 0.9 over 1 m", "dispersive_wake_froude_0_9.png");
  return measure_wake_envelope_angle(wake, state, 2 * radius, 3.0, 1.0);
}

TEST(DispersiveWake, TheCuspWidensAsTheDepthFroudeNumberNearsOneAsHavelockFound) {
  // The same patch over 1 m of water. Havelock's cusp widens from 19.47 deg (deep) to 24.32 deg at
  // Fr_d = 0.8 and 34.62 deg at 0.9. The envelope ray is the line of the largest amplitude, which
  // lies on the cusp only far behind the hull (the cusp is a caustic whose amplitude decays as
  // x^(-1/3) against x^(-1/2) for the rest of the pattern, a slow race); the window holds 40 m,
  // five transverse wavelengths at 0.8 (8 m each: k d = 0.78 at 0.9, 0.98 at 0.8). Near the critical
  // speed the pattern also takes long to form (its energy moves slowly relative to the hull). So:
  // at 0.8 within 2.5 deg of Havelock (measured 22.7 vs 24.3 deg, the ray still inside the cusp);
  // at 0.9 the ray must be wider still, and the gap to Havelock (25.3 vs 34.6 deg) is reported in
  // docs/ships.md as what limits the match.
  const WakeAngle at_08 = patch_wake_at_froude(0.8, false);
  const WakeAngle at_09 = patch_wake_at_froude(0.9, true);
  std::printf("Fr_d = 0.8: envelope ray %.2f deg over %d stations (r^2 %.3f, wedge %s); Havelock %.2f deg\n",
              at_08.half_angle_deg, at_08.stations, at_08.r_squared, at_08.wedge ? "yes" : "no",
              havelock_cusp_angle_deg(0.8));
  std::printf("Fr_d = 0.9: envelope ray %.2f deg over %d stations (r^2 %.3f, wedge %s); Havelock %.2f deg; deep %.2f deg\n",
              at_09.half_angle_deg, at_09.stations, at_09.r_squared, at_09.wedge ? "yes" : "no",
              havelock_cusp_angle_deg(0.9), havelock_cusp_angle_deg(0.01));
  EXPECT_NEAR(havelock_cusp_angle_deg(0.01), std::asin(1.0 / 3.0) * kDeg, 0.01);  // the relation's deep limit
  EXPECT_TRUE(at_08.wedge);
  EXPECT_TRUE(at_09.wedge);
  EXPECT_NEAR(at_08.half_angle_deg, havelock_cusp_angle_deg(0.8), 2.5);
  EXPECT_GT(at_09.half_angle_deg, at_08.half_angle_deg + 1.0);
  EXPECT_GT(at_09.half_angle_deg, std::asin(1.0 / 3.0) * kDeg + 4.0);  // clearly wider than Kelvin's
}

// A 20 m Wigley hull sailing east under a speed order, in a fleet over a flat seabed.
ShipFleet sail_wigley(double depth_m, double speed_m_s, double seconds) {
  ShipFleet fleet;
  fleet.set_seabed(Seabed::flat(depth_m));
  ShipDefinition d;
  d.name = "Wigley";
  d.hull = wigley_hull(20, 2, 1, 2);
  d.loading.draft_m = 1.0;
  d.hull_points = 1000;
  d.heading_deg = 90.0;
  d.initial_speed_m_s = speed_m_s;
  d.orders.speed_m_s = speed_m_s;
  d.dispersive_wake = true;
  fleet.add_ship(d);
  for (int k = 0; k < static_cast<int>(seconds * 30); ++k) fleet.step(nullptr, 1.0 / 30);
  return fleet;
}

TEST(DispersiveWake, AShipInDeepWaterShowsTheDispersiveLayerAloneAndMakesAKelvinWake) {
  // Ordered to 4.5 m/s over 30 m, the hull makes about 3.7 m/s (its engine's limit): Fr_d = 0.21
  // (k d = 22 for its transverse wave: deep), length Froude number 0.26. The fleet shows the
  // dispersive layer alone, so the fleet's query is that layer's height and the displacement is
  // counted once. The hull's transverse wave is 8.7 m (22 nodes of 0.39 m).
  const ShipFleet fleet = sail_wigley(30.0, 4.5, 25.0);
  const Ship& ship = fleet.ship(0);
  ASSERT_NE(ship.dispersive_wake(), nullptr);
  EXPECT_LT(ship.depth_froude_number(), 0.7);
  EXPECT_EQ(ship.dispersive_weight(), 1.0);
  EXPECT_EQ(ship.bow_wave()->shown_weight(), 0.0);
  const ShipState& state = ship.body().state();
  double worst = 0.0, peak = 0.0;
  for (double dx = -60.0; dx <= 20.0; dx += 1.3)
    for (double dy = -30.0; dy <= 30.0; dy += 1.7) {
      const double x = state.position_m.x() + dx, y = state.position_m.y() + dy;
      const double layer = ship.dispersive_wake()->elevation_m(x, y);
      worst = std::max(worst, std::abs(fleet.bow_wave_elevation_m(x, y) - layer));
      peak = std::max(peak, std::abs(layer));
    }
  EXPECT_EQ(worst, 0.0);  // the shallow-water grid adds nothing
  EXPECT_GT(peak, 1e-3);
  EXPECT_EQ(fleet.bow_wave_fields().size(), 1u);
  const WakeAngle angle = measure_wake_envelope_angle(*ship.dispersive_wake(), state, 20.0, 1.0, 1.0);
  write_picture(*ship.dispersive_wake(), state, "Wigley 20 m at 3.7 m/s over 30 m (Fr_d = 0.21)",
                "dispersive_wake_wigley.png");
  std::printf("Wigley 20 m at %.2f m/s over 30 m: Fr_d %.3f, envelope ray %.2f deg over %d stations (r^2 %.3f, wedge %s); "
              "Kelvin 19.47 deg\n",
              state.velocity_m_s.norm(), ship.depth_froude_number(), angle.half_angle_deg, angle.stations, angle.r_squared,
              angle.wedge ? "yes" : "no");
  // A hull, not a smooth patch: its bow and stern make two wave systems whose interference puts
  // lumps of largest amplitude on either side of the cusp line (the picture), so the stations
  // scatter about the line (r^2 about 0.6 against 0.89 for the patch) and the ray is found to a
  // few degrees; the window holds only 1-3 ship lengths of wake. 4 deg and r^2 > 0.45: a wedge at
  // Kelvin's angle, not the shallow-water grid's "no wedge" (docs/ships.md, measured 21.1 deg).
  EXPECT_GT(angle.r_squared, 0.45);
  EXPECT_NEAR(angle.half_angle_deg, std::asin(1.0 / 3.0) * kDeg, 4.0);
}

TEST(DispersiveWake, AShipNearTheCriticalSpeedShowsTheShallowWaterGridAndFadesBetweenLayers) {
  // 4 m/s over 2 m: Fr_d = 0.90 > 0.8, the shallow-water grid alone.
  const ShipFleet fleet = sail_wigley(2.0, 4.0, 2.0);
  const Ship& ship = fleet.ship(0);
  EXPECT_GT(ship.depth_froude_number(), 0.8);
  EXPECT_EQ(ship.dispersive_weight(), 0.0);
  EXPECT_EQ(ship.bow_wave()->shown_weight(), 1.0);
  EXPECT_EQ(ship.dispersive_wake()->shown_weight(), 0.0);
  const ShipState& state = ship.body().state();
  for (double dx = -30.0; dx <= 10.0; dx += 2.1) {
    const double x = state.position_m.x() + dx, y = state.position_m.y() + 3.0;
    EXPECT_EQ(fleet.bow_wave_elevation_m(x, y), ship.bow_wave()->elevation_m(x, y));
  }
  // Slowing to 2 m/s (Fr_d 0.45) switches to the dispersive layer over fade_s (2 s); meanwhile the
  // two weights sum to one.
  ShipFleet slowing = sail_wigley(2.0, 4.0, 1.0);
  ShipOrders slow;
  slow.speed_m_s = 2.0;
  slowing.ship(0).set_orders(slow);
  bool faded = false;
  for (int k = 0; k < 30 * 30 && !faded; ++k) {
    slowing.step(nullptr, 1.0 / 30);
    const Ship& s = slowing.ship(0);
    EXPECT_NEAR(s.bow_wave()->shown_weight() + s.dispersive_wake()->shown_weight(), 1.0, 1e-12);
    faded = s.dispersive_weight() == 1.0;
  }
  std::printf("slowing from Fr_d 0.90: dispersive layer shown alone at Fr_d %.3f\n",
              slowing.ship(0).depth_froude_number());
  EXPECT_TRUE(faded);
  EXPECT_LT(slowing.ship(0).depth_froude_number(), 0.7);
}

// Michell's integral (Michell 1898; Wehausen 1973, "The wave resistance of ships") for the
// Wigley hull Y(x, z) = (B / 2)(1 - (2x / L)^2)(1 - (z / T)^2), evaluated here from its own formula:
//   R = (4 rho g^2 / (pi U^2)) int_0^{pi/2} |I(theta)|^2 sec^3 theta d theta,
//   I = int int dY/dx exp(k0 z sec^2 theta + i k0 x sec theta) dx dz,  k0 = g / U^2,
// separable for this hull: I = (B / 2) X Z, X = -16 i (sin(a h) - a h cos(a h)) / (L^2 a^2),
// a = k0 sec theta, h = L / 2; Z = int_{-T}^0 (1 - z^2 / T^2) e^{b z} dz, b = k0 sec^2 theta.
// `band` (optional) multiplies the integrand by what a grid of spacing dx keeps of the wave
// (kx, ky) = (a, b sin theta): the layer's smoothing cos^(2P)(kx dx / 2) cos^(2P)(ky dx / 2), squared
// (the forcing and the Lagally sum each carry it), and nothing above pi / (2 dx).
double michell_wigley_resistance_N(double length_m, double beam_m, double draft_m, double speed_m_s, double density,
                                   double band_spacing_m = 0.0, int passes = 0) {
  const double k0 = kG / (speed_m_s * speed_m_s), h = 0.5 * length_m, T = draft_m;
  auto integrand = [&](double t) {  // t = tan theta: sec^3 theta d theta = sqrt(1 + t^2) dt
    const double sec = std::sqrt(1.0 + t * t), a = k0 * sec, b = k0 * sec * sec;
    const double x_part = 16.0 * (std::sin(a * h) - a * h * std::cos(a * h)) / (length_m * length_m * a * a);
    const double e = std::exp(-b * T);
    const double z_part = (1.0 - e) / b - (2.0 / (b * b * b) - e * (T * T / b + 2.0 * T / (b * b) + 2.0 / (b * b * b))) / (T * T);
    double keep = 1.0;
    if (band_spacing_m > 0.0) {
      const double kx = a, ky = b * t / sec, cut = std::numbers::pi / (2.0 * band_spacing_m);
      if (kx >= cut || ky >= cut) return 0.0;
      const double cx = std::cos(0.5 * kx * band_spacing_m), cy = std::cos(0.5 * ky * band_spacing_m);
      keep = std::pow(cx * cx * cy * cy, 2 * passes);
    }
    const double i2 = std::pow(0.5 * beam_m * x_part * z_part, 2);
    return i2 * sec * keep;
  };
  // Simpson over t in [0, 80] (theta to 89.3 deg; the integrand falls as sec^-4 beyond the hull's
  // wavenumbers).
  const int n = 40000;
  const double t_max = 80.0, dt = t_max / n;
  double sum = integrand(0.0) + integrand(t_max);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * integrand(i * dt);
  const double integral = sum * dt / 3.0;
  return 4.0 * density * kG * kG / (std::numbers::pi * speed_m_s * speed_m_s) * integral;
}

// A hull towed along +x at `speed` from rest (a half-cosine ramp over 6 s), upright at its design
// draft in still deep water, forcing a dispersive layer by its thin-ship sources. Returns the mean
// wave resistance (N) over the last `average_s` of `seconds`.
double towed_wave_resistance_N(const HullMesh& hull, double draft_m, double speed_m_s, double seconds, double average_s,
                               const DispersiveWakeOptions& options = {}) {
  HullSamples samples = sample_hull(hull, 4000);
  HullLoading loading;
  loading.draft_m = draft_m;
  ShipParticulars particulars = particulars_for_hull("towed", hull, samples, loading);
  ShipState state;
  const double keel_z = particulars.hull_centre_m.z() - 0.5 * particulars.depth_m;
  state.position_m = {0.0, 0.0, particulars.centre_of_gravity_m.z() - (keel_z + particulars.design_draft_m)};
  const ShipState start = state;
  ShipBody body(std::move(samples), particulars, state);
  body.step(ShipEnvironment{}, ShipControls{}, ExternalLoad{}, 1e-6);  // sizes the water it saw: still, 0
  DispersiveWake wake(particulars, options);
  const double dt = 1.0 / 30.0, ramp_s = 6.0;
  double x = 0.0, force = 0.0;
  int averaged = 0;
  const int frames = static_cast<int>(seconds / dt);
  for (int f = 1; f <= frames; ++f) {
    const double t = f * dt;
    const double u = t < ramp_s ? 0.5 * speed_m_s * (1.0 - std::cos(std::numbers::pi * t / ramp_s)) : speed_m_s;
    x += u * dt;
    ShipState s = start;
    s.position_m.x() += x;
    s.velocity_m_s = {u, 0.0, 0.0};
    body.set_state(s);
    wake.update(body, nullptr, dt);
    if (t > seconds - average_s) {
      force += -wake.wave_force_N().x();
      ++averaged;
    }
  }
  return force / std::max(averaged, 1);
}

TEST(DispersiveWake, TheThinShipWaveResistanceOfTheWigleyHullIsMichellsIntegral) {
  // The ITTC Wigley hull (B / L = 0.1, T / L = 0.0625) at 20 m, towed at length Froude numbers 0.3
  // and 0.4 in deep water: the Lagally force of the layer's free waves on the hull's sources
  // against Michell's integral of the analytic hull, evaluated in this test (above). The layer's
  // window (5 lengths, 256 nodes of 0.39 m) keeps the waves below pi / (2 dx) = 4 rad/m after its
  // smoothing, so the test also gives Michell's integral over what that grid keeps ("band").
  const double length = 20.0, beam = 2.0, draft = 1.25, rho = 1025.0;
  const HullMesh hull = wigley_hull(length, beam, draft, 2.5, 81, 16);
  const double spacing = 5.0 * length / 256;
  const int passes = DispersiveWakeOptions{}.source_smoothing_passes;
  for (const double froude : {0.3, 0.4}) {
    const double speed = froude * std::sqrt(kG * length);
    const double simulated = towed_wave_resistance_N(hull, draft, speed, 25.0, 7.5);
    const double michell = michell_wigley_resistance_N(length, beam, draft, speed, rho);
    const double band = michell_wigley_resistance_N(length, beam, draft, speed, rho, spacing, passes);
    std::printf("Wigley 20 m, Fn %.2f (%.2f m/s): layer %.1f N, Michell %.1f N (over the grid's band %.1f N): %+.1f %% "
                "(%+.1f %% of the band)\n",
                froude, speed, simulated, michell, band, 100 * (simulated / michell - 1), 100 * (simulated / band - 1));
    // Against the integral over the grid's band: the layer's own discretisation (8 depth levels,
    // the sources' splat, the start-up's residual oscillation over the last 7.5 s), measured 2.7 %
    // and 0.3 %: within 5 %. Against the whole integral, the band's loss adds Michell's integrand
    // beyond pi / (2 dx) (2.2 % and 1.9 %): within 8 %.
    EXPECT_NEAR(simulated, band, 0.05 * band);
    EXPECT_NEAR(simulated, michell, 0.08 * michell);
  }
}

// The default tug (the C API's: 24 x 9 m, draft 3 m, every ShipDefinition default) sailing east at
// `speed` over a flat 10 m bed for `seconds`; `breaking` false turns the layer's breaking off.
ShipFleet sail_default_tug(double speed_m_s, double seconds, bool breaking) {
  ShipFleet fleet;
  fleet.set_seabed(Seabed::flat(10.0));
  ShipDefinition d;
  d.name = "Tug";
  d.hull = harbour_tug();
  d.loading.draft_m = 3.0;
  d.heading_deg = 90.0;
  d.initial_speed_m_s = speed_m_s;
  d.orders.speed_m_s = speed_m_s;
  if (!breaking) d.dispersive_wake_options.breaking_slope = 0.0;
  fleet.add_ship(d);
  for (int k = 0; k < static_cast<int>(seconds * 30); ++k) fleet.step(nullptr, 1.0 / 30);
  return fleet;
}

// The highest crest and the deepest trough of the drawn ship waves (the fleet's sum of its layers)
// outside the hull: points further than half the beam plus 2 m from the hull's centreline segment.
struct WaveExtremes {
  double crest = 0.0, trough = 0.0;
  Eigen::Vector2d crest_at = Eigen::Vector2d::Zero(), trough_at = Eigen::Vector2d::Zero();  ///< from G: ahead, to port
};
WaveExtremes drawn_wave_extremes_m(const ShipFleet& fleet, double length_m, double beam_m) {
  const ShipState& state = fleet.ship(0).body().state();
  const Eigen::Vector3d ahead3 = state.orientation * Eigen::Vector3d::UnitX();
  const Eigen::Vector2d ahead = ahead3.head<2>().normalized(), g = state.position_m.head<2>();
  const Eigen::Vector2d port(-ahead.y(), ahead.x());
  WaveExtremes e;
  for (double dx = -100.0; dx <= 40.0; dx += 0.2)
    for (double dy = -60.0; dy <= 60.0; dy += 0.2) {
      const Eigen::Vector2d p = g + Eigen::Vector2d(dx, dy);
      const double along = std::clamp((p - g).dot(ahead), -0.5 * length_m, 0.5 * length_m);
      if ((p - (g + along * ahead)).norm() < 0.5 * beam_m + 2.0) continue;
      const double eta = fleet.bow_wave_elevation_m(p.x(), p.y());
      const Eigen::Vector2d at((p - g).dot(ahead), (p - g).dot(port));
      if (eta > e.crest) e.crest = eta, e.crest_at = at;
      if (eta < e.trough) e.trough = eta, e.trough_at = at;
    }
  return e;
}

TEST(DispersiveWake, TheDefaultTugsDrawnWakeStaysUnderTheBreakingLimit) {
  // Michell's limit H <= 0.142 lambda for the tug's transverse wave lambda = 2 pi U^2 / g (deep
  // water; over 10 m it is longer, so the limit is the stricter one). H is taken as the highest crest
  // minus the deepest trough anywhere outside the hull: larger than any one wave's height. With the
  // pressure-patch forcing the same tug at 3 m/s drew a +4.55 m crest (docs/ships.md).
  for (const double speed : {1.5, 3.0, 5.0}) {
    const double lambda = 2 * std::numbers::pi * speed * speed / kG, limit = 0.142 * lambda;
    const ShipFleet fleet = sail_default_tug(speed, 10.0, true);
    const Ship& ship = fleet.ship(0);
    const WaveExtremes broken = drawn_wave_extremes_m(fleet, 24.0, 9.0);
    const ShipFleet unbroken = sail_default_tug(speed, 10.0, false);
    const WaveExtremes linear = drawn_wave_extremes_m(unbroken, 24.0, 9.0);
    std::printf("tug at %.1f m/s (Fr_d %.2f, dispersive weight %.2f, %zu breaking points, %zu crest foam decals): crest "
                "%+.3f m, trough %+.3f m, H %.3f m against 0.142 lambda = %.3f m; without breaking %+.3f m at (%.1f, %.1f) "
                "/ %+.3f m at (%.1f, %.1f) m from G (ahead, to port)\n",
                speed, ship.depth_froude_number(), ship.dispersive_weight(),
                ship.dispersive_wake() ? ship.dispersive_wake()->breaking_nodes().size() : 0u, ship.crest_foam().decals().size(),
                broken.crest, broken.trough, broken.crest - broken.trough, limit, linear.crest, linear.crest_at.x(),
                linear.crest_at.y(), linear.trough, linear.trough_at.x(), linear.trough_at.y());
    EXPECT_LT(broken.crest - broken.trough, limit);
  }
  // At 3 and 5 m/s the Kelvin waves are resolved (5.8 m and 16 m on 0.47 m nodes): the dispersive
  // layer is shown; at 1.5 m/s (1.4 m, 3 nodes) the shallow-water grid is.
  EXPECT_EQ(sail_default_tug(1.5, 3.0, true).ship(0).dispersive_weight(), 0.0);
  EXPECT_EQ(sail_default_tug(3.0, 3.0, true).ship(0).dispersive_weight(), 1.0);
}

}  // namespace
}  // namespace nearshore::ships
