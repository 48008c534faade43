#pragma once
// ShipFleet: every ship of a scene, stepped together on the shown sea. What a host (the viewer,
// the C API) calls once per displayed frame:
//
//   ShipFleet fleet;
//   fleet.set_site(engine.site());                        // grounding and the bow waves' bottom
//   fleet.add_ship(definition);                           // or load_scenario(path, fleet)
//   for each frame:
//     engine.advance_to(t);
//     fleet.step(engine.snapshot(), dt);                  // bodies, bow waves, wakes, contacts
//     for (const Ship& s : fleet.ships()) draw(s.body().state(), s.bow_wave()->field(), s.wake().decals());
//     double eta = fleet.shown_elevation_m(sampler, x, y);  // the sea + every ship's bow wave
//
// One step (dt, s), in this order:
//   1. orders -> controls: a route is followed by a heading autopilot (rudder = clamp(2 e - T r),
//      e the heading error to the next waypoint, r the yaw rate, T = L / U), a speed order by the
//      engine (feed-forward (U / U_service)^2 plus proportional); a manual engine order and rudder
//      (controls(i)) apply otherwise.
//   2. ship-ship repulsion (seed 002 eq. 3, F_c) from the current poses: each hull's waterplane is
//      a capsule (its centreline segment, radius half the beam); within a margin of half the summed
//      radii a repulsion grows as m_r v_0^2 (s_0 / gap - 1) / s_0 (m_r the reduced mass,
//      v_0 = 3 m/s: the barrier stops a closing speed of 7 m/s before contact), plus a damping of
//      the closing speed, at the closest points, with their torques.
//   3. each body steps on the sampled surface plus the OTHER ships' bow waves, over the seabed.
//   4. each bow wave moves and steps with its hull; each wake ages and drops decals, and foam is
//      dropped where the shown dispersive layer broke (CrestFoam, stern_wake.hpp). A ship with a
//      dispersive wake (dispersive_wake.hpp) has two bow-wave layers and shows one, chosen by its
//      depth Froude number Fr_d = U / sqrt(g d) (WakeLayerChoice below), so that the hull's
//      displacement is counted once: the shown weights of the two layers sum to 1.
//   5. structures: a ship whose hull touches a breakwater, quay, pier or the land (the body's
//      contact, ship_body.hpp) gets an event naming the structure, where and how fast it struck, and
//      another when it is clear again. A strike faster than 0.5 m/s (above the berthing speeds of
//      PIANC's fender guidance) is a collision: its orders are dropped and the engine stopped, as
//      on grounding; a gentler touch keeps the orders (a tug pushes on a quay).
//   6. grounding: a ship with hull points below the seabed is aground; its engine is stopped (its
//      orders dropped: the ship stops by the bed's friction), and an event says where, how deep and
//      at what heel; refloating is said too.
#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nearshore/runtime/surface_sampler.hpp"
#include "nearshore/ships/bow_wave.hpp"
#include "nearshore/ships/dispersive_wake.hpp"
#include "nearshore/ships/hull_mesh.hpp"
#include "nearshore/ships/seabed.hpp"
#include "nearshore/ships/ship_body.hpp"
#include "nearshore/ships/stern_wake.hpp"

namespace nearshore::ships {

/// What a ship is told to do. Either an engine order or a speed; optionally a route.
struct ShipOrders {
  std::optional<double> engine_order;      ///< [-1, 1]
  std::optional<double> speed_m_s;         ///< held by the engine (ahead only)
  std::vector<Eigen::Vector2d> route_m;    ///< waypoints, site frame; followed by the autopilot
  double waypoint_radius_lengths = 1.5;    ///< a waypoint is reached within this many ship lengths
};

/// Which bow-wave layer a ship with a dispersive wake shows. Its own transverse wave (wavelength
/// 2 pi U^2 / g) has k d = 1 / Fr_d^2: below dispersive_below_froude (k d > 2, tanh(k d) > 0.96:
/// deep to intermediate water) the waves are dispersive and small, which the linear layer with its
/// exact dispersion carries and the shallow-water grid cannot (it has no subcritical waves at all);
/// above shallow_above_froude the ship nears the critical speed, where linear theory's amplitude
/// grows without bound and the nonlinear shallow-water grid (with its beach and wetting) is the
/// better model. The band between is hysteresis, so a ship at a Froude number near a threshold does
/// not flicker between layers. A switch fades over fade_s: weight w on the dispersive layer, 1 - w
/// on the shallow-water grid; a layer whose weight reaches 0 stops and restarts from rest when
/// it is chosen again. The depth d is the seabed's under the hull's centre (without a seabed:
/// the dispersive layer's max_depth_m).
/// The dispersive layer is also chosen only when its window resolves the ship's waves: the
/// transverse wavelength 2 pi U^2 / g (deep water; longer in finite depth) at least
/// resolved_wave_nodes of the layer's spacing (8: the forcing's smoothing keeps 39 % of an 8-node
/// wave, 2 % of a 4-node one). Slower, the Kelvin waves are shorter than the window can draw, and
/// the shallow-water grid (the hull's depression and push) is shown; the choice goes back below
/// 3/4 of that length (hysteresis). A ship at rest or creeping therefore shows the grid.
struct WakeLayerChoice {
  double dispersive_below_froude = 0.7;
  double shallow_above_froude = 0.8;
  double resolved_wave_nodes = 8.0;
  double fade_s = 2.0;
};

struct ShipDefinition {
  std::string name;
  HullMesh hull;
  int hull_points = 2000;                  ///< feature points (hull_samples.hpp)
  HullLoading loading;
  double x_m = 0.0, y_m = 0.0;             ///< start position of the hull's centre, site frame
  double heading_deg = 0.0;                ///< compass (clockwise from north)
  double initial_speed_m_s = 0.0;          ///< along the heading
  ShipOrders orders;
  bool bow_wave = true;
  BowWaveOptions bow_wave_options;
  /// A dispersive linear wave layer besides the shallow-water grid (Kelvin's pattern; needs
  /// bow_wave), forced by the hull's thin-ship sources and limited by breaking (dispersive_wake.hpp);
  /// shown where WakeLayerChoice calls for it. On by default.
  bool dispersive_wake = true;
  DispersiveWakeOptions dispersive_wake_options;
  /// Squat and the shallow-water resistance (restricted_water.hpp) from the depth under the hull.
  /// On by default; off gives the hull its deep-water behaviour in any depth (comparisons, tests of
  /// the contact mechanics alone).
  bool restricted_water = true;
  WakeLayerChoice wake_layer;
  SternWakeOptions wake_options;
};

/// A ship touching, or coming clear of, a structure or the land (harbour_obstacles.hpp).
struct ContactEvent {
  std::string ship;                 ///< the ship's name
  std::size_t ship_index = 0;       ///< its index when the event happened
  bool began = true;                ///< true: it struck; false: it is clear again
  int structure = 0;                ///< 0 the land, k >= 1 structure k
  bool wall = false;                ///< a quay wall (porosity < 0.05); else a porous breakwater or land
  double porosity = 1.0;            ///< the structure's lowest porosity (1 for land)
  std::string description;          ///< HarbourStructure::describe()
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< the deepest contact point, site frame
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();      ///< the face's normal there, out of the solid
  double closing_speed_m_s = 0.0;   ///< how fast the hull met the face (began) or 0
  double time_s = 0.0;              ///< the fleet's time (sum of its steps)
};

struct ShipStatus {
  int structure_contact = -1;       ///< the structure (0 land) the hull touches, -1 none
  bool aground = false;
  Eigen::Vector3d contact_position_m = Eigen::Vector3d::Zero();
  double max_penetration_m = 0.0;
  int waypoint = 0;                        ///< index of the next waypoint
};

class Ship {
 public:
  Ship(std::string name, ShipBody body, ShipOrders orders, std::unique_ptr<BowWave> bow_wave, SternWake wake);
  const std::string& name() const { return name_; }
  const ShipBody& body() const { return body_; }
  ShipBody& body() { return body_; }
  const BowWave* bow_wave() const { return bow_wave_.get(); }
  /// The dispersive layer (null unless ShipDefinition::dispersive_wake).
  const DispersiveWake* dispersive_wake() const { return dispersive_wake_.get(); }
  /// The depth Froude number of the last step (speed over ground / sqrt(g d)) and the weight of
  /// the dispersive layer in what is shown (0: the shallow-water grid alone; WakeLayerChoice).
  double depth_froude_number() const { return depth_froude_; }
  double dispersive_weight() const { return std::max(dispersive_weight_, 0.0); }
  const SternWake& wake() const { return wake_; }
  /// Foam where the ship's shown dispersive layer broke (its crests past the breaking limit).
  const CrestFoam& crest_foam() const { return crest_foam_; }
  const ShipStatus& status() const { return status_; }
  const ShipOrders& orders() const { return orders_; }
  /// Replaces the orders (a host's engine telegraph and helm): clears the route unless given.
  /// Throws nearshore::Error naming the ship and the field for an order out of its range
  /// (ship_limits.hpp: engine order in [-1, 1], speed ahead up to max_speed_m_s, finite waypoints).
  void set_orders(ShipOrders orders);
  /// Manual controls: used when the orders hold no engine order, speed or route (a viewer's keys).
  ShipControls& manual_controls() { return manual_; }
  const ShipControls& controls() const { return controls_; }

 private:
  friend class ShipFleet;
  std::string name_;
  ShipBody body_;
  ShipOrders orders_;
  std::unique_ptr<BowWave> bow_wave_;
  std::unique_ptr<DispersiveWake> dispersive_wake_;
  WakeLayerChoice wake_layer_;
  double depth_froude_ = 0.0, dispersive_weight_ = -1.0;  // < 0: no step yet
  bool dispersive_chosen_ = false;
  SternWake wake_;
  CrestFoam crest_foam_;
  ShipStatus status_;
  ShipControls manual_, controls_;
  ExternalLoad external_;
};

struct FleetOptions {
  WaterProperties water;
  double repulsion_speed_m_s = 3.0;  ///< v_0 above
  /// Structures and land as obstacles (crest height, band of the distance field).
  HarbourObstacleOptions obstacles;
};

class ShipFleet {
 public:
  explicit ShipFleet(FleetOptions options = {});

  /// The seabed under the fleet: a site's harbour grid (grounding, placement, bow-wave bottom).
  /// Without one the sea is bottomless (bow waves at max_depth_m).
  void set_site(std::shared_ptr<const runtime::HarbourSite> site);
  void set_seabed(Seabed seabed);
  const Seabed* seabed() const { return seabed_ ? &*seabed_ : nullptr; }

  /// Builds a ship (samples its hull, its particulars, its bow wave and wake) upright at its
  /// design draft. Throws nearshore::Error naming the ship when its mass cannot float or it is
  /// placed on land or in water shallower than its draft.
  std::size_t add_ship(const ShipDefinition& definition);
  /// Removes ship `index` (later ships move down by one).
  void remove_ship(std::size_t index);

  /// One frame on the sea a snapshot shows.
  void step(const runtime::SurfaceSnapshot& snapshot, double dt_s);
  /// One frame on a sampler's sea (null: flat still water).
  void step(const runtime::SurfaceSampler* water, double dt_s);

  std::size_t size() const { return ships_.size(); }
  Ship& ship(std::size_t index) { return *ships_.at(index); }
  const Ship& ship(std::size_t index) const { return *ships_.at(index); }

  /// Sum of the ships' bow-wave heights at (x, y) (m), leaving out ship `exclude` (-1: none).
  double bow_wave_elevation_m(double x_m, double y_m, long exclude = -1) const;
  /// The shown surface at (x, y) with every ship's bow wave: what a host's other buoyant objects
  /// and the renderer use.
  double shown_elevation_m(const runtime::SurfaceSampler& water, double x_m, double y_m) const;
  /// Every shown bow-wave layer's field (a ship with a dispersive wake gives one or two, by weight).
  std::vector<BowWaveField> bow_wave_fields() const;

  /// Messages since the last call ("ship 'Tug 1' ran aground at (812.4, 1033.0) m ..."), oldest first.
  std::vector<std::string> take_events();
  /// Contacts with structures and land since the last call, oldest first (each is also a message).
  std::vector<ContactEvent> take_contacts();

 private:
  void apply_orders(Ship& ship);
  void update_bow_waves(Ship& ship, double dt_s);
  void repel();
  void report_structure_contact(Ship& ship, std::size_t index);

  FleetOptions options_;
  std::optional<Seabed> seabed_;
  std::vector<std::unique_ptr<Ship>> ships_;
  std::vector<std::string> events_;
  std::vector<ContactEvent> contacts_;
  double time_s_ = 0.0;
};

}  // namespace nearshore::ships
