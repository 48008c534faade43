// Ships through the C API (nearshore_fleet_*, docs/ships.md): bad hulls, masses and positions are
// refused with a message naming the file or the ship while the fleet goes on; a box floats at
// Archimedes' draft; a ship under way makes a bow wave that the fleet's queries add to the sea
// exactly as its height field says; a ship driven onto land grounds and says so; the wake drops
// decals. The numbers come from hydrostatics and from the contract of the returned fields, not
// from the code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "capi_test_support.hpp"
#include "nearshore.h"

namespace {
namespace fs = std::filesystem;
using namespace nearshore::capi_test;

constexpr double kWaterDensityKgM3 = 1025.0;  // the fleet's sea water (ships::WaterProperties)

fs::path write_text(const std::string& name, const std::string& text) {
  const fs::path path = scratch_folder() / ("capi_fleet_" + name);
  std::ofstream(path) << text;
  return path;
}

// A unit cube as OBJ, outward (counter-clockwise seen from outside), with `drop` faces left out
// and `invert` reversing every face.
std::string cube_obj(int drop, bool invert) {
  std::string text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
  const int faces[12][3] = {{1, 3, 2}, {1, 4, 3}, {5, 6, 7}, {5, 7, 8}, {1, 2, 6}, {1, 6, 5},
                            {2, 3, 7}, {2, 7, 6}, {3, 4, 8}, {3, 8, 7}, {4, 1, 5}, {4, 5, 8}};
  for (int f = drop; f < 12; ++f) {
    const int* v = faces[f];
    text += invert ? "f " + std::to_string(v[0]) + " " + std::to_string(v[2]) + " " + std::to_string(v[1]) + "\n"
                   : "f " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
  }
  return text;
}

std::string error() { return nearshore_last_error(); }

TEST(CApiFleet, BadHullsMassesAndPositionsAreRefusedByNameAndNothingElseStops) {
  nearshore_sea* sea = open_calm(write_sequence("fleet_bad", 0.0, 8));
  ASSERT_NE(sea, nullptr);
  nearshore_fleet* fleet = nullptr;
  ASSERT_EQ(nearshore_fleet_create(sea, &fleet), NEARSHORE_OK) << error();
  nearshore_ship_options options;
  nearshore_ship_options_init(&options);
  options.x_m = 60.0;
  options.y_m = 60.0;
  int ship = -1;

  options.name = "Holed";
  const fs::path open = write_text("open.obj", cube_obj(1, false));
  options.hull = open.c_str();
  EXPECT_EQ(nearshore_fleet_add_ship(fleet, &options, &ship), NEARSHORE_FORMAT_ERROR);
  EXPECT_NE(error().find(open.string()), std::string::npos) << error();
  EXPECT_NE(error().find("not closed"), std::string::npos) << error();
  EXPECT_NE(error().find("Holed"), std::string::npos) << error();

  const fs::path inverted = write_text("inverted.obj", cube_obj(0, true));
  options.hull = inverted.c_str();
  EXPECT_EQ(nearshore_fleet_add_ship(fleet, &options, &ship), NEARSHORE_FORMAT_ERROR);
  EXPECT_NE(error().find(inverted.string()), std::string::npos) << error();
  EXPECT_NE(error().find("inward"), std::string::npos) << error();

  options.hull = "/nonexistent/hull.obj";
  EXPECT_EQ(nearshore_fleet_add_ship(fleet, &options, &ship), NEARSHORE_IO_ERROR);
  EXPECT_NE(error().find("/nonexistent/hull.obj"), std::string::npos) << error();

  // A 20 x 8 x 3 m barge displaces at most 20 * 8 * 3 * 1025 = 4.9e5 kg: 1e6 kg sinks it.
  options.name = "Overloaded";
  options.hull = "box_barge";
  options.mass_kg = 1e6;
  EXPECT_EQ(nearshore_fleet_add_ship(fleet, &options, &ship), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("Overloaded"), std::string::npos) << error();
  EXPECT_NE(error().find("cannot float"), std::string::npos) << error();

  // The eastern 8 columns (x > 128 m) are land.
  options.name = "Ashore";
  options.mass_kg = 0.0;
  options.draft_m = 1.0;
  options.x_m = 150.0;
  EXPECT_EQ(nearshore_fleet_add_ship(fleet, &options, &ship), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("Ashore"), std::string::npos) << error();
  EXPECT_NE(error().find("placed on land"), std::string::npos) << error();

  options.hull = "";
  EXPECT_EQ(nearshore_fleet_add_ship(fleet, &options, &ship), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("hull"), std::string::npos) << error();

  // Nothing was added, and the fleet works on: a good ship is ship 0 and steps.
  int count = -1;
  ASSERT_EQ(nearshore_fleet_ship_count(fleet, &count), NEARSHORE_OK);
  EXPECT_EQ(count, 0);
  options.name = "Good";
  options.hull = "tug";
  options.draft_m = 3.0;
  options.x_m = 60.0;
  options.bow_wave_cells = 64;
  ASSERT_EQ(nearshore_fleet_add_ship(fleet, &options, &ship), NEARSHORE_OK) << error();
  EXPECT_EQ(ship, 0);
  ASSERT_EQ(nearshore_sea_advance(sea, 0.1), NEARSHORE_OK);
  EXPECT_EQ(nearshore_fleet_step(fleet, 0.1), NEARSHORE_OK) << error();
  EXPECT_EQ(nearshore_fleet_step(fleet, 0.0), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_EQ(nearshore_fleet_set_controls(fleet, 1, 0.5, 0.0), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("ship = 1"), std::string::npos) << error();
  EXPECT_EQ(nearshore_fleet_set_controls(fleet, 0, 2.0, 0.0), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("engine_order"), std::string::npos) << error();
  EXPECT_EQ(nearshore_fleet_add_ship(nullptr, &options, &ship), NEARSHORE_INVALID_ARGUMENT);
  nearshore_fleet_destroy(fleet);
  nearshore_sea_close(sea);
}

TEST(CApiFleet, ABoxFloatsAtTheDraftOfArchimedesAndDoesNotDrift) {
  nearshore_sea* sea = open_calm(write_sequence("fleet_box", 0.0));
  ASSERT_NE(sea, nullptr);
  nearshore_fleet* fleet = nullptr;
  ASSERT_EQ(nearshore_fleet_create(sea, &fleet), NEARSHORE_OK) << error();
  nearshore_ship_options options;
  nearshore_ship_options_init(&options);
  options.name = "Barge";
  options.hull = "box_barge";  // 20 x 8 x 3 m
  const double draft_m = 1.5;
  options.mass_kg = kWaterDensityKgM3 * 20.0 * 8.0 * draft_m;
  options.x_m = 80.0;
  options.y_m = 60.0;
  options.heading_deg = 90.0;
  options.bow_wave_cells = 64;
  ASSERT_EQ(nearshore_fleet_add_ship(fleet, &options, nullptr), NEARSHORE_OK) << error();
  for (int frame = 1; frame <= 300; ++frame) {
    ASSERT_EQ(nearshore_sea_advance(sea, frame / 30.0), NEARSHORE_OK);
    ASSERT_EQ(nearshore_fleet_step(fleet, 1.0 / 30.0), NEARSHORE_OK) << error();
  }
  nearshore_ship_pose pose;
  pose.struct_size = sizeof pose;
  ASSERT_EQ(nearshore_fleet_ship_pose(fleet, 0, &pose), NEARSHORE_OK) << error();
  // G of a uniform box is at half its depth, 1.5 m above the keel; at draft m / (rho L B) = 1.5 m
  // the keel is 1.5 m down, so G sits at the still-water level: within 1 % of the draft.
  std::printf("barge: G at z = %.4f m (0 expected), at (%.3f, %.3f) m, heading %.2f deg\n", pose.z_m, pose.x_m, pose.y_m,
              pose.heading_deg);
  EXPECT_NEAR(pose.z_m, 0.0, 0.01 * draft_m);
  EXPECT_NEAR(pose.x_m, 80.0, 0.01);
  EXPECT_NEAR(pose.y_m, 60.0, 0.01);
  EXPECT_NEAR(pose.heading_deg, 90.0, 0.01);
  EXPECT_NEAR(pose.roll_deg, 0.0, 0.01);
  EXPECT_EQ(pose.aground, 0);
  nearshore_fleet_destroy(fleet);
  nearshore_sea_close(sea);
}

TEST(CApiFleet, AShipUnderWayMakesABowWaveThatTheFleetQueriesAddAndAWake) {
  nearshore_sea* sea = open_calm(write_sequence("fleet_bow", 0.0));
  ASSERT_NE(sea, nullptr);
  nearshore_fleet* fleet = nullptr;
  ASSERT_EQ(nearshore_fleet_create(sea, &fleet), NEARSHORE_OK) << error();
  nearshore_ship_options options;
  nearshore_ship_options_init(&options);
  options.name = "Tug";
  options.x_m = 30.0;
  options.y_m = 60.0;
  options.heading_deg = 90.0;  // east
  options.order = NEARSHORE_ORDER_SPEED;
  options.speed_m_s = 3.0;
  options.initial_speed_m_s = 3.0;
  options.bow_wave_cells = 64;
  options.dispersive_wake = 0;  // the grid alone (the default before version 9): its layout contract
  ASSERT_EQ(nearshore_fleet_add_ship(fleet, &options, nullptr), NEARSHORE_OK) << error();
  for (int frame = 1; frame <= 450; ++frame) {
    ASSERT_EQ(nearshore_sea_advance(sea, frame / 30.0), NEARSHORE_OK);
    ASSERT_EQ(nearshore_fleet_step(fleet, 1.0 / 30.0), NEARSHORE_OK) << error();
  }
  nearshore_ship_pose pose;
  pose.struct_size = sizeof pose;
  ASSERT_EQ(nearshore_fleet_ship_pose(fleet, 0, &pose), NEARSHORE_OK);
  std::printf("tug under way: (%.1f, %.1f) m, %.2f m/s, heading %.1f deg\n", pose.x_m, pose.y_m, pose.speed_m_s,
              pose.heading_deg);
  EXPECT_GT(pose.x_m, 50.0);
  EXPECT_NEAR(pose.speed_m_s, 3.0, 0.5);  // the engine holds the ordered speed

  nearshore_bow_wave_field field;
  field.struct_size = sizeof field;
  ASSERT_EQ(nearshore_fleet_bow_wave(fleet, 0, &field, nullptr, 0), NEARSHORE_OK) << error();
  ASSERT_EQ(field.columns, 64);
  std::vector<float> heights(static_cast<std::size_t>(field.columns) * field.rows);
  EXPECT_EQ(nearshore_fleet_bow_wave(fleet, 0, &field, heights.data(), 10), NEARSHORE_INVALID_ARGUMENT);
  ASSERT_EQ(nearshore_fleet_bow_wave(fleet, 0, &field, heights.data(), heights.size()), NEARSHORE_OK);
  // The crest outside the hull (the hull's depression is under the ship, 9 m wide around its track).
  std::size_t crest = 0;
  for (std::size_t k = 0; k < heights.size(); ++k)
    if (heights[k] > heights[crest]) crest = k;
  ASSERT_GT(heights[crest], 0.005f);
  // At that texel's centre the fleet's query is the sea's plus exactly that texel (the field's
  // layout contract: row 0 south, texel centres at origin + (i + 0.5) spacing).
  const int i = static_cast<int>(crest % field.columns), j = static_cast<int>(crest / field.columns);
  const double xy[2] = {field.origin_x_m + (i + 0.5) * field.spacing_m, field.origin_y_m + (j + 0.5) * field.spacing_m};
  nearshore_surface_sample sea_only, with_ships;
  ASSERT_EQ(nearshore_sea_query(sea, xy, 1, &sea_only), NEARSHORE_OK);
  ASSERT_EQ(nearshore_fleet_query(fleet, xy, 1, &with_ships), NEARSHORE_OK) << error();
  std::printf("bow-wave crest %.4f m at (%.1f, %.1f) m; fleet query - sea query = %.4f m\n", heights[crest], xy[0], xy[1],
              with_ships.elevation_m - sea_only.elevation_m);
  EXPECT_NEAR(with_ships.elevation_m - sea_only.elevation_m, heights[crest], 1e-5);
  EXPECT_LE(with_ships.normal[2], 1.0f);
  nearshore_surface_sample at_time;
  ASSERT_EQ(nearshore_fleet_query_at(fleet, 450 / 30.0, xy, 1, &at_time), NEARSHORE_OK) << error();
  EXPECT_NEAR(at_time.elevation_m, with_ships.elevation_m, 1e-5);

  size_t decal_count = 0;
  ASSERT_EQ(nearshore_fleet_wake_decals(fleet, 0, nullptr, 0, &decal_count), NEARSHORE_OK);
  // One decal per beam (9 m) of travel: about 3 m/s * 15 s / 9 m = 5.
  EXPECT_GE(decal_count, 3u);
  std::vector<nearshore_wake_decal> decals(decal_count);
  ASSERT_EQ(nearshore_fleet_wake_decals(fleet, 0, decals.data(), decals.size(), &decal_count), NEARSHORE_OK);
  for (const nearshore_wake_decal& d : decals) {
    EXPECT_GT(d.opacity, 0.f);
    EXPECT_LE(d.opacity, 1.f);
    EXPECT_LT(d.x_m, pose.x_m);  // behind the ship, on its track
    EXPECT_NEAR(d.y_m, 60.0, 1.0);
  }
  nearshore_fleet_destroy(fleet);
  nearshore_sea_close(sea);
}

// A ship with a dispersive wake (API version 4) at depth Froude number 0.3 shows that layer alone:
// the bow-wave grid's heights carry weight 0, and the fleet's query adds exactly the dispersive
// layer's texel (the layout contract of nearshore_bow_wave_field, as above).
TEST(CApiFleet, ADispersiveWakeIsShownBelowFroudeSevenTenthsAndQueriedLikeABowWave) {
  nearshore_sea* sea = open_calm(write_sequence("fleet_kelvin", 0.0));
  ASSERT_NE(sea, nullptr);
  nearshore_fleet* fleet = nullptr;
  ASSERT_EQ(nearshore_fleet_create(sea, &fleet), NEARSHORE_OK) << error();
  nearshore_ship_options options;
  nearshore_ship_options_init(&options);
  EXPECT_EQ(options.dispersive_wake, 1);  // on by default since version 9
  options.name = "Tug";
  options.x_m = 30.0;
  options.y_m = 60.0;
  options.heading_deg = 90.0;
  options.order = NEARSHORE_ORDER_SPEED;
  options.speed_m_s = 3.0;
  options.initial_speed_m_s = 3.0;
  options.bow_wave_cells = 64;
  options.dispersive_wake = 1;
  ASSERT_EQ(nearshore_fleet_add_ship(fleet, &options, nullptr), NEARSHORE_OK) << error();
  for (int frame = 1; frame <= 150; ++frame) {
    ASSERT_EQ(nearshore_sea_advance(sea, frame / 30.0), NEARSHORE_OK);
    ASSERT_EQ(nearshore_fleet_step(fleet, 1.0 / 30.0), NEARSHORE_OK) << error();
  }
  nearshore_bow_wave_field grid, wake;
  grid.struct_size = wake.struct_size = sizeof grid;
  ASSERT_EQ(nearshore_fleet_bow_wave(fleet, 0, &grid, nullptr, 0), NEARSHORE_OK) << error();
  ASSERT_EQ(nearshore_fleet_dispersive_wake(fleet, 0, &wake, nullptr, 0), NEARSHORE_OK) << error();
  ASSERT_GT(wake.columns, 0);
  std::vector<float> grid_heights(static_cast<std::size_t>(grid.columns) * grid.rows);
  std::vector<float> wake_heights(static_cast<std::size_t>(wake.columns) * wake.rows);
  ASSERT_EQ(nearshore_fleet_bow_wave(fleet, 0, &grid, grid_heights.data(), grid_heights.size()), NEARSHORE_OK);
  ASSERT_EQ(nearshore_fleet_dispersive_wake(fleet, 0, &wake, wake_heights.data(), wake_heights.size()), NEARSHORE_OK);
  for (float h : grid_heights) ASSERT_EQ(h, 0.0f);  // the grid is not shown at Fr_d 0.3
  std::size_t crest = 0;
  for (std::size_t k = 0; k < wake_heights.size(); ++k)
    if (wake_heights[k] > wake_heights[crest]) crest = k;
  ASSERT_GT(wake_heights[crest], 0.0f);
  const int i = static_cast<int>(crest % wake.columns), j = static_cast<int>(crest / wake.columns);
  const double xy[2] = {wake.origin_x_m + (i + 0.5) * wake.spacing_m, wake.origin_y_m + (j + 0.5) * wake.spacing_m};
  nearshore_surface_sample sea_only, with_ships;
  ASSERT_EQ(nearshore_sea_query(sea, xy, 1, &sea_only), NEARSHORE_OK);
  ASSERT_EQ(nearshore_fleet_query(fleet, xy, 1, &with_ships), NEARSHORE_OK) << error();
  EXPECT_NEAR(with_ships.elevation_m - sea_only.elevation_m, wake_heights[crest], 1e-5);
  // Since version 9 the decals hold the breaking crests' foam after the stern wake's: the tug's
  // waves break at 3 m/s (docs/ships.md), so there are more decals than the stern wake's one per
  // beam (9 m) of travel, 2 in these 5 s, each within the layer's window around the tug.
  size_t decal_count = 0;
  ASSERT_EQ(nearshore_fleet_wake_decals(fleet, 0, nullptr, 0, &decal_count), NEARSHORE_OK);
  std::vector<nearshore_wake_decal> decals(decal_count);
  ASSERT_EQ(nearshore_fleet_wake_decals(fleet, 0, decals.data(), decals.size(), &decal_count), NEARSHORE_OK);
  std::printf("tug with its dispersive wake at 3 m/s: %zu decals (stern wake and crest foam)\n", decal_count);
  EXPECT_GT(decal_count, 10u);
  for (const nearshore_wake_decal& d : decals) {
    EXPECT_GT(d.opacity, 0.0f);
    EXPECT_LE(d.opacity, 1.0f);
    EXPECT_NEAR(d.y_m, 60.0f, 60.0f);  // inside the 120 m window
  }
  // A ship without one reports none.
  options.name = "Barge";
  options.y_m = 100.0;
  options.dispersive_wake = 0;
  int second = -1;
  ASSERT_EQ(nearshore_fleet_add_ship(fleet, &options, &second), NEARSHORE_OK) << error();
  ASSERT_EQ(nearshore_fleet_dispersive_wake(fleet, second, &wake, nullptr, 0), NEARSHORE_OK);
  EXPECT_EQ(wake.columns, 0);
  nearshore_fleet_destroy(fleet);
  nearshore_sea_close(sea);
}

// Version 8: every wave layer of a ship is listed (nearshore_fleet_wave_layer_count / _wave_layer),
// each with its kind and shown weight, its field the same as the single-layer calls give: layer 0
// is the grid of nearshore_fleet_bow_wave, layer 1 the layer of nearshore_fleet_dispersive_wake.
// The weights sum to 1 before the first step and after (the fleet counts the displacement once).
TEST(CApiFleet, EveryWaveLayerOfAShipIsListedWithItsKindAndShownWeight) {
  nearshore_sea* sea = open_calm(write_sequence("fleet_layers", 0.0));
  ASSERT_NE(sea, nullptr);
  nearshore_fleet* fleet = nullptr;
  ASSERT_EQ(nearshore_fleet_create(sea, &fleet), NEARSHORE_OK) << error();
  nearshore_ship_options options;
  nearshore_ship_options_init(&options);
  options.x_m = 30.0;
  options.heading_deg = 90.0;
  options.order = NEARSHORE_ORDER_SPEED;
  options.speed_m_s = 3.0;
  options.initial_speed_m_s = 3.0;
  options.bow_wave_cells = 64;
  options.name = "Both";
  options.y_m = 25.0;
  options.dispersive_wake = 1;
  ASSERT_EQ(nearshore_fleet_add_ship(fleet, &options, nullptr), NEARSHORE_OK) << error();
  options.name = "Grid";
  options.y_m = 60.0;
  options.dispersive_wake = 0;
  ASSERT_EQ(nearshore_fleet_add_ship(fleet, &options, nullptr), NEARSHORE_OK) << error();
  options.name = "None";
  options.y_m = 95.0;
  options.bow_wave = 0;
  ASSERT_EQ(nearshore_fleet_add_ship(fleet, &options, nullptr), NEARSHORE_OK) << error();

  int counts[3] = {-1, -1, -1};
  for (int ship = 0; ship < 3; ++ship)
    ASSERT_EQ(nearshore_fleet_wave_layer_count(fleet, ship, &counts[ship]), NEARSHORE_OK) << error();
  EXPECT_EQ(counts[0], 2);
  EXPECT_EQ(counts[1], 1);
  EXPECT_EQ(counts[2], 0);

  nearshore_wave_layer info;
  info.struct_size = sizeof info;
  nearshore_bow_wave_field field;
  field.struct_size = sizeof field;
  auto weight_sum = [&](int ship) {
    double sum = 0.0;
    for (int layer = 0; layer < counts[ship]; ++layer) {
      EXPECT_EQ(nearshore_fleet_wave_layer(fleet, ship, layer, &info, &field, nullptr, 0), NEARSHORE_OK) << error();
      EXPECT_GE(info.shown_weight, 0.0);
      EXPECT_LE(info.shown_weight, 1.0);
      sum += info.shown_weight;
    }
    return sum;
  };
  EXPECT_DOUBLE_EQ(weight_sum(0), 1.0);  // before the first step too
  EXPECT_DOUBLE_EQ(weight_sum(1), 1.0);

  for (int frame = 1; frame <= 90; ++frame) {
    ASSERT_EQ(nearshore_sea_advance(sea, frame / 30.0), NEARSHORE_OK);
    ASSERT_EQ(nearshore_fleet_step(fleet, 1.0 / 30.0), NEARSHORE_OK) << error();
  }
  EXPECT_DOUBLE_EQ(weight_sum(0), 1.0);
  EXPECT_DOUBLE_EQ(weight_sum(1), 1.0);
  // The kinds in their order, and each layer's field and heights as the single-layer calls give them.
  for (int layer = 0; layer < 2; ++layer) {
    nearshore_bow_wave_field single;
    single.struct_size = sizeof single;
    ASSERT_EQ(nearshore_fleet_wave_layer(fleet, 0, layer, &info, &field, nullptr, 0), NEARSHORE_OK) << error();
    EXPECT_EQ(info.kind, layer == 0 ? NEARSHORE_WAVE_LAYER_SHALLOW_WATER : NEARSHORE_WAVE_LAYER_DISPERSIVE);
    ASSERT_EQ(layer == 0 ? nearshore_fleet_bow_wave(fleet, 0, &single, nullptr, 0)
                         : nearshore_fleet_dispersive_wake(fleet, 0, &single, nullptr, 0),
              NEARSHORE_OK);
    ASSERT_GT(field.columns, 0);
    EXPECT_EQ(field.columns, single.columns);
    EXPECT_EQ(field.rows, single.rows);
    EXPECT_EQ(field.origin_x_m, single.origin_x_m);
    EXPECT_EQ(field.origin_y_m, single.origin_y_m);
    EXPECT_EQ(field.spacing_m, single.spacing_m);
    EXPECT_EQ(field.serial, single.serial);
    std::vector<float> listed(static_cast<std::size_t>(field.columns) * field.rows), alone(listed.size());
    ASSERT_EQ(nearshore_fleet_wave_layer(fleet, 0, layer, &info, &field, listed.data(), listed.size()), NEARSHORE_OK);
    ASSERT_EQ(layer == 0 ? nearshore_fleet_bow_wave(fleet, 0, &single, alone.data(), alone.size())
                         : nearshore_fleet_dispersive_wake(fleet, 0, &single, alone.data(), alone.size()),
              NEARSHORE_OK);
    EXPECT_EQ(listed, alone);
    // Too small a buffer is refused naming capacity.
    EXPECT_EQ(nearshore_fleet_wave_layer(fleet, 0, layer, &info, &field, listed.data(), 10), NEARSHORE_INVALID_ARGUMENT);
    EXPECT_NE(error().find("capacity"), std::string::npos) << error();
  }
  ASSERT_EQ(nearshore_fleet_wave_layer(fleet, 1, 0, &info, &field, nullptr, 0), NEARSHORE_OK) << error();
  EXPECT_EQ(info.kind, NEARSHORE_WAVE_LAYER_SHALLOW_WATER);
  EXPECT_EQ(info.shown_weight, 1.0);

  // Refusals name what is wrong.
  EXPECT_EQ(nearshore_fleet_wave_layer(fleet, 0, 2, &info, &field, nullptr, 0), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("layer = 2"), std::string::npos) << error();
  EXPECT_NE(error().find("has 2"), std::string::npos) << error();
  EXPECT_EQ(nearshore_fleet_wave_layer(fleet, 2, 0, &info, &field, nullptr, 0), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("layer = 0"), std::string::npos) << error();
  EXPECT_EQ(nearshore_fleet_wave_layer(fleet, 0, -1, &info, &field, nullptr, 0), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_EQ(nearshore_fleet_wave_layer(fleet, 3, 0, &info, &field, nullptr, 0), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("ship = 3"), std::string::npos) << error();
  EXPECT_EQ(nearshore_fleet_wave_layer(fleet, 0, 0, nullptr, &field, nullptr, 0), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("info"), std::string::npos) << error();
  EXPECT_EQ(nearshore_fleet_wave_layer(fleet, 0, 0, &info, nullptr, nullptr, 0), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("field"), std::string::npos) << error();
  info.struct_size = 4;
  EXPECT_EQ(nearshore_fleet_wave_layer(fleet, 0, 0, &info, &field, nullptr, 0), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("nearshore_wave_layer.struct_size"), std::string::npos) << error();
  EXPECT_EQ(nearshore_fleet_wave_layer_count(fleet, 0, nullptr), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("count"), std::string::npos) << error();
  EXPECT_EQ(nearshore_fleet_wave_layer_count(nullptr, 0, &counts[0]), NEARSHORE_INVALID_ARGUMENT);
  nearshore_fleet_destroy(fleet);
  nearshore_sea_close(sea);
}

// The basin's land (x > 128 m, 2 m high) rises from 10 m of water in one cell: a quay face. Since
// API version 5 it stops the hull sideways (before, the hull ran on until its keel met the bed's
// interpolated slope and grounded): the ship strikes it, stays there with its engine pushing, and
// the contact comes back as a struct naming the land and the face's normal (-x).
// The contact is near-plastic (ship_body.cpp: e = 0 and Coulomb friction, Pedersen & Zhang 1998):
// the tug stays at the face (with restitution 0.2 it rebounded and was at 0.34 m/s after the run).
TEST(CApiFleet, AShipDrivenAtTheLandStrikesItsFaceAndSaysSo) {
  nearshore_sea* sea = open_calm(write_sequence("fleet_ground", 0.0, 8));
  ASSERT_NE(sea, nullptr);
  nearshore_fleet* fleet = nullptr;
  ASSERT_EQ(nearshore_fleet_create(sea, &fleet), NEARSHORE_OK) << error();
  nearshore_ship_options options;
  nearshore_ship_options_init(&options);
  options.name = "Runaway";
  options.x_m = 70.0;
  options.y_m = 60.0;
  options.heading_deg = 90.0;  // towards the land east of x = 128 m
  options.bow_wave = 0;
  ASSERT_EQ(nearshore_fleet_add_ship(fleet, &options, nullptr), NEARSHORE_OK) << error();
  ASSERT_EQ(nearshore_fleet_set_controls(fleet, 0, 1.0, 0.0), NEARSHORE_OK) << error();
  std::string events;
  std::vector<nearshore_ship_contact> contacts;
  nearshore_ship_pose pose{};
  pose.struct_size = sizeof pose;
  for (int frame = 1; frame <= 1800; ++frame) {
    ASSERT_EQ(nearshore_sea_advance(sea, frame / 30.0), NEARSHORE_OK);
    ASSERT_EQ(nearshore_fleet_step(fleet, 1.0 / 30.0), NEARSHORE_OK) << error();
    ASSERT_EQ(nearshore_fleet_ship_pose(fleet, 0, &pose), NEARSHORE_OK);
    char text[512];
    int has_event = 1;
    while (has_event) {
      ASSERT_EQ(nearshore_fleet_next_event(fleet, text, sizeof text, &has_event), NEARSHORE_OK);
      if (has_event) events += std::string(text) + "\n";
    }
    nearshore_ship_contact contact{};
    contact.struct_size = sizeof contact;
    int has_contact = 1;
    while (has_contact) {
      ASSERT_EQ(nearshore_fleet_next_contact(fleet, &contact, &has_contact), NEARSHORE_OK) << error();
      if (has_contact) contacts.push_back(contact);
    }
    if (!contacts.empty() && frame > 600) break;
  }
  std::printf("%s", events.c_str());
  EXPECT_NE(events.find("ship 'Runaway' struck the land"), std::string::npos) << events;
  ASSERT_FALSE(contacts.empty());
  const nearshore_ship_contact& c = contacts.front();
  EXPECT_EQ(c.ship, 0);
  EXPECT_EQ(c.began, 1);
  EXPECT_EQ(c.structure, 0);
  EXPECT_STREQ(c.description, "the land");
  EXPECT_NEAR(c.normal[0], -1.0, 0.02);  // the face runs north-south; its normal points west
  EXPECT_NEAR(c.x_m, 128.0, 1.0);
  // Held at the face: the tug's stem (12 m ahead of its centre, less its centre of gravity's
  // offset) within a metre of x = 128 m, at rest, not aground.
  EXPECT_LT(pose.x_m + 12.0, 129.5);
  EXPECT_LT(std::abs(pose.speed_m_s), 0.05);
  EXPECT_EQ(pose.aground, 0);
  nearshore_ship_contact bad{};
  int has = 0;
  EXPECT_EQ(nearshore_fleet_next_contact(fleet, &bad, &has), NEARSHORE_INVALID_ARGUMENT);  // struct_size 0
  nearshore_fleet_destroy(fleet);
  nearshore_sea_close(sea);
}

// Issue 44, the fleet's probes: each was accepted (and then crashed, hung or allocated 24 GB) or
// came back as NEARSHORE_INTERNAL_ERROR; each is now NEARSHORE_INVALID_ARGUMENT with a message
// naming the field and its range, before anything is built, and the fleet goes on.
TEST(CApiFleet, OutOfRangeShipParametersAreRefusedNamingTheFieldAndTheFleetGoesOn) {
  nearshore_sea* sea = open_calm(write_sequence("fleet_ranges", 0.0));
  ASSERT_NE(sea, nullptr);
  nearshore_fleet* fleet = nullptr;
  ASSERT_EQ(nearshore_fleet_create(sea, &fleet), NEARSHORE_OK) << error();
  auto fresh = [] {
    nearshore_ship_options o;
    nearshore_ship_options_init(&o);
    o.name = "Probe";
    o.x_m = 60.0;
    o.y_m = 60.0;
    o.bow_wave_cells = 32;
    o.hull_points = 400;
    return o;
  };
  struct Probe {
    const char* what;
    void (*edit)(nearshore_ship_options&);
    const char* field;
  };
  const Probe probes[] = {
      {"initial speed 1e308 m/s (then a segfault in Seabed::depth_m)", [](nearshore_ship_options& o) { o.initial_speed_m_s = 1e308; }, "initial_speed_m_s"},
      {"initial speed 1e8 m/s (then a hang)", [](nearshore_ship_options& o) { o.initial_speed_m_s = 1e8; }, "initial_speed_m_s"},
      {"initial speed 1e5 m/s (ran on with OK)", [](nearshore_ship_options& o) { o.initial_speed_m_s = 1e5; }, "initial_speed_m_s"},
      // 20 m/s is under the 30 m/s cap but above the 24 m tug's length Froude number 1 (15.3 m/s).
      {"initial speed 20 m/s on a 24 m tug", [](nearshore_ship_options& o) { o.initial_speed_m_s = 20.0; }, "initial_speed_m_s"},
      {"mass 1e-300 kg (hung BowWave::update)", [](nearshore_ship_options& o) { o.mass_kg = 1e-300; }, "mass_kg"},
      // 1 kg is a mass, but it floats the tug on 0.1 mm of water.
      {"mass 1 kg", [](nearshore_ship_options& o) { o.mass_kg = 1.0; }, "mass_kg"},
      {"length 1e9 m (24 GB)", [](nearshore_ship_options& o) { o.length_m = 1e9; }, "length_m"},
      {"beam 1e9 m", [](nearshore_ship_options& o) { o.beam_m = 1e9; }, "beam_m"},
      {"depth inf", [](nearshore_ship_options& o) { o.depth_m = INFINITY; }, "depth_m"},
      {"hull points 2e9", [](nearshore_ship_options& o) { o.hull_points = 2000000000; }, "hull_points"},
      {"bow-wave cells 1e5", [](nearshore_ship_options& o) { o.bow_wave_cells = 100000; }, "bow_wave_cells"},
      {"draft nan", [](nearshore_ship_options& o) { o.draft_m = NAN; }, "draft_m"},
      {"x 1e300 m", [](nearshore_ship_options& o) { o.x_m = 1e300; }, "x_m"},
      {"heading nan", [](nearshore_ship_options& o) { o.heading_deg = NAN; }, "heading_deg"},
      {"speed order 1e308 m/s",
       [](nearshore_ship_options& o) {
         o.order = NEARSHORE_ORDER_SPEED;
         o.speed_m_s = 1e308;
       },
       "speed_m_s"},
  };
  for (const Probe& probe : probes) {
    nearshore_ship_options options = fresh();
    probe.edit(options);
    int ship = -1;
    EXPECT_EQ(nearshore_fleet_add_ship(fleet, &options, &ship), NEARSHORE_INVALID_ARGUMENT) << probe.what << ": " << error();
    EXPECT_NE(error().find(probe.field), std::string::npos) << probe.what << ": " << error();
    EXPECT_NE(error().find("Probe"), std::string::npos) << probe.what << ": " << error();
    EXPECT_EQ(error().find("internal"), std::string::npos) << probe.what << ": " << error();
    EXPECT_LT(error().size(), 600u) << probe.what << ": no 309-digit numbers echoed: " << error();
  }
  std::printf("e.g. %s\n", error().c_str());

  // Nothing was added; a ship at the edge of the ranges sails, and its orders are checked too.
  int count = -1;
  ASSERT_EQ(nearshore_fleet_ship_count(fleet, &count), NEARSHORE_OK);
  EXPECT_EQ(count, 0);
  nearshore_ship_options options = fresh();
  options.heading_deg = 90.0;
  options.initial_speed_m_s = 15.0;  // under the 24 m tug's limit sqrt(9.81 * 24) = 15.3 m/s
  ASSERT_EQ(nearshore_fleet_add_ship(fleet, &options, nullptr), NEARSHORE_OK) << error();
  EXPECT_EQ(nearshore_fleet_set_speed(fleet, 0, 1e5, nullptr, 0), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("speed_m_s"), std::string::npos) << error();
  EXPECT_EQ(nearshore_fleet_set_speed(fleet, 0, NAN, nullptr, 0), NEARSHORE_INVALID_ARGUMENT);
  const double far_route[2] = {1e300, 0.0};
  EXPECT_EQ(nearshore_fleet_set_speed(fleet, 0, 3.0, far_route, 1), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_NE(error().find("waypoint 0"), std::string::npos) << error();
  EXPECT_EQ(nearshore_fleet_set_controls(fleet, 0, NAN, 0.0), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_EQ(nearshore_fleet_set_controls(fleet, 0, 0.0, INFINITY), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_EQ(nearshore_fleet_step(fleet, INFINITY), NEARSHORE_INVALID_ARGUMENT);
  EXPECT_EQ(nearshore_fleet_step(fleet, NAN), NEARSHORE_INVALID_ARGUMENT);
  for (int frame = 1; frame <= 60; ++frame) {
    ASSERT_EQ(nearshore_sea_advance(sea, frame / 30.0), NEARSHORE_OK);
    ASSERT_EQ(nearshore_fleet_step(fleet, 1.0 / 30.0), NEARSHORE_OK) << error();
  }
  nearshore_ship_pose pose{};
  pose.struct_size = sizeof pose;
  ASSERT_EQ(nearshore_fleet_ship_pose(fleet, 0, &pose), NEARSHORE_OK);
  EXPECT_TRUE(std::isfinite(pose.x_m) && std::isfinite(pose.speed_m_s));
  EXPECT_LT(std::abs(pose.speed_m_s), 15.5);
  nearshore_fleet_destroy(fleet);
  nearshore_sea_close(sea);
}

// Every double field of nearshore_ship_options, set to each hostile value in turn: never a crash,
// a hang or NEARSHORE_INTERNAL_ERROR; a refused ship leaves the fleet as it was.
// Traced: the ship-ship repulsion was sound; the ships with heading_deg = +-1e308 (finite, so
// accepted) had NaN orientations, because 1e308 deg times pi overflowed to infinity before the
// reduction to radians, and their NaN capsules made every other ship's repulsion NaN. The heading is
// now reduced modulo 360 first (yaw_from_heading_rad). 61 of the 198 ships are accepted (values in
// range, or fields their order ignores) and all step.
TEST(CApiFleet, HostileValuesInEveryShipFieldAreAnsweredWithAStatus) {
  nearshore_sea* sea = open_calm(write_sequence("fleet_hostile", 0.0));
  ASSERT_NE(sea, nullptr);
  nearshore_fleet* fleet = nullptr;
  ASSERT_EQ(nearshore_fleet_create(sea, &fleet), NEARSHORE_OK) << error();
  double nearshore_ship_options::*const fields[] = {
      &nearshore_ship_options::length_m,  &nearshore_ship_options::beam_m,       &nearshore_ship_options::depth_m,
      &nearshore_ship_options::draft_m,   &nearshore_ship_options::mass_kg,      &nearshore_ship_options::x_m,
      &nearshore_ship_options::y_m,       &nearshore_ship_options::heading_deg,  &nearshore_ship_options::initial_speed_m_s,
      &nearshore_ship_options::engine_order, &nearshore_ship_options::speed_m_s};
  const double values[] = {NAN, INFINITY, -INFINITY, 1e308, -1e308, 1e-300, -1.0, 1e9, 0.0};
  int accepted = 0;
  for (auto field : fields)
    for (double value : values)
      for (nearshore_ship_order order : {NEARSHORE_ORDER_ENGINE, NEARSHORE_ORDER_SPEED}) {
        nearshore_ship_options o;
        nearshore_ship_options_init(&o);
        o.x_m = 60.0;
        o.y_m = 60.0;
        o.bow_wave_cells = 32;
        o.hull_points = 200;
        o.order = order;
        o.engine_order = 0.5;
        o.speed_m_s = 3.0;
        o.*field = value;
        int ship = -1;
        const nearshore_status status = nearshore_fleet_add_ship(fleet, &o, &ship);
        ASSERT_TRUE(status == NEARSHORE_OK || status == NEARSHORE_INVALID_ARGUMENT) << nearshore_status_name(status) << ": " << error();
        if (status == NEARSHORE_OK) ++accepted;
      }
  int count = -1;
  ASSERT_EQ(nearshore_fleet_ship_count(fleet, &count), NEARSHORE_OK);
  EXPECT_EQ(count, accepted);
  for (int frame = 1; frame <= 5; ++frame) {
    ASSERT_EQ(nearshore_sea_advance(sea, frame / 30.0), NEARSHORE_OK);
    ASSERT_EQ(nearshore_fleet_step(fleet, 1.0 / 30.0), NEARSHORE_OK) << error();
  }
  std::printf("%d of %zu hostile ships accepted (values that are in range), all stepped\n", accepted,
              std::size(fields) * std::size(values) * 2);
  nearshore_fleet_destroy(fleet);
  nearshore_sea_close(sea);
}

}  // namespace
