// The case-file fuzzer's lay_structures. The library's (bake/src/structure_fit.cpp) fits porous
// layers in the Boussinesq solver's flume, and the solver does not build under clang (GCC vector
// builtins in its sweep). The fuzzed cases cannot reach it: their grids are generated flumes and
// shoals, which carry no coastal structures. Reaching it is a finding (a trap), not a rejection.
#include "nearshore/bake/structure_layers.hpp"

namespace nearshore::bake {

std::vector<StructureLayer> lay_structures(HarbourGrid&, const boussinesq::SolverParameters&, const StructureSeaState&,
                                           std::vector<std::string>&, double) {
  __builtin_trap();
}

}  // namespace nearshore::bake
