#pragma once
// The square-cell regression scenario of issue 15 (rectangular cells): every term of the solver at
// once on square cells, so that a change of the rectangular-cell code that moves a single bit of
// the square scheme shows in the XXH64 of the saved state. The rough basin (porous breakwater,
// quay wall, beached island: wetting and drying), a 0.8 m hump that breaks on the island, an
// oblique regular wave from a source line facing south, sponges on two sides, friction, two ADI
// passes with alternating sweep order and the Shapiro filter. 120 steps.
#include <cstdint>
#include <numbers>
#include <span>
#include <sstream>
#include <string>

#include "boussinesq_test_support.hpp"
#include "nearshore/core/hash.hpp"

namespace nearshore::boussinesq::testing {

inline std::uint64_t square_regression_state_hash() {
  const HarbourGrid harbour = rough_basin();
  SolverParameters parameters;  // friction, breaking and porous resistance on
  // The seed's scheme as it was before issue 19 changed the defaults (fully nonlinear terms, mean
  // face depth, second-order generation: their invariants are boussinesq_fully_nonlinear_test.cpp's),
  // so the hash keeps guarding every bit of it. (Issue 19's breaking event that travels with the
  // front does not act in these 120 steps: the hash is the one recorded before it. Its thresholds on
  // the still-water depth do: boussinesq_rectangular_test.cpp.)
  parameters.equations = Equations::kWeaklyNonlinear;
  parameters.face_depth = SolverParameters::FaceDepth::kLargerOfMeanAndAboveBed;
  parameters.dispersion_cutoff_depth_m = 0.3;
  parameters.sponges = {{Side::kWest, 6.0}, {Side::kNorth, 5.0}};
  parameters.adi_passes = 2;
  parameters.alternate_sweep_order = true;
  WaveMaker maker;
  maker.kind = WaveMaker::Kind::kComponents;
  maker.sea_state.components = {{0.05, 2.0 * std::numbers::pi / 4.0, 0.4 * std::numbers::pi, 0.3}};
  maker.source_line_m = 4.0;
  maker.facing = Side::kSouth;
  maker.ramp_time_s = 2.0;
  maker.second_order = false;
  BoussinesqSolver solver(harbour, parameters, maker);
  solver.set_surface_elevation(
      [](double x, double y) { return 0.8 * std::exp(-((x - 30) * (x - 30) + (y - 20) * (y - 20)) / 20.0); });
  for (int i = 0; i < 120; ++i) solver.step();
  std::ostringstream state;
  solver.save_state(state);
  const std::string bytes = state.str();
  return xxh64(std::span(reinterpret_cast<const std::byte*>(bytes.data()), bytes.size()));
}

}  // namespace nearshore::boussinesq::testing
