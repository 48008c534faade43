// The fully nonlinear equations (SolverParameters::equations = kFullyNonlinear, issue 19) keep every
// invariant the seed's equations have: a lake at rest stays at rest over rough bathymetry with
// wetting, drying and porous cells; a closed basin keeps its water to round-off while a hump runs
// up a beach; one and two threads give the same bits; a saved state resumes bit-identically (the
// remainder's history is part of it); a wave along y is the wave along x transposed. And the
// second-order generation of a regular wave (WaveMaker::second_order) takes the free-harmonic beat
// out of a flat flume. Where cells break the terms fade (BreakingParameters::fade_fully_nonlinear_terms),
// through the breaking strength alone. Their nonlinear accuracy: boussinesq_nonlinear_test.cpp.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <sstream>
#include <vector>

#include "boussinesq_test_support.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::boussinesq {

using namespace nearshore::ocean;
namespace {

SolverParameters fully_nonlinear() {
  SolverParameters parameters;  // friction, breaking, porous resistance on
  parameters.equations = Equations::kFullyNonlinear;
  parameters.face_depth = SolverParameters::FaceDepth::kMeanWhereWet;
  return parameters;
}

WaveMaker oblique_regular_waves() {
  WaveMaker maker;
  maker.kind = WaveMaker::Kind::kComponents;
  maker.sea_state.components = {{0.2, 2.0 * std::numbers::pi / 4.0, 0.3, 0.5}};
  maker.source_line_m = 12.0;
  maker.facing = Side::kWest;
  maker.ramp_time_s = 4.0;
  return maker;
}

void add_hump(BoussinesqSolver& solver) {
  solver.set_surface_elevation([](double x, double y) { return 0.8 * std::exp(-((x - 30) * (x - 30) + (y - 20) * (y - 20)) / 20.0); });
}

TEST(FullyNonlinear, LakeAtRestOverRoughBathymetryStaysExactlyAtRest) {
  const HarbourGrid harbour = testing::rough_basin();
  SolverParameters parameters = fully_nonlinear();
  parameters.sponges = {{Side::kWest, 6.0}};
  BoussinesqSolver solver(harbour, parameters, WaveMaker{});
  for (int i = 0; i < 200; ++i) solver.step();
  // The remainder is built from velocities and slopes of the surface, all exactly 0 at rest (land
  // cells carry minus their elevation, as with the seed's equations).
  Raster<float> flux_x, flux_y;
  solver.cell_centred_fluxes(flux_x, flux_y);
  for (int r = 0; r < 40; ++r)
    for (int c = 0; c < 60; ++c) {
      if (harbour.still_water_depth_m(c, r) > 0.0) {
        ASSERT_EQ(solver.surface_elevation_m()(c, r), 0.0f) << c << ", " << r;
      }
      ASSERT_EQ(flux_x(c, r), 0.0f);
      ASSERT_EQ(flux_y(c, r), 0.0f);
    }
}

TEST(FullyNonlinear, ClosedBasinKeepsItsWaterToRoundOffWhileAHumpRunsUpTheBeach) {
  const HarbourGrid harbour = testing::rough_basin();
  SolverParameters parameters = fully_nonlinear();
  parameters.dispersion_cutoff_depth_m = 0.3;
  BoussinesqSolver solver(harbour, parameters, WaveMaker{});
  add_hump(solver);
  const double initial_m3 = solver.water_volume_m3();
  double worst_relative = 0.0, wetted = 0.0;
  for (int i = 0; i < 400; ++i) {
    solver.step();
    worst_relative = std::max(worst_relative, std::abs(solver.water_volume_m3() / initial_m3 - 1.0));
    for (int r = 0; r < 40; ++r)
      for (int c = 0; c < 60; ++c)
        if (harbour.still_water_depth_m(c, r) < 0.0)
          wetted = std::max(wetted, harbour.still_water_depth_m(c, r) + double(solver.surface_elevation_m()(c, r)));
  }
  ASSERT_FALSE(solver.check_stability().has_value()) << solver.check_stability()->what;
  // The terms act in the momentum equations only: the mass equation is the seed's flux form.
  EXPECT_LT(worst_relative, 1e-12);
  std::printf("worst relative volume change %.3g, highest water on initially dry land %.3f m\n", worst_relative, wetted);
  EXPECT_GT(wetted, 0.02);
}

TEST(FullyNonlinear, OneAndTwoThreadsGiveBitIdenticalResults) {
  const HarbourGrid harbour = testing::rough_basin();
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    SolverParameters parameters = fully_nonlinear();
    parameters.alternate_sweep_order = true;
    parameters.dispersion_cutoff_depth_m = 0.3;
    parameters.sponges = {{Side::kWest, 6.0}, {Side::kEast, 6.0}};
    BoussinesqSolver solver(harbour, parameters, oblique_regular_waves());
    for (int i = 0; i < 150; ++i) solver.step();
    return testing::solver_snapshot(solver);
  };
  const std::vector<float> one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(float)), 0);
}

TEST(FullyNonlinear, SavedStateResumesBitIdenticallyAndIsRefusedByTheSeedsEquations) {
  const HarbourGrid harbour = testing::rough_basin();
  SolverParameters parameters = fully_nonlinear();
  parameters.sponges = {{Side::kWest, 6.0}};
  BoussinesqSolver uninterrupted(harbour, parameters, oblique_regular_waves());
  add_hump(uninterrupted);
  for (int i = 0; i < 120; ++i) uninterrupted.step();
  std::stringstream state;
  {
    BoussinesqSolver first_half(harbour, parameters, oblique_regular_waves());
    add_hump(first_half);
    for (int i = 0; i < 60; ++i) first_half.step();
    first_half.save_state(state);
  }
  const std::string bytes = state.str();
  BoussinesqSolver resumed(harbour, parameters, oblique_regular_waves());
  resumed.load_state(state);
  for (int i = 0; i < 60; ++i) resumed.step();
  const std::vector<float> a = testing::solver_snapshot(uninterrupted), b = testing::solver_snapshot(resumed);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
  // The same grid with the seed's equations: refused, naming the equations as a possible cause.
  SolverParameters seed = parameters;
  seed.equations = Equations::kWeaklyNonlinear;
  BoussinesqSolver other(harbour, seed, oblique_regular_waves());
  std::stringstream again(bytes);
  try {
    other.load_state(again);
    FAIL() << "a fully nonlinear state loaded into the seed's equations";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("equations"), std::string::npos) << e.what();
  }
}

// BreakingParameters::fade_fully_nonlinear_terms: a hump of a third of the depth runs up a 1:10
// beach in a flume one cell across and breaks (the eddy viscosity's strength B reaches 1). The fade
// acts only through B: until a cell first breaks the faded and unfaded runs are the same bits, and
// after it they part; with the seed's equations the flag does nothing; the water is kept to
// round-off; and a state saved while cells break resumes bit for bit (the x sweep's copy of B is
// rebuilt from the saved strength). Its effect on the surf zone's mean level is measured on Hansen &
// Svendsen (docs/solver.md, "The fully nonlinear terms where waves break").
HarbourGrid breaking_beach() {
  HarbourGrid harbour = testing::flume(320, 1, 0.025, 0.36);
  for (int c = 0; c < 320; ++c) {
    const double x = (c + 0.5) * 0.025;
    harbour.still_water_depth_m(c, 0) = static_cast<float>(std::min(0.36, 0.36 - (x - 3.0) / 10.0));
  }
  return harbour;
}

SolverParameters beach_parameters(bool fade) {
  SolverParameters parameters = fully_nonlinear();  // closed: a sponge would take water
  parameters.breaking.fade_fully_nonlinear_terms = fade;
  return parameters;
}

void add_beach_hump(BoussinesqSolver& solver) {
  solver.set_surface_elevation([](double x, double) { return 0.12 * std::exp(-(x - 2.0) * (x - 2.0) / 0.08); });
}

float largest_breaking_strength(const BoussinesqSolver& solver) {
  const std::vector<float>& strength = solver.breaking_indicator().values();
  return *std::max_element(strength.begin(), strength.end());
}

TEST(FullyNonlinearFade, ActsOnlyWhereCellsBreakAndKeepsTheWater) {
  const HarbourGrid harbour = breaking_beach();
  BoussinesqSolver faded(harbour, beach_parameters(true), WaveMaker{}), kept(harbour, beach_parameters(false), WaveMaker{});
  add_beach_hump(faded);
  add_beach_hump(kept);
  const double initial_m3 = faded.water_volume_m3();
  int first_break = -1, identical_steps = 0;
  float strongest = 0.0f;
  double parted_m = 0.0;
  for (int i = 0; i < 1200; ++i) {
    const bool breaks = largest_breaking_strength(faded) > 0.0f;  // B of the state this step starts from
    if (breaks && first_break < 0) first_break = i;
    faded.step();
    kept.step();
    strongest = std::max(strongest, largest_breaking_strength(faded));
    const std::vector<float> a = testing::solver_snapshot(faded), b = testing::solver_snapshot(kept);
    const bool same = std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
    if (first_break < 0) {
      ASSERT_TRUE(same) << "the runs parted at step " << i << " before any cell broke";
      ++identical_steps;
    }
    const std::vector<float>&eta_a = faded.surface_elevation_m().values(), &eta_b = kept.surface_elevation_m().values();
    for (std::size_t k = 0; k < eta_a.size(); ++k) parted_m = std::max(parted_m, std::abs(double(eta_a[k]) - double(eta_b[k])));
  }
  ASSERT_FALSE(faded.check_stability().has_value()) << faded.check_stability()->what;
  std::printf("first break at step %d (identical before it: %d steps), strongest B %.2f, largest difference of the surface %.3g m\n",
              first_break, identical_steps, strongest, parted_m);
  ASSERT_GT(first_break, 10);   // the hump needs to run up the beach first
  EXPECT_EQ(strongest, 1.0f);   // it breaks in full
  EXPECT_GT(parted_m, 1e-4);    // and the fade acts where it does (0.1 mm)
  EXPECT_LT(std::abs(faded.water_volume_m3() / initial_m3 - 1.0), 1e-12);
}

TEST(FullyNonlinearFade, DoesNothingWithTheSeedsEquationsAndResumesFromASavedState) {
  const HarbourGrid harbour = breaking_beach();
  // The seed's equations have no fully nonlinear terms to fade.
  std::string states[2];
  for (int k = 0; k < 2; ++k) {
    SolverParameters parameters = beach_parameters(k == 0);
    parameters.equations = Equations::kWeaklyNonlinear;
    BoussinesqSolver solver(harbour, parameters, WaveMaker{});
    add_beach_hump(solver);
    for (int i = 0; i < 700; ++i) solver.step();
    std::ostringstream out;
    solver.save_state(out);
    states[k] = out.str();
  }
  EXPECT_EQ(states[0], states[1]);
  // Saved while cells break, loaded into a new solver: the same bits as the run that went on.
  BoussinesqSolver uninterrupted(harbour, beach_parameters(true), WaveMaker{});
  add_beach_hump(uninterrupted);
  int i = 0;
  while (largest_breaking_strength(uninterrupted) == 0.0f && i < 1200) {
    uninterrupted.step();
    ++i;
  }
  ASSERT_LT(i, 1200) << "nothing broke";
  for (int k = 0; k < 20; ++k) uninterrupted.step();  // well inside the event
  ASSERT_GT(largest_breaking_strength(uninterrupted), 0.0f);
  std::stringstream saved;
  uninterrupted.save_state(saved);
  BoussinesqSolver resumed(harbour, beach_parameters(true), WaveMaker{});
  resumed.load_state(saved);
  for (int k = 0; k < 60; ++k) {
    uninterrupted.step();
    resumed.step();
  }
  const std::vector<float> a = testing::solver_snapshot(uninterrupted), b = testing::solver_snapshot(resumed);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
}

// The code of the y direction against the x direction's: a regular wave along a flume laid along
// y is the same wave as along x. Not bit for bit (x is swept first), so within 1e-4 of its height.
TEST(FullyNonlinear, AWaveAlongYIsTheWaveAlongXTransposed) {
  const int length = 200, width = 3;
  const double dx = 0.05, depth = 0.4;
  auto run = [&](bool along_x) {
    const HarbourGrid harbour = along_x ? testing::flume(length, width, dx, depth) : testing::flume(width, length, dx, depth);
    SolverParameters parameters = fully_nonlinear();
    parameters.chezy_coefficient = 0.0;
    parameters.breaking.enabled = false;
    parameters.sponges = {{along_x ? Side::kEast : Side::kNorth, 2.0}};
    WaveMaker maker;
    maker.kind = WaveMaker::Kind::kComponents;
    maker.sea_state.components = {{0.02, 2.0 * std::numbers::pi / 1.2, along_x ? 0.0 : 0.5 * std::numbers::pi, 0.0}};
    maker.source_line_m = 2.0;
    maker.facing = along_x ? Side::kWest : Side::kSouth;
    maker.ramp_time_s = 1.2;
    BoussinesqSolver solver(harbour, parameters, maker);
    for (int i = 0; i < 600; ++i) solver.step();
    std::vector<double> profile(length);
    for (int i = 0; i < length; ++i) profile[i] = along_x ? solver.surface_elevation_m()(i, 1) : solver.surface_elevation_m()(1, i);
    return profile;
  };
  const std::vector<double> x = run(true), y = run(false);
  double largest = 0.0, difference = 0.0;
  for (int i = 0; i < length; ++i) {
    largest = std::max(largest, std::abs(x[i]));
    difference = std::max(difference, std::abs(x[i] - y[i]));
  }
  EXPECT_GT(largest, 0.015);
  EXPECT_LT(difference, 1e-4 * 0.04) << "largest difference " << difference << " m";
}

// Hansen & Svendsen's 031041 wave (H = 4.11 cm, T = 3.33 s, 0.36 m deep: Ursell 33) along an 80 m
// flat flume. A source of the first harmonic alone sheds a free second harmonic of the opposite
// sign to the bound one; the two beat along the flume (length 2 pi / (k(2w) - 2 k(w)), about 35 m)
// and the height swings by +-6 %, about a mean 5 % above the request (the wave's odd harmonics
// add to its crest-to-trough height). With second_order the line radiates the bound harmonic as a
// free wave and sets the first harmonic by the crest-to-trough height: the mean is the request
// within 1 %, and what swings is the third-order beat of the third harmonic (length
// 2 pi / (k(3w) - 3 k(w)), about 10 m), +-3 % (measured 6.5 %, 5.5 % with the seed's equations).
TEST(SecondOrderGeneration, RemovesTheFreeSecondHarmonicBeatFromAFlatFlume) {
  const double depth_m = 0.36, period_s = 3.33, height_m = 0.0411, dx = 0.05;
  for (const Equations equations : {Equations::kWeaklyNonlinear, Equations::kFullyNonlinear}) {
    auto spread = [&](bool second_order, double& mean_height_m) {
      const HarbourGrid harbour = testing::flume(1600, 1, dx, depth_m);
      SolverParameters parameters = testing::inviscid_parameters(0.5);
      parameters.equations = equations;
      parameters.face_depth = SolverParameters::FaceDepth::kMeanWhereWet;
      parameters.sponges = {{Side::kWest, 6.0}, {Side::kEast, 12.0}};
      WaveMaker maker;
      maker.kind = WaveMaker::Kind::kComponents;
      maker.sea_state.components = {{0.5 * height_m, 2.0 * std::numbers::pi / period_s, 0.0, 0.0}};
      maker.source_line_m = 11.0;
      maker.facing = Side::kWest;
      maker.ramp_time_s = 2 * period_s;
      maker.second_order = second_order;
      BoussinesqSolver solver(harbour, parameters, maker);
      std::vector<double> highest, lowest;  // per gauge and period
      std::vector<std::vector<double>> heights;
      const int gauges = 27;
      heights.assign(gauges, {});
      highest.assign(gauges, -1.0);
      lowest.assign(gauges, 1.0);
      double window_start = 50.0;
      while (solver.time_s() < 80.0) {
        solver.step();
        if (solver.time_s() < window_start) continue;
        for (int g = 0; g < gauges; ++g) {
          const double eta = solver.surface_elevation_at(13.0 + 2.0 * g, 0.5 * dx);
          highest[g] = std::max(highest[g], eta);
          lowest[g] = std::min(lowest[g], eta);
        }
        if (solver.time_s() >= window_start + period_s) {  // one whole period per sample
          for (int g = 0; g < gauges; ++g) {
            heights[g].push_back(highest[g] - lowest[g]);
            highest[g] = -1.0, lowest[g] = 1.0;
          }
          window_start += period_s;
        }
      }
      double smallest = 1.0, largest = 0.0, sum = 0.0;
      for (const auto& gauge : heights) {
        double mean = 0.0;
        for (double h : gauge) mean += h / gauge.size();
        smallest = std::min(smallest, mean), largest = std::max(largest, mean), sum += mean / gauges;
      }
      mean_height_m = sum;
      return (largest - smallest) / sum;
    };
    double linear_mean = 0.0, second_mean = 0.0;
    const double linear = spread(false, linear_mean), second = spread(true, second_mean);
    std::printf("%s: height spread along the flume %.1f %% (mean %.2f mm) first harmonic alone, %.1f %% (mean %.2f mm) second order\n",
                equations == Equations::kFullyNonlinear ? "fully nonlinear" : "seed's equations", 100 * linear, 1000 * linear_mean,
                100 * second, 1000 * second_mean);
    EXPECT_GT(linear, 0.10);
    EXPECT_LT(second, 0.075);
    EXPECT_NEAR(second_mean / height_m, 1.0, 0.01);
  }
}

}  // namespace
}  // namespace nearshore::boussinesq
