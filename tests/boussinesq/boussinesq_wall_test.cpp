// Walls inside the grid (docs/solver.md, "Walls and the dispersive terms"): with
// SolverParameters::WallDispersion::kMirrorAtWalls an interior wall reflects exactly as the grid's
// edge does, and the water beside a grid-aligned pier stays quiet with the grid-scale filter, where
// the default (the dispersive terms end one cell before a wall) grows a mode along the pier's faces.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "boussinesq_test_support.hpp"

namespace nearshore::boussinesq {
namespace {

// Two runs of the same waves: one in a grid whose north and east edges are walls, one in a grid
// four cells longer and wider whose extra cells are land standing 1 m above the water (a quay on
// two sides). Oblique waves (0.3 rad), so both walls see them, 1 s in 0.5 m (k d = 2.1, the
// dispersive terms at full strength), 10 mm: the fully nonlinear terms act too. With the walls
// mirrored the water cells must agree to round-off: the difference allowed, 1e-8 m, is 1e-6 of the
// waves and covers the float in which the fully nonlinear remainder is stored (it reached 9e-10 m);
// with the default the first row beside the quay has no dispersive terms and the runs part by
// millimetres. The weakly nonlinear equations agree to the bit (checked when this was written).
TEST(BoussinesqWalls, AnInteriorWallReflectsAsTheGridEdgeDoes) {
  const double spacing_m = 0.05, depth_m = 0.5;
  const int columns = 160, rows = 20, land = 4;
  SolverParameters parameters = testing::inviscid_parameters(0.5);
  parameters.shapiro_filter_order = 0;
  parameters.sponges = {{Side::kWest, 2.0}};
  WaveMaker maker;
  maker.kind = WaveMaker::Kind::kComponents;
  maker.sea_state.components = {{0.01, 2.0 * kPi / 1.0, 0.0, 0.3}};
  maker.source_line_m = 3.0;
  maker.facing = Side::kWest;
  maker.ramp_time_s = 2.0;
  HarbourGrid quayed = testing::flume(columns + land, rows + land, spacing_m, depth_m);
  for (int r = 0; r < rows + land; ++r)
    for (int c = 0; c < columns + land; ++c)
      if (c >= columns || r >= rows) {
        quayed.still_water_depth_m(c, r) = -1.0f;
        quayed.land(c, r) = kLandCell;
      }
  for (const auto walls : {SolverParameters::WallDispersion::kMirrorAtWalls, SolverParameters::WallDispersion::kEndBeforeWalls}) {
    parameters.wall_dispersion = walls;
    BoussinesqSolver edge(testing::flume(columns, rows, spacing_m, depth_m), parameters, maker);
    BoussinesqSolver quay(quayed, parameters, maker);
    while (edge.time_s() < 10.0) {
      edge.step();
      quay.step();
    }
    double largest_m = 0.0, difference_m = 0.0;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < columns; ++c) {
        const double at_edge = edge.surface_elevation_m()(c, r), at_quay = quay.surface_elevation_m()(c, r);
        largest_m = std::max(largest_m, std::abs(at_edge));
        difference_m = std::max(difference_m, std::abs(at_edge - at_quay));
      }
    const bool mirrored = walls == SolverParameters::WallDispersion::kMirrorAtWalls;
    std::printf("%s: largest |eta| %.4f m, largest difference between the edge and the quay %.3g m\n",
                mirrored ? "mirror_at_walls" : "end_before_walls", largest_m, difference_m);
    EXPECT_GT(largest_m, 0.01);
    if (mirrored)
      EXPECT_LT(difference_m, 1e-8);
    else
      EXPECT_GT(difference_m, 1e-4) << "the default now mirrors walls: update docs/solver.md";
  }
}

// A square pier aligned with the grid on cells of half the depth (a harbour bake's spacing) in still
// water with 5 micrometres of noise and no waves, run to 150 s with the default grid-scale filter;
// returns the largest |eta| in the water.
double noise_beside_a_square_pier_m(SolverParameters::WallDispersion walls, bool taper_dispersion_at_walls = true) {
  const double depth_m = 0.5, spacing_m = 0.25, half_side_m = 0.646, centre_x_m = 7.5, centre_y_m = 7.0, noise_m = 5e-6;
  SolverParameters parameters = testing::inviscid_parameters(0.5);
  parameters.wall_dispersion = walls;
  parameters.taper_dispersion_at_walls = taper_dispersion_at_walls;
  parameters.sponges = {{Side::kWest, 2.0}, {Side::kEast, 4.0}};
  const int columns = static_cast<int>(std::lround(21.0 / spacing_m)), rows = static_cast<int>(std::lround(14.0 / spacing_m));
  HarbourGrid harbour = testing::flume(columns, rows, spacing_m, depth_m);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c)
      if (std::abs((c + 0.5) * spacing_m - centre_x_m) < half_side_m && std::abs((r + 0.5) * spacing_m - centre_y_m) < half_side_m) {
        harbour.still_water_depth_m(c, r) = -1.0f;
        harbour.land(c, r) = kLandCell;
      }
  BoussinesqSolver solver(harbour, parameters, WaveMaker{});
  testing::UniformNoise noise(2.0 * noise_m);
  solver.set_surface_elevation([&](double x_m, double y_m) {
    const double value = noise();  // drawn for every cell, so the sequence does not depend on the disc
    return std::hypot(x_m - centre_x_m, y_m - centre_y_m) < 3.0 ? value : 0.0;
  });
  while (solver.time_s() < 150.0) solver.step();
  double largest_m = 0.0;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c)
      if (harbour.still_water_depth_m(c, r) > 0.0f) largest_m = std::max(largest_m, std::abs(double{solver.surface_elevation_m()(c, r)}));
  return largest_m;
}

// With the walls mirrored the noise decays (it stays below its own 5 micrometres).
TEST(BoussinesqWalls, TheWaterBesideAMirroredPierStaysQuietWithTheGridScaleFilter) {
  const double largest_m = noise_beside_a_square_pier_m(SolverParameters::WallDispersion::kMirrorAtWalls);
  EXPECT_LT(largest_m, 5e-6) << "the noise grew to " << largest_m << " m beside the pier";
}

// The default: the dispersive terms end one cell before the pier and rise to full weight over the
// filter's half-stencil (SolverParameters::taper_dispersion_at_walls): the noise decays.
TEST(BoussinesqWalls, TheWaterBesideAPierStaysQuietWithTheGridScaleFilter) {
  const double largest_m = noise_beside_a_square_pier_m(SolverParameters::WallDispersion::kEndBeforeWalls);
  EXPECT_LT(largest_m, 5e-6) << "the noise grew to " << largest_m << " m beside the pier";
}

// What the taper cures, kept as a check that it still is the cure: at full weight from the second
// row a mode two cells long along the pier's faces, in the first row beside them, grows from the
// corners to about 0.2 m (two fifths of the depth) by 100-150 s, where it saturates, so the solver's
// blow-up guard never sees it (docs/solver.md, "The water beside a wall").
TEST(BoussinesqWalls, WithoutTheTaperTheWaterBesideAPierGrowsAMode) {
  const double largest_m = noise_beside_a_square_pier_m(SolverParameters::WallDispersion::kEndBeforeWalls, false);
  EXPECT_GT(largest_m, 0.05) << "the mode no longer grows without the taper: the taper may no longer be needed";
}

}  // namespace
}  // namespace nearshore::boussinesq
