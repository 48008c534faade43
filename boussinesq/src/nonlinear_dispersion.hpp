#pragma once
// The fully nonlinear dispersive terms (Equations::kFullyNonlinear, docs/solver.md "Fully nonlinear
// dispersion"): what the Serre-Green-Naghdi dispersive terms with the Madsen & Sorensen (1992)
// enhancement on the total depth add to the seed's linear ones,
//
//   Psi_full = -(1/3) grad(h^3 Gamma) - B h^2 grad(div S)
//   Gamma    = div u_t + u . grad(div u) - (div u)^2,   u = (P, Q) / h
//   S        = (P, Q)_t + div((P, Q) (P, Q) / h) + g h grad(eta)      (the shallow-water residual)
//
// minus the same operator linearised about rest (h -> d), so that at small amplitude the equations
// are exactly seed 003 eq. (1)-(5), bed-slope terms included. The difference is O(eta/d). Its part
// in the flux rate along a sweep's own lines (P_t in the x sweep: the Serre term's
// -(1/3) d/dx (h^3 d/dx (P_t/h)) and the enhancement's -B h^2 P_xxt, less their linearisation) is
// tridiagonal and implicit in the sweep, time-centred with everything else there; the rest (the
// velocities and their products, h_t, the rate across the lines, gravity and convection in S) is
// the explicit remainder here: evaluated time-centred at t^{n+1/2} from the step just finished (eta^n,
// eta^{n+1}, P^n, P^{n+1}; centred differences in time) and extrapolated linearly to the next
// step's t^{n+3/2} (second order in dt).
// Private to boussinesq/.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "nearshore/ocean/linear_waves.hpp"

namespace nearshore::boussinesq::detail {

/// The weight of the fully nonlinear terms at a face from its elevation and still-water depth d (at
/// t^{n+1/2}): 1 where |eta| <= 0.6 d, 0 where |eta| >= 0.8 d, a cubic smooth step between (d below
/// the dry depth counts as the dry depth). FUNWAVE-TVD switches its Boussinesq terms off where
/// |eta| / d > 0.8 (its SWE_ETA_DEP, default 0.8; Shi et al. 2012): the run-up tongue, thin
/// backwash and bores, where the seed's equations hold the flow (their dispersion, on d, vanishes
/// at the still-water line). The ramp below 0.8 keeps the switch from making noise. Used alike by
/// the sweep and the remainder, times the face's subcritical weight (below).
inline double fully_nonlinear_weight(double elevation_m, double still_water_depth_m, double dry_depth_m) {
  // std::abs and std::min/max of values (not ?:, with which GCC 12 stops with an internal error
  // vectorising the sweep's loops; not fmax, a library call that keeps them scalar).
  const double ratio = std::abs(elevation_m) / std::max(still_water_depth_m, dry_depth_m);
  const double s = std::min(std::max((0.8 - ratio) * 5.0, 0.0), 1.0);
  return s * s * (3.0 - 2.0 * s);
}

/// The second factor of the weight, in a cell of speed |u| and total depth h: 1 / (1 + (Fr / 0.9)^16),
/// Fr = |u| / sqrt(g h) the Froude number (0.998 at Fr 0.6, 0.87 at 0.8, 0.16 at 1, 0.003 at 1.3).
/// Supercritical flow is a backwash sheet or the hydraulic jump where it meets standing water, not
/// a wave (a wave's particles move slower than its crest: Fr = 0.23 at the crest of a solitary wave
/// of H/d = 0.3, 0.4-0.5 at Hansen & Svendsen's break points). A jump that stands still escapes the
/// breaking model's onset (its eta_t is small), and there the terms' velocity products, (div u)^2
/// and u . grad(div u) across the jump, grew without bound: the Synolakis breaking case at d/40
/// stopped at t = 8.6-9.2 s in the backwash. A face takes the least factor of the cells its terms
/// read (NonlinearDispersion::update_subcritical).
inline double subcritical_weight(double speed_m_s, double total_depth_m, double dry_depth_m) {
  const double p = speed_m_s * speed_m_s / (0.81 * ocean::kGravity_m_s2 * std::max(total_depth_m, dry_depth_m));
  const double p2 = p * p, p4 = p2 * p2;
  return 1.0 / (1.0 + p4 * p4);
}

/// 1/d of the linearised velocity rate P_t/d at a face of still-water depth d, never above 1/dry (a
/// face at or above the still-water line is wet only in the swash, where the terms' weight is 0): one rule for the sweep and the remainder, and no select (GCC 12 vectorises it in the sweep).
inline double linear_inverse_depth(double still_water_depth_m, double dry_depth_m) {
  return 1.0 / std::max(still_water_depth_m, dry_depth_m);
}

/// The grid the terms see, in the solver's natural layouts (cells r * nx + c, x faces f * ny + r,
/// y faces k * nx + c; boussinesq_solver.cpp).
struct NonlinearDispersionGrid {
  int nx = 0, ny = 0;
  double dx = 1.0, dy = 1.0;
  const float* depth_m = nullptr;            ///< d per cell (land negative)
  const float* porosity = nullptr;           ///< n per cell: the terms act only in open water (n = 1)
  const float* face_weight_x = nullptr;      ///< the dispersion taper of the x faces (x-face layout)
  const float* face_weight_y = nullptr;      ///< the dispersion taper of the y faces (y-face layout)
  double dispersion_coefficient = 1.0 / 15.0;  ///< B
  double dry_depth_m = 0.01;
  /// SolverParameters::WallDispersion::kMirrorAtWalls: the walls the mask marks are read as mirrors.
  bool mirror_walls = false;
  /// SolverParameters::current: the grid's edges hold the imposed current's flux (open), so the
  /// velocities there are the edge faces' flux over their cell's depth, not a wall's 0.
  bool open_edges = false;
};

/// The state of one step, all in the natural layouts.
struct StepPair {
  const double* eta_old;         ///< eta^n, cells
  const double* eta_new;         ///< eta^{n+1}, cells
  const double* flux_x_new;      ///< P^{n+1}, x faces
  const double* flux_x_change;   ///< P^{n+1} - P^n, x faces
  const double* flux_y_new;      ///< Q^{n+1}, y faces
  const double* flux_y_change;   ///< Q^{n+1} - Q^n, y faces
  const unsigned char* dispersive;  ///< the solver's dispersion mask of eta^n (boussinesq_sweep.hpp, kDispersive, kMirror*)
  double time_step_s;
  /// The breaking strength B of the step per cell (0 to 1), by which each cell's share of the terms
  /// fades (BreakingParameters::fade_fully_nonlinear_terms), or nullptr: no fade.
  const float* breaking_strength = nullptr;
};

class NonlinearDispersion {
 public:
  NonlinearDispersion() = default;
  explicit NonlinearDispersion(const NonlinearDispersionGrid& grid);

  /// The subcritical factor of the terms' weight at the faces for the coming step, from eta^n and
  /// the fluxes at t^n (natural layouts): subcritical_weight of each open-water cell (0 where porous
  /// or dry), then for a face the least over its two cells and their four neighbours each, the cells
  /// its terms read. Not per face alone: in a backwash sheet the Froude number alternates cell by
  /// cell, and a face weight that flips with it switches the terms on amid cells where they are off,
  /// with differences taken across the switch. A wall beside a cell (`dispersive`, the solver's mask
  /// of this step: boussinesq_sweep.hpp, kMirror*) is read as the cell itself, as the grid's edges
  /// are. `scratch`, `scratch_around`: nx * ny values each (the cells' own factors, and each cell's
  /// least over itself and its neighbours).
  void update_subcritical(const double* eta, const double* flux_x, const double* flux_y, const unsigned char* dispersive,
                          double* scratch, double* scratch_around);
  const float* subcritical_x() const { return subcritical_x_.data(); }
  const float* subcritical_y() const { return subcritical_y_.data(); }

  /// Evaluates the remainder at t^{n+1/2} of the step `pair` and updates the force for the next
  /// step: 2 R^{n+1/2} - R^{n-1/2} (R^{n+1/2} alone after the first step since a start).
  /// `scratch` holds six arrays of at least nx * ny values: the caller's work arrays that are free
  /// at the end of a step, overwritten.
  void update(const StepPair& pair, double* const scratch[6]);

  /// The force of the next step on the x faces and the y faces (m^2/s^2, added to the momentum
  /// equation's left side like Psi), or nullptr while there is none.
  const float* force_x() const { return evaluations_ > 0 ? force_x_.data() : nullptr; }
  const float* force_y() const { return evaluations_ > 0 ? force_y_.data() : nullptr; }

  /// Forgets the history (a new initial condition): the next step runs without the force.
  void reset();

  /// The history a saved state must carry to continue bit-identically: the force, the last
  /// remainder (x then y faces) and the number of evaluations so far (0, 1 or 2 = "two or more").
  std::vector<float>& force_x_storage() { return force_x_; }
  std::vector<float>& force_y_storage() { return force_y_; }
  std::vector<float>& last_x_storage() { return last_x_; }
  std::vector<float>& last_y_storage() { return last_y_; }
  int& evaluations() { return evaluations_; }
  std::size_t memory_bytes() const;

 private:
  NonlinearDispersionGrid grid_;
  // Float: a correction of a few per cent of the dispersive terms, which are themselves O(mu^2);
  // its rounding (6e-8) is far below the extrapolation's O(dt^2). 16 bytes per cell in all, and 8
  // for the faces' subcritical factors (recomputed from the state each step: not part of the saved state).
  std::vector<float> force_x_, force_y_, last_x_, last_y_;
  std::vector<float> subcritical_x_, subcritical_y_;
  int evaluations_ = 0;
};

}  // namespace nearshore::boussinesq::detail
