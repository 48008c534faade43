#pragma once
// The 6-degree-of-freedom rigid body of one ship on the shown sea (seed 000 section 4.2.2,
// eq. 4.17-4.22; seed 002 section 2.1, eq. 1-4).
//
// Forces, summed over the hull's feature points i (hull_samples.hpp) and applied at the centre of
// gravity G (world frame: site metres, z up; body frame: x forward, y port, z up):
//   pressure   p = rho g (eta_i - z) over hull piece i, eta_i the surface over its centroid (seed
//              000 eq. 4.21-4.22 with the area and the sign of an outward normal): integrated
//              exactly over the piece's wet part (p linear over the piece, cut where p = 0):
//              F_i = -rho g [integral (eta_i - z)+ dA] n_i, T_i = -rho g [integral (eta_i - z)+ r dA] x n_i,
//              so a piece the waterline cuts counts exactly its wet part and a hull at rest in still
//              water feels no horizontal force or yaw moment from the sampling. eta is the shown
//              surface (SurfaceSampler, displaced query) plus the other
//              ships' bow waves: the hydrostatic pressure under the local surface, i.e. hydrostatics
//              and the Froude-Krylov force of the waves in their long-wave (hydrostatic) limit.
//   gravity    m g at G.
//   drag       body axes, relative to the water's velocity at G: -(D_l v + D_q |v| v) for surge,
//              sway, heave and -(D_l w + D_q |w| w) for roll, pitch, yaw, scaled by the wetted area
//              over the upright design wetted area (no drag in the air). The surge and sway forces
//              act at the heights where the water resists (ShipParticulars::surge_drag_z_m,
//              sway_drag_z_m), not at G: the sway force at the underwater lateral area's centroid is
//              what heels a turning ship outward by m V^2 / R (KG - T/2) (issue 42).
//   engine     thrust along body x at the propeller (seed 002 eq. 3 F_e), order in [-1, 1].
//   rudder     lift 1/2 rho A_R C_L' delta V_R^2 along body -y at the rudder, V_R^2 = u^2 + 8 T /
//              (pi rho D_p^2) (the propeller slipstream by momentum theory, so a ship with the
//              engine on turns at low speed).
//   contact    seabed (grounding): a wet point below the seabed z_b = -depth(x, y) pushes up with
//              k A_i (z_b - z_i) - c A_i dz_i/dt (k = 50 rho g: a sand bed 50 times stiffer than
//              the water's hydrostatic stiffness, c = 0.1 s k), with Coulomb friction mu = 0.4
//              (regularised below 5 cm/s) against the point's horizontal velocity.
//   structures breakwaters, quays, piers and land (the seabed's HarbourObstacles): a hull point at
//              horizontal depth p = -phi inside a solid and below its top pushes out along the
//              face's normal n with k_s A_i (p - t_s v.n) (k_s = 500 rho g: a face 10 times stiffer
//              than the sand bed, so that a tug at 3 m/s stops within a few decimetres; t_s = 0.02 s
//              keeps the explicit step stable, k_s A t_s dt / m well under 2), with Coulomb friction
//              mu = 0.4 against the point's velocity along the face (steel on concrete or rock).
//              An impact is near-plastic (ship_body.cpp step 7: restitution 0 at the deepest point,
//              a friction impulse of at most mu times the normal one, Pedersen & Zhang 1998), and
//              the penalty pushes the hull out no faster than 5 cm/s: a struck ship stays at the face.
//   squat      in shallow water (restricted_water.hpp: Tuck 1966 / ICORELS 1980 / Barrass 2004 at the
//              mean depth under the hull and the speed through the water): the return flow's
//              pressure deficit as a vertical force -rho g A_wp S_m at the centre of flotation and
//              a trimming couple K_pitch theta, the loads the hull's own hydrostatics balance at
//              the published sinkage S_m and trim theta; so squat builds up and decays with the
//              hull's heave and pitch dynamics and can put the keel on the bed.
//   shallow    the surge drag evaluated at Lackenby's (1963) equivalent deep-water speed
//              (restricted_water.hpp): at a fixed engine order the ship is slowed by the published
//              speed loss.
//   external   ship-ship repulsion (ship_fleet.hpp), given as a force and a torque about G.
// Dynamics: Newton for the translation with the world-frame mass matrix M = R (m Id + A_t) R^T
// (eq. 4.17 with the added masses A_t of surge, sway, heave) and the added masses' Coriolis force
// of Kirchhoff's equations, A_t (w x v_r) - w x (A_t v_r) (so a turning ship needs (m + A_11) V^2 / R
// of lateral force, not (m + A_22) V^2 / R; the Munk moment that goes with it is left out: the body
// has no linear hull lift to balance it, and with it the launch ran into a spin at 0.1 rad (6 deg) of rudder),
// Euler's equations with the world-frame inertia tensor I = R (I_G + A_r) R^T (eq. 4.18-4.20):
//   dw/dt = I^-1 [T - w x (I w)]
// Integrator: semi-implicit (symplectic) Euler, velocities first, then position and the
// orientation quaternion q <- exp(w dt / 2) q, in substeps of at most 1/60 s: stable at a host's
// 30-60 Hz for the hydrostatic stiffness (w_heave dt ~ 0.1) and the seabed's (~0.6). It replaces
// the seed's ad-hoc velocity damping mu (eq. 4.23-4.24) and height override (eq. 4.25) by the
// physical drag above, so a ship keeps its momentum and settles by itself.
#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "nearshore/runtime/surface_sampler.hpp"
#include "nearshore/ships/hull_samples.hpp"
#include "nearshore/ships/restricted_water.hpp"
#include "nearshore/ships/seabed.hpp"

namespace nearshore::ships {

struct WaterProperties {
  double density_kg_m3 = 1025.0;  ///< sea water
  double gravity_m_s2 = 9.81;
};

/// Everything about a ship that its motion needs; particulars_for_hull fills it from a hull.
/// Vectors of three along body axes: (surge, sway, heave) or (roll, pitch, yaw).
struct ShipParticulars {
  double mass_kg = 0.0;
  Eigen::Vector3d centre_of_gravity_m = Eigen::Vector3d::Zero();  ///< body frame
  Eigen::Matrix3d inertia_kg_m2 = Eigen::Matrix3d::Zero();        ///< about G, body axes
  Eigen::Vector3d added_mass_kg = Eigen::Vector3d::Zero();
  Eigen::Vector3d added_inertia_kg_m2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d linear_damping_N_s_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d linear_damping_N_m_s = Eigen::Vector3d::Zero();      ///< N m per rad/s
  Eigen::Vector3d quadratic_drag_N_s2_m2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d quadratic_drag_N_m_s2 = Eigen::Vector3d::Zero();     ///< N m per (rad/s)^2
  double design_wetted_area_m2 = 1.0;  ///< upright at the design draft: drag scales with wetted / this
  double max_thrust_N = 0.0, max_astern_thrust_N = 0.0;
  Eigen::Vector3d propeller_position_m = Eigen::Vector3d::Zero();  ///< body frame
  double propeller_diameter_m = 1.0;
  double rudder_area_m2 = 0.0;
  Eigen::Vector3d rudder_position_m = Eigen::Vector3d::Zero();     ///< body frame
  double rudder_lift_slope_per_rad = 2.7;   ///< C_L' of a low-aspect-ratio rudder (2 pi A / (A + 2), A ~ 1.5)
  double max_rudder_angle_rad = 0.61;       ///< 35 degrees
  double rudder_rate_rad_s = 0.049;         ///< 2.8 degrees per second (SOLAS: 35 to 30 degrees in 28 s)
  // Main dimensions (from the hull's samples), for the wake, the contact capsule and the bow wave.
  double length_m = 0.0, beam_m = 0.0, depth_m = 0.0, design_draft_m = 0.0;
  Eigen::Vector3d hull_centre_m = Eigen::Vector3d::Zero();  ///< body-frame centre of the hull's bounding box
  double service_speed_m_s = 0.0;
  // Restricted water (restricted_water.hpp), from the hull upright at the design draft. A ship
  // whose squat.length_pp_m or midship_area_m2 is zero feels no squat or no shallow-water resistance.
  SquatParticulars squat;              ///< Lpp (waterline length), T, Cb, displaced volume
  double midship_area_m2 = 0.0;        ///< A_M: the section at mid-length below the waterline
  double waterplane_area_m2 = 0.0;     ///< A_wp: the squat's vertical load is rho g A_wp S_m
  double flotation_centre_x_m = 0.0;   ///< body x of the waterplane's centroid (LCF), where that load acts
  double pitch_stiffness_N_m_rad = 0.0;  ///< hydrostatic restoring moment per radian of trim, about G
  /// KM: the transverse metacentre above the keel, KB + I_wp / nabla, upright at the design draft
  /// (GM = KM - KG; informative: the body integrates the pressure, not this number).
  double metacentre_height_m = 0.0;
  /// Body z where the surge and the sway drag act (the resistance is spread over the wet hull, not
  /// at G): the wetted surface's centroid for surge, the underwater lateral area's for sway
  /// (about T/2 for a wall-sided hull). NaN (a hand-made ShipParticulars): at G.
  double surge_drag_z_m = std::numeric_limits<double>::quiet_NaN();
  double sway_drag_z_m = std::numeric_limits<double>::quiet_NaN();
};

/// How a hull is loaded: its mass (or the draft to float at) and, optionally, where G is.
struct HullLoading {
  std::optional<double> mass_kg;          ///< else the displacement at draft_m
  std::optional<double> draft_m;          ///< body z of the waterline; used when mass_kg is absent
  std::optional<double> centre_of_gravity_height_m;  ///< KG, body z; else the solid's centroid
  std::optional<double> service_speed_m_s;           ///< else Froude number 0.25 on the length
  WaterProperties water;
};

/// Particulars from the hull: G (over the centre of buoyancy of the design waterline, so the ship
/// floats upright on an even keel; KG the solid's centroid unless given, but no higher than
/// KM - 0.15 m, the IS Code's least GM0), inertia (the closed-mesh integrals of the solid, scaled to
/// the mass, about G), the design draft (displaced_volume_m3 = m / rho), added masses from flat-plate strip
/// values (heave rho pi B^2 L / 8, sway rho pi T^2 L / 2, surge 5 % of m, roll 10 % of I_xx, pitch
/// and yaw the heave and sway values times L^2 / 12), quadratic drag (surge 1/2 rho S C_T with
/// C_T = 0.006 on the wetted area S, sway and heave 1/2 rho C_D A with C_D = 1 on the lateral and
/// bottom areas, yaw and pitch the sway and heave drag integrated along the length: C L^4 / 32),
/// linear damping at 5 % of critical in heave, roll and pitch (radiation) and with a 30 s time
/// constant in surge, sway and yaw (low-speed viscous drag: a ship left alone comes to rest), the
/// engine sized to hold
/// the service speed at full order, a rudder of 2 % of L T at the stern.
/// Throws nearshore::Error naming `ship_name` when the mass cannot float (more than the whole
/// hull displaces) or the loading is not positive.
ShipParticulars particulars_for_hull(const std::string& ship_name, const HullMesh& mesh, const HullSamples& samples,
                                     const HullLoading& loading);

/// Position and motion of G in the site frame.
struct ShipState {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();            ///< G, site frame (z up from still water)
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< body -> world
  Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_rad_s = Eigen::Vector3d::Zero();  ///< world frame

  /// Yaw (counter-clockwise from east), pitch (bow down > 0) and roll (starboard down > 0), the
  /// z-y-x Euler angles of the orientation (rad).
  double yaw_rad() const;
  double pitch_rad() const;
  double roll_rad() const;
  /// Compass heading (clockwise from north, degrees in [0, 360)).
  double heading_deg() const;
  /// Speed over ground along the body's x axis (m/s).
  double forward_speed_m_s() const;
};

/// An orientation from yaw, pitch, roll (rad; as ShipState reports them).
Eigen::Quaterniond orientation_from_euler(double yaw_rad, double pitch_rad, double roll_rad);
/// Yaw (counter-clockwise from east, rad) of a compass heading (degrees clockwise from north).
double yaw_from_heading_rad(double heading_deg);

struct ShipControls {
  double engine_order = 0.0;       ///< [-1, 1]: full astern .. full ahead
  double rudder_order_rad = 0.0;   ///< > 0 turns the ship to port; clamped to the maximum
};

/// Force and torque about G from outside the ship (world frame).
struct ExternalLoad {
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque_N_m = Eigen::Vector3d::Zero();
};

/// Where a ship is and what the water and the ground do to it.
struct ShipEnvironment {
  const runtime::SurfaceSampler* water = nullptr;  ///< null: flat still water, no current
  /// Height (m) added to the sampled surface at (x, y): the other ships' bow waves. May be empty.
  std::function<double(double x_m, double y_m)> extra_elevation_m;
  const Seabed* seabed = nullptr;                  ///< null: bottomless
  WaterProperties water_properties;
};

/// What the last step saw (for hosts, tests and the bench).
struct BodyReport {
  int wet_points = 0;
  double wetted_area_m2 = 0.0;
  Eigen::Vector3d pressure_force_N = Eigen::Vector3d::Zero();
  int contact_points = 0;                 ///< points below the seabed
  double max_penetration_m = 0.0;
  Eigen::Vector3d contact_position_m = Eigen::Vector3d::Zero();  ///< mean of the contact points
  /// Contact with the harbour's structures and land (harbour_obstacles.hpp): hull points inside a
  /// solid and below its top; the solid and the point of deepest penetration.
  int structure_contact_points = 0;
  int structure = -1;                     ///< 0 land, k >= 1 structure k, -1 none
  double structure_penetration_m = 0.0;
  Eigen::Vector3d structure_contact_m = Eigen::Vector3d::Zero();
  Eigen::Vector2d structure_normal = Eigen::Vector2d::Zero();  ///< out of the solid, at that point
  double structure_closing_speed_m_s = 0.0;  ///< the largest speed of a point into the solid (over the step's substeps)
  double structure_force_N = 0.0;         ///< the contact's normal force, summed over the points
  /// Restricted water (restricted_water.hpp): the mean seabed depth under the hull's bottom (NaN
  /// without a seabed), the squat the loads aim at, and the surge drag's deep-water speed.
  double depth_under_hull_m = 0.0;
  Squat squat;
  double deep_water_equivalent_speed_m_s = 0.0;
  double rudder_angle_rad = 0.0;          ///< the rudder's actual angle (it moves at its rate)
  double thrust_N = 0.0;
};

class ShipBody {
 public:
  ShipBody(HullSamples samples, ShipParticulars particulars, ShipState initial);

  /// Advances by dt_s (split into substeps of at most max_substep_s) on `environment`.
  void step(const ShipEnvironment& environment, const ShipControls& controls, const ExternalLoad& external,
            double dt_s);

  const ShipState& state() const { return state_; }
  void set_state(const ShipState& state) { state_ = state; }
  const ShipParticulars& particulars() const { return particulars_; }
  const HullSamples& samples() const { return samples_; }
  const BodyReport& report() const { return report_; }
  /// World positions of the hull points at the current state (site frame).
  std::vector<Eigen::Vector3d> world_points_m() const;
  /// The surface elevation (m) over each hull point as the last substep sampled it (with the
  /// other ships' bow waves): what the bow wave's forcing measures the hull's immersion against.
  const std::vector<double>& water_elevations_m() const { return elevations_m_; }
  /// A body-frame point (e.g. the stern) in the site frame.
  Eigen::Vector3d to_world(const Eigen::Vector3d& body_point_m) const;

  double max_substep_s = 1.0 / 60.0;

 private:
  void substep(const ShipEnvironment& environment, const ShipControls& controls, const ExternalLoad& external,
               double dt_s);
  // A substep's steps (ship_body.cpp), in the order it takes them; the loads about G in the site
  // frame are summed in that order, so the result does not depend on how they are split.
  struct Loads {
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  };
  struct WaterMotion {  // the hull's motion relative to the water, body axes
    Eigen::Vector3d current_m_s, velocity_m_s, angular_velocity_rad_s;
    double wet_fraction = 0.0;
  };
  void sample_water(const ShipEnvironment& environment, const Eigen::Matrix3d& rotation);
  void add_pressure_and_seabed(const ShipEnvironment& environment, const Eigen::Matrix3d& rotation, Loads& loads, BodyReport& report,
                               double& bottom_area_m2, double& bottom_area_depth_m3) const;
  void add_structure_contact(const ShipEnvironment& environment, Loads& loads, BodyReport& report) const;
  WaterMotion water_motion(const ShipEnvironment& environment, const Eigen::Matrix3d& rotation, const BodyReport& report) const;
  void add_restricted_water_and_drag(const WaterMotion& motion, const Eigen::Matrix3d& rotation, double bottom_area_m2,
                                     double bottom_area_depth_m3, const WaterProperties& water, Loads& loads, BodyReport& report) const;
  double add_engine_and_rudder(const ShipControls& controls, const WaterMotion& motion, const Eigen::Matrix3d& rotation, double density_kg_m3,
                               double dt_s, Loads& loads);
  void integrate(const Loads& loads, const WaterMotion& motion, const Eigen::Matrix3d& rotation, const BodyReport& report, double dt_s);

  HullSamples samples_;
  std::vector<Eigen::Vector3d> arm_m_;  ///< sample positions relative to G, body frame
  std::vector<std::array<Eigen::Vector3d, 3>> corner_arm_m_;  ///< the pieces' corners relative to G
  ShipParticulars particulars_;
  ShipState state_;
  BodyReport report_;
  double rudder_angle_rad_ = 0.0;
  // Scratch (no allocation per step).
  std::vector<runtime::SitePoint> query_points_;
  std::vector<double> elevations_m_;
  std::vector<Eigen::Vector3d> world_arm_m_;
};

}  // namespace nearshore::ships
