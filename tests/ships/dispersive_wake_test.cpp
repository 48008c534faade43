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

}  // namespace
}  // namespace nearshore::ships
