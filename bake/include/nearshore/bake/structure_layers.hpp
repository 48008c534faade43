#pragma once
// The harbour's coastal structures (core/coastal_structure.hpp) laid into the grid the solver runs
// on, as porous layers of seed 003 eq. (2)-(3) whose porosity is fitted, in the model's own flume
// (boussinesq/porous_layer_flume.hpp), to the reflection or transmission coefficient each structure
// asks for, at the bake's cells, the still-water depth in front of it, and the peak period and
// height of the sea the bake makes. Every bake of every sea state does its own fit: the same
// breakwater reflects its requested fraction of a 6 s sea and of a 14 s swell.
//
// Per structure:
//   1. its reflection coefficient: as given, or for a sloping rubble face from the sea state by
//      Zanuttigh & van der Meer (2008) (reflection_of_slope);
//   2. its footprint at the grid's cells (bathymetry/structure_footprint.hpp): core cells are
//      walls (porosity 0), face cells porous;
//   3. the flume: the still-water depth in front of it (the median depth of its wet face cells; no
//      shallower than where the sea's shortest wave is kFlumeCellsPerShortestWave cells long),
//      the faces' depth across (footprint half-width less the core), the sea state as up to five
//      waves of equal energy spread over its spectrum (StructureSeaState::waves), run together,
//      wall behind for an impermeable structure (fit Kr), open water behind otherwise (fit Kt); the
//      fitted coefficient is the sea's, sqrt(reflected energy / incident energy), the reflected Hs
//      over the incident Hs as Zanuttigh & van der Meer define theirs;
//      where even the least reflecting porosity reflects more than asked (a layer too thin against a
//      long wave), the faces are widened by whole cells into the water in front, up to four cells
//      or half a wavelength of layer; where that is still not enough (short waves: a layer whose
//      resistance, with the solver's stones, lets them through to the core and back), the layer's
//      resistance is fitted too: finer effective stones, D / sqrt(10) a step, at most four steps
//      (docs/structures.md, "When porosity is not enough"). The layer stands for a sloping mound
//      whose waves also break and run up on the slope, so its stone diameter is an effective one, a
//      resistance, as MIKE 21 BW's porosity layers take theirs;
//   4. each wave's own response is recorded, so a user sees how the layer's reflection moves with
//      k h across the sea's band (frequency dependence is physics: a real mound's does too).
// Structures that give their porosity keep it (no fit); they are recorded likewise.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "nearshore/boussinesq/boussinesq_solver.hpp"
#include "nearshore/boussinesq/porous_layer_flume.hpp"
#include "nearshore/core/harbour_grid.hpp"

namespace nearshore::bake {

/// What the structures are fitted to: the sea the bake makes.
struct StructureSeaState {
  double significant_wave_height_m = 0.0;  ///< Hs = 4 sqrt(m0)
  double peak_period_s = 0.0;              ///< Tp
  double spectral_period_s = 0.0;          ///< T_m-1,0 = m_-1 / m0 (Zanuttigh & van der Meer's period)
  double shortest_period_s = 0.0, longest_period_s = 0.0;  ///< the band the bake makes
  /// The waves that stand for it in the flume: up to five, each carrying an equal share of the
  /// variance, at the quantiles 0.2 - 0.8 of the spectrum's cumulative variance held within a factor
  /// 1.9 in frequency (so their heights together make the sea's Hs, the layer's turbulent resistance
  /// feels the sea's velocities, and no two waves' bound waves fall on a third); one regular wave
  /// for a regular maker; H = Hs / sqrt 2 at the mean zero-crossing period for a time series.
  std::vector<boussinesq::FlumeWave> waves;
};

/// The sea a wave maker makes: from its components (m0, m_-1 and the peak of their variance), or
/// from a time series (Hs = 4 sigma, every period the mean zero up-crossing period); empty (Hs = 0)
/// for a solitary wave or no maker.
StructureSeaState structure_sea_state(const boussinesq::WaveMaker& maker);

/// Kr of a sloping face by Zanuttigh & van der Meer (2008, Coastal Engineering 55, eq. 10 and
/// Table 4): Kr = tanh(a xi^b), a = 0.167 (1 - exp(-3.2 gamma_f)), b = 1.49 (gamma_f - 0.38)^2 + 0.86,
/// xi = tan(alpha) / sqrt(Hs / L0) the breaker parameter with L0 = g T_m-1,0^2 / (2 pi).
/// `side_slope` is cot(alpha) (> 0).
double reflection_of_slope(double side_slope, double roughness_factor, double significant_wave_height_m, double spectral_period_s);

/// One structure as the bake laid it.
struct StructureLayer {
  std::string name, kind;
  double reflection_requested = 1.0;    ///< Kr after step 1
  std::string reflection_from;          ///< "given" or the Zanuttigh & van der Meer breaker parameter
  double transmission_requested = 0.0;  ///< Kt (0 for an impermeable core)
  bool fitted = false;                  ///< false: the source gave its porosity
  bool reached = true;                  ///< the fit reached the request within its tolerance
  double face_porosity = 1.0;
  /// D of the faces' porous resistance, metres: the solver's (PorousResistance::stone_diameter_m)
  /// unless the fit needed finer effective stones to reach the request (then the harbour grid's
  /// porous_stone_diameter_m holds it at the faces).
  double stone_diameter_m = 1.0;
  bool stones_fitted = false;  ///< the fit made the stones finer than the solver's
  double depth_m = 0.0, face_width_m = 0.0;
  /// The still water the flume ran the fit in: depth_m (to within the shared fits' 10 % bins), or,
  /// where the sea's shortest flume wave is shorter than kFlumeCellsPerShortestWave cells there, the
  /// shallowest depth where it is that long (the grid cannot carry the wave in shallower water, and a
  /// flume of it measures noise: docs/structures.md, "Water too shallow for the grid's waves").
  double flume_depth_m = 0.0;
  double wave_period_s = 0.0;  ///< the sea's peak period
  /// How far the faces reach beyond the footprint: a layer too thin against the wave to absorb
  /// what the structure does not reflect is widened a cell at a time (up to four cells or half a
  /// wavelength of layer) until its chart reaches the request.
  double widening_m = 0.0;
  boussinesq::LayerResponse in_the_sea;  ///< the fitted layer in the flume's sea (its waves together)
  std::vector<boussinesq::LayerResponse> across_band;  ///< each flume wave's own response, longest period first
  std::size_t core_cells = 0, face_cells = 0;
  int flume_runs = 0;
};

/// The fit's tolerance on Kr and Kt: 0.02 absolute, the repeatability of laboratory reflection
/// measurements with three-gauge separation (Mansard & Funke 1980 report a few per cent).
inline constexpr double kStructureFitTolerance = 0.02;

/// The fewest cells per wavelength of the sea's shortest flume wave at which a layer is fitted: in
/// shallower water the fit runs at the depth where the wave is this long. Below it the scheme
/// carries the wave as little more than a two-cell pattern, and the flume's Mansard & Funke
/// separation gave per-wave coefficients of 1.2-33 (Commencement Bay at 12 m cells: 144 layers, every
/// one with fewer than 3.4 cells per wavelength, none above 3.5).
inline constexpr double kFlumeCellsPerShortestWave = 4.0;
/// Finer effective stones tried, each D / sqrt(10) of the one before, where porosity and widening
/// alone cannot absorb what a structure does not reflect or transmit: at most a hundredth of the
/// solver's D (a metre's stones become 1 cm: past that the layer turns into a wall again).
inline constexpr int kMostStoneDiameterSteps = 4;

/// Lays every structure of `grid` (which must carry them) at its cells: the porosity channel
/// becomes 1 everywhere but the footprints, the stone diameter channel (HarbourGrid::
/// porous_stone_diameter_m) is made where a fit needed stones of its own and is empty otherwise. `sea` may be empty (Hs = 0): then no fit is possible,
/// each face keeps `fallback_porosity` and a warning says so. Warnings (a request no layer of that
/// width reaches, a structure off the grid) are appended to `warnings`, naming the structure.
std::vector<StructureLayer> lay_structures(HarbourGrid& grid, const boussinesq::SolverParameters& solver,
                                           const StructureSeaState& sea, std::vector<std::string>& warnings,
                                           double fallback_porosity = 0.45);

nlohmann::json structure_layers_record(const std::vector<StructureLayer>& layers);
/// One line per structure for the bake's report: name, Kr asked -> got at the peak, over the band, porosity.
std::string describe_structure_layers(const std::vector<StructureLayer>& layers);

}  // namespace nearshore::bake
