#pragma once
// The parameters of the Boussinesq solver (boussinesq_solver.hpp holds the solver and its equations,
// seed 003 eq. (1)-(7)): the scheme's options (SolverParameters), the breaking closure, the porous
// resistance, the sponge layers, the wave maker, and the limits and revision the bake checks a case
// against. They stand apart from the solver so that the sweep, the source function and the bake's
// case reader reach them without the solver class. docs/solver.md gives every rule in full.
//
// Units: metres, seconds, radians throughout (angles named _deg are degrees). x = 0 is the west edge
// of the grid, y = 0 the south edge (GridGeometry origin); positions such as WaveMaker::source_line_m
// are in the grid's own frame (origin included).
#include <cmath>
#include <limits>
#include <vector>

#include "nearshore/boussinesq/model_nonlinear.hpp"
#include "nearshore/ocean/linear_waves.hpp"
#include "nearshore/ocean/wave_component.hpp"

namespace nearshore::boussinesq {

/// A side of the rectangular grid. x = 0 is west, y = 0 is south.
enum class Side { kWest, kEast, kSouth, kNorth };

/// An absorbing layer of `width_m` metres along one side (Larsen & Dancy 1983): eta, P and Q are
/// relaxed towards rest with a damping that grows smoothly from 0 at the inner edge to its maximum
/// at the boundary, so waves leave with a few per cent reflection when width >= one wavelength.
struct SpongeLayer {
  Side side = Side::kWest;
  double width_m = 0.0;
};

/// The closure of wave breaking (docs/solver.md, "Breaking"). `model` chooses it:
///
/// kEddyViscosity, Kennedy et al. (2000): a cell starts breaking when d(eta)/dt exceeds
/// onset_celerity_fraction * sqrt(g d), d the still-water depth; the threshold relaxes linearly to
/// stop_celerity_fraction * sqrt(g d) over transition_time_factor * sqrt(d/g) seconds; the eddy
/// viscosity is nu = delta^2 (d + eta) * B(eta_t) * eta_t with mixing length delta =
/// mixing_length_coefficient (Kennedy's delta = 1.2).
///
/// kRoller, the surface roller of Schaffer, Madsen & Deigaard (1993) as used with the Madsen-Sorensen
/// equations by Madsen, Sorensen & Schaffer (1997, Part I): where the front of a wave is steeper than
/// tan(phi), the water above the line of slope tan(phi) tangent to the front at its toe, times the
/// shape factor, is a roller of thickness delta carried at the celerity c = roller_celerity_factor *
/// sqrt(g h); it adds the momentum flux delta (c - P/h)^2 / (1 - delta/h) to the momentum
/// equations. phi = roller_onset_angle_deg when a roller forms and decays to roller_final_angle_deg
/// with the half time roller_half_time_periods * T (T the wave maker's peak period).
struct BreakingParameters {
  enum class Model { kEddyViscosity, kRoller };
  bool enabled = true;
  Model model = Model::kEddyViscosity;
  double onset_celerity_fraction = 0.65;   ///< eta_t^(I) = 0.65 sqrt(g d), d the still-water depth
  double stop_celerity_fraction = 0.15;    ///< eta_t^(F) = 0.15 sqrt(g d)
  double transition_time_factor = 5.0;     ///< T* = 5 sqrt(d/g)
  double mixing_length_coefficient = 1.2;  ///< delta
  /// Equations::kFullyNonlinear with the eddy viscosity: where a cell breaks, its share of the fully
  /// nonlinear dispersive terms (what they add to the seed's) is weighted by 1 - B, B its breaking
  /// strength, inside the derivative of the non-hydrostatic momentum flux (conservation form), so
  /// the fade adds no force of its own. The Serre-type terms at a broken front are outside the range
  /// they were derived for, and their mean there raised Hansen & Svendsen's inner set-up by half
  /// its error; FUNWAVE-TVD drops its dispersive terms in breaking cells likewise (docs/solver.md,
  /// "The fully nonlinear terms where waves break"). The seed's dispersive terms stay.
  bool fade_fully_nonlinear_terms = true;
  // The roller (Madsen, Sorensen & Schaffer 1997, Part I, their published values).
  double roller_onset_angle_deg = 20.0;    ///< phi_B: the front slope tan(phi_B) at which a roller forms, degrees
  double roller_final_angle_deg = 10.0;    ///< phi_0: the slope it decays to, degrees
  double roller_half_time_periods = 0.2;   ///< t_1/2 of the decay of phi, in wave periods (T / 5)
  /// t_1/2 in seconds; 0 = roller_half_time_periods times the wave maker's peak period (a run with no
  /// periodic wave maker, such as a solitary wave, must give it).
  double roller_half_time_s = 0.0;
  double roller_celerity_factor = 1.3;     ///< c = 1.3 sqrt(g h)
  double roller_shape_factor = 1.5;        ///< f_delta: roller thickness over the height above the tangent line
  /// Order (even, 0 = none) of the Shapiro filter the roller adds on the faces within three cells of
  /// where its force acts, beside the grid-wide one (SolverParameters::shapiro_filter_order): a bore
  /// sheds waves 4-5 cells long (k h ~ 5, beyond the equations' range) that the roller, adding no
  /// dissipation, lets grow and the grid-wide 8th-order filter passes (response 0.94 per step at 4 dx;
  /// 4th order: 0.75). Only in the surf zone, so resolved waves elsewhere keep the 8th order's
  /// accuracy (docs/solver.md, "The surface roller").
  int roller_filter_order = 4;
};

/// Porous resistance of seed 003 eq. (2)-(3) in cells with porosity 0 < n < 1 (rubble mounds),
/// Van Gent (1995) / Madsen (1974) form:
///   a_l = laminar_alpha * nu_w (1 - n)^2 / (n^3 D^2),  a_t = turbulent_beta (1 - n) / (n^3 D)
/// (nu_w = SolverParameters::kinematic_viscosity_m2_s)
/// the resistance acceleration being n (a_l u + a_t u |u|) with u the seepage velocity.
struct PorousResistance {
  double laminar_alpha = 1000.0;   ///< alpha, dimensionless
  double turbulent_beta = 1.1;     ///< beta, dimensionless
  double stone_diameter_m = 1.0;   ///< D, metres
};

/// Internal wave generation (Wei, Kirby & Sun 1999): a source term in the mass equation along a
/// line, so waves reflected back to it pass through and leave through a sponge.
struct WaveMaker {
  enum class Kind { kNone, kComponents, kTimeSeries } kind = Kind::kNone;
  ocean::SeaState sea_state;                 ///< kComponents: linear components (wave_component.hpp)
  double source_line_m = 0.0;         ///< position of the source line along the axis normal to `facing`
                                      ///< (x for kWest/kEast, y for kSouth/kNorth), metres, grid frame
  Side facing = Side::kSouth;         ///< waves are generated travelling AWAY from this side
  double ramp_time_s = 0.0;           ///< smooth start over this time, seconds: (1 - cos(pi t / T)) / 2
  /// The stretch of the source line the source acts on: cells [span_begin_cell, span_end_cell) along
  /// the line (columns for a line facing south or north, rows for west or east), clamped to the grid.
  /// The default is the whole line; the bake's case reader sets it to the one wet span the source is
  /// meant for, so that no water cut off from it by land (a cove behind a headland) gets a source of
  /// its own (docs/solver.md, "Wave maker": what such a span radiates). The line's depth, which sets
  /// the source's strength, is the mean over this span's wet cells.
  int span_begin_cell = 0;
  int span_end_cell = std::numeric_limits<int>::max();
  /// Second-order generation of a regular wave (kComponents with one component): the line also
  /// radiates, as a free wave at 2w, the bound second harmonic of the equations' own steady wave
  /// (model_nonlinear.hpp) in phase with it at the line. A source of the first harmonic alone sheds
  /// a free second harmonic of the opposite sign, which beats with the bound one along the flume
  /// (H +-10 % over tens of metres for Hansen & Svendsen's 031041); this one cancels it
  /// (docs/solver.md, "Wave maker"). Ignored for several components (their sum and difference
  /// interactions are not generated).
  bool second_order = true;
  std::vector<double> series_time_s, series_elevation_m;  ///< kTimeSeries: eta(t) at the source line
};

/// A steady current imposed on the whole grid (docs/solver.md, "Currents"): the depth-uniform
/// velocity (u, v) the wave field rides on, m/s, x east and y north. The solver starts from the
/// flux P = u d, Q = v d on every open face between two water cells (d the still-water depth of the
/// face), the grid's edges hold that flux for good (an open boundary feeding and draining the
/// current; with no current they are walls, flux 0), and the sponges relax the flux towards it
/// instead of towards rest. Over a flat bed without friction the current is a steady solution of
/// the equations; over a chart it adjusts to the bed and the coast during the spin-up. The wave
/// maker generates in the moving water: its frequency is the absolute one, its wavenumber from the
/// Doppler-shifted dispersion relation (w - k.U)^2 M(k^2) = k^2 G(k^2) of the equations
/// (model_dispersion.hpp).
struct ImposedCurrent {
  double velocity_x_m_s = 0.0;
  double velocity_y_m_s = 0.0;
  bool any() const { return velocity_x_m_s != 0.0 || velocity_y_m_s != 0.0; }
  double speed_m_s() const { return std::hypot(velocity_x_m_s, velocity_y_m_s); }  ///< |U|
};

/// The speed the Courant number is taken of (docs/solver.md, "Currents"): the fastest signal on the
/// grid, the shallow-water gravity wave over the deepest cell carried by the imposed current,
/// |U| + sqrt(g d_max). Without a current it is sqrt(g d_max) exactly. The current matters because
/// what the scheme advances explicitly is advection at the current's speed: the convection
/// (P^2/h)_x is iterated from the step's first guess, and the fully nonlinear terms' remainder,
/// extrapolated from the steps before, carries -2 (B+1/3) U d^2 P_xxx (the Serre and enhancement
/// terms linearised about P = U d), which is the whole of the advection M (D/Dt) of the waves at
/// short wavelengths; gravity alone is implicit.
inline double courant_speed_m_s(double deepest_m, const ImposedCurrent& current) {
  return current.speed_m_s() + std::sqrt(ocean::kGravity_m_s2 * deepest_m);
}

/// The stability limit of the Courant number (|U| + sqrt(g d_max)) dt / dx: beyond it the iterated explicit
/// terms stop converging (docs/solver.md). The solver refuses a larger step; the bake's case reader
/// checks the same limit first, so that its message names the case file's key.
inline constexpr double kMaxCourantNumber = 2.0;

/// The revision of what the solver computes: raised whenever a change makes the same parameters give
/// other results on purpose (a closure, a default inside the scheme, a discretisation; not a speed-up
/// that keeps the bits). A bake checkpoint records it, and a bake is only resumed by a solver of the
/// same revision, so one sequence never holds two physics; the manifest's solver record carries it.
/// The list of revisions is docs/solver.md, "Physics revision". 1: the solver of 2026-11-28 (issue 19's
/// defaults, Kennedy et al.'s thresholds on the still-water depth, the laminar film's bed stress).
/// 2: the fully nonlinear terms fade where waves break (BreakingParameters::fade_fully_nonlinear_terms).
/// 3: on an imposed current, the Courant number counts the current (courant_speed_m_s) and the wave
/// maker radiates its second-harmonic correction only where it is carried (docs/solver.md "Currents").
/// 4: the wave maker's source is as narrow as its shortest component needs and a time series' phases
/// are its line's (docs/solver.md "Wave maker"); with the grid-scale filter on, the dispersive terms
/// rise over the filter's half-stencil beside land and walls (taper_dispersion_at_walls).
inline constexpr int kSolverPhysicsRevision = 4;

/// Porosity below which a cell is a solid wall (a quay): no flux through its faces, no shoreline on it.
inline constexpr double kWallPorosity = 0.05;

struct SolverParameters {
  double time_step_s = 0.0;           ///< 0 = from courant_number
  double courant_number = 0.5;        ///< (|U| + sqrt(g d_max)) dt / dx when time_step_s = 0 (courant_speed_m_s)
  double dispersion_coefficient = 1.0 / 15.0;  ///< B, Madsen & Sorensen (1992)
  /// The nonlinear terms of the momentum equations (model_nonlinear.hpp, docs/solver.md "Fully
  /// nonlinear dispersion"): kFullyNonlinear (default since issue 19) adds to seed 003 eq. (1)-(7)
  /// the Serre-Green-Naghdi dispersive terms with the enhancement on the total depth, whose bound
  /// harmonics and amplitude dispersion follow Stokes to k d ~ 1-2 (docs/validation.md "Nonlinear
  /// checks"); kWeaklyNonlinear is the seed's equations as written (nonlinear only in the
  /// shallow-water terms), half the cost of a step. Not with dispersion_depth = kTotal.
  Equations equations = Equations::kFullyNonlinear;
  /// The depth in the dispersive terms: still-water d (seed 003 eq. 4-5, default) or total h = d + eta
  /// (an option, docs/solver.md "Dispersion depth"; its nonlinear properties: model_nonlinear.hpp).
  DispersionDepth dispersion_depth = DispersionDepth::kStillWater;
  /// Total depth h of a face in the gravity term n g h eta_x and the resistance (docs/solver.md,
  /// "Face depth"). kMeanWhereWet (default since issue 19): the mean of the two cells where both are
  /// wet, the water above the higher bed only next to a dry cell (flooding). kLargerOfMeanAndAboveBed:
  /// the larger of the two everywhere (the solver before issue 19): on a flat bed that is
  /// d + max(eta_L, eta_R), a first-order error g |eta_x| eta_x dx / 2 that acts as a spurious
  /// amplitude dispersion (it stood in for the physical one the seed's equations lack).
  enum class FaceDepth { kMeanWhereWet, kLargerOfMeanAndAboveBed };
  FaceDepth face_depth = FaceDepth::kMeanWhereWet;
  /// The dispersive terms beside a wall (docs/solver.md, "Walls and the dispersive terms"). A wall
  /// is a dry neighbour of porosity below kWallPorosity or whose bed stands at least a cell's length
  /// above this cell's (a step steeper than 1:1: a quay, a pier, a breakwater's face; a beach's dry
  /// cell is none). kEndBeforeWalls (default): the terms need the cell and its four neighbours wet,
  /// so the first row of cells beside a wall has none. kMirrorAtWalls: that row has them, reading the
  /// wall's cell as the mirror of its own, per direction, as the grid's edges do (an interior wall
  /// then reflects exactly as the grid's edge does); it keeps the water beside grid-aligned walls
  /// quiet with the grid-scale filter, where the default grows a mode two cells long along them,
  /// but puts a staircase circle's wall amplitudes further from MacCamy & Fuchs (5.6 against 3.2 %
  /// RMS at 6.5 cells per radius), so it is not the default.
  enum class WallDispersion { kEndBeforeWalls, kMirrorAtWalls };
  WallDispersion wall_dispersion = WallDispersion::kEndBeforeWalls;
  /// With the grid-scale filter on (shapiro_filter_order = 2p > 0) and kEndBeforeWalls, the
  /// dispersive terms rise smoothly from nothing in the first row beside land or a wall to their full
  /// weight p cells further out, where the filter's stencil no longer reaches the land: between the
  /// dispersion mask's edge (the second row) and the filter's (p + 2 rows out) the water otherwise has
  /// dispersion at full weight and no filter, where the mode of "The water beside a wall" grows
  /// (docs/solver.md). No effect with the filter off or kMirrorAtWalls.
  bool taper_dispersion_at_walls = true;
  /// Dispersion taper: the dispersive terms are multiplied by a weight that is 1 where the still-water
  /// depth d >= 2 * dispersion_cutoff_depth_m, 0 where d <= dispersion_cutoff_depth_m and a smooth
  /// (cubic) ramp between; likewise for the local k h of the peak wave when dispersion_cutoff_kh > 0
  /// (weight 0 below kh_cut, 1 above 2 kh_cut). 0 disables the respective taper. See docs/solver.md.
  double dispersion_cutoff_depth_m = 0.0;
  double dispersion_cutoff_kh = 0.0;
  /// Effective-depth limit, metres (0 = none): every term of the equations, and the source
  /// function, sees min(d, effective_depth_limit_m) as the still-water depth. Waves with k d > pi
  /// do not feel the bottom (tanh k d > 0.996), so over a channel deeper than the limit the waves
  /// keep their deep-water speed while the B = 1/15 equations stay inside the k d they hold
  /// (docs/solver.md, "Effective depth"; effective_depth_limit_m() in model_dispersion.hpp).
  double effective_depth_limit_m = 0.0;
  double dry_depth_m = 0.01;          ///< wet/dry threshold of the moving shoreline, metres
  double chezy_coefficient = 60.0;    ///< C, m^0.5/s (0 = no turbulent friction)
  /// Kinematic viscosity of the water, m^2/s, for the bed stress of a laminar film: a sheet of
  /// water thin and slow enough to stay laminar (the run-up tongue of a laboratory wave, a few
  /// millimetres thick) carries the Poiseuille stress tau_b = 3 rho nu u / h, which grows as 1/h^2
  /// in the momentum of the flux form. The bed stress is the larger of this and the Chezy stress
  /// (the flow's regime: they cross at the film Reynolds number u h / nu = 3 C^2 / g, 1100 at
  /// C = 60, inside the laminar-turbulent transition of a sheet flow; docs/solver.md, "Bed
  /// friction"). The laminar part of the porous resistance (PorousResistance::laminar_alpha) takes
  /// it too. 1.0e-6 is fresh water at 20 C (sea water at 15 C: 1.19e-6); 0 = no laminar stress.
  double kinematic_viscosity_m2_s = 1.0e-6;
  BreakingParameters breaking;
  PorousResistance porous;
  std::vector<SpongeLayer> sponges;
  ImposedCurrent current;             ///< none by default: the grid's edges are walls
  int nonlinear_iterations = 2;       ///< passes of the time-centred (Crank-Nicolson) iteration per half step
  /// x + y sweep pairs per step. The first pair's first sweep takes the across terms (the other
  /// flux and its rate at t^{n+1/2}) from last step's increment; the second pair re-solves with this
  /// step's, which removes that lag: one pair leaves a splitting error first order in dt (the demo
  /// harbour's Hs 3.5 % low against the time-converged run; two pairs 0.1 %), for 1.4 times the
  /// cost of a step (docs/solver.md, "ADI passes"). 1 is the fast option for previews.
  int adi_passes = 2;
  /// Sweep order x-y on even steps, y-x on odd steps, so the lag of the across terms in the first
  /// sweep falls on each direction in turn: it removes about half of the fixed order's splitting
  /// bias where waves focus, but lets the fine-grid across mode grow even with the grid-scale filter
  /// (docs/solver.md, "Sweep order"); adi_passes = 2 removes the bias instead.
  bool alternate_sweep_order = false;
  /// Order 2p of the Shapiro (1970) filter applied to P and Q every step (even, 0 = off): it removes
  /// the grid-scale two-dimensional mode of fine grids and leaves resolved waves alone (response
  /// 1 - sin^{2p}(k dx/2); docs/solver.md, "Grid-scale filter").
  int shapiro_filter_order = 8;
  double blowup_elevation_depth_ratio = 5.0;   ///< |eta| > ratio * max(d, 1 m) => unstable
};

}  // namespace nearshore::boussinesq
