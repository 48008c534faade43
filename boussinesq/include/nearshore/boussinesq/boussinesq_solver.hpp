#pragma once
// BoussinesqSolver: the enhanced Boussinesq equations of seed 003 (Li, Jin, Ren & Hua 2010) eq. (1)-(7)
// in flux form, on a rectangular staggered grid (surface elevation eta at cell centres, flux P on the
// x-faces, flux Q on the y-faces), time-centred implicit finite differences solved by ADI: an x sweep
// for (eta, P) then a y sweep for (eta, Q), each a set of independent tridiagonal systems (one per row
// or column) solved by the double sweep (Thomas algorithm), rows in parallel with oneTBB.
//
//   mass      n eta_t + P_x + Q_y = 0                                                    seed 003 eq. (1)
//   x-mom.    P_t + (P^2/h)_x + (PQ/h)_y + g h eta_x + n^2 g P |U| / (C^2 h^2)
//             + porous resistance (alpha, beta) + Psi_x - F_x = 0                        seed 003 eq. (2)
//   y-mom.    likewise for Q                                                             seed 003 eq. (3)
//   Psi_x     Madsen & Sorensen (1992) dispersion with B = 1/15 and the bed-slope terms  seed 003 eq. (4)
//   F_x, F_y  eddy-viscosity stress from wave breaking (Kennedy et al. 2000)             seed 003 eq. (6)-(7)
//             or, as an option, the surface roller's momentum flux (Madsen et al. 1997)  BreakingParameters
// with total depth h = d + eta. docs/solver.md gives the equations as implemented and every rule
// (dispersion taper, breaking, wet/dry, sponges, source function) in full. The parameters (the
// scheme's options, breaking, porous resistance, sponges, the wave maker) are solver_parameters.hpp.
//
// Units: metres, seconds, radians throughout. x = 0 is the west edge of the grid, y = 0 the south
// edge (GridGeometry origin); x_m, y_m arguments are in the grid's own frame (origin included).
#include <array>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "nearshore/boussinesq/solver_parameters.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/raster.hpp"

namespace nearshore::boussinesq {

/// Where and when the solution went wrong (check_stability()).
struct InstabilityReport {
  double time_s = 0.0;
  int column = 0, row = 0;
  double x_m = 0.0, y_m = 0.0, depth_m = 0.0, value = 0.0;
  std::string what;  ///< "NaN surface elevation", "surface elevation 12.3 m exceeds 5 x depth", ...
};

/// Bytes one time step moves through main memory per grid cell, by the count of docs/solver.md
/// ("Memory traffic"): every array a pass of step() reads or writes, once per pass (the re-reads
/// inside a block of lines stay in the cache), writes counted twice (the line is read before it is
/// written). A model for the roofline line of `nearshore bench bake`, not a measurement; faces are
/// counted as cells. `breaking`: cells break this step (the sweeps then read the eddy viscosity).
double streamed_bytes_per_cell_step(const SolverParameters& parameters, bool breaking);

class BoussinesqSolver {
 public:
  /// Throws nearshore::Error for inconsistent input (a sponge wider than the grid, a source line
  /// outside it, a time step above the stability limit, a time series that is not increasing...).
  BoussinesqSolver(const HarbourGrid& harbour, const SolverParameters& parameters, const WaveMaker& wave_maker);
  ~BoussinesqSolver();
  BoussinesqSolver(const BoussinesqSolver&) = delete;
  BoussinesqSolver& operator=(const BoussinesqSolver&) = delete;

  /// Replaces the surface elevation by eta(x, y) at the cell centres (metres, grid frame) on water
  /// cells and sets every flux to rest: an initial condition for tests and hot starts (standing
  /// waves, humps); with an imposed current (SolverParameters::current) the fluxes are set to the
  /// current's instead. Land cells keep h = 0. Values are not checked: check_stability() reports NaN.
  void set_surface_elevation(const std::function<double(double x_m, double y_m)>& surface_elevation_m);
  /// Replaces eta on every cell with water (still-water depth > 0) and the fluxes on every open wet
  /// face by the given functions of position (metres, grid frame: cell centres for eta, face centres
  /// for P and Q), and resets the flux rates: an initial condition with motion, such as a solitary
  /// wave (initial_conditions.hpp). Call it before the first step. With an imposed current the given
  /// fluxes replace the current's on the interior faces (include it in them); the edges keep theirs.
  void set_initial_condition(const std::function<double(double x_m, double y_m)>& surface_elevation_m,
                             const std::function<double(double x_m, double y_m)>& flux_x_m2_s,
                             const std::function<double(double x_m, double y_m)>& flux_y_m2_s);
  /// How set_still_water_level treats the water: kMoveWater adds the change of level to it;
  /// kStateHoldsIt only takes the level (a state just loaded with load_state, which does not store
  /// the level, already holds its water).
  enum class LevelChange { kMoveWater, kStateHoldsIt };
  /// The still-water level, metres above the level the grid's depths were given at (0 at
  /// construction): a tide or surge that varies slowly over a run (docs/solver.md, "Tides"). The
  /// change since the last call is added to the surface elevation of every cell holding water (the
  /// tidal wave is far longer than a harbour grid, so the basin rises and falls as one: the volume the
  /// open sea feeds it), never below a cell's bed; the sponges relax eta towards the level instead of
  /// 0. The depths of the equations' coefficients (dispersion, breaking thresholds) stay the grid's.
  void set_still_water_level(double level_m, LevelChange change = LevelChange::kMoveWater);
  double still_water_level_m() const;        ///< the level of the last set_still_water_level, metres
  void step();                               ///< one ADI step of time_step_s()
  double time_s() const;                     ///< simulated time, seconds
  double time_step_s() const;                ///< dt, seconds
  long step_count() const;
  const GridGeometry& geometry() const;
  const Raster<float>& surface_elevation_m() const;                 ///< eta at cell centres, metres
  /// P and Q averaged from the faces to the cell centres, m^2/s (resized as needed).
  void cell_centred_fluxes(Raster<float>& flux_x_m2_s, Raster<float>& flux_y_m2_s) const;
  const Raster<float>& breaking_indicator() const;                  ///< 0..1 per cell
  /// Surface elevation at a point, metres, for gauges: bilinear between the four cell centres around
  /// it, over those that hold water now (wet, porosity > 0; their weights renormalised), so a gauge
  /// beside a quay, a wall or a dry beach reads the water and not the ground; where none of the four
  /// holds water, the nearest cell's eta (on dry land: the ground's height).
  double surface_elevation_at(double x_m, double y_m) const;
  /// Depth-integrated flux (P, Q) at a point, m^2/s, for gauges (the direction of the waves there,
  /// ocean/record_spectrum.hpp): the faces' fluxes averaged to the cell centres as
  /// cell_centred_fluxes does, then bilinear over the same wet cells as surface_elevation_at; where
  /// none of the four holds water, the nearest cell's.
  std::array<double, 2> flux_at(double x_m, double y_m) const;
  std::optional<InstabilityReport> check_stability() const;         ///< NaN or |eta| too large
  double water_volume_m3() const;            ///< sum of n * h * area over wet cells (for mass tests)
  /// Bytes of every grid-sized array the solver holds (state, work, static coefficients, sponge
  /// lists, output rasters, per-thread sweep scratch): what a bake's memory estimate is built from.
  /// docs/solver.md ("Memory") lists the arrays, their precision and why each is needed.
  std::size_t memory_bytes() const;
  /// Binary: everything needed to continue bit-identically (grid size, dt and a parameter hash are
  /// checked on load).
  void save_state(std::ostream& out) const;
  void load_state(std::istream& in);         ///< throws nearshore::Error on a mismatched/corrupt state

 private:
  struct Implementation;
  std::unique_ptr<Implementation> implementation_;
};

}  // namespace nearshore::boussinesq
