#pragma once
// Bow waves: a local shallow-water grid that moves with its ship (seed 000 section 4.2.3 (1), after
// Cords 2008), solved by the Kurganov-Petrova scheme (shallow_water.hpp) and forced by the hull's
// displacement, drawn as a height field added to the shown surface.
//
// Forcing. The seed pushes the grid's velocities near the hull points (eq. 4.26-4.28, with a tuned
// anisotropy E_v). Here the hull is what it physically is to the water, a moving pressure on the
// surface (Havelock's pressure-patch ship): its head zeta(x, y) = p / (rho g) is the depth of the
// hull below the local surface, zeta = sum over wet points of (eta - z) (-n_z) A / dx^2 splatted
// bilinearly on the grid's corners (the vertical projection of the displaced volume, so
// sum zeta dx^2 = the displaced volume) and smoothed by two binomial passes. The scheme carries
// it exactly like a raised bottom, so a hull at rest sits in its depression without making waves,
// and a moving one pushes water ahead and aside at the speed the grid's depth allows.
//
// Window. The grid is aligned with the site axes and centred on the hull; when the hull has moved
// one cell or more it shifts by whole cells (no interpolation, no numerical diffusion from the
// move). Its bottom is the seabed (the harbour grid's depth, clamped to max_depth_m: the
// shallow-water wave speed sqrt(g d) of deep water would need tiny time steps and is wrong for
// short waves anyway, see "what limits the match" in docs/ships.md).
//
// Edges. Waves leave through open edges (zero gradient) and an absorbing layer of
// absorbing_fraction of the side, where w, hu, hv relax to rest at a rate rising as the square of
// the depth into the layer (the seed's radial fade, eq. 4.16, as a sponge).
//
// Drawn height: eta_bow = w (the surface above still water) where the cell is wet, 0 where dry;
// under the hull it is the depression -zeta (hidden inside the hull). A host adds eta_bow to the
// shown surface (BowWaveField, for the GPU, or elevation_m for the CPU queries); a ship's own
// physics sees the other ships' bow waves, not its own (ship_fleet.hpp).
#include <vector>

#include "nearshore/ships/seabed.hpp"
#include "nearshore/ships/shallow_water.hpp"
#include "nearshore/ships/ship_body.hpp"

namespace nearshore::ships {

struct BowWaveOptions {
  int cells = 128;                  ///< N: the grid is N x N
  double side_in_lengths = 4.0;     ///< side of the grid / the ship's length
  double max_depth_m = 10.0;        ///< the grid's bottom: the seabed, at most this deep
  double absorbing_fraction = 0.15; ///< width of the absorbing layer on each side / the side
  double absorbing_rate_per_s = 3.0;  ///< relaxation rate at the outer edge
  int smoothing_passes = 2;         ///< binomial passes over the pressure head
  ShallowWaterOptions solver;
};

/// What a renderer uploads: N x N cell-centred heights (m), row 0 south, cell (i, j) centred at
/// (origin_x_m + (i + 0.5) spacing_m, origin_y_m + (j + 0.5) spacing_m) in the site frame.
struct BowWaveField {
  double origin_x_m = 0.0, origin_y_m = 0.0, spacing_m = 1.0;
  int columns = 0, rows = 0;
  const std::vector<float>* heights_m = nullptr;
  unsigned long long serial = 0;  ///< changes with every update (upload once per serial)
};

/// The hull's pressure head zeta = p / (rho g) (m) on the (n + 1) x (n + 1) corners of a window
/// whose corner (0, 0) is site node (origin_i, origin_j) at spacing_m: the vertical projection of
/// the displaced volume of the wet samples under the water the body saw in its last step, splatted
/// bilinearly (so sum zeta dx^2 = the displaced volume) and smoothed by smoothing_passes binomial
/// passes. The forcing of the shallow-water grid (BowWave) and of DispersiveWake with its
/// pressure_patch option (its default is the thin ship, dispersive_wake.hpp).
void hull_pressure_head(const ShipBody& body, long long origin_i, long long origin_j, double spacing_m, int n,
                        int smoothing_passes, std::vector<double>& head);

/// A field's height (m) at site point (x, y): bilinear between cell centres, 0 outside.
double field_elevation_m(const BowWaveField& field, double x_m, double y_m);

class BowWave {
 public:
  BowWave(const ShipParticulars& particulars, BowWaveOptions options = {});

  /// Moves the window with the body, sets the bottom from `seabed` (null: max_depth_m everywhere),
  /// forces with the hull's displacement under the water the body saw in its last step, and
  /// advances dt_s. The first call starts from rest with the hull in its depression.
  void update(const ShipBody& body, const Seabed* seabed, double dt_s);

  /// eta_bow (m) at site point (x, y): bilinear between cell centres, 0 outside the grid.
  double elevation_m(double x_m, double y_m) const;
  BowWaveField field() const;
  /// The weight of the drawn heights (the fleet's blend with the dispersive layer, 0..1; 1 by default).
  void set_shown_weight(double weight);
  double shown_weight() const { return shown_weight_; }
  /// Forgets the waves: the next update starts from rest.
  void restart() { started_ = false; }
  const BowWaveGrid& grid() const { return grid_; }
  const BowWaveOptions& options() const { return options_; }
  int last_steps() const { return last_steps_; }

 private:
  void set_bottom(const Seabed* seabed);
  void set_pressure_head(const ShipBody& body);
  void absorb(double dt_s);
  void refresh_heights();

  BowWaveOptions options_;
  double spacing_m_;
  BowWaveGrid grid_;  ///< float: see "Precision" in shallow_water.hpp
  bool started_ = false;
  long long origin_i_ = 0, origin_j_ = 0;  ///< the window's south-west corner in cells of the site frame
  std::vector<double> head_;               ///< corners, scratch
  std::vector<float> heights_m_;
  unsigned long long serial_ = 0;
  int last_steps_ = 0;
  double shown_weight_ = 1.0;
};

/// The half-angle of a wake pattern (degrees) measured on a bow-wave grid, for a ship moving along
/// its body x axis: in the ship's frame, for each distance xi behind the bow from `start_lengths`
/// to where the absorbing layer begins, the outermost lateral offset where |eta_bow| exceeds
/// threshold_fraction of the largest |eta_bow| outside the hull, on each side; a least-squares line
/// through those offsets against xi gives the angle (atan of its slope, both sides averaged).
/// The outermost disturbance is sensitive to noise (a start-up ring, the sponge); see
/// measure_wake_envelope_angle for the robust measurement.
struct WakeAngle {
  double half_angle_deg = 0.0;
  int stations = 0;        ///< distances xi used (both sides)
  double fit_rms_m = 0.0;  ///< scatter of the offsets about the line
  double r_squared = 0.0;  ///< coefficient of determination of the line (1: every station on it)
  /// A wedge was found: the offsets grow with distance (angle above 1 deg) and the line explains
  /// most of their scatter (r_squared >= 0.6). False: the pattern does not spread, the number is noise.
  bool wedge = false;
};
WakeAngle measure_wake_half_angle(const BowWave& wave, const ShipState& state, double length_m,
                                  double threshold_fraction = 0.1, double start_lengths = 1.0);
/// The same on any field whose absorbing layers are absorbing_fraction of its side.
WakeAngle measure_wake_half_angle(const BowWaveField& field, double absorbing_fraction, const ShipState& state,
                                  double length_m, double threshold_fraction, double start_lengths);

/// The half-angle of the wake's envelope (degrees): for each distance xi behind the bow from
/// start_lengths ship lengths to the absorbing layer, the lateral offset on each side where |eta_bow|
/// is largest (the ray of the envelope's maximum: Kelvin's cusp line at 19.47 deg in deep water,
/// the Mach line asin(1 / Fr_d) above the critical speed in shallow water), offsets within
/// min_lateral_m of the track left out (the hull's own trough); a least-squares line through
/// the (xi, offset) pairs of both sides. Only the largest value per station enters, so the
/// measurement does not depend on a threshold or on the weak start-up ring.
WakeAngle measure_wake_envelope_angle(const BowWave& wave, const ShipState& state, double length_m,
                                      double start_lengths = 1.0, double min_lateral_m = 0.0);
/// The same on any field whose absorbing layers are absorbing_fraction of its side (the one
/// implementation behind both layers' measurements).
WakeAngle measure_wake_envelope_angle(const BowWaveField& field, double absorbing_fraction, const ShipState& state,
                                      double length_m, double start_lengths, double min_lateral_m);

}  // namespace nearshore::ships
