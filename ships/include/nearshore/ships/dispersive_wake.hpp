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
// Hull forcing (HullForcing). A pressure patch of the hull's draft (hull_pressure_head) is linear
// theory's forcing only while k zeta << 1: behind a blunt stern at low speed (a 24 x 9 x 3 m tug at
// 3 m/s has k zeta = g T / U^2 = 3.3) it makes waves metres high. The default is therefore Michell's
// thin ship (Michell 1898; Wehausen 1973, "The wave resistance of ships", Adv. Appl. Mech. 13):
// the hull is a distribution of sources on its centreplane whose strength is the normal
// velocity of the wet surface, m = (v . n) dA (volume per second) for each wet piece, put at the
// piece's depth z below the local surface on the body's centreplane: both sides of a thin hull add
// to 2 U dY/dx per unit area of the centreplane, Michell's source density (Y the half-breadth).
// The sources' potential under a rigid lid and over the bed, phi_0, splits off exactly in linear
// theory (phi = phi_0 + phi_w, phi_0z = 0 at z = 0): phi_w is a free-surface potential forced
// by the surface pressure head zeta = (d phi_0 / dt) / g, so the layer above carries it unchanged.
// Per Fourier mode (FFTW's sign, phi_0^(k) = sum_p m_p G_k(z_p) e^{-i k.x_p},
// G_k(z) = -cosh(k (d - z)) / (k sinh(k d)), z the depth below the surface; the sources move with
// the hull's velocity V: d phi_0 / dt = -(V . grad) phi_0):
//   zeta^(k) = i (k . V) A(k) / (g k tanh(k d)),   A(k) = sum_p m_p cosh(k (d - z_p)) / cosh(k d) e^{-i k.x_p}
// For a hull in steady motion in deep water, on the ring of the waves it makes ((k . V)^2 = g k)
// zeta^ is the displaced volume weighted by e^{-k z} per column: the deep parts of a blunt stern
// are attenuated as Michell's integral attenuates them (exp(k0 z sec^2 theta)), while the pressure
// patch weights them 1. A hull at rest makes no forcing (no depression of its own: the hull's
// volume is not a wave). The depth factor is applied on source_layers depth levels (linear in
// depth between them, a chord error (k dz)^2 / 8 of the exponential) on a grid of twice the
// layer's spacing, whose band (waves of 4 nodes and longer) is the filter: no further smoothing by
// default (source_smoothing_passes), since each pass lowers the wave resistance below Michell's.
// The Lagally force of phi_w on the same sources is the hull's wave resistance
// (wave_force_N: Michell's integral for a steady hull in deep water; tested against it).
//
// Breaking (breaking_slope). Linear waves have no height limit; a wave breaks where its steepness
// passes Michell's limit H / lambda = 0.142 (Michell 1893), a slope a k = pi 0.142 = 0.446 for the
// linear wave of that height. After each step, where the surface slope |grad eta| (central
// differences) exceeds breaking_slope, eta + zeta and phi at that node are scaled by
// breaking_slope / |grad eta|: the excess energy is dissipated there, as phase-resolving wave
// models dissipate where a local onset criterion is passed (Kennedy et al. 2000's Boussinesq
// breaking: d eta / dt above a fraction of the wave speed, for a progressive wave a slope times its
// phase speed). breaking_nodes() lists where it happened in the last update (the fleet's crest
// foam, ship_fleet.hpp).
//
// Structures and land (issue 42). The layer is one depth over a periodic window, so it cannot
// carry a wall's boundary condition; what it does carry is that no wave crosses a solid. Held at
// rest after every step (e = eta + zeta = 0, phi = 0) are the window's nodes inside the harbour's
// structures and land (HarbourObstacles' signed distance < 0, the seabed's obstacles), and the
// water nodes the hull's node does not reach through water (4-connected, inside the window: the
// far side of a breakwater that spans the window); on all of them the hull's forcing is also
// zeroed (the drawn height there is 0), because the sources' head zeta reaches every node of the window (its tails decay as a
// near field, not at a face) and would make waves there directly. So the wake stops at a
// breakwater's or quay's face and does not run through it or onto land, and it passes an
// entrance (a gap joins the two sides). What the face sends back is not a wall's reflection (a
// node held at rest is a soft boundary, and the spectral step spreads the hold over a node or
// two), and diffraction through a gap is the layer's own: the shallow-water grid is the layer that
// reflects (HarbourObstacles.ABowWaveIsDoubledAtAQuayAsAReflectingWallDoes). The solid mask follows
// the window like the state (only the nodes that enter it are looked up); the reach is a flood
// fill each update while the window holds a solid.
//
// Drawn height: eta (with the pressure patch: the depression -zeta under the hull, hidden in it)
// times the layer's shown weight (the fleet's blend between this layer and the shallow-water grid,
// ship_fleet.hpp).
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "nearshore/ships/bow_wave.hpp"
#include "nearshore/ships/seabed.hpp"
#include "nearshore/ships/ship_body.hpp"
#include "nearshore/ships/stern_wake.hpp"

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
  /// How a hull forces the layer (header): Michell's thin-ship sources or the draft's pressure patch.
  enum class HullForcing { thin_ship, pressure_patch };
  HullForcing forcing = HullForcing::thin_ship;
  int source_layers = 8;              ///< depth levels of the thin-ship sources' attenuation (2-32)
  /// Binomial passes (as cos^(2P)(k dx / 2) per mode) over the thin-ship head: 0, because the
  /// sources are splatted on a grid of twice the spacing, whose band (waves of 4 nodes and longer)
  /// is the filter; each pass takes Michell's wave resistance further below the integral's value
  /// (the Wigley hull at Fn 0.3: -5 % with 0 passes, -12 % with 1, -34 % with 6; docs/ships.md).
  int source_smoothing_passes = 0;
  /// Largest surface slope |grad eta| before the wave breaks (header); 0: no breaking. 0.446 is
  /// Michell's H / lambda = 0.142 as the slope a k of a linear wave.
  double breaking_slope = 0.446;
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
  /// The seabed's structures and land (Seabed::obstacles) stop the waves (header).
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
  /// Marks the window's nodes inside the solids of `obstacles` (null: none) and those the hull at
  /// site point (hull_x_m, hull_y_m) does not reach through water, held at rest by the following
  /// advances (header). update() calls it with the seabed's obstacles and the hull's centre.
  void set_solids(const HarbourObstacles* obstacles, double hull_x_m, double hull_y_m);
  /// Whether node (i, j) is inside a structure or land (the last set_solids).
  bool solid(int i, int j) const { return any_solid_ && solid_[index(i, j)] == kSolid; }
  /// Whether node (i, j) is held at rest: solid, or water the hull does not reach (the last set_solids).
  bool held(int i, int j) const { return any_solid_ && held_[index(i, j)] != 0; }
  /// Advances dt_s over still-water depth depth_m (exact in time, see above), then absorbs.
  void advance(double dt_s, double depth_m);

  /// Drawn height (m) at site point (x, y): bilinear between nodes, 0 outside the window.
  double elevation_m(double x_m, double y_m) const;
  /// What a renderer uploads (cell (i, j) of the field centred on node (i, j)).
  BowWaveField field() const;
  /// The weight of the drawn heights (the fleet's blend, 0..1; 1 by default).
  void set_shown_weight(double weight);
  double shown_weight() const { return shown_weight_; }

  /// The hull's thin-ship sources (header) for the next advance(): sets the pressure head from the
  /// wet pieces of `body` (their velocities from its state) over depth_m, in the current window.
  /// Public for towed hulls (tests); update() calls it with the forcing option thin_ship.
  void force_with_thin_ship(const ShipBody& body, double depth_m);
  /// The Lagally force of the free waves on the hull's sources, -rho sum_p m_p grad phi_w(x_p, z_p)
  /// (horizontal, site frame, N; rho 1025 kg/m^3): the wave resistance is minus its component along
  /// the motion. Michell's integral for a steady thin ship. Zero before the thin-ship forcing.
  /// Uses the layer's transform buffers: not concurrently with update() or advance().
  Eigen::Vector2d wave_force_N(double density_kg_m3 = 1025.0) const;
  /// Nodes where the last update broke a crest (site frame, m) and by how much the slope exceeded
  /// the limit (|grad eta| / breaking_slope - 1), at most one per 2 x 2 nodes.
  using BreakingNode = BreakingCrest;
  const std::vector<BreakingNode>& breaking_nodes() const { return breaking_; }

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
  void hold_solids_at_rest();
  void cut_off_forcing();
  void refresh_heights();
  void break_steep_crests(std::vector<BreakingNode>* record);

  DispersiveWakeOptions options_;
  int n_;
  double spacing_m_;
  std::unique_ptr<Spectral> spectral_;
  std::vector<float> eta_, phi_, zeta_;
  // Per-mode rotation for the last (dt, depth): cos, sin k tanh(kd) / w, -sin g / w.
  std::vector<float> cos_, eta_from_phi_, phi_from_eta_;
  std::vector<float> keep_;  ///< absorbing layer factor per node for the last dt
  // Nodes inside structures or land (header): kWater, kSolid, or kUnknown (entered the window since
  // the last set_solids); for the obstacles of solids_of_.
  static constexpr unsigned char kWater = 0, kSolid = 1, kUnknown = 2;
  std::vector<unsigned char> solid_;
  std::vector<unsigned char> held_;   ///< 1: solid or out of the hull's reach (set_solids)
  std::vector<int> fill_scratch_;     ///< the flood fill's stack
  long long reach_origin_i_ = 0, reach_origin_j_ = 0;  ///< the window the reach was filled for
  const HarbourObstacles* solids_of_ = nullptr;
  bool any_solid_ = false;
  double rotation_dt_s_ = -1.0, rotation_depth_m_ = -1.0;
  double depth_m_ = 0.0;
  bool started_ = false;
  long long origin_i_ = 0, origin_j_ = 0;
  std::vector<double> head_;  ///< corners, scratch (hull_pressure_head)
  std::vector<float> heights_m_;
  double shown_weight_ = 1.0;
  unsigned long long serial_ = 0;
  // Thin-ship sources: their depth-attenuated spectrum A(k) on the half-resolution band (kept for
  // the Lagally force), the layers' splats (scratch), the grid's depth when they were made.
  struct Sources;
  std::unique_ptr<Sources> sources_;
  std::vector<BreakingNode> breaking_;
  std::vector<std::pair<std::size_t, float>> break_scratch_;
  struct SourcePoint {
    double x, y, depth, strength;
  };
  std::vector<SourcePoint> source_scratch_;
};

/// The envelope ray of a dispersive wake (measure_wake_envelope_angle of bow_wave.hpp on this
/// layer's field): Kelvin's cusp line in deep water.
WakeAngle measure_wake_envelope_angle(const DispersiveWake& wake, const ShipState& state, double length_m,
                                      double start_lengths = 1.0, double min_lateral_m = 0.0);

}  // namespace nearshore::ships
