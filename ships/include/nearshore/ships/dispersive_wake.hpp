#pragma once
// The dispersive wake: a linear free-surface wave layer with the exact finite-depth dispersion of
// linear theory, moving with its ship and forced by the same hull pressure as the shallow-water bow
// wave (bow_wave.hpp). It is what makes Kelvin's pattern (19.47 deg in deep water; Havelock's wider
// cusp as the depth Froude number nears 1), which the non-dispersive shallow-water grid cannot
// (docs/ships.md, "The wake angle").
//
// Model (linearised potential flow, the surface conditions at z = 0 with a surface pressure p):
//   d eta / dt = phi_z              -> in Fourier space  d eta^ / dt = k tanh(k d) phi^
//   d phi / dt = -g eta - p / rho   ->                   d phi^ / dt = -g (eta^ + zeta^)
// with phi the velocity potential at the surface, d the still-water depth, zeta = p / (rho g) the
// hull's pressure head (its displaced volume per area, hull_pressure_head in bow_wave.hpp). Over a
// step in which zeta is held, e = eta + zeta and phi rotate exactly at omega(k) = sqrt(g k tanh(k d)):
//   e'   = e cos(w dt) + (k tanh(k d) / w) sin(w dt) phi
//   phi' = phi cos(w dt) - (g / w) sin(w dt) e
// so free waves keep their amplitude and travel at the phase speed of linear theory for every k
// the grid holds, at any time step (no CFL limit); a hull at rest sits in its depression eta = -zeta.
// The k = 0 mode keeps its mean elevation (volume) and its potential is irrelevant (set to 0).
//
// Grid. N x N nodes at spacing dx, periodic for the FFT (FFTW r2c / c2r in float, plans made once).
// The state (eta, phi) is kept in space between steps, because the absorbing layer and the window
// shift are spatial: a step is two forward and two inverse transforms. An absorbing layer of
// absorbing_fraction of the side relaxes eta and phi to rest at a rate rising as the square of the
// depth into the layer, so the periodic wrap does not bring the wake back.
//
// Window. Aligned with the site axes; its centre sits astern_fraction of the side behind the hull
// (along the hull's heading), so that most of the window holds the wake; it follows by whole nodes
// (an exact shift, the new nodes at rest). One depth d for the whole window: the seabed under the
// hull's centre, at most max_depth_m (k d > 10 is deep water to 1e-8 in tanh). Refraction and
// shoaling inside the window are therefore not modelled (the shallow-water grid is the layer for
// shoaling water, ship_fleet.hpp).
//
// Drawn height: eta (the depression -zeta under the hull, hidden in it) times the layer's shown
// weight (the fleet's blend between this layer and the shallow-water grid, ship_fleet.hpp).
#include <memory>
#include <vector>

#include "nearshore/ships/bow_wave.hpp"
#include "nearshore/ships/seabed.hpp"
#include "nearshore/ships/ship_body.hpp"

namespace nearshore::ships {

struct DispersiveWakeOptions {
  int cells = 256;                    ///< N: N x N nodes (even, at least 32)
  double side_in_lengths = 5.0;       ///< side of the window / the ship's length
  double astern_fraction = 0.2;       ///< window centre behind the hull, as a fraction of the side
  double max_depth_m = 200.0;         ///< the layer's depth: the seabed under the hull, at most this
  double absorbing_fraction = 0.15;   ///< width of the absorbing layer on each side / the side
  double absorbing_rate_per_s = 4.0;  ///< relaxation rate at the outer edge
  double max_step_s = 1.0 / 30.0;     ///< longer updates are split (the hull moves < 1 node a step)
  /// Binomial passes over the pressure head: each keeps cos^2(k dx / 2) of a wave, so 6 passes leave
  /// 2 % of the 4-node waves a sharp hull would excite unresolved and 39 % of 8-node waves.
  int smoothing_passes = 6;
};

class DispersiveWake {
 public:
  /// A window of options.cells nodes over side_in_lengths ship lengths.
  DispersiveWake(const ShipParticulars& particulars, DispersiveWakeOptions options = {});
  /// A window of `cells` nodes at `spacing_m` (tests, pressure patches without a hull).
  DispersiveWake(double spacing_m, DispersiveWakeOptions options);
  ~DispersiveWake();
  DispersiveWake(const DispersiveWake&) = delete;
  DispersiveWake& operator=(const DispersiveWake&) = delete;

  /// Moves the window with the body, takes the depth under the hull from `seabed` (null:
  /// max_depth_m), forces with the hull's displacement and advances dt_s. The first call (and the
  /// first after restart()) starts from rest with the hull in its depression.
  void update(const ShipBody& body, const Seabed* seabed, double dt_s);
  /// Forgets the waves: the next update starts from rest.
  void restart() { started_ = false; }

  // The parts update() is made of, public for pressure patches without a hull (tests):
  /// Puts node (0, 0) at site node (origin_i, origin_j) (in units of spacing_m): the state moves
  /// with the water, nodes that enter the window are at rest.
  void move_window(long long origin_i, long long origin_j);
  /// The pressure head zeta (m) at node (i, j), held over the next advance().
  float& pressure_head_m(int i, int j) { return zeta_[index(i, j)]; }
  float& surface_elevation_m(int i, int j) { return eta_[index(i, j)]; }
  float& velocity_potential_m2_s(int i, int j) { return phi_[index(i, j)]; }
  /// Sets eta = -zeta everywhere, phi = 0 (the hull in its depression, at rest).
  void rest_in_depression();
  /// Advances dt_s over still-water depth depth_m (exact in time, see above), then absorbs.
  void advance(double dt_s, double depth_m);

  /// Drawn height (m) at site point (x, y): bilinear between nodes, 0 outside the window.
  double elevation_m(double x_m, double y_m) const;
  /// What a renderer uploads (cell (i, j) of the field centred on node (i, j)).
  BowWaveField field() const;
  /// The weight of the drawn heights (the fleet's blend, 0..1; 1 by default).
  void set_shown_weight(double weight);
  double shown_weight() const { return shown_weight_; }

  int cells() const { return n_; }
  double spacing_m() const { return spacing_m_; }
  double depth_m() const { return depth_m_; }
  long long origin_i() const { return origin_i_; }
  long long origin_j() const { return origin_j_; }
  const DispersiveWakeOptions& options() const { return options_; }

 private:
  struct Spectral;  // FFTW plans and buffers
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * n_ + i; }
  void prepare_rotation(double dt_s, double depth_m);
  void step();
  void absorb();
  void refresh_heights();

  DispersiveWakeOptions options_;
  int n_;
  double spacing_m_;
  std::unique_ptr<Spectral> spectral_;
  std::vector<float> eta_, phi_, zeta_;
  // Per-mode rotation for the last (dt, depth): cos, sin k tanh(kd) / w, -sin g / w.
  std::vector<float> cos_, eta_from_phi_, phi_from_eta_;
  std::vector<float> keep_;  ///< absorbing layer factor per node for the last dt
  double rotation_dt_s_ = -1.0, rotation_depth_m_ = -1.0;
  double depth_m_ = 0.0;
  bool started_ = false;
  long long origin_i_ = 0, origin_j_ = 0;
  std::vector<double> head_;  ///< corners, scratch (hull_pressure_head)
  std::vector<float> heights_m_;
  double shown_weight_ = 1.0;
  unsigned long long serial_ = 0;
};

/// The envelope ray of a dispersive wake (measure_wake_envelope_angle of bow_wave.hpp on this
/// layer's field): Kelvin's cusp line in deep water.
WakeAngle measure_wake_envelope_angle(const DispersiveWake& wake, const ShipState& state, double length_m,
                                      double start_lengths = 1.0, double min_lateral_m = 0.0);

}  // namespace nearshore::ships
