// The case-file fuzzer's lay_structures. The library's (bake/src/structure_fit.cpp) fits porous
// layers in the Boussinesq solver's flume, and the solver does not build under clang (GCC vector
// builtins in its sweep). The fuzzed cases cannot reach it: their grids are generated flumes and
// shoals, which carry no coastal structures. Reaching it is a finding (a trap), not a rejection.
// Likewise the solver's memory-traffic count behind bake::streamed_bytes_per_cell_step
// (bake_estimate.cpp), which only `nearshore bench bake` asks for, never a case read.
#include "nearshore/bake/structure_layers.hpp"
#include "nearshore/boussinesq/solver_parameters.hpp"

namespace nearshore::boussinesq {

double streamed_bytes_per_cell_step(const SolverParameters&, bool) { __builtin_trap(); }

}  // namespace nearshore::boussinesq

namespace nearshore::bake {

std::vector<StructureLayer> lay_structures(HarbourGrid&, const boussinesq::SolverParameters&, const StructureSeaState&,
                                           std::vector<std::string>&, double) {
  __builtin_trap();
}

}  // namespace nearshore::bake
