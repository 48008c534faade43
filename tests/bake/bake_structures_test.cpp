// The harbour's coastal structures laid at the bake's cells with their porous faces fitted to the
// reflection each asks for (bake/structure_layers.hpp), and the literature defaults they start from.
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_bathymetry.hpp"
#include "nearshore/bake/structure_layers.hpp"
#include "nearshore/boussinesq/porous_layer_flume.hpp"

namespace nearshore::bake {
namespace {

TEST(StructureReflection, FollowsZanuttighAndVanDerMeer) {
  // Zanuttigh & van der Meer (2008), Table 4: rock on a permeable core Kr = tanh(0.12 xi^0.87),
  // smooth impermeable slopes tanh(0.16 xi^1.43); their general fit in gamma_f reproduces both to
  // the table's two digits (a within 0.005, b within 0.01): Kr within 0.01 over xi 1.5 .. 10.
  for (double xi = 1.5; xi <= 10.0; xi += 0.5) {
    // A slope and sea with this breaker parameter: tan(alpha) = xi sqrt(Hs / L0).
    const double hs = 1.0, tm10 = 10.0, l0 = 9.81 * tm10 * tm10 / (2 * std::numbers::pi);
    const double cot_alpha = 1.0 / (xi * std::sqrt(hs / l0));
    EXPECT_NEAR(reflection_of_slope(cot_alpha, 0.40, hs, tm10), std::tanh(0.12 * std::pow(xi, 0.87)), 0.01) << xi;
    EXPECT_NEAR(reflection_of_slope(cot_alpha, 1.0, hs, tm10), std::tanh(0.16 * std::pow(xi, 1.43)), 0.015) << xi;
  }
  // No slope (a vertical face) or no sea: nothing to compute it from, full reflection.
  EXPECT_EQ(reflection_of_slope(0.0, 0.4, 1.0, 10.0), 1.0);
}

TEST(StructureSeaState, IsTheMakersSpectrum) {
  boussinesq::WaveMaker maker;
  maker.kind = boussinesq::WaveMaker::Kind::kComponents;
  // Two frequencies: 12 s carries four times the variance of 8 s.
  const double w12 = 2 * std::numbers::pi / 12.0, w8 = 2 * std::numbers::pi / 8.0;
  maker.sea_state.components = {{0.2, w12, 0.0, 0.0}, {0.1, w8, 0.1, 0.0}};
  const StructureSeaState sea = structure_sea_state(maker);
  const double m0 = 0.5 * (0.04 + 0.01);
  EXPECT_NEAR(sea.significant_wave_height_m, 4 * std::sqrt(m0), 1e-12);
  EXPECT_NEAR(sea.peak_period_s, 12.0, 1e-12);
  EXPECT_NEAR(sea.spectral_period_s, (0.02 * 12.0 + 0.005 * 8.0) / m0, 1e-12);
  EXPECT_NEAR(sea.longest_period_s, 12.0, 1e-12);
  EXPECT_NEAR(sea.shortest_period_s, 8.0, 1e-12);
  // Two frequencies: the flume runs them as they are, each with its own variance (H = 2 sqrt(2 var)).
  ASSERT_EQ(sea.waves.size(), 2u);
  EXPECT_NEAR(sea.waves[0].period_s, 12.0, 1e-12);
  EXPECT_NEAR(sea.waves[0].height_m, 0.4, 1e-12);
  // A spectrum of many components: five waves of equal shares whose heights make its Hs.
  boussinesq::WaveMaker jonswap;
  jonswap.kind = boussinesq::WaveMaker::Kind::kComponents;
  for (int i = 0; i < 40; ++i) {
    const double f_hz = 0.05 + 0.0025 * i, peak_hz = 1.0 / 12.0;
    const double shape = std::pow(f_hz / peak_hz, -5.0) * std::exp(-1.25 * std::pow(peak_hz / f_hz, 4.0));
    jonswap.sea_state.components.push_back({0.1 * std::sqrt(shape), 2 * std::numbers::pi * f_hz, 0.0, 0.0});
  }
  const StructureSeaState spread = structure_sea_state(jonswap);
  ASSERT_EQ(spread.waves.size(), 5u);
  double variance_m2 = 0.0;
  for (const auto& wave : spread.waves) variance_m2 += wave.height_m * wave.height_m / 8.0;
  EXPECT_NEAR(4.0 * std::sqrt(variance_m2), spread.significant_wave_height_m, 1e-9);
  for (std::size_t i = 1; i < 5; ++i) EXPECT_LT(spread.waves[i].period_s, spread.waves[i - 1].period_s);  // longest first
  EXPECT_EQ(structure_sea_state(boussinesq::WaveMaker{}).significant_wave_height_m, 0.0);
}

// A 600 m x 200 m basin 8 m deep in 8 m cells, with a rubble-mound breakwater across it at x = 300 m.
HarbourGrid basin_with_breakwater() {
  GridGeometry geometry;
  geometry.columns = 75;
  geometry.rows = 25;
  geometry.spacing_m = 8.0;
  HarbourGrid grid = HarbourGrid::open_water(geometry, 8.0f);
  CoastalStructure mound;
  mound.name = "test mound";
  mound.kind = "rubble_mound_breakwater";
  mound.lines = {{{300.0, -10.0}, {300.0, 210.0}}};
  mound.crest_width_m = 10.0;
  mound.crest_elevation_m = 3.0;
  mound.side_slope = 1.5;
  mound.reflection_coefficient = 0.5;
  grid.structures = {mound};
  return grid;
}

TEST(StructureLayers, LayACoreAndFacesFittedToTheRequestedReflection) {
  HarbourGrid grid = basin_with_breakwater();
  boussinesq::SolverParameters solver;
  StructureSeaState sea;
  sea.significant_wave_height_m = 1.5;
  sea.peak_period_s = sea.spectral_period_s = 12.0;
  sea.longest_period_s = 16.0;
  sea.shortest_period_s = 8.0;
  // The demo's 1.5 m JONSWAP swell as five waves of equal energy (StructureSeaState::waves).
  for (double period_s : {16.0, 13.4, 12.0, 10.6, 8.5}) sea.waves.push_back({period_s, 2.0 * std::sqrt(2.0 * 0.140625 / 5.0)});
  std::vector<std::string> warnings;
  const std::vector<StructureLayer> layers = lay_structures(grid, solver, sea, warnings);
  ASSERT_EQ(layers.size(), 1u);
  const StructureLayer& layer = layers[0];
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_TRUE(layer.fitted);
  EXPECT_TRUE(layer.reached);
  EXPECT_NEAR(layer.in_the_sea.reflection_coefficient, 0.5, kStructureFitTolerance);
  EXPECT_NEAR(layer.depth_m, 8.0, 1e-6);
  // Footprint half-width 5 + 1.5 (3 + 8) = 21.5 m: the core where the line runs (column 37, whose
  // centre is x = 300 m), faces out to 21.5 m from it: columns 36 and 38 (8 m), 35 and 39 (16 m),
  // and as many more each side as the faces were widened by to absorb enough.
  const int per_side = 2 + static_cast<int>(std::lround(layer.widening_m / 8.0));
  EXPECT_LE(per_side, 2 + 4);
  for (int row = 0; row < grid.geometry.rows; ++row) {
    EXPECT_EQ(grid.porosity(37, row), 0.0f);
    for (int k = 1; k <= per_side; ++k) {
      EXPECT_FLOAT_EQ(grid.porosity(37 - k, row), static_cast<float>(layer.face_porosity));
      EXPECT_FLOAT_EQ(grid.porosity(37 + k, row), static_cast<float>(layer.face_porosity));
    }
    EXPECT_EQ(grid.porosity(37 - per_side - 1, row), 1.0f);
    EXPECT_EQ(grid.porosity(37 + per_side + 1, row), 1.0f);
  }
  EXPECT_EQ(layer.core_cells, 25u);
  EXPECT_EQ(layer.face_cells, static_cast<std::size_t>(2 * per_side * 25));
  // The response over the band is measured at the fitted porosity and recorded.
  ASSERT_EQ(layer.across_band.size(), 5u);
  const nlohmann::json record = structure_layers_record(layers);
  EXPECT_EQ(record[0]["name"], "test mound");
  EXPECT_EQ(record[0]["across_band"].size(), 5u);
  const std::string described = describe_structure_layers(layers);
  std::printf("%s\n", described.c_str());
  EXPECT_NE(described.find("test mound"), std::string::npos);
}

TEST(StructureLayers, AGivenPorosityIsKeptAndNoSeaStateIsSaid) {
  HarbourGrid grid = basin_with_breakwater();
  grid.structures[0].porosity = 0.3;  // the source gave it: a permeable layer, no core, no fit
  std::vector<std::string> warnings;
  std::vector<StructureLayer> layers = lay_structures(grid, boussinesq::SolverParameters{}, StructureSeaState{}, warnings);
  EXPECT_FALSE(layers[0].fitted);
  EXPECT_EQ(layers[0].core_cells, 0u);
  EXPECT_FLOAT_EQ(grid.porosity(37, 5), 0.3f);
  EXPECT_TRUE(warnings.empty());
  // Without a sea state a structure that asks for a reflection cannot be fitted: said, naming it.
  grid = basin_with_breakwater();
  layers = lay_structures(grid, boussinesq::SolverParameters{}, StructureSeaState{}, warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("test mound"), std::string::npos);
  EXPECT_EQ(grid.porosity(37, 5), 0.0f);  // the core is laid all the same
}

TEST(StructureLayers, SurviveResamplingAndTheHarbourGridFile) {
  HarbourGrid grid = basin_with_breakwater();
  const auto file = testing::scratch_folder() / "depth.exr";
  write_harbour_grid(file, grid);
  const HarbourGrid again = read_harbour_grid(file);
  EXPECT_EQ(nlohmann::json(again.structures), nlohmann::json(grid.structures));
  const HarbourGrid coarse = resample_harbour_grid(again, CellSize(16.0));
  EXPECT_EQ(coarse.structures.size(), 1u);
}

}  // namespace
}  // namespace nearshore::bake
