// The harbour's coastal structures laid at the bake's cells with their porous faces fitted to the
// reflection each asks for (bake/structure_layers.hpp), and the literature defaults they start from.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_bathymetry.hpp"
#include "nearshore/bake/structure_layers.hpp"
#include "nearshore/boussinesq/boussinesq_solver.hpp"
#include "nearshore/boussinesq/incident_reflected.hpp"
#include "nearshore/boussinesq/model_dispersion.hpp"
#include "nearshore/boussinesq/porous_layer_flume.hpp"
#include "nearshore/ocean/linear_waves.hpp"

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

// A flat basin of `columns` x `rows` square cells with one line structure across it at x = `x_m`
// (from y = -10 m to 10 m beyond the grid's north edge).
HarbourGrid basin_with(int columns, int rows, double spacing_m, float depth_m, double x_m, CoastalStructure structure) {
  GridGeometry geometry;
  geometry.columns = columns;
  geometry.rows = rows;
  geometry.spacing_m = spacing_m;
  HarbourGrid grid = HarbourGrid::open_water(geometry, depth_m);
  structure.lines = {{{x_m, -10.0}, {x_m, rows * spacing_m + 10.0}}};
  grid.structures = {structure};
  return grid;
}

// A 600 m x 200 m basin 8 m deep in 8 m cells, with a rubble-mound breakwater across it at x = 300 m.
HarbourGrid basin_with_breakwater() {
  CoastalStructure mound;
  mound.name = "test mound";
  mound.kind = "rubble_mound_breakwater";
  mound.crest_width_m = 10.0;
  mound.crest_elevation_m = 3.0;
  mound.side_slope = 1.5;
  mound.reflection_coefficient = 0.5;
  return basin_with(75, 25, 8.0, 8.0f, 300.0, mound);
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

// Issue 39 "done when": the Kr a structure asks for is what the BAKE gives, not only the flume the
// fit runs. A channel six cells wide with a rubble mound across it asking Kr 0.5, its footprint
// (core and faces, widened as the fit needs) laid by lay_structures at the case's cells, run by
// the 2-D solver with a regular wave from the west; Kr by Mansard & Funke in front of the faces,
// relative to the same channel with the faces open (the core alone), as the fit reads it. Across
// the k h of the demo's sea (16, 12 and 8.5 s over 8 m faces on 8 m cells: k h 0.36-0.76) and of a
// Tacoma wind sea (6 and 5 s over 12 m on 4 and 3 m cells: k h 1.5-2.0). Tolerance 0.05: the fit's
// 0.02 (kStructureFitTolerance), the separation's 0.02 over a partly standing wave (the flume's
// own five-wave check), and the one-cell difference a footprint laid from a line may make.
double channel_reflection(const HarbourGrid& grid, const boussinesq::SolverParameters& base, double period_s, double height_m,
                          double depth_m, double first_gauge_m, double last_gauge_m) {
  const double dx = grid.geometry.spacing_m, omega = 2.0 * std::numbers::pi / period_s;
  const double k = boussinesq::boussinesq_wavenumber(omega, depth_m, base.dispersion_coefficient);
  const double L = 2.0 * std::numbers::pi / k;
  boussinesq::SolverParameters parameters = base;
  parameters.breaking.enabled = false;
  parameters.sponges = {{boussinesq::Side::kWest, 1.5 * L}};
  const int steps_per_period = std::max(8, static_cast<int>(std::ceil(period_s / (0.5 * dx / std::sqrt(9.81 * depth_m)))));
  parameters.time_step_s = period_s / steps_per_period;
  boussinesq::WaveMaker maker;
  maker.kind = boussinesq::WaveMaker::Kind::kComponents;
  maker.sea_state.components.push_back({0.5 * height_m, omega, 0.0, 0.0});
  maker.source_line_m = 2.5 * L;
  maker.facing = boussinesq::Side::kWest;
  maker.ramp_time_s = 2.0 * period_s;
  boussinesq::BoussinesqSolver solver(grid, parameters, maker);
  std::vector<int> gauges;
  for (double x = first_gauge_m; x <= last_gauge_m + 1e-9; x += std::max(0.1 * L, dx)) gauges.push_back(static_cast<int>(x / dx));
  gauges.erase(std::unique(gauges.begin(), gauges.end()), gauges.end());
  // Steady after the front has crossed to the structure and back twice, with the ramp to spare.
  const double crossing_s = grid.geometry.columns * dx / ocean::group_speed_m_s(k, depth_m);
  const long spin_up_steps = static_cast<long>(std::ceil((3.0 * period_s + 2.5 * crossing_s) / period_s)) * steps_per_period;
  const long last_step = spin_up_steps + 4L * steps_per_period;
  std::vector<std::vector<double>> records(gauges.size());
  const int row = grid.geometry.rows / 2;
  for (long step = 1; step <= last_step; ++step) {
    solver.step();
    if (step <= spin_up_steps) continue;
    for (std::size_t g = 0; g < gauges.size(); ++g) records[g].push_back(solver.surface_elevation_m()(gauges[g], row));
  }
  std::vector<double> positions;
  std::vector<std::complex<double>> amplitudes;
  for (std::size_t g = 0; g < gauges.size(); ++g) {
    positions.push_back((gauges[g] + 0.5) * dx);
    amplitudes.push_back(boussinesq::harmonic_amplitude(records[g], (spin_up_steps + 1) * parameters.time_step_s, parameters.time_step_s, omega));
  }
  return boussinesq::separate_incident_reflected(positions, amplitudes, k).reflection_coefficient();
}

// The 2-D bake reflects what the flume fitted, across the k h of the demo (12 s swell over 8 m)
// and Tacoma (5-6 s over 12 m) seas: a straight mound across a six-row channel, Kr separated in
// front of it (Mansard & Funke) and divided by the core alone's, against the fit's own Kr in the
// sea and the request (at 6 and 5 s reached only with the layer's stones fitted too). Tolerance 0.05: the fit's depth bin moves Kr by
// <= 0.02 and the fit's tolerance is kStructureFitTolerance; the rest is what a 2-D channel with
// side walls and a bent footprint adds to the 1-D flume (measured <= 0.031). Before the faces were
// laid as the core dilated by the fitted count and the flume's wall was an interior wall, this
// read 0.298 at 16 s and 0.837 at 5 s for 0.5 asked (docs/structures.md).
TEST(StructureLayers, TheBakeReflectsWhatTheStructureAsksAcrossTheKhOfTheDemoAndTacomaSeas) {
  struct Case {
    double period_s, depth_m, cell_m, height_m;
  };
  for (const Case c : {Case{16.0, 8.0, 8.0, 1.0}, Case{12.0, 8.0, 8.0, 1.0}, Case{8.5, 8.0, 8.0, 1.0}, Case{6.0, 12.0, 4.0, 0.8},
                       Case{5.0, 12.0, 3.0, 0.8}}) {
    const double omega = 2.0 * std::numbers::pi / c.period_s;
    boussinesq::SolverParameters solver;
    if (c.cell_m >= 0.25 * c.depth_m) solver.shapiro_filter_order = 0;  // as the bake decides (docs/solver.md)
    const double k = boussinesq::boussinesq_wavenumber(omega, c.depth_m, solver.dispersion_coefficient);
    const double L = 2.0 * std::numbers::pi / k;
    // West sponge 1.5 L, source at 2.5 L, gauges from 3.3 L over 0.4 L, the mound's toe 0.3 L
    // beyond them, its centre line one footprint further, water behind to the east wall.
    GridGeometry geometry;
    geometry.spacing_m = c.cell_m;
    geometry.rows = 6;
    CoastalStructure mound;
    mound.name = "channel mound";
    mound.kind = "rubble_mound_breakwater";
    mound.crest_width_m = 10.0;
    mound.crest_elevation_m = 3.0;
    mound.side_slope = 1.5;
    mound.reflection_coefficient = 0.5;
    const double reach_m = mound.footprint_half_width_m(c.depth_m) + 6.0 * c.cell_m;  // faces widened by up to 4 cells
    const double first_gauge_m = 3.3 * L, last_gauge_m = 3.7 * L, centre_m = last_gauge_m + 0.3 * L + reach_m;
    geometry.columns = static_cast<int>(std::ceil((centre_m + reach_m + 2.0 * c.cell_m) / c.cell_m));
    HarbourGrid grid = HarbourGrid::open_water(geometry, static_cast<float>(c.depth_m));
    mound.lines = {{{centre_m, -10.0}, {centre_m, geometry.rows * c.cell_m + 10.0}}};
    grid.structures = {mound};
    StructureSeaState sea;
    sea.significant_wave_height_m = c.height_m;
    sea.peak_period_s = sea.spectral_period_s = sea.longest_period_s = sea.shortest_period_s = c.period_s;
    sea.waves = {{c.period_s, c.height_m}};
    std::vector<std::string> warnings;
    const std::vector<StructureLayer> layers = lay_structures(grid, solver, sea, warnings);
    ASSERT_EQ(layers.size(), 1u);
    ASSERT_TRUE(layers[0].fitted) << c.period_s << " s";
    // Every request is reached: at 6 s and 5 s only with finer effective stones (with the solver's
    // 1 m stones the widest layer reflects at least 0.8 of a 6 s wave and 0.55 of a 5 s one).
    EXPECT_TRUE(layers[0].reached) << c.period_s << " s: " << (warnings.empty() ? std::string() : warnings[0]);
    EXPECT_TRUE(warnings.empty()) << c.period_s << " s";
    EXPECT_EQ(layers[0].stones_fitted, c.period_s < 8.0) << c.period_s << " s";
    if (layers[0].stones_fitted) {
      ASSERT_EQ(grid.porous_stone_diameter_m.size(), grid.porosity.size());
      EXPECT_LT(layers[0].stone_diameter_m, solver.porous.stone_diameter_m);
    } else {
      EXPECT_EQ(grid.porous_stone_diameter_m.size(), 0u);
    }
    const double with_faces = channel_reflection(grid, solver, c.period_s, c.height_m, c.depth_m, first_gauge_m, last_gauge_m);
    HarbourGrid core_alone = grid;
    for (float& n : core_alone.porosity.values())
      if (n > 0.0f) n = 1.0f;
    const double wall = channel_reflection(core_alone, solver, c.period_s, c.height_m, c.depth_m, first_gauge_m, last_gauge_m);
    const double kr = with_faces / wall;
    std::printf("%.1f s over %.0f m on %.0f m cells (k h %.2f): faces n %.3f, stones %.3g m, %.0f m widened; Kr in the flume %.3f, in "
                "the 2-D bake %.3f (%.3f / wall alone %.3f)\n",
                c.period_s, c.depth_m, c.cell_m, k * c.depth_m, layers[0].face_porosity, layers[0].stone_diameter_m, layers[0].widening_m,
                layers[0].in_the_sea.reflection_coefficient, kr, with_faces, wall);
    EXPECT_NEAR(kr, layers[0].in_the_sea.reflection_coefficient, 0.05) << c.period_s << " s, k h " << k * c.depth_m;
    EXPECT_NEAR(kr, 0.5, 0.05) << c.period_s << " s, k h " << k * c.depth_m;
  }
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

// A pier on piles (Kt 0.9 asked) in 0.5 m of water on 12 m cells under Commencement Bay's carried
// band (four waves of 7.3-10 s, Hs 0.34 m): there the waves are 1.5-1.8 cells long, which neither the
// flume nor the bake carries, and a fit in that water measured each wave's transmission as 0.0-33.
// The fit runs in the shallowest water where the shortest wave is four cells long (docs/structures.md,
// "Water too shallow for the grid's waves"), so what it measures is a porous layer's: no wave
// comes through stronger than it went in.
TEST(StructureLayers, AFitInWaterTooShallowForTheGridsWavesRunsWhereTheyAreCarried) {
  CoastalStructure pier;
  pier.name = "shallow pier";
  pier.kind = "pier";
  pier.crest_width_m = 6.0;
  pier.crest_elevation_m = 2.5;
  pier.side_slope = 0.0;
  pier.reflection_coefficient = 0.1;
  pier.transmission_coefficient = 0.9;
  HarbourGrid grid = basin_with(40, 6, 12.0, 0.5f, 240.0, pier);
  boussinesq::SolverParameters solver;
  solver.dispersion_cutoff_depth_m = 0.5;  // the Tacoma case's
  solver.shapiro_filter_order = 0;         // as the bake derives it for 12 m cells there
  StructureSeaState sea;
  sea.significant_wave_height_m = 0.34;
  sea.peak_period_s = sea.spectral_period_s = 8.0;
  sea.longest_period_s = 10.0;
  sea.shortest_period_s = 7.3;
  for (double period_s : {10.0, 8.9, 8.0, 7.3}) sea.waves.push_back({period_s, 2.0 * std::sqrt(2.0 * std::pow(0.34 / 4.0, 2) / 4.0)});
  std::vector<std::string> warnings;
  const std::vector<StructureLayer> layers = lay_structures(grid, solver, sea, warnings);
  ASSERT_EQ(layers.size(), 1u);
  const StructureLayer& layer = layers[0];
  ASSERT_TRUE(layer.fitted);
  EXPECT_NEAR(layer.depth_m, 0.5, 1e-6);
  // Four cells of 12 m for the 7.3 s wave (Airy): tanh(k d) = omega^2 / (g k), k = 2 pi / 48 m.
  const double k = 2.0 * std::numbers::pi / 48.0, omega = 2.0 * std::numbers::pi / 7.3;
  const double resolved_m = std::atanh(omega * omega / (9.81 * k)) / k;
  EXPECT_NEAR(layer.flume_depth_m, resolved_m, 0.01);
  EXPECT_NEAR(layer.in_the_sea.transmission_coefficient, 0.9, kStructureFitTolerance);
  ASSERT_EQ(layer.across_band.size(), 4u);
  for (const auto& wave : layer.across_band) {
    EXPECT_LE(wave.transmission_coefficient, 1.0 + kStructureFitTolerance) << wave.period_s << " s";
    EXPECT_GE(wave.transmission_coefficient, 0.7) << wave.period_s << " s";
  }
  const std::string report = describe_structure_layers(layers);
  RecordProperty("report", report);
  EXPECT_NE(report.find(fmt::format("fitted in {:.1f} m", resolved_m)), std::string::npos) << report;
  EXPECT_DOUBLE_EQ(structure_layers_record(layers)[0]["flume_depth_m"].get<double>(), layer.flume_depth_m);
}

TEST(StructureLayers, SurviveResamplingAndTheHarbourGridFile) {
  HarbourGrid grid = basin_with_breakwater();
  const auto file = testing::scratch_folder() / "depth.exr";
  write_harbour_grid(file, grid);
  const HarbourGrid again = read_harbour_grid(file);
  EXPECT_EQ(nlohmann::json(again.structures), nlohmann::json(grid.structures));
  const HarbourGrid coarse = resample_harbour_grid(again, CellSize(16.0));
  EXPECT_EQ(coarse.structures.size(), 1u);
  EXPECT_EQ(again.porous_stone_diameter_m.size(), 0u);  // a grid without stones of its own reads as one

  // Stones of its own (a fit that needed them) survive the file and resampling; a file whose
  // channel holds no positive diameter is refused, naming the file and the cell.
  grid.porous_stone_diameter_m = Raster<float>(grid.geometry.columns, grid.geometry.rows, 1.0f);
  grid.porous_stone_diameter_m(37, 5) = 0.1f;
  write_harbour_grid(file, grid);
  const HarbourGrid with_stones = read_harbour_grid(file);
  ASSERT_EQ(with_stones.porous_stone_diameter_m.size(), grid.porosity.size());
  EXPECT_EQ(with_stones.porous_stone_diameter_m.values(), grid.porous_stone_diameter_m.values());
  const HarbourGrid same_cells = resample_harbour_grid(with_stones, CellSize(grid.geometry.spacing_x_m()));
  EXPECT_EQ(same_cells.porous_stone_diameter_m.values(), grid.porous_stone_diameter_m.values());
  grid.porous_stone_diameter_m(3, 4) = -1.0f;
  write_harbour_grid(file, grid);
  try {
    (void)read_harbour_grid(file);
    ADD_FAILURE() << "a negative stone diameter was read";
  } catch (const Error& error) {
    EXPECT_NE(error.problem().find("(3, 4)"), std::string::npos) << error.problem();
    EXPECT_NE(error.subject().find("depth.exr"), std::string::npos) << error.subject();
  }
}

}  // namespace
}  // namespace nearshore::bake
