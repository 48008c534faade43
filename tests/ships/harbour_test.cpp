// Ships in a harbour (issue 42): structures and land as solid obstacles. A tug steered at a
// breakwater laid at 30 deg to the grid stops at its face, along the face's true normal (not the
// cells' staircase), and the fleet names the breakwater; a ship's bow wave passing a quay is
// doubled at the wall, as a perfectly reflecting vertical wall does in linear theory (the method
// of images); the obstacle field itself against its analytic distance.
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "nearshore/ships/dispersive_wake.hpp"
#include "nearshore/ships/generic_hulls.hpp"
#include "nearshore/ships/harbour_obstacles.hpp"
#include "nearshore/ships/ship_fleet.hpp"
#include "ships_test_support.hpp"

namespace nearshore::ships {
namespace {

constexpr double kHarbourCellM = 4.0;

// A 384 m x 384 m basin of 4 m cells, 10 m deep, with the structure cells `inside(x, y)` says.
template <class Inside>
std::shared_ptr<const runtime::HarbourSite> basin_with_structure(Inside inside, float porosity) {
  GridGeometry geometry;
  geometry.columns = 96;
  geometry.rows = 96;
  geometry.spacing_m = kHarbourCellM;
  auto site = std::make_shared<runtime::HarbourSite>();
  site->harbour = HarbourGrid::open_water(geometry, 10.0f);
  for (int j = 0; j < geometry.rows; ++j)
    for (int i = 0; i < geometry.columns; ++i)
      if (inside((i + 0.5) * kHarbourCellM, (j + 0.5) * kHarbourCellM)) site->harbour.porosity(i, j) = porosity;
  site->width_m = geometry.width_m();
  site->height_m = geometry.height_m();
  return site;
}

// The breakwater: a 12 m wide strip whose centreline runs through (192, 250) m at 30 deg north of
// east; its southern face has the outward normal -n, n = (-sin 30, cos 30).
const Eigen::Vector2d kBreakwaterCentre(192.0, 250.0);
const Eigen::Vector2d kBreakwaterNormal(-0.5, std::sqrt(3.0) / 2.0);
constexpr double kBreakwaterHalfWidthM = 6.0;

bool in_breakwater(double x, double y) {
  return std::abs((Eigen::Vector2d(x, y) - kBreakwaterCentre).dot(kBreakwaterNormal)) <= kBreakwaterHalfWidthM;
}

// Measured: distance error 0.82 m, normal error 2.5 deg (the smoothed indicator's gradient, the
// normal before the line fit, gave 7.7 deg).
TEST(HarbourObstacles, TheFieldFindsAStraightFaceAtThirtyDegreesAndItsNormalOffTheStaircase) {
  const auto site = basin_with_structure(in_breakwater, 0.4f);
  const HarbourObstacles obstacles(site->harbour);
  ASSERT_EQ(obstacles.structures().size(), 1u);
  EXPECT_FALSE(obstacles.structures()[0].wall);
  EXPECT_NEAR(obstacles.structures()[0].porosity, 0.4, 1e-6);
  // Along the southern face, 1-3 m off it in the water: the distance within a quarter cell of the
  // true one (the cells' centres decide which are solid, so the face is only known to a cell's
  // resolution; the smoothed field puts it on the line, not on the staircase), the normal within
  // 5 deg of the face's true outward normal (the staircase would give 0 or 90 deg, 30 deg off).
  double worst_distance = 0.0, worst_angle_deg = 0.0;
  const Eigen::Vector2d along(kBreakwaterNormal.y(), -kBreakwaterNormal.x());
  for (double s = -60.0; s <= 60.0; s += 1.7)
    for (double off : {1.0, 2.0, 3.0}) {
      const Eigen::Vector2d p = kBreakwaterCentre + s * along - (kBreakwaterHalfWidthM + off) * kBreakwaterNormal;
      const ObstacleSample o = obstacles.sample(p.x(), p.y());
      worst_distance = std::max(worst_distance, std::abs(o.signed_distance_m - off));
      worst_angle_deg = std::max(worst_angle_deg, std::acos(std::clamp(o.normal.dot(-kBreakwaterNormal), -1.0, 1.0)) * 180 / std::numbers::pi);
      EXPECT_EQ(o.structure, 1);
    }
  std::printf("face at 30 deg: distance error <= %.2f m, normal error <= %.2f deg (4 m cells)\n", worst_distance, worst_angle_deg);
  EXPECT_LT(worst_distance, 0.25 * kHarbourCellM);
  EXPECT_LT(worst_angle_deg, 5.0);
  // Inside the strip the field is negative (its depth there is smoothed: 1.5 cells wide each side).
  EXPECT_LT(obstacles.signed_distance_m(kBreakwaterCentre.x(), kBreakwaterCentre.y()), -1.5);
}

// Measured: the tug strikes at 3.00 m/s (engine stopped), gets 0.40 m past the face, and with the
// near-plastic contact (ship_body.cpp: e = 0, Pedersen & Zhang 1998) is at 0.012 m/s after 60 s,
// heading 328.2 deg: the impact at the bow, 2 deg off the hull's axis (the fitted normal's error
// there), leaves it a yaw of 0.002 rad/s that the yaw damping takes tens of seconds to stop. With
// the earlier restitution 0.2 it rebounded at 0.6 m/s and was 19 m off after 60 s.
TEST(HarbourObstacles, ATugSteeredAtABreakwaterStopsAtItsFaceAndTheFleetNamesIt) {
  ShipFleet fleet;
  fleet.set_site(basin_with_structure(in_breakwater, 0.4f));
  ShipDefinition tug;
  tug.name = "Tug 7";
  tug.hull = harbour_tug();
  tug.loading.draft_m = 3.0;
  tug.hull_points = 800;
  tug.bow_wave_options.cells = 64;
  // 60 m south of the face, heading straight at it (along n: compass 330 deg), 3 m/s ordered.
  const Eigen::Vector2d start = kBreakwaterCentre - (kBreakwaterHalfWidthM + 60.0) * kBreakwaterNormal;
  tug.x_m = start.x();
  tug.y_m = start.y();
  tug.heading_deg = 330.0;
  tug.initial_speed_m_s = 3.0;
  tug.orders.speed_m_s = 3.0;
  // The contact mechanics alone: with squat and the shallow-water resistance (10 m of water, Fnh
  // 0.3) the tug met the face at 2.91 m/s trimmed 0.4 deg by the bow, and the yaw the strike
  // left turned it to 324.0 deg after 60 s (measured before issue 42's loading and speed-order
  // changes; without them it is now 328.2 deg).
  tug.restricted_water = false;
  fleet.add_ship(tug);
  std::vector<ContactEvent> contacts;
  std::vector<std::string> events;
  double deepest_m = -1e9;  // how far the hull ever got past the face (m, > 0 inside)
  double closest_end_m = 0.0;  // and where its closest point ends (m, < 0: short of the face)
  const double frame = 1.0 / 30;
  for (int k = 0; k < 60 * 30; ++k) {
    fleet.step(nullptr, frame);
    for (auto& c : fleet.take_contacts()) contacts.push_back(c);
    for (auto& e : fleet.take_events()) events.push_back(e);
    closest_end_m = -1e9;
    for (const Eigen::Vector3d& p : fleet.ship(0).body().world_points_m())
      if (p.z() < 2.5) {
        const double past = (p.head<2>() - kBreakwaterCentre).dot(kBreakwaterNormal) + kBreakwaterHalfWidthM;
        deepest_m = std::max(deepest_m, past);
        closest_end_m = std::max(closest_end_m, past);
      }
  }
  const ShipState& s = fleet.ship(0).body().state();
  std::printf("%s\nafter 60 s: speed %.3f m/s, deepest hull point %.2f m past the face, heading %.1f deg\n",
              events.empty() ? "(no event)" : events.front().c_str(), s.velocity_m_s.head<2>().norm(), deepest_m,
              s.heading_deg());
  ASSERT_FALSE(contacts.empty());
  const ContactEvent& c = contacts.front();
  EXPECT_TRUE(c.began);
  EXPECT_EQ(c.ship, "Tug 7");
  EXPECT_EQ(c.structure, 1);
  EXPECT_FALSE(c.wall);
  EXPECT_NEAR(c.porosity, 0.4, 1e-6);
  EXPECT_NEAR(c.closing_speed_m_s, 3.0, 0.5);  // it met the face at its ordered speed
  EXPECT_LT(std::acos(std::clamp(c.normal.dot(-kBreakwaterNormal), -1.0, 1.0)) * 180 / std::numbers::pi, 5.0);
  ASSERT_FALSE(events.empty());
  EXPECT_NE(events.front().find("struck structure 1 (a rubble-mound breakwater, porosity 0.40"), std::string::npos)
      << events.front();
  // It met the face at 3 m/s, above the berthing speeds (0.5 m/s): a collision, engine stopped.
  EXPECT_NE(events.front().find("engine stopped"), std::string::npos) << events.front();
  // Stopped at the face: no hull point ever more than a quarter cell past the line (the field's
  // placement of the face, tested above) plus 0.5 m of compression at the impact; at rest within
  // a few metres of the face after 60 s (the contact is damped: no bounce back across the basin),
  // not aground, its heading within 5 deg of the approach (pushed back along the true normal).
  EXPECT_LT(deepest_m, 0.25 * kHarbourCellM + 0.5);
  EXPECT_GT(closest_end_m, -5.0);
  EXPECT_LT(s.velocity_m_s.head<2>().norm(), 0.05);
  EXPECT_FALSE(fleet.ship(0).status().aground);
  EXPECT_NEAR(s.heading_deg(), 330.0, 5.0);
}

// The same face at every angle from 0 to 90 deg in steps of 7.5 deg, also on the structure's far
// (northern) side: the line fit is no property of 30 deg. A strip 12 m wide (3 cells) is thin enough
// that the far side's edges lie within the fit's radius, which the fit must leave out.
TEST(HarbourObstacles, TheFittedNormalHoldsAtEveryAngleOnBothFaces) {
  // The centreline is moved off the cell centres' lattice by a fraction of a cell, so that no centre
  // lies exactly on a face at 0 or 90 deg (where rounding would put a one-cell step in the face).
  const Eigen::Vector2d centre = kBreakwaterCentre + Eigen::Vector2d(0.37, 0.21);
  double worst_angle_deg = 0.0, worst_at_deg = 0.0;
  for (double angle_deg = 0.0; angle_deg <= 90.0; angle_deg += 7.5) {
    const double a = angle_deg * std::numbers::pi / 180.0;
    const Eigen::Vector2d normal(-std::sin(a), std::cos(a)), along(std::cos(a), std::sin(a));
    const auto site = basin_with_structure(
        [&](double x, double y) {
          return std::abs((Eigen::Vector2d(x, y) - centre).dot(normal)) <= kBreakwaterHalfWidthM;
        },
        0.4f);
    const HarbourObstacles obstacles(site->harbour);
    for (double side : {-1.0, 1.0})
      for (double s = -60.0; s <= 60.0; s += 1.7)
        for (double off : {1.0, 2.0, 3.0}) {
          const Eigen::Vector2d p = centre + s * along + side * (kBreakwaterHalfWidthM + off) * normal;
          const ObstacleSample o = obstacles.sample(p.x(), p.y());
          const double error_deg =
              std::acos(std::clamp(o.normal.dot(side * normal), -1.0, 1.0)) * 180 / std::numbers::pi;
          if (error_deg > worst_angle_deg) {
            worst_angle_deg = error_deg;
            worst_at_deg = angle_deg;
          }
        }
  }
  std::printf("faces at 0-90 deg, both sides: normal error <= %.2f deg (at %.1f deg)\n", worst_angle_deg, worst_at_deg);
  // Measured 5.1 deg worst, at 7.5 deg (and 82.5), under 4 deg at every other angle. A face that
  // close to an axis steps one cell every 7.6 cells, so the fit's window (radius 4.5 cells) sees
  // one step or none, and the line's direction is known only to about atan(0.5 / 4.5) = 6.3 deg;
  // the staircase itself would be 7.5 deg off there, and 45 deg off at 45 deg.
  EXPECT_LT(worst_angle_deg, 6.3);
}

TEST(HarbourObstacles, AShipPlacedOnABreakwaterIsRefusedNamingIt) {
  ShipFleet fleet;
  fleet.set_site(basin_with_structure(in_breakwater, 0.4f));
  ShipDefinition tug;
  tug.name = "Misplaced";
  tug.hull = harbour_tug();
  tug.loading.draft_m = 3.0;
  tug.hull_points = 400;
  tug.x_m = kBreakwaterCentre.x();
  tug.y_m = kBreakwaterCentre.y();
  const std::string message = testing::error_of([&] { fleet.add_ship(tug); });
  EXPECT_NE(message.find("Misplaced"), std::string::npos) << message;
  EXPECT_NE(message.find("structure 1"), std::string::npos) << message;
}

// The largest |eta_bow| over the bow-wave cells whose centres lie between y0 and y1, within
// +-length of the ship's x.
double largest_bow_wave_between(const BowWave& wave, double x_ship, double length, double y0, double y1) {
  const BowWaveField f = wave.field();
  double largest = 0.0;
  for (int j = 0; j < f.rows; ++j)
    for (int i = 0; i < f.columns; ++i) {
      const double x = f.origin_x_m + (i + 0.5) * f.spacing_m, y = f.origin_y_m + (j + 0.5) * f.spacing_m;
      if (y < y0 || y > y1 || std::abs(x - x_ship) > length) continue;
      largest = std::max(largest, std::abs(static_cast<double>((*f.heights_m)[static_cast<std::size_t>(j) * f.columns + i])));
    }
  return largest;
}

// The default tug sailing east at 5 m/s from (x_m, y_m), ordered to hold it (the runs along a
// quay and a breakwater).
ShipDefinition tug_sailing_east(std::string name, double x_m, double y_m, int bow_wave_cells) {
  ShipDefinition tug;
  tug.name = std::move(name);
  tug.hull = harbour_tug();
  tug.loading.draft_m = 3.0;
  tug.hull_points = 800;
  tug.bow_wave_options.cells = bow_wave_cells;
  tug.x_m = x_m;
  tug.y_m = y_m;
  tug.heading_deg = 90.0;
  tug.initial_speed_m_s = 5.0;
  tug.orders.speed_m_s = 5.0;
  return tug;
}

// The largest drawn |eta| of the dispersive layer over its nodes between x0 and x1, y0 and y1.
double largest_kelvin_wave_between(const DispersiveWake& wake, double x0, double x1, double y0, double y1) {
  double largest = 0.0;
  for (int j = 0; j < wake.cells(); ++j)
    for (int i = 0; i < wake.cells(); ++i) {
      const double x = static_cast<double>(wake.origin_i() + i) * wake.spacing_m();
      const double y = static_cast<double>(wake.origin_j() + j) * wake.spacing_m();
      if (x < x0 || x > x1 || y < y0 || y > y1) continue;
      largest = std::max(largest, std::abs(wake.elevation_m(x, y)));
    }
  return largest;
}

TEST(HarbourObstacles, TheKelvinWakeStopsAtABreakwaterAndDoesNotCrossIt) {
  // A 12 m rubble-mound breakwater (porosity 0.4) along y = 220-232 m with open water beyond it; a
  // tug sails east at 5 m/s, its centreline 20 m off the south face, over 10 m: Fr_d 0.50, so the
  // fleet shows the dispersive layer. After 20 s its Kelvin wake fills the window astern; the
  // layer's largest wave beyond the breakwater (y 236-270 m, abreast of and astern of the hull) is
  // compared with the same window in open water (no breakwater). Linear waves cross nothing
  // solid: the layer holds the nodes inside the structure at rest, so what lies beyond is what
  // leaks round the mask in the spectral step, asserted below 5 % of the open-water waves there;
  // inside the breakwater the drawn height is 0. Seaward of the face the wake is still there
  // (over 40 % of open water's: the hold is a soft face, not a wall's doubling, header).
  constexpr double kFaceM = 220.0, kBackM = 232.0;
  auto run = [&](bool breakwater) {
    ShipFleet fleet;
    fleet.set_site(basin_with_structure([&](double, double y) { return breakwater && y > kFaceM && y < kBackM; }, 0.4f));
    const ShipDefinition tug =
        tug_sailing_east(breakwater ? "Along the breakwater" : "In open water", 60.0, kFaceM - 20.0, 64);
    fleet.add_ship(tug);
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < 20 * 30; ++k) fleet.step(nullptr, 1.0 / 30);
    std::printf("%s: %.2f ms a frame (20 s at 30 Hz, this test's build)\n", tug.name.c_str(),
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / 600.0);
    const Ship& ship = fleet.ship(0);
    EXPECT_NE(ship.dispersive_wake(), nullptr);
    EXPECT_GE(ship.dispersive_weight(), 0.5) << "the fleet shows the dispersive layer";
    const DispersiveWake& wake = *ship.dispersive_wake();
    const double x = ship.body().state().position_m.x();
    const double beyond = largest_kelvin_wave_between(wake, x - 80.0, x + 12.0, kBackM + 4.0, kBackM + 38.0);
    const double seaward = largest_kelvin_wave_between(wake, x - 80.0, x + 12.0, kFaceM - 8.0, kFaceM - 1.0);
    const double inside = largest_kelvin_wave_between(wake, x - 80.0, x + 12.0, kFaceM + 2.0, kBackM - 2.0);
    return std::make_tuple(beyond, seaward, inside, ship.body().state().position_m.y());
  };
  const auto [beyond_bw, seaward_bw, inside_bw, y_bw] = run(true);
  const auto [beyond_open, seaward_open, inside_open, y_open] = run(false);
  std::printf("Kelvin wake beyond the breakwater %.4f m (open water %.4f m, ratio %.3f); seaward of the face %.4f m "
              "(open %.4f m, ratio %.2f); inside the breakwater %.4f m (open %.4f m); track y %.2f / %.2f m\n",
              beyond_bw, beyond_open, beyond_bw / beyond_open, seaward_bw, seaward_open, seaward_bw / seaward_open,
              inside_bw, inside_open, y_bw, y_open);
  EXPECT_GT(beyond_open, 0.01);  // open water: the wake is there
  EXPECT_LT(beyond_bw, 0.05 * beyond_open);
  EXPECT_EQ(inside_bw, 0.0);
  EXPECT_GT(seaward_bw, 0.4 * seaward_open);
}

TEST(HarbourObstacles, ABowWaveIsDoubledAtAQuayAsAReflectingWallDoes) {
  // A quay wall (porosity 0) filling y > 220 m; a tug sails east along it at 5 m/s, its centreline
  // 14 m off the face (a 9.5 m gap to its side). The same run in open water is the reference.
  constexpr double kFaceM = 220.0;
  auto run = [&](bool quay) {
    ShipFleet fleet;
    fleet.set_site(basin_with_structure([&](double, double y) { return quay && y > kFaceM; }, 0.0f));
    ShipDefinition tug = tug_sailing_east(quay ? "Along the quay" : "In open water", 80.0, kFaceM - 14.0, 128);
    // The shallow-water grid's reflection: at 5 m/s the fleet would show the dispersive layer, which
    // stops its waves at structures but does not reflect them (dispersive_wake.hpp).
    tug.dispersive_wake = false;
    fleet.add_ship(tug);
    for (int k = 0; k < 15 * 30; ++k) fleet.step(nullptr, 1.0 / 30);
    const Ship& ship = fleet.ship(0);
    const double x = ship.body().state().position_m.x();
    // The first bow-wave cells seaward of the face (within 1.5 m of it), abeam of the hull.
    const double at_face = largest_bow_wave_between(*ship.bow_wave(), x, 24.0, kFaceM - 1.5, kFaceM);
    const double inside = largest_bow_wave_between(*ship.bow_wave(), x, 24.0, kFaceM + 2.0, kFaceM + 20.0);
    return std::make_tuple(at_face, inside, ship.body().state().position_m.y());
  };
  const auto [with_quay, inside_quay, y_quay] = run(true);
  const auto [open_water, inside_open, y_open] = run(false);
  const double ratio = with_quay / open_water;
  std::printf("bow wave 0-1.5 m off the face: %.4f m at the quay, %.4f m in open water (ratio %.2f); inside the "
              "quay %.4f m; track y %.2f / %.2f m\n",
              with_quay, open_water, ratio, inside_quay, y_quay, y_open);
  // Linear theory: a vertical wall is the mirror image of the ship (the method of images), so at
  // the wall the disturbance is twice that of one ship at the same distance; the image cells lie
  // within half a bow-wave cell (0.4 m) of the face and the scheme is nonlinear and dissipative,
  // so 2 within 25 %.
  EXPECT_GT(ratio, 1.5);
  EXPECT_LT(ratio, 2.5);
  EXPECT_EQ(inside_quay, 0.0);  // no water inside the wall
  EXPECT_GT(open_water, 0.002);
}

}  // namespace
}  // namespace nearshore::ships
