// Ships together: grounding on the demo harbour's beach, ship-ship repulsion, stern-wake decals,
// scenario files.
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "nearshore/bathymetry/demo_harbour.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/ships/generic_hulls.hpp"
#include "nearshore/ships/scenario.hpp"
#include "nearshore/ships/ship_fleet.hpp"
#include "nearshore/ships/restricted_water.hpp"
#include "ships_test_support.hpp"

namespace nearshore::ships {
namespace {

using testing::scratch_folder;
using testing::error_of;

// The demo harbour (bathymetry/demo_harbour.hpp) as a runtime site: its analytic depth at the
// cell centres of an 8 m grid, land where the depth is negative.
std::shared_ptr<const runtime::HarbourSite> demo_site() {
  const bathymetry::DemoHarbourOptions options;
  GridGeometry geometry;
  geometry.spacing_m = 8.0;
  geometry.columns = static_cast<int>(options.width_m / geometry.spacing_m);
  geometry.rows = static_cast<int>(options.height_m / geometry.spacing_m);
  auto site = std::make_shared<runtime::HarbourSite>();
  site->harbour = HarbourGrid::open_water(geometry, 0.0f);
  for (int j = 0; j < geometry.rows; ++j)
    for (int i = 0; i < geometry.columns; ++i) {
      const double d = bathymetry::demo_harbour_depth_m(options, (i + 0.5) * geometry.spacing_m, (j + 0.5) * geometry.spacing_m);
      site->harbour.still_water_depth_m(i, j) = static_cast<float>(d);
      site->harbour.land(i, j) = d < 0.0 ? 1 : 0;
    }
  site->width_m = geometry.width_m();
  site->height_m = geometry.height_m();
  return site;
}

// Issue 44 through the C++ API: every out-of-range field of a ShipDefinition, its orders and the
// fleet's step is a nearshore::Error naming the ship, the field and its range, before anything is
// built (a 1e9 m hull is refused before it is cut into pieces), and the fleet goes on.
TEST(ShipFleet, OutOfRangeDefinitionsOrdersAndStepsAreRefusedNamingTheField) {
  ShipFleet fleet;
  fleet.set_seabed(Seabed::flat(20.0));
  auto tug = [] {
    ShipDefinition d;
    d.name = "Range";
    d.hull = harbour_tug();
    d.loading.draft_m = 3.0;
    d.hull_points = 400;
    d.bow_wave_options.cells = 32;
    return d;
  };
  struct Case {
    const char* field;
    std::function<void(ShipDefinition&)> edit;
  };
  const std::vector<Case> cases = {
      {"initial_speed_m_s", [](ShipDefinition& d) { d.initial_speed_m_s = 1e308; }},
      {"initial_speed_m_s", [](ShipDefinition& d) { d.initial_speed_m_s = 1e8; }},
      {"initial_speed_m_s", [](ShipDefinition& d) { d.initial_speed_m_s = std::nan(""); }},
      {"mass_kg", [](ShipDefinition& d) { d.loading.mass_kg = 1e-300; }},
      {"mass_kg", [](ShipDefinition& d) { d.loading.mass_kg = 2.0; }},  // floats the tug on 0.03 mm
      {"draft_m", [](ShipDefinition& d) { d.loading.draft_m = -1.0; }},
      {"hull_points", [](ShipDefinition& d) { d.hull_points = 2000000000; }},
      {"bow_wave_options.cells", [](ShipDefinition& d) { d.bow_wave_options.cells = 1 << 20; }},
      {"x_m", [](ShipDefinition& d) { d.x_m = std::numeric_limits<double>::infinity(); }},
      {"speed_m_s", [](ShipDefinition& d) { d.orders.speed_m_s = 1e5; }},
      {"engine_order", [](ShipDefinition& d) { d.orders.engine_order = std::nan(""); }},
      {"waypoint 0", [](ShipDefinition& d) { d.orders.route_m = {{1e300, 0.0}}; }},
  };
  for (const Case& c : cases) {
    ShipDefinition d = tug();
    c.edit(d);
    const std::string message = error_of([&] { fleet.add_ship(d); });
    EXPECT_NE(message.find(c.field), std::string::npos) << c.field << ": " << message;
    EXPECT_NE(message.find("Range"), std::string::npos) << message;
  }
  // Dimensions are refused by the generic hulls before they are lofted.
  for (const char* name : {"tug", "wigley", "box_barge"}) {
    EXPECT_NE(error_of([&] { generic_hull(name, {1e9, 0, 0, 0}); }).find("length_m"), std::string::npos) << name;
    EXPECT_NE(error_of([&] { generic_hull(name, {0, 1e9, 0, 0}); }).find("beam_m"), std::string::npos) << name;
  }
  EXPECT_EQ(fleet.size(), 0u);
  fleet.add_ship(tug());
  EXPECT_NE(error_of([&] { fleet.ship(0).set_orders(ShipOrders{std::nullopt, 1e5, {}}); }).find("speed_m_s"), std::string::npos);
  EXPECT_NE(error_of([&] { fleet.step(nullptr, std::numeric_limits<double>::infinity()); }).find("dt_s"), std::string::npos);
  fleet.ship(0).manual_controls().engine_order = std::nan("");
  EXPECT_NE(error_of([&] { fleet.step(nullptr, 1.0 / 30); }).find("engine_order"), std::string::npos);
  fleet.ship(0).manual_controls().engine_order = 5.0;  // clamped to full ahead
  for (int k = 0; k < 30; ++k) fleet.step(nullptr, 1.0 / 30);
  EXPECT_TRUE(fleet.ship(0).body().state().position_m.allFinite());
}

// The tug of the demo beach runs: 5 m of water, the beach (shore at y = 1045 m) ahead, meeting the
// depth contours obliquely so that one side takes the ground first.
ShipDefinition beach_run_tug() {
  ShipDefinition tug;
  tug.name = "Tug 1";
  tug.hull = harbour_tug();
  tug.loading.draft_m = 3.0;
  tug.hull_points = 800;
  tug.x_m = 200.0;
  tug.y_m = 860.0;
  tug.heading_deg = 40.0;
  return tug;
}

TEST(ShipFleet, ATugSteeredOntoTheDemoBeachGroundsStopsListsAndSaysSo) {
  ShipFleet fleet;
  fleet.set_site(demo_site());
  ShipDefinition tug = beach_run_tug();
  tug.initial_speed_m_s = 3.0;
  tug.orders.engine_order = 1.0;
  tug.bow_wave_options.cells = 64;
  // A hard grounding on the slope: without squat (ShipFleet.ATugAtSpeedTouchesBottomBySquat...
  // below is the same run with it, where the tug touches first in deeper water and refloats).
  tug.restricted_water = false;
  fleet.add_ship(tug);
  const double frame = 1.0 / 30;
  std::vector<std::string> events;
  double aground_at = -1.0;
  for (int k = 0; k < 120 * 30; ++k) {
    fleet.step(nullptr, frame);
    for (auto& e : fleet.take_events()) events.push_back(e);
    if (aground_at < 0 && fleet.ship(0).status().aground) aground_at = k * frame;
    if (aground_at >= 0 && k * frame > aground_at + 30.0) break;
  }
  ASSERT_GE(aground_at, 0.0) << "the tug never reached the beach";
  const Ship& ship = fleet.ship(0);
  const ShipState& s = ship.body().state();
  const double speed = s.velocity_m_s.head<2>().norm();
  const double heel_deg = s.roll_rad() * 180 / std::numbers::pi, trim_deg = s.pitch_rad() * 180 / std::numbers::pi;
  std::printf("aground after %.1f s at (%.1f, %.1f) m; 30 s later: speed %.3f m/s, heel %.2f deg, trim %.2f deg\n%s\n",
              aground_at, ship.status().contact_position_m.x(), ship.status().contact_position_m.y(), speed, heel_deg,
              trim_deg, events.empty() ? "(no event)" : events.front().c_str());
  ASSERT_FALSE(events.empty());
  EXPECT_NE(events.front().find("Tug 1"), std::string::npos);
  EXPECT_NE(events.front().find("ran aground"), std::string::npos);
  EXPECT_TRUE(ship.status().aground);
  EXPECT_LT(speed, 0.05);                 // stopped by the bed's friction, engine stopped
  EXPECT_GT(std::abs(heel_deg), 0.2);     // lists: the bed rises under one side first
  EXPECT_GT(std::abs(trim_deg), 0.2);     // and its bow rides up the slope
}

TEST(ShipFleet, ATugAtSpeedTouchesBottomBySquatWhereItsDraftClears) {
  // The beach run above with squat (restricted_water.hpp): at full ahead over the shoaling bed
  // the tug sinks and trims by the bow (Cb > 0.7, Barrass), so its keel meets the bed where the
  // water is deeper than its static draft by its bow squat (ICORELS, at the speed and the depth
  // under the hull the step before it touches), within 0.2 m: the tug pitches by about +-0.013 rad
  // (+-0.16 m at its ends) after the squat's trim sets in, and the bed is met by the lowest hull
  // point, not exactly at the bow. Then it stops on the bed (engine stopped on grounding).
  ShipFleet fleet;
  fleet.set_site(demo_site());
  ShipDefinition tug = beach_run_tug();
  tug.initial_speed_m_s = 3.0;
  tug.orders.engine_order = 1.0;
  tug.bow_wave_options.cells = 64;
  fleet.add_ship(tug);
  const double frame = 1.0 / 30;
  double aground_at = -1.0, bow_squat_m = 0.0, speed_at_touch = 0.0;
  std::vector<std::string> events;
  for (int k = 0; k < 90 * 30; ++k) {
    const Squat before = fleet.ship(0).body().report().squat;
    const double speed_before = fleet.ship(0).body().state().forward_speed_m_s();
    fleet.step(nullptr, frame);
    for (auto& e : fleet.take_events()) events.push_back(e);
    if (aground_at < 0 && fleet.ship(0).status().aground) {
      aground_at = k * frame;
      bow_squat_m = before.max_squat_m;
      speed_at_touch = speed_before;
    }
  }
  ASSERT_GE(aground_at, 0.0) << "the tug never touched";
  ASSERT_GT(bow_squat_m, 0.0);
  ASSERT_FALSE(events.empty());
  const std::string& touch = events.front();
  const auto at = touch.find("where the water is ");
  ASSERT_NE(at, std::string::npos) << touch;
  const double depth_at_touch = std::stod(touch.substr(at + 19));
  const ShipState& s = fleet.ship(0).body().state();
  std::printf("%s\nat %.1f s, %.2f m/s, ICORELS bow squat %.3f m; 90 s: aground %d, speed %.3f m/s\n", touch.c_str(),
              aground_at, speed_at_touch, bow_squat_m, fleet.ship(0).status().aground ? 1 : 0,
              s.velocity_m_s.head<2>().norm());
  EXPECT_NE(touch.find("Tug 1"), std::string::npos);
  EXPECT_GT(depth_at_touch, 3.0 + 0.3);  // deeper than the static draft: squat, not the draft, touched
  EXPECT_NEAR(depth_at_touch - 3.0, bow_squat_m, 0.2);
  EXPECT_LT(s.velocity_m_s.head<2>().norm(), 0.05);
}

// True when a body-frame point lies inside the Wigley hull 20 x 2 x 1 (depth 2) of the test below.
bool inside_wigley(const Eigen::Vector3d& p) {
  const double L = 20, B = 2, T = 1, D = 2;
  if (std::abs(p.x()) >= L / 2 || p.z() <= 0 || p.z() >= D) return false;
  const double f = 1 - std::pow(2 * p.x() / L, 2);
  const double zeta = p.z() < T ? (T - p.z()) / T : 0.0;
  return std::abs(p.y()) < B / 2 * f * (1 - zeta * zeta);
}

TEST(ShipFleet, TwoShipsOnACollisionCourseArePushedApartWithoutInterpenetrating) {
  ShipFleet fleet;
  for (int k = 0; k < 2; ++k) {
    ShipDefinition d;
    d.name = k == 0 ? "East-bound" : "West-bound";
    d.hull = wigley_hull(20, 2, 1, 2);
    d.loading.draft_m = 1.0;
    d.x_m = k == 0 ? 0.0 : 100.0;
    d.y_m = k == 0 ? 0.0 : 0.5;  // nearly head on
    d.heading_deg = k == 0 ? 90.0 : 270.0;
    d.initial_speed_m_s = 3.0;
    d.orders.speed_m_s = 3.0;
    d.hull_points = 600;
    d.bow_wave = false;  // the repulsion alone
    fleet.add_ship(d);
  }
  int intrusions = 0;
  double closest = 1e9;
  for (int k = 0; k < 40 * 30; ++k) {
    fleet.step(nullptr, 1.0 / 30);
    for (int a = 0; a < 2; ++a) {
      const ShipBody& me = fleet.ship(a).body();
      const ShipBody& other = fleet.ship(1 - a).body();
      const Eigen::Quaterniond to_other = other.state().orientation.conjugate();
      for (const Eigen::Vector3d& p : me.world_points_m()) {
        const Eigen::Vector3d body =
            to_other * (p - other.state().position_m) + other.particulars().centre_of_gravity_m;
        if (inside_wigley(body)) ++intrusions;
      }
    }
    closest = std::min(closest, (fleet.ship(0).body().state().position_m - fleet.ship(1).body().state().position_m).head<2>().norm());
  }
  const double separation = (fleet.ship(0).body().state().position_m - fleet.ship(1).body().state().position_m).head<2>().norm();
  std::printf("closest approach of the centres %.2f m, final separation %.2f m, hull points inside the other hull: %d\n",
              closest, separation, intrusions);
  EXPECT_EQ(intrusions, 0);
  EXPECT_GT(closest, 2.0);  // at least a beam apart (capsules of radius 1 m each)
}

TEST(SternWake, DecalsAreDroppedEveryBeamAndFadeOverTheirLifetime) {
  ShipFleet fleet;
  ShipDefinition d;
  d.name = "Wake";
  d.hull = harbour_tug();
  d.loading.draft_m = 3.0;
  d.heading_deg = 90.0;
  d.initial_speed_m_s = 3.0;
  d.orders.speed_m_s = 3.0;
  d.bow_wave = false;
  d.hull_points = 600;
  d.wake_options.lifetime_s = 20.0;
  fleet.add_ship(d);
  for (int k = 0; k < 30 * 30; ++k) fleet.step(nullptr, 1.0 / 30);
  const auto& decals = fleet.ship(0).wake().decals();
  ASSERT_GT(decals.size(), 3u);
  // About 20 s x 3 m/s / 9 m beam = 6-7 decals alive, oldest first, fading and widening with age.
  EXPECT_LE(decals.size(), 8u);
  for (std::size_t k = 1; k < decals.size(); ++k) {
    EXPECT_GE(decals[k - 1].age_s, decals[k].age_s);
    EXPECT_LE(decals[k - 1].opacity(), decals[k].opacity());
    EXPECT_GE(decals[k - 1].width_m, decals[k].width_m);
    EXPECT_NEAR(std::hypot(decals[k].x_m - decals[k - 1].x_m, decals[k].y_m - decals[k - 1].y_m), 9.0, 1.0);
  }
  EXPECT_LT(decals.front().age_s, 20.0);
}

TEST(Scenario, TheExampleFileLoadsAndSails) {
  const std::filesystem::path file = std::filesystem::path(NEARSHORE_SOURCE_DIR) / "data" / "ships" / "demo_harbour.toml";
  const auto definitions = read_scenario(file);
  ASSERT_GE(definitions.size(), 2u);
  ShipFleet fleet;
  fleet.set_site(demo_site());
  EXPECT_EQ(load_scenario(file, fleet), definitions.size());
  for (int k = 0; k < 5 * 30; ++k) fleet.step(nullptr, 1.0 / 30);
  for (std::size_t k = 0; k < fleet.size(); ++k) EXPECT_FALSE(fleet.ship(k).status().aground) << fleet.ship(k).name();
}

TEST(Scenario, BadFilesAndShipsAreClearErrorsNamingTheFileAndTheShip) {
  const auto folder = scratch_folder();
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(folder / name) << text;
    return folder / name;
  };
  ShipFleet fleet;
  fleet.set_site(demo_site());

  std::string m = error_of([&] { read_scenario(write("syntax.toml", "[[ship]]\nname = \"A\nhull = 1\n")); });
  EXPECT_NE(m.find("syntax.toml"), std::string::npos) << m;
  EXPECT_NE(m.find("line"), std::string::npos) << m;

  m = error_of([&] { read_scenario(write("hull.toml", "[[ship]]\nname = \"A\"\nhull = \"no_such_hull.obj\"\ndraft_m = 1\nposition_m = [0, 0]\n")); });
  EXPECT_NE(m.find("hull.toml"), std::string::npos) << m;
  EXPECT_NE(m.find("no_such_hull.obj"), std::string::npos) << m;

  m = error_of([&] { read_scenario(write("key.toml", "[[ship]]\nname = \"A\"\nhull = \"tug\"\ndraft_m = 3\nposition_m = [300, 300]\nspeed_knots = 3\n")); });
  EXPECT_NE(m.find("speed_knots"), std::string::npos) << m;

  // restricted_water (squat and shallow-water resistance) is read as a boolean, and nothing else.
  const std::string restricted = "[[ship]]\nname = \"A\"\nhull = \"tug\"\ndraft_m = 3\nposition_m = [300, 300]\n";
  EXPECT_FALSE(read_scenario(write("restricted.toml", restricted + "restricted_water = false\n")).front().restricted_water);
  EXPECT_TRUE(read_scenario(write("default.toml", restricted)).front().restricted_water);
  m = error_of([&] { read_scenario(write("restricted_bad.toml", restricted + "restricted_water = 1\n")); });
  EXPECT_NE(m.find("restricted_bad.toml"), std::string::npos) << m;
  EXPECT_NE(m.find("restricted_water"), std::string::npos) << m;
  for (const std::string key : {"bow_wave", "dispersive_wake"}) {  // the other switches likewise
    m = error_of([&] { read_scenario(write("switch_bad.toml", restricted + key + " = 1\n")); });
    EXPECT_NE(m.find(key), std::string::npos) << m;
  }

  const std::string sinks =
      "[[ship]]\nname = \"Fine\"\nhull = \"tug\"\ndraft_m = 3\nposition_m = [300, 300]\n"
      "[[ship]]\nname = \"Lead\"\nhull = \"tug\"\nmass_kg = 5e6\nposition_m = [500, 300]\n";
  m = error_of([&] { load_scenario(write("sinks.toml", sinks), fleet); });
  EXPECT_NE(m.find("sinks.toml"), std::string::npos) << m;
  EXPECT_NE(m.find("Lead"), std::string::npos) << m;
  EXPECT_NE(m.find("cannot float"), std::string::npos) << m;
  EXPECT_EQ(fleet.size(), 0u);  // nothing of a refused file is added

  m = error_of([&] { load_scenario(write("land.toml", "[[ship]]\nname = \"Ashore\"\nhull = \"tug\"\ndraft_m = 3\nposition_m = [200, 1100]\n"), fleet); });
  EXPECT_NE(m.find("land.toml"), std::string::npos) << m;
  EXPECT_NE(m.find("Ashore"), std::string::npos) << m;
  EXPECT_NE(m.find("on land"), std::string::npos) << m;

  m = error_of([&] { load_scenario(write("shallow.toml", "[[ship]]\nname = \"Shoal\"\nhull = \"tug\"\ndraft_m = 3\nposition_m = [200, 1010]\n"), fleet); });
  EXPECT_NE(m.find("Shoal"), std::string::npos) << m;
  EXPECT_NE(m.find("shallower than its draft"), std::string::npos) << m;
  EXPECT_EQ(fleet.size(), 0u);
}

}  // namespace
}  // namespace nearshore::ships
