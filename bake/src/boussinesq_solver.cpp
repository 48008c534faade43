// First compiling version of the solver interface: construction and accessors only. The ADI
// numerics follow in the next commits (docs/solver.md).
#include "nearshore/bake/boussinesq_solver.hpp"

#include <cmath>
#include <istream>
#include <ostream>

#include "nearshore/core/error.hpp"

namespace nearshore::bake {

struct BoussinesqSolver::Implementation {
  GridGeometry geometry;
  SolverParameters parameters;
  WaveMaker wave_maker;
  double time_step_s = 0.0;
  double time_s = 0.0;
  long step_count = 0;
  Raster<float> surface_elevation_m, breaking_indicator;
};

BoussinesqSolver::BoussinesqSolver(const HarbourGrid& harbour, const SolverParameters& parameters,
                                   const WaveMaker& wave_maker)
    : implementation_(std::make_unique<Implementation>()) {
  auto& s = *implementation_;
  s.geometry = harbour.geometry;
  s.parameters = parameters;
  s.wave_maker = wave_maker;
  s.surface_elevation_m = Raster<float>(harbour.geometry.columns, harbour.geometry.rows, 0.0f);
  s.breaking_indicator = Raster<float>(harbour.geometry.columns, harbour.geometry.rows, 0.0f);
  float max_depth_m = 0.0f;
  for (float d : harbour.still_water_depth_m.values()) max_depth_m = std::max(max_depth_m, d);
  s.time_step_s = parameters.time_step_s > 0.0
                      ? parameters.time_step_s
                      : parameters.courant_number * harbour.geometry.spacing_m / std::sqrt(kGravity_m_s2 * max_depth_m);
}

BoussinesqSolver::~BoussinesqSolver() = default;

void BoussinesqSolver::step() {
  throw Error("BoussinesqSolver", "step() is not implemented yet in this revision", "update to a later commit");
}
double BoussinesqSolver::time_s() const { return implementation_->time_s; }
double BoussinesqSolver::time_step_s() const { return implementation_->time_step_s; }
long BoussinesqSolver::step_count() const { return implementation_->step_count; }
const GridGeometry& BoussinesqSolver::geometry() const { return implementation_->geometry; }
const Raster<float>& BoussinesqSolver::surface_elevation_m() const { return implementation_->surface_elevation_m; }
void BoussinesqSolver::cell_centred_fluxes(Raster<float>& flux_x_m2_s, Raster<float>& flux_y_m2_s) const {
  flux_x_m2_s = Raster<float>(implementation_->geometry.columns, implementation_->geometry.rows, 0.0f);
  flux_y_m2_s = flux_x_m2_s;
}
const Raster<float>& BoussinesqSolver::breaking_indicator() const { return implementation_->breaking_indicator; }
double BoussinesqSolver::surface_elevation_at(double, double) const { return 0.0; }
std::optional<InstabilityReport> BoussinesqSolver::check_stability() const { return std::nullopt; }
double BoussinesqSolver::water_volume_m3() const { return 0.0; }
void BoussinesqSolver::save_state(std::ostream&) const {
  throw Error("BoussinesqSolver", "save_state() is not implemented yet in this revision", "update to a later commit");
}
void BoussinesqSolver::load_state(std::istream&) {
  throw Error("BoussinesqSolver", "load_state() is not implemented yet in this revision", "update to a later commit");
}

}  // namespace nearshore::bake
