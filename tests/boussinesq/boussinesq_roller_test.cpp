// The surface roller breaking model (BreakingParameters::Model::kRoller; Schaffer, Madsen & Deigaard
// 1993, Madsen, Sorensen & Schaffer 1997): where it forms, which way it pushes, that it leaves
// waves that do not break alone, and that it refuses to run without the time scale of its decay.
// Its laboratory score is the Hansen & Svendsen (1979) validation (docs/validation.md).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <vector>

#include "boussinesq_test_support.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::boussinesq::testing {
namespace {

constexpr double kDepth_m = 0.5, kSpacing_m = 0.05;
constexpr int kColumns = 200, kRows = 3;

SolverParameters roller_parameters() {
  SolverParameters parameters = inviscid_parameters();
  parameters.breaking.enabled = true;
  parameters.breaking.model = BreakingParameters::Model::kRoller;
  parameters.breaking.roller_half_time_s = 0.4;  // no wave maker: the decay's time scale given directly
  parameters.shapiro_filter_order = 0;           // the comparisons below see the roller's force alone
  return parameters;
}

// A bore-like surface travelling east: still water ahead of x_toe, a straight front rising at
// `slope` (m/m) up to the crest level `crest_m`, a flat crest behind it; the flux P = c eta with the
// long-wave celerity, so the water under the crest moves with the wave.
struct Front {
  double x_toe_m = 6.0, slope = 0.5, crest_m = 0.1;
  double eta(double x) const { return std::clamp((x_toe_m - x) * slope, 0.0, crest_m); }
};

BoussinesqSolver& start(BoussinesqSolver& solver, const Front& front) {
  const double celerity = std::sqrt(9.81 * kDepth_m);
  solver.set_initial_condition([&](double x, double) { return front.eta(x); },
                               [&](double x, double) { return celerity * front.eta(x); }, [](double, double) { return 0.0; });
  return solver;
}

// Two steps: a roller needs a rising front (eta^n > eta^{n-1}), so the first step from rest
// finds none; the second finds the roller of the state after the first.
void two_steps(BoussinesqSolver& solver) {
  solver.step();
  solver.step();
}

// The cells flagged by the breaking indicator on the middle row.
std::vector<int> roller_cells(const BoussinesqSolver& solver) {
  std::vector<int> cells;
  for (int c = 0; c < kColumns; ++c)
    if (solver.breaking_indicator()(c, 1) > 0.0f) cells.push_back(c);
  return cells;
}

TEST(BoussinesqRoller, FormsOnAFrontSteeperThanTheOnsetAngleOnly) {
  const HarbourGrid harbour = flume(kColumns, kRows, kSpacing_m, kDepth_m);
  // tan(20 deg) = 0.364: a front of slope 0.5 breaks, one of 0.3 does not (Madsen et al. 1997).
  BoussinesqSolver steep(harbour, roller_parameters(), WaveMaker{});
  two_steps(start(steep, Front{6.0, 0.5, 0.1}));
  const std::vector<int> cells = roller_cells(steep);
  ASSERT_FALSE(cells.empty());
  // The roller lies on the front, between its toe (x = 6 m, cell 120) and its crest (x = 5.8 m,
  // cell 116); the 1-2-1 smoothing of the stresses does not move the indicator.
  for (int c : cells) {
    EXPECT_GE(c, 113) << c;
    EXPECT_LE(c, 122) << c;
  }
  BoussinesqSolver gentle(harbour, roller_parameters(), WaveMaker{});
  two_steps(start(gentle, Front{6.0, 0.3, 0.1}));
  EXPECT_TRUE(roller_cells(gentle).empty());
}

TEST(BoussinesqRoller, PushesMomentumFromTheCrestToTheToe) {
  // The roller's excess momentum flux R = delta (c - u)^2 / (1 - delta/h) is largest on the front
  // and zero ahead of the toe: its divergence -dR/dx accelerates the water at the toe and
  // decelerates it behind (Schaffer et al. 1993), and sums to zero over the flume (a stress).
  const HarbourGrid harbour = flume(kColumns, kRows, kSpacing_m, kDepth_m);
  SolverParameters none = roller_parameters();
  none.breaking.enabled = false;
  BoussinesqSolver with_roller(harbour, roller_parameters(), WaveMaker{});
  BoussinesqSolver without(harbour, none, WaveMaker{});
  const Front front{6.0, 0.5, 0.1};
  two_steps(start(with_roller, front));
  two_steps(start(without, front));
  Raster<float> p_roller, q_roller, p_none, q_none;
  with_roller.cell_centred_fluxes(p_roller, q_roller);
  without.cell_centred_fluxes(p_none, q_none);
  double ahead = 0.0, behind = 0.0, total = 0.0, largest = 0.0;
  for (int c = 0; c < kColumns; ++c) {
    const double change = p_roller(c, 1) - p_none(c, 1);
    total += change;
    largest = std::max(largest, std::abs(change));
    if (c >= 118 && c <= 122) ahead += change;
    if (c >= 110 && c <= 116) behind += change;
  }
  EXPECT_GT(largest, 1e-5);  // the roller acts (m^2/s in one step)
  EXPECT_GT(ahead, 0.0);
  EXPECT_LT(behind, 0.0);
  // Sum of a divergence over cells averaged from faces: zero up to float output (1e-7 relative).
  EXPECT_LT(std::abs(total), 1e-3 * largest);
}

TEST(BoussinesqRoller, LeavesWavesThatDoNotBreakBitIdentical) {
  // A standing wave of 1 cm in 0.5 m never steepens to 20 degrees: the roller model must give the
  // eddy-viscosity model's state bit for bit (neither model acts; the step is the same code).
  const HarbourGrid harbour = flume(60, 5, 0.1, kDepth_m);
  SolverParameters eddy = roller_parameters();
  eddy.breaking.model = BreakingParameters::Model::kEddyViscosity;
  eddy.shapiro_filter_order = 8;
  SolverParameters roller = roller_parameters();
  roller.shapiro_filter_order = 8;
  std::string states[2];
  int k = 0;
  for (const SolverParameters& parameters : {eddy, roller}) {
    BoussinesqSolver solver(harbour, parameters, WaveMaker{});
    solver.set_surface_elevation([](double x, double) { return 0.01 * std::cos(M_PI * x / 6.0); });
    for (int i = 0; i < 200; ++i) solver.step();
    std::ostringstream out;
    solver.save_state(out);
    states[k++] = out.str();
  }
  EXPECT_EQ(states[0], states[1]);
}

TEST(BoussinesqRoller, ContinuesBitIdenticallyFromASavedState) {
  // The roller's state is the solver's (start times in breaking_start_s, eta^{n-1}): a run saved
  // while a roller lives and loaded into a new solver goes on with the same bits.
  const HarbourGrid harbour = flume(kColumns, kRows, kSpacing_m, kDepth_m);
  BoussinesqSolver first(harbour, roller_parameters(), WaveMaker{});
  two_steps(start(first, Front{6.0, 0.5, 0.1}));
  ASSERT_FALSE(roller_cells(first).empty());
  std::stringstream saved;
  first.save_state(saved);
  BoussinesqSolver second(harbour, roller_parameters(), WaveMaker{});
  second.load_state(saved);
  for (int i = 0; i < 5; ++i) {
    first.step();
    second.step();
  }
  std::ostringstream a, b;
  first.save_state(a);
  second.save_state(b);
  EXPECT_EQ(a.str(), b.str());
}

TEST(BoussinesqRoller, NeedsTheHalfTimeOfItsDecayWithoutAPeriodicWaveMaker) {
  SolverParameters parameters = roller_parameters();
  parameters.breaking.roller_half_time_s = 0.0;  // and the wave maker has no period to take it from
  EXPECT_THROW(BoussinesqSolver(flume(20, 3, 0.1, kDepth_m), parameters, WaveMaker{}), Error);
}

}  // namespace
}  // namespace nearshore::boussinesq::testing
