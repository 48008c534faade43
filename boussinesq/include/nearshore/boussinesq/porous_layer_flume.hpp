#pragma once
// A numerical flume of the model itself that measures what a porous layer (seed 003 eq. (2)-(3):
// porosity n and the Van Gent (1995) resistance of PorousResistance) does to a regular wave: its
// reflection and transmission coefficients, the incident and reflected waves separated by Mansard &
// Funke (1980) (incident_reflected.hpp). These are the porosity charts MIKE 21 BW users read layer
// porosities from, made by the solver that will run the layer, at the cell size, depth, period and
// height of the bake; and their inverses: the porosity that gives a requested reflection (a layer
// in front of a wall: a rubble mound's faces, a quay's absorbing layer) or transmission (a layer
// with open water behind: a pier on piles, a permeable mound).
//
// The flume, along x, one cell across (the solver's 1-D road: docs/solver.md "Modes across a
// narrow flume"), flat bed at `still_water_depth_m`, cells of `spacing_m`:
//   west sponge (1.5 L) | source line (Wei et al. 1999) | gauges over 0.4 L | 0.3 L | the layer, `layer_width_m`
//   | wall_behind: two wall cells (porosity 0, as the bake lays a core)   else: open water, 5 gauges, east sponge (2 L)
// L the model's wavelength (model_dispersion.hpp) of the longest wave. The waves ramp up over two
// of their longest periods; the record is one common period of them all (eight longest periods)
// after the waves reflected from the far end have passed the gauges (group speed of the slowest).
// A whole number of steps per record makes the harmonic analysis exact. Breaking is off (the
// layer's own resistance is what is measured).
//
// Frequency dependence is physics: a layer of fixed width and porosity reflects less as it grows
// longer against the wave (W / L), and the turbulent resistance makes it depend on the height too;
// the bake fits at its sea state's peak and reports the response over its band (bake/structure_layers.hpp).
#include <string>
#include <vector>

#include "nearshore/boussinesq/boussinesq_solver.hpp"

namespace nearshore::boussinesq {

/// One wave the flume's source line makes.
struct FlumeWave {
  double period_s = 10.0;
  double height_m = 1.0;  ///< incident height (twice the amplitude)
};

struct PorousLayerFlume {
  double still_water_depth_m = 10.0;
  /// The incident waves: one regular wave, or several that stand for a sea state (they run together,
  /// so the turbulent resistance feels their combined velocity as it does the sea's). Periods are
  /// moved to the nearest whole number of cycles in the common record (eight times the longest
  /// period), so the harmonic analysis separates them exactly.
  std::vector<FlumeWave> waves = {FlumeWave{}};
  double spacing_m = 10.0;        ///< cell size along the flume (the bake's, so the layer is resolved as there)
  double layer_width_m = 20.0;    ///< the layer's extent along the flume (at least one cell)
  bool wall_behind = true;        ///< true: an impermeable wall right behind the layer; false: open water
  /// The bake's solver (equations, dispersion, bed friction, PorousResistance); the flume sets its
  /// own sponges and time step and turns breaking off.
  SolverParameters solver;
};

struct LayerResponse {
  double porosity = 1.0;
  double stone_diameter_m = 1.0;  ///< D of the layer's resistance (the flume solver's PorousResistance)
  /// Reflected / incident height in front of the layer; for several waves the energy ratio's root,
  /// sqrt(sum |Z_R|^2 / sum |Z_I|^2): the reflected Hs over the incident Hs of the sea they stand for.
  double reflection_coefficient = 0.0;
  double transmission_coefficient = 0.0;  ///< transmitted / incident height likewise (0 with a wall behind)
  double relative_depth_kh = 0.0;         ///< k h of the wave (the model's k); of the middle wave for several
  double layer_width_wavelengths = 0.0;   ///< layer_width_m / L, likewise
  double period_s = 0.0;                  ///< the (moved) period; of the middle wave for several
  std::vector<LayerResponse> per_wave;    ///< each wave's own response, when there are several
};

/// Runs the flume with the layer's cells at `porosity` (kWallPorosity < n <= 1). Throws
/// nearshore::Error (subject "porous layer flume") for inputs outside their ranges or an unstable run.
LayerResponse measure_porous_layer(const PorousLayerFlume& flume, double porosity);

/// The porosity whose layer reflects (wall_behind) or transmits (open water behind) a requested
/// fraction of the incident height, within `tolerance` (absolute): the chart walked from n = 1
/// down until it brackets the request, then regula falsi (Illinois) on the flume.
/// Where no porosity reaches the request (a layer too thin against the wave cannot absorb enough:
/// its reflection has a minimum over n), `reached` is false and `response` is the closest one.
struct PorosityFit {
  LayerResponse response;
  bool reached = true;
  int flume_runs = 0;
};
/// The lowest porosity fitted: a layer nearly closed acts as a wall (seed 003's n -> 0), and the
/// branch of n above the reflection's minimum is the one a rubble layer is on.
inline constexpr double kLowestFittedPorosity = 0.08;
PorosityFit fit_porosity_to_reflection(const PorousLayerFlume& flume, double reflection_coefficient, double tolerance = 0.02);
/// The coefficients fitted (and returned) are the layer's: Kr relative to the wall alone in the same
/// flume, Kt relative to the same flume without the layer (so the bed friction on the way, strong
/// in shallow water, is not counted against the layer).
PorosityFit fit_porosity_to_transmission(const PorousLayerFlume& flume, double transmission_coefficient, double tolerance = 0.02);

}  // namespace nearshore::boussinesq
