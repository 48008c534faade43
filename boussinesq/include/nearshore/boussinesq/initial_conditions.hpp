#pragma once
// Initial conditions beside the solver: states it starts from instead of rest. Run-up cases
// (Synolakis 1987) start from a solitary wave already in the domain.
#include "nearshore/boussinesq/boussinesq_solver.hpp"
#include "nearshore/core/harbour_grid.hpp"

namespace nearshore::boussinesq {

/// A solitary wave of height H above still water, crest at `crest_position_m` along the travel axis
/// (x for west/east, y for south/north; metres, grid frame), travelling away from `facing`.
struct SolitaryWave {
  double height_m = 0.0;
  double crest_position_m = 0.0;
  Side facing = Side::kSouth;
};

/// Sets the solver's state to the solitary wave on depth d (the mean still-water depth of the grid
/// line under the crest): eta = H sech^2(K (s - s0)), K = sqrt(3H / (4 d^3)), with the Boussinesq
/// speed c = sqrt(g (d + H)) and the flux P = c eta, which satisfies the mass equation exactly for a
/// wave of permanent form (eta_t = -c eta_s). Throws nearshore::Error when H <= 0 or the crest's grid
/// line is dry.
void start_solitary_wave(BoussinesqSolver& solver, const HarbourGrid& harbour, const SolitaryWave& wave);

}  // namespace nearshore::boussinesq
