// [solver] settings of a case file, and the record of them the sequence keeps.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "case_reader.hpp"

namespace nearshore::bake::detail {

using namespace nearshore::ocean;       // spectra, sea states, the deep-water field
using namespace nearshore::boussinesq;  // the solver and its parameters

namespace {
const char* wall_dispersion_name(SolverParameters::WallDispersion wall_dispersion) {
  return wall_dispersion == SolverParameters::WallDispersion::kMirrorAtWalls ? "mirror_at_walls" : "end_before_walls";
}
const char* face_depth_name(SolverParameters::FaceDepth face_depth) {
  return face_depth == SolverParameters::FaceDepth::kMeanWhereWet ? "mean_where_wet" : "larger_of_mean_and_above_bed";
}
const char* equations_name(Equations equations) {
  return equations == Equations::kFullyNonlinear ? "fully_nonlinear" : "weakly_nonlinear";
}
const char* breaking_model_name(BreakingParameters::Model model) {
  return model == BreakingParameters::Model::kRoller ? "roller" : "eddy_viscosity";
}
}  // namespace

SolverParameters read_solver(TableReader& solver) {
  SolverParameters p;
  p.dispersion_coefficient = solver.number("dispersion_coefficient", p.dispersion_coefficient, 0.0, 1.0, false, "B (1/15 in Madsen & Sorensen 1992)");
  p.dispersion_cutoff_depth_m = solver.non_negative("dispersion_cutoff_depth_m", p.dispersion_cutoff_depth_m, "depth in metres below which dispersion is off");
  p.dispersion_cutoff_kh = solver.non_negative("dispersion_cutoff_kh", p.dispersion_cutoff_kh, "k h below which dispersion is off");
  // 0 = none; left out, the bake derives it from the band it carries (bake_case.cpp).
  p.effective_depth_limit_m = solver.non_negative("effective_depth_limit_m", 0.0,
                                                  "depth in metres the equations see at most (0 = no limit; docs/solver.md, \"Effective depth\")");
  p.dry_depth_m = solver.positive("dry_depth_m", p.dry_depth_m, "wet/dry threshold in metres");
  p.chezy_coefficient = solver.non_negative("chezy_coefficient", p.chezy_coefficient, "Chezy C in m^0.5/s (0 = no turbulent friction)");
  // Water's kinematic viscosity is 1.0e-6 m^2/s at 20 degC and 1.8e-6 m^2/s at 0 degC (sea water
  // 1.83e-6, ITTC 2011 fresh and sea water properties); a hundred times that is no water. Without
  // the bound, 1 m^2/s made the laminar bed stress 3 nu u / h outgrow the flow and the blow-up
  // message blamed the time step (issue 44).
  constexpr double kMostKinematicViscosity_m2_s = 1e-4;
  p.kinematic_viscosity_m2_s = solver.number("kinematic_viscosity_m2_s", p.kinematic_viscosity_m2_s, 0.0,
                                             kMostKinematicViscosity_m2_s, false,
                                             "kinematic viscosity of the water in m^2/s (1.0e-6 at 20 degC, 1.8e-6 at 0 degC; a "
                                             "hundred times that is no water), for the laminar film's bed stress (0 = none)");
  // The nonlinear terms (docs/solver.md "Fully nonlinear dispersion"), the depth of the dispersive
  // terms and of a face (docs/solver.md "Dispersion depth", "Face depth").
  p.equations = solver.choice("equations", equations_name(p.equations), {"weakly_nonlinear", "fully_nonlinear"}) == 1
                    ? Equations::kFullyNonlinear : Equations::kWeaklyNonlinear;
  p.dispersion_depth = solver.choice("dispersion_depth", "still_water", {"still_water", "total"}) == 1
                           ? DispersionDepth::kTotal : DispersionDepth::kStillWater;
  p.face_depth = solver.choice("face_depth", face_depth_name(p.face_depth), {"mean_where_wet", "larger_of_mean_and_above_bed"}) == 0
                     ? SolverParameters::FaceDepth::kMeanWhereWet : SolverParameters::FaceDepth::kLargerOfMeanAndAboveBed;
  p.wall_dispersion = solver.choice("wall_dispersion", wall_dispersion_name(p.wall_dispersion), {"end_before_walls", "mirror_at_walls"}) == 1
                          ? SolverParameters::WallDispersion::kMirrorAtWalls : SolverParameters::WallDispersion::kEndBeforeWalls;
  p.taper_dispersion_at_walls = solver.boolean("taper_dispersion_at_walls", p.taper_dispersion_at_walls);
  p.nonlinear_iterations = solver.integer("nonlinear_iterations", p.nonlinear_iterations, 1, 20, "iterations per half step");
  p.adi_passes = solver.integer("adi_passes", p.adi_passes, 1, 4, "x + y sweep pairs per step");
  p.alternate_sweep_order = solver.boolean("alternate_sweep_order", p.alternate_sweep_order);
  p.shapiro_filter_order = solver.integer("shapiro_filter_order", p.shapiro_filter_order, 0, 16, "order of the grid-scale flux filter (even, 0 = off)");
  if (p.shapiro_filter_order % 2 != 0)
    solver.fail(solver.full("shapiro_filter_order"), "is odd", "give an even order: 8 (the default), or 0 to turn the filter off");
  if (p.equations == Equations::kFullyNonlinear && p.dispersion_depth == DispersionDepth::kTotal)
    solver.fail(solver.full("dispersion_depth"), "is \"total\" with equations = \"fully_nonlinear\", whose dispersive terms already carry the total depth",
                "leave dispersion_depth out (\"still_water\") with the fully nonlinear equations");
  p.blowup_elevation_depth_ratio = solver.positive("blowup_elevation_depth_ratio", p.blowup_elevation_depth_ratio, "|eta| / depth ratio that stops the run");
  TableReader breaking = solver.table("breaking");
  p.breaking.enabled = breaking.boolean("enabled", p.breaking.enabled);
  // The closure (docs/solver.md "Breaking"): Kennedy et al. (2000) or the surface roller of
  // Schaffer et al. (1993) / Madsen et al. (1997), with their published constants as defaults.
  p.breaking.model = breaking.choice("model", breaking_model_name(p.breaking.model), {"eddy_viscosity", "roller"}) == 1
                         ? BreakingParameters::Model::kRoller : BreakingParameters::Model::kEddyViscosity;
  p.breaking.onset_celerity_fraction = breaking.positive("onset_celerity_fraction", p.breaking.onset_celerity_fraction, "fraction of sqrt(g d), d the still-water depth");
  p.breaking.stop_celerity_fraction = breaking.positive("stop_celerity_fraction", p.breaking.stop_celerity_fraction, "fraction of sqrt(g d)");
  p.breaking.transition_time_factor = breaking.positive("transition_time_factor", p.breaking.transition_time_factor, "T* in units of sqrt(d/g)");
  p.breaking.mixing_length_coefficient = breaking.positive("mixing_length_coefficient", p.breaking.mixing_length_coefficient, "delta");
  p.breaking.fade_fully_nonlinear_terms = breaking.boolean("fade_fully_nonlinear_terms", p.breaking.fade_fully_nonlinear_terms);
  p.breaking.roller_onset_angle_deg = breaking.number("roller_onset_angle_deg", p.breaking.roller_onset_angle_deg, 0.0, 90.0, false, "phi_B in degrees");
  p.breaking.roller_final_angle_deg = breaking.number("roller_final_angle_deg", p.breaking.roller_final_angle_deg, 0.0, 90.0, false, "phi_0 in degrees");
  p.breaking.roller_half_time_periods = breaking.positive("roller_half_time_periods", p.breaking.roller_half_time_periods, "t_1/2 in wave periods");
  p.breaking.roller_half_time_s = breaking.non_negative("roller_half_time_s", p.breaking.roller_half_time_s, "t_1/2 in seconds (0 = from the wave maker's period)");
  p.breaking.roller_celerity_factor = breaking.positive("roller_celerity_factor", p.breaking.roller_celerity_factor, "c / sqrt(g h)");
  p.breaking.roller_shape_factor = breaking.positive("roller_shape_factor", p.breaking.roller_shape_factor, "f_delta");
  p.breaking.roller_filter_order = breaking.integer("roller_filter_order", p.breaking.roller_filter_order, 0, 16, "order of the roller's surf-zone flux filter (even, 0 = off)");
  if (p.breaking.roller_filter_order % 2 != 0)
    breaking.fail(breaking.full("roller_filter_order"), "is odd", "give an even order: 4 (the default), or 0 for no surf-zone filter");
  if (p.breaking.roller_final_angle_deg > p.breaking.roller_onset_angle_deg)
    breaking.fail(breaking.full("roller_final_angle_deg"), "is larger than roller_onset_angle_deg", "make the final angle at most the onset angle (10 and 20 degrees in Madsen et al. 1997)");
  if (p.breaking.stop_celerity_fraction > p.breaking.onset_celerity_fraction)
    breaking.fail(breaking.full("stop_celerity_fraction"), "is larger than onset_celerity_fraction", "make the stop threshold smaller than the onset threshold");
  breaking.finish();
  TableReader porous = solver.table("porous");
  p.porous.laminar_alpha = porous.non_negative("laminar_alpha", p.porous.laminar_alpha, "alpha (dimensionless)");
  p.porous.turbulent_beta = porous.non_negative("turbulent_beta", p.porous.turbulent_beta, "beta (dimensionless)");
  p.porous.stone_diameter_m = porous.positive("stone_diameter_m", p.porous.stone_diameter_m, "stone diameter in metres");
  porous.finish();
  return p;
}

json solver_record(const SolverParameters& p) {
  json sponges = json::array();
  for (const SpongeLayer& sponge : p.sponges) sponges.push_back({{"side", side_name(sponge.side)}, {"width_m", sponge.width_m}});
  json record = {{"physics_revision", kSolverPhysicsRevision},  // docs/solver.md, "Physics revision"
          {"time_step_s", p.time_step_s},
          {"dispersion_coefficient", p.dispersion_coefficient},
          {"dispersion_cutoff_depth_m", p.dispersion_cutoff_depth_m},
          {"dispersion_cutoff_kh", p.dispersion_cutoff_kh},
          {"effective_depth_limit_m", p.effective_depth_limit_m},
          {"dry_depth_m", p.dry_depth_m},
          {"chezy_coefficient", p.chezy_coefficient},
          {"kinematic_viscosity_m2_s", p.kinematic_viscosity_m2_s},
          {"dispersion_depth", p.dispersion_depth == DispersionDepth::kTotal ? "total" : "still_water"},
          {"face_depth", face_depth_name(p.face_depth)},
          {"wall_dispersion", wall_dispersion_name(p.wall_dispersion)},
          {"taper_dispersion_at_walls", p.taper_dispersion_at_walls},
          {"nonlinear_iterations", p.nonlinear_iterations},
          {"adi_passes", p.adi_passes},
          {"shapiro_filter_order", p.shapiro_filter_order},
          {"alternate_sweep_order", p.alternate_sweep_order},
          {"blowup_elevation_depth_ratio", p.blowup_elevation_depth_ratio},
          {"breaking",
           {{"enabled", p.breaking.enabled},
            {"onset_celerity_fraction", p.breaking.onset_celerity_fraction},
            {"stop_celerity_fraction", p.breaking.stop_celerity_fraction},
            {"transition_time_factor", p.breaking.transition_time_factor},
            {"mixing_length_coefficient", p.breaking.mixing_length_coefficient}}},
          {"porous",
           {{"laminar_alpha", p.porous.laminar_alpha},
            {"turbulent_beta", p.porous.turbulent_beta},
            {"stone_diameter_m", p.porous.stone_diameter_m}}},
          {"sponges", sponges}};
  // The equations only when they are not the seed's: the record of a weakly nonlinear bake stays what
  // it was before the option existed (no "equations" key means "weakly_nonlinear").
  if (p.equations != Equations::kWeaklyNonlinear) {
    record["equations"] = equations_name(p.equations);
    // Only where it acts (the fully nonlinear terms): a weakly nonlinear record stays as it was.
    record["breaking"]["fade_fully_nonlinear_terms"] = p.breaking.fade_fully_nonlinear_terms;
  }
  // The roller's settings only when it is the model: the record of an eddy-viscosity bake stays
  // what it was before the roller existed (no "model" key means "eddy_viscosity").
  if (p.breaking.model == BreakingParameters::Model::kRoller) {
    json& breaking = record["breaking"];
    breaking["model"] = breaking_model_name(p.breaking.model);
    breaking["roller_onset_angle_deg"] = p.breaking.roller_onset_angle_deg;
    breaking["roller_final_angle_deg"] = p.breaking.roller_final_angle_deg;
    breaking["roller_half_time_periods"] = p.breaking.roller_half_time_periods;
    breaking["roller_half_time_s"] = p.breaking.roller_half_time_s;
    breaking["roller_celerity_factor"] = p.breaking.roller_celerity_factor;
    breaking["roller_shape_factor"] = p.breaking.roller_shape_factor;
    breaking["roller_filter_order"] = p.breaking.roller_filter_order;
  }
  // The imposed current only when there is one: a record without it is the record of before.
  if (p.current.any())
    record["current"] = {{"u_m_s", p.current.velocity_x_m_s}, {"v_m_s", p.current.velocity_y_m_s}};
  return record;
}


}  // namespace nearshore::bake::detail
