// The solver's memory per cell (issue 15): the arrays of docs/solver.md "Memory" add up to what
// BoussinesqSolver::memory_bytes() counts, within the budget that lets a 4000 x 4000 harbour bake
// in 24 GB. Deterministic: it counts allocations, it does not read the resident set.
#include <gtest/gtest.h>

#include <numbers>

#include "boussinesq_test_support.hpp"

namespace nearshore::boussinesq {
namespace {

// A 600 x 500 harbour (1 m cells, so the per-line sweep scratch is small next to the cells) with
// sponges on three sides, waves and breaking on: every array a bake allocates.
TEST(BoussinesqMemory, ArraysPerCellStayWithinTheBudget) {
  HarbourGrid harbour = testing::flume(600, 500, 1.0, 3.0);
  for (int r = 0; r < 500; ++r)
    for (int c = 0; c < 600; ++c) harbour.porosity(c, r) = (r == 250 && c > 100) ? 0.4f : 1.0f;
  SolverParameters parameters;
  parameters.sponges = {{Side::kSouth, 20.0}, {Side::kWest, 20.0}, {Side::kEast, 20.0}};
  WaveMaker wave_maker;
  wave_maker.kind = WaveMaker::Kind::kComponents;
  wave_maker.sea_state.components = {{0.2, 2.0 * std::numbers::pi / 6.0, 0.5 * std::numbers::pi, 0.0}};
  wave_maker.source_line_m = 40.0;
  wave_maker.facing = Side::kSouth;
  BoussinesqSolver solver(harbour, parameters, wave_maker);
  solver.step();  // the per-thread sweep scratch exists from the first step
  const double cells = 600.0 * 500.0;
  const double bytes_per_cell = static_cast<double>(solver.memory_bytes()) / cells;
  RecordProperty("solver_bytes_per_cell", std::to_string(bytes_per_cell));
  // docs/solver.md "Memory": 173 B per cell of arrays, 28 B of the fully nonlinear remainder's
  // history, subcritical factors and the breaking strength they fade by (the default equations) and 16 B of the second ADI pass's
  // previous increment and surface (the default two passes), plus 48 B per cell of sponge (12 % of
  // this grid: ~6 B) and the per-line scratch (~2.9 kB per column of the longest line per thread:
  // ~6 B per cell on 1-2 threads here); measured 234 B. The bound is the table's sum with a margin of about 5 %.
  EXPECT_LE(bytes_per_cell, 240.0) << "an array was added to the solver: update docs/solver.md \"Memory\"";
  EXPECT_GE(bytes_per_cell, 217.0) << "memory_bytes() no longer counts every array";
  // A 4000 x 4000 grid's solver arrays fit well inside 24 GB.
  EXPECT_LT(bytes_per_cell * 4000.0 * 4000.0, 4e9);
}

}  // namespace
}  // namespace nearshore::boussinesq
