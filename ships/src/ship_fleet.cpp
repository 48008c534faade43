#include "nearshore/ships/ship_fleet.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"
#include "nearshore/ships/ship_limits.hpp"

namespace nearshore::ships {
namespace {

constexpr double kPi = std::numbers::pi;
// Berthing velocities for fender design (PIANC WG 33, 2002, after Brolsma et al. 1977) reach
// 0.1-0.5 m/s, the highest for small ships in difficult conditions: a closing speed above 0.5 m/s
// is a collision, not a berthing (ShipFleet step 5).
constexpr double kBerthingSpeedLimit_m_s = 0.5;

double wrap_angle(double a) {
  while (a > kPi) a -= 2 * kPi;
  while (a < -kPi) a += 2 * kPi;
  return a;
}

// Closest points of segments p0 + s d1 and q0 + t d2, s, t in [0, 1] (Ericson, Real-Time Collision
// Detection, 5.1.9).
void closest_points(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& q0,
                    const Eigen::Vector2d& q1, Eigen::Vector2d& on_p, Eigen::Vector2d& on_q) {
  const Eigen::Vector2d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= 1e-12 && e <= 1e-12) {
  } else if (a <= 1e-12) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 1e-12) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denominator = a * e - b * b;
      s = denominator > 1e-12 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  on_p = p0 + s * d1;
  on_q = q0 + t * d2;
}

struct Capsule {
  Eigen::Vector2d a, b;
  double radius_m = 0.0;
  double z_m = 0.0;
};

Capsule capsule_of(const ShipBody& body) {
  const ShipParticulars& p = body.particulars();
  const double r = 0.5 * p.beam_m;
  const double half = std::max(0.5 * p.length_m - r, 0.0);
  const double z = p.hull_centre_m.z() - 0.5 * p.depth_m + p.design_draft_m;
  const Eigen::Vector3d a = body.to_world({p.hull_centre_m.x() - half, p.hull_centre_m.y(), z});
  const Eigen::Vector3d b = body.to_world({p.hull_centre_m.x() + half, p.hull_centre_m.y(), z});
  return {{a.x(), a.y()}, {b.x(), b.y()}, r, 0.5 * (a.z() + b.z())};
}

// Every input is range-checked (ship_limits.hpp), so a ship whose state is not finite or moves
// faster than any force here can drive it is a bug: it stops the step with a message saying so,
// before a non-finite position reaches the seabed lookup or the bow-wave grid's window.
void require_sound_motion(const Ship& ship) {
  const ShipState& s = ship.body().state();
  const double speed = s.velocity_m_s.norm(), turn = s.angular_velocity_rad_s.norm();
  if (s.position_m.allFinite() && s.orientation.coeffs().allFinite() && speed <= 2.0 * limits::kSpeed.max &&
      turn <= 10.0)
    return;
  throw Error(fmt::format("ship '{}'", ship.name()),
              fmt::format("internal error: its motion diverged (speed {} m/s, turn rate {} rad/s, at ({}, {}) m)",
                          format_value(speed), format_value(turn), format_value(s.position_m.x()),
                          format_value(s.position_m.y())),
              "please report this with the ship's definition and orders");
}

// The orders' ranges (ship_limits.hpp): an engine order in [-1, 1], a speed ahead below the ship's
// limit, finite waypoints within the site's reach and a positive waypoint radius.
void check_orders(const std::string& subject, const ShipOrders& o, double speed_limit_m_s) {
  if (o.engine_order && !(std::abs(*o.engine_order) <= 1.0))
    throw Error(subject,
                fmt::format("engine_order = {} is outside [-1, 1] (full astern .. full ahead)", format_value(*o.engine_order)),
                "give an engine order in [-1, 1]");
  if (o.speed_m_s && !(*o.speed_m_s >= 0.0 && *o.speed_m_s <= speed_limit_m_s))
    throw Error(subject,
                fmt::format("speed_m_s = {} is outside [0, {:.3g}] m/s: {}", format_value(*o.speed_m_s), speed_limit_m_s,
                            limits::kSpeed.reason),
                fmt::format("order a speed ahead of at most {:.3g} m/s for this ship", speed_limit_m_s));
  if (o.route_m.size() > 100000)
    throw Error(subject, fmt::format("has a route of {} waypoints", o.route_m.size()), "give at most 100000 waypoints");
  for (std::size_t k = 0; k < o.route_m.size(); ++k) {
    require_in_range(subject, fmt::format("waypoint {} x_m", k), o.route_m[k].x(), limits::kSiteCoordinate);
    require_in_range(subject, fmt::format("waypoint {} y_m", k), o.route_m[k].y(), limits::kSiteCoordinate);
  }
  if (!o.route_m.empty() && !(o.waypoint_radius_lengths > 0.0 && o.waypoint_radius_lengths <= 100.0))
    throw Error(subject,
                fmt::format("waypoint_radius_lengths = {} is outside (0, 100] ship lengths",
                            format_value(o.waypoint_radius_lengths)),
                "give the radius within which a waypoint counts as reached, in ship lengths (1.5 by default)");
}

}  // namespace

void Ship::set_orders(ShipOrders orders) {
  check_orders(fmt::format("ship '{}'", name_), orders, max_speed_m_s(body_.particulars().length_m));
  orders_ = std::move(orders);
}

Ship::Ship(std::string name, ShipBody body, ShipOrders orders, std::unique_ptr<BowWave> bow_wave, SternWake wake)
    : name_(std::move(name)),
      body_(std::move(body)),
      orders_(std::move(orders)),
      bow_wave_(std::move(bow_wave)),
      wake_(std::move(wake)) {}

ShipFleet::ShipFleet(FleetOptions options) : options_(options) {}

void ShipFleet::set_site(std::shared_ptr<const runtime::HarbourSite> site) {
  if (site)
    seabed_.emplace(std::move(site), options_.obstacles);
  else
    seabed_.reset();
}

void ShipFleet::set_seabed(Seabed seabed) { seabed_.emplace(std::move(seabed)); }

std::size_t ShipFleet::add_ship(const ShipDefinition& d) {
  const std::string subject = fmt::format("ship '{}'", d.name);
  // 1. Every parameter in its range (ship_limits.hpp) before anything is allocated or stepped.
  require_in_range(subject, "hull_points", d.hull_points, limits::kHullPoints);
  require_in_range(subject, "x_m", d.x_m, limits::kSiteCoordinate);
  require_in_range(subject, "y_m", d.y_m, limits::kSiteCoordinate);
  if (!std::isfinite(d.heading_deg))
    throw Error(subject, fmt::format("heading_deg = {} is not a compass heading", format_value(d.heading_deg)),
                "give degrees clockwise from north");
  if (d.bow_wave) require_in_range(subject, "bow_wave_options.cells", d.bow_wave_options.cells, limits::kBowWaveCells);
  if (d.bow_wave && d.dispersive_wake)
    require_in_range(subject, "dispersive_wake_options.cells", d.dispersive_wake_options.cells, limits::kBowWaveCells);
  if (d.loading.mass_kg) require_in_range(subject, "mass_kg", *d.loading.mass_kg, limits::kMass);
  if (!d.loading.mass_kg && d.loading.draft_m) require_in_range(subject, "draft_m", *d.loading.draft_m, limits::kDraft);
  if (d.loading.service_speed_m_s)
    require_in_range(subject, "service_speed_m_s", *d.loading.service_speed_m_s,
                     {0.1, limits::kSpeed.max, limits::kSpeed.unit, limits::kSpeed.reason});
  if (d.hull.vertices_m.empty() || d.hull.triangles.empty())
    throw Error(subject, "has an empty hull mesh", "give a generic hull or a closed triangle mesh");
  double hull_length_m = 0.0;
  {
    // The main dimensions from the mesh's box, before the hull is sampled: a 1e9 m hull would
    // otherwise be cut into pieces first (issue 44: 24 GB).
    Eigen::Vector3d low = d.hull.vertices_m.front(), high = low;
    for (const auto& v : d.hull.vertices_m) {
      if (!v.allFinite()) throw Error(subject, fmt::format("hull {} has a vertex that is not finite", d.hull.name), "fix the mesh");
      low = low.cwiseMin(v);
      high = high.cwiseMax(v);
    }
    require_in_range(subject, fmt::format("the length of hull {}", d.hull.name), high.x() - low.x(), limits::kLength);
    require_in_range(subject, fmt::format("the beam of hull {}", d.hull.name), high.y() - low.y(), limits::kBeam);
    require_in_range(subject, fmt::format("the depth of hull {}", d.hull.name), high.z() - low.z(), limits::kDepth);
    hull_length_m = high.x() - low.x();
  }
  const double speed_limit = max_speed_m_s(hull_length_m, options_.water.gravity_m_s2);
  check_orders(subject, d.orders, speed_limit);
  if (!(std::abs(d.initial_speed_m_s) <= speed_limit))
    throw Error(subject,
                fmt::format("initial_speed_m_s = {} is outside [-{:.3g}, {:.3g}] m/s: {}", format_value(d.initial_speed_m_s),
                            speed_limit, speed_limit, limits::kSpeed.reason),
                fmt::format("give a speed of at most {:.3g} m/s for this {:.3g} m hull", speed_limit, hull_length_m));
  {
    const WakeLayerChoice& c = d.wake_layer;
    if (d.dispersive_wake &&
        !(c.dispersive_below_froude > 0.0 && c.shallow_above_froude >= c.dispersive_below_froude &&
          c.shallow_above_froude < 100.0 && c.fade_s >= 0.0 && c.fade_s <= 3600.0 && c.resolved_wave_nodes >= 0.0 &&
          c.resolved_wave_nodes <= 1000.0))
      throw Error(subject,
                  fmt::format("has wake_layer thresholds dispersive_below_froude = {}, shallow_above_froude = {}, "
                              "fade_s = {}, resolved_wave_nodes = {}",
                              format_value(c.dispersive_below_froude), format_value(c.shallow_above_froude),
                              format_value(c.fade_s), format_value(c.resolved_wave_nodes)),
                  "use 0 < dispersive_below_froude <= shallow_above_froude < 100, 0 <= fade_s <= 3600 and "
                  "0 <= resolved_wave_nodes <= 1000");
  }

  HullSamples samples = sample_hull(d.hull, d.hull_points, static_cast<std::size_t>(2 * limits::kHullPoints.max));
  HullLoading loading = d.loading;
  loading.water = options_.water;
  ShipParticulars particulars = particulars_for_hull(subject, d.hull, samples, loading);
  if (!d.restricted_water) {  // no squat, no shallow-water resistance (ship_body.hpp)
    particulars.squat = {};
    particulars.midship_area_m2 = 0.0;
  }
  // 2. The loading floats the hull at a draft a ship has (limits::kMinDraftFractionOfDepth).
  if (particulars.design_draft_m < limits::kMinDraftFractionOfDepth * particulars.depth_m) {
    const double half_depth_kg =
        options_.water.density_kg_m3 *
        displaced_volume_m3(samples, particulars.hull_centre_m.z() - 0.5 * particulars.depth_m + 0.5 * particulars.depth_m);
    throw Error(subject,
                fmt::format("{} = {} floats hull {} at a draft of {:.3g} m, under {:.0f} % of its depth {:.3g} m: no ship "
                            "floats that light (a light ship displaces 20-40 % of its loaded displacement), and the bow "
                            "wave would have no hull to push",
                            d.loading.mass_kg ? "mass_kg" : "draft_m",
                            format_value(d.loading.mass_kg ? *d.loading.mass_kg : d.loading.draft_m.value_or(0.0)),
                            d.hull.name, particulars.design_draft_m, 100 * limits::kMinDraftFractionOfDepth,
                            particulars.depth_m),
                fmt::format("give the displacement in kg (about {:.3g} kg floats it at half its depth)", half_depth_kg));
  }

  // Upright at the design draft, the hull's centre at (x, y).
  const double yaw = yaw_from_heading_rad(d.heading_deg);
  ShipState state;
  state.orientation = orientation_from_euler(yaw, 0.0, 0.0);
  const double keel_z = particulars.hull_centre_m.z() - 0.5 * particulars.depth_m;
  const double waterline_z = keel_z + particulars.design_draft_m;
  const Eigen::Vector3d offset = state.orientation * (particulars.centre_of_gravity_m - particulars.hull_centre_m);
  state.position_m = {d.x_m + offset.x(), d.y_m + offset.y(), particulars.centre_of_gravity_m.z() - waterline_z};
  state.velocity_m_s = d.initial_speed_m_s * (state.orientation * Eigen::Vector3d::UnitX());

  // Placement: the water under the hull's ends and centre must be deeper than the draft.
  if (seabed_) {
    ShipBody probe(HullSamples{}, particulars, state);
    for (double along : {-0.45, 0.0, 0.45}) {
      const Eigen::Vector3d at = probe.to_world(particulars.hull_centre_m + Eigen::Vector3d(along * particulars.length_m, 0, 0));
      const double depth = seabed_->depth_m(at.x(), at.y());
      if (depth <= 0.0)
        throw Error(subject,
                    fmt::format("is placed on land: the ground at ({:.1f}, {:.1f}) m is {:.2f} m above still water",
                                at.x(), at.y(), -depth),
                    "move its position_m into the water");
      if (const HarbourObstacles* obstacles = seabed_->obstacles()) {
        const ObstacleSample o = obstacles->sample(at.x(), at.y());
        if (o.signed_distance_m < 0.0 && o.structure >= 1)
          throw Error(subject,
                      fmt::format("is placed on {}: its hull at ({:.1f}, {:.1f}) m is {:.2f} m inside it",
                                  obstacles->describe(o.structure).describe(), at.x(), at.y(), -o.signed_distance_m),
                      "move its position_m into open water");
      }
      if (depth < particulars.design_draft_m)
        throw Error(subject,
                    fmt::format("is placed where the water at ({:.1f}, {:.1f}) m is {:.2f} m deep, shallower than its "
                                "draft {:.2f} m",
                                at.x(), at.y(), depth, particulars.design_draft_m),
                    "move it into deeper water or lighten it");
    }
  }

  std::unique_ptr<BowWave> wave;
  if (d.bow_wave) wave = std::make_unique<BowWave>(particulars, d.bow_wave_options);
  std::unique_ptr<DispersiveWake> dispersive;
  if (d.bow_wave && d.dispersive_wake) {
    dispersive = std::make_unique<DispersiveWake>(particulars, d.dispersive_wake_options);
  }
  ShipBody body(std::move(samples), std::move(particulars), state);
  auto ship = std::make_unique<Ship>(d.name, std::move(body), d.orders, std::move(wave),
                                     SternWake(d.wake_options, 0x5eed + ships_.size()));
  ship->dispersive_wake_ = std::move(dispersive);
  ship->wake_layer_ = d.wake_layer;
  ships_.push_back(std::move(ship));
  return ships_.size() - 1;
}

void ShipFleet::remove_ship(std::size_t index) {
  if (index < ships_.size()) ships_.erase(ships_.begin() + static_cast<std::ptrdiff_t>(index));
}

void ShipFleet::apply_orders(Ship& ship) {
  const ShipParticulars& p = ship.body_.particulars();
  const ShipState& s = ship.body_.state();
  ShipControls c = ship.manual_;
  // The host's keys (manual_controls) are clamped to their ranges; a value that is no number is
  // refused, naming the ship, before it reaches the body.
  if (!std::isfinite(c.engine_order) || !std::isfinite(c.rudder_order_rad))
    throw Error(fmt::format("ship '{}'", ship.name_),
                fmt::format("manual_controls() holds engine_order = {}, rudder_order_rad = {}", format_value(c.engine_order),
                            format_value(c.rudder_order_rad)),
                "set an engine order in [-1, 1] and a rudder angle in rad");
  c.engine_order = std::clamp(c.engine_order, -1.0, 1.0);
  const ShipOrders& o = ship.orders_;
  if (o.engine_order) c.engine_order = std::clamp(*o.engine_order, -1.0, 1.0);
  if (o.speed_m_s) {
    // The engine order that holds `target` against the ship's own surge drag (ship_body.hpp: linear
    // and quadratic, at Lackenby's deep-water speed over the depth under the hull) plus a
    // proportional term with the gain 2 / V_service. Surge under this law is first order,
    // (m + A_11) du/dt = F(u) with F decreasing through F(target) = 0, so u approaches the order
    // without crossing it: no overshoot, and no steady error (the former feed-forward
    // (target / V_service)^2 counted the linear drag as quadratic and left the tug 3.6 % short).
    const double target = std::max(*o.speed_m_s, 0.0), service = std::max(p.service_speed_m_s, 1e-3);
    const double u = s.forward_speed_m_s();
    double drag_speed = target;
    const double depth = ship.body_.report().depth_under_hull_m;
    if (p.midship_area_m2 > 0.0 && std::isfinite(depth) && depth > 0.0)
      drag_speed = deep_water_equivalent_speed_m_s(p.midship_area_m2, depth, p.squat.draft_m, target,
                                                   options_.water.gravity_m_s2);
    const double holding_N =
        p.linear_damping_N_s_m.x() * drag_speed + p.quadratic_drag_N_s2_m2.x() * drag_speed * drag_speed;
    const double holding_order = p.max_thrust_N > 0.0 ? holding_N / p.max_thrust_N : 0.0;
    c.engine_order = std::clamp(holding_order + 2.0 * (target - u) / service, -1.0, 1.0);
  }
  if (!o.route_m.empty()) {
    int& next = ship.status_.waypoint;
    const Eigen::Vector2d here(s.position_m.x(), s.position_m.y());
    while (next < static_cast<int>(o.route_m.size()) &&
           (o.route_m[next] - here).norm() < o.waypoint_radius_lengths * p.length_m)
      ++next;
    if (next < static_cast<int>(o.route_m.size())) {
      const Eigen::Vector2d to = o.route_m[next] - here;
      const double error = wrap_angle(std::atan2(to.y(), to.x()) - s.yaw_rad());
      const double yaw_rate = s.angular_velocity_rad_s.z();
      const double time_constant = p.length_m / std::max(std::abs(s.forward_speed_m_s()), 1.0);
      c.rudder_order_rad = std::clamp(2.0 * error - time_constant * yaw_rate, -p.max_rudder_angle_rad, p.max_rudder_angle_rad);
    } else {
      c.rudder_order_rad = std::clamp(-p.length_m * s.angular_velocity_rad_s.z(), -p.max_rudder_angle_rad,
                                      p.max_rudder_angle_rad);
    }
  }
  ship.controls_ = c;
}

void ShipFleet::repel() {
  for (auto& s : ships_) s->external_ = ExternalLoad{};
  for (std::size_t a = 0; a < ships_.size(); ++a)
    for (std::size_t b = a + 1; b < ships_.size(); ++b) {
      Ship& A = *ships_[a];
      Ship& B = *ships_[b];
      const Capsule ca = capsule_of(A.body_), cb = capsule_of(B.body_);
      Eigen::Vector2d pa, pb;
      closest_points(ca.a, ca.b, cb.a, cb.b, pa, pb);
      const double distance = (pa - pb).norm();
      const double reach = ca.radius_m + cb.radius_m;
      const double gap = distance - reach;
      const double margin = 0.5 * reach;
      if (gap >= margin || distance <= 1e-9) continue;
      const Eigen::Vector2d normal = (pa - pb) / distance;  // from B towards A
      const double ma = A.body_.particulars().mass_kg, mb = B.body_.particulars().mass_kg;
      const double reduced = ma * mb / (ma + mb);
      const double v0 = options_.repulsion_speed_m_s;
      const double clamped_gap = std::max(gap, 0.02 * margin);
      double force = reduced * v0 * v0 / margin * (margin / clamped_gap - 1.0);
      // Contact points on the hulls' sides, at the waterline.
      const Eigen::Vector3d contact_a(pa.x() - normal.x() * ca.radius_m, pa.y() - normal.y() * ca.radius_m, ca.z_m);
      const Eigen::Vector3d contact_b(pb.x() + normal.x() * cb.radius_m, pb.y() + normal.y() * cb.radius_m, cb.z_m);
      const ShipState& sa = A.body_.state();
      const ShipState& sb = B.body_.state();
      const Eigen::Vector3d va = sa.velocity_m_s + sa.angular_velocity_rad_s.cross(contact_a - sa.position_m);
      const Eigen::Vector3d vb = sb.velocity_m_s + sb.angular_velocity_rad_s.cross(contact_b - sb.position_m);
      const double closing = -(va - vb).head<2>().dot(normal);  // > 0 when approaching
      if (closing > 0.0) force += reduced * closing / 1.0;      // damped over about a second
      const Eigen::Vector3d f(normal.x() * force, normal.y() * force, 0.0);
      A.external_.force_N += f;
      A.external_.torque_N_m += (contact_a - sa.position_m).cross(f);
      B.external_.force_N -= f;
      B.external_.torque_N_m += (contact_b - sb.position_m).cross(-f);
    }
}

void ShipFleet::step(const runtime::SurfaceSnapshot& snapshot, double dt_s) {
  const runtime::SurfaceSampler sampler(snapshot);
  step(&sampler, dt_s);
}

void ShipFleet::step(const runtime::SurfaceSampler* water, double dt_s) {
  if (dt_s == 0.0) return;
  if (!(dt_s > 0.0 && dt_s <= 1.0))
    throw Error("ShipFleet::step", fmt::format("dt_s = {} is outside (0, 1] s", format_value(dt_s)),
                "step once per displayed frame");
  for (auto& s : ships_) apply_orders(*s);
  time_s_ += dt_s;
  repel();
  for (std::size_t k = 0; k < ships_.size(); ++k) {
    Ship& ship = *ships_[k];
    ShipEnvironment environment;
    environment.water = water;
    environment.seabed = seabed();
    environment.water_properties = options_.water;
    if (ships_.size() > 1)
      environment.extra_elevation_m = [this, k](double x, double y) {
        return bow_wave_elevation_m(x, y, static_cast<long>(k));
      };
    ship.body_.step(environment, ship.controls_, ship.external_, dt_s);
    require_sound_motion(ship);
  }
  for (std::size_t k = 0; k < ships_.size(); ++k) {
    auto& s = ships_[k];
    update_bow_waves(*s, dt_s);
    s->wake_.update(s->body_, s->controls_.engine_order, dt_s);
    const BodyReport& r = s->body_.report();
    report_structure_contact(*s, k);
    const bool aground = r.contact_points > 0;
    if (aground && !s->status_.aground) {
      s->orders_ = ShipOrders{};
      s->manual_ = ShipControls{};
      const double depth = seabed_ ? seabed_->depth_m(r.contact_position_m.x(), r.contact_position_m.y()) : 0.0;
      events_.push_back(fmt::format(
          "ship '{}' ran aground at ({:.1f}, {:.1f}) m where the water is {:.2f} m deep (draft {:.2f} m), "
          "heel {:.1f} deg, trim {:.1f} deg; engine stopped",
          s->name_, r.contact_position_m.x(), r.contact_position_m.y(), depth, s->body_.particulars().design_draft_m,
          s->body_.state().roll_rad() * 180.0 / kPi, s->body_.state().pitch_rad() * 180.0 / kPi));
    } else if (!aground && s->status_.aground) {
      events_.push_back(fmt::format("ship '{}' is afloat again at ({:.1f}, {:.1f}) m", s->name_,
                                    s->body_.state().position_m.x(), s->body_.state().position_m.y()));
    }
    s->status_.aground = aground;
    if (aground) {
      s->status_.contact_position_m = r.contact_position_m;
      s->status_.max_penetration_m = r.max_penetration_m;
    }
  }
}

void ShipFleet::update_bow_waves(Ship& s, double dt_s) {
  if (!s.bow_wave_) return;
  if (!s.dispersive_wake_) {
    s.bow_wave_->update(s.body_, seabed(), dt_s);
    return;
  }
  // The layer by the depth Froude number (WakeLayerChoice), with hysteresis, and the fade.
  const ShipState& state = s.body_.state();
  const Eigen::Vector3d centre = s.body_.to_world(s.body_.particulars().hull_centre_m);
  const double depth = seabed() != nullptr ? seabed()->depth_m(centre.x(), centre.y())
                                           : s.dispersive_wake_->options().max_depth_m;
  const double speed = std::hypot(state.velocity_m_s.x(), state.velocity_m_s.y());
  s.depth_froude_ = depth > 0.0 ? speed / std::sqrt(options_.water.gravity_m_s2 * depth) : 1e9;
  const WakeLayerChoice& c = s.wake_layer_;
  // The transverse wave 2 pi U^2 / g in nodes of the dispersive layer (its resolution, WakeLayerChoice).
  const double wave_nodes =
      2.0 * std::numbers::pi * speed * speed / options_.water.gravity_m_s2 / s.dispersive_wake_->spacing_m();
  if (s.depth_froude_ < c.dispersive_below_froude && wave_nodes >= c.resolved_wave_nodes) s.dispersive_chosen_ = true;
  if (s.depth_froude_ > c.shallow_above_froude || wave_nodes < 0.75 * c.resolved_wave_nodes) s.dispersive_chosen_ = false;
  const double target = s.dispersive_chosen_ ? 1.0 : 0.0;
  // The first step shows the chosen layer at once (nothing to fade from).
  const double rate = c.fade_s > 0.0 && s.dispersive_weight_ >= 0.0 ? dt_s / c.fade_s : 1.0;
  if (s.dispersive_weight_ < 0.0) s.dispersive_weight_ = target;
  s.dispersive_weight_ = target > s.dispersive_weight_ ? std::min(target, s.dispersive_weight_ + rate)
                                                       : std::max(target, s.dispersive_weight_ - rate);
  // A layer is stepped while it is shown or chosen; once it is neither, it restarts from rest.
  auto drive = [&](auto& layer, double weight, bool chosen) {
    if (weight > 0.0 || chosen) {
      layer.update(s.body_, seabed(), dt_s);
      layer.set_shown_weight(weight);
    } else {
      layer.set_shown_weight(0.0);
      layer.restart();
    }
  };
  drive(*s.dispersive_wake_, s.dispersive_weight_, s.dispersive_chosen_);
  drive(*s.bow_wave_, 1.0 - s.dispersive_weight_, !s.dispersive_chosen_);
  // Foam where the shown layer broke: patches of 4 of its nodes (the 2 x 2 blocks it reports).
  const DispersiveWake& layer = *s.dispersive_wake_;
  s.crest_foam_.update(s.dispersive_weight_ > 0.0 ? layer.breaking_nodes() : std::vector<BreakingCrest>{},
                       4.0 * layer.spacing_m(), state.yaw_rad(), s.dispersive_weight_, dt_s);
}

double ShipFleet::bow_wave_elevation_m(double x_m, double y_m, long exclude) const {
  double eta = 0.0;
  for (std::size_t k = 0; k < ships_.size(); ++k) {
    if (static_cast<long>(k) == exclude) continue;
    const Ship& s = *ships_[k];
    // Each layer's heights carry its shown weight (the weights sum to 1: one displacement).
    if (s.bow_wave_ && s.bow_wave_->shown_weight() > 0.0) eta += s.bow_wave_->elevation_m(x_m, y_m);
    if (s.dispersive_wake_ && s.dispersive_wake_->shown_weight() > 0.0) eta += s.dispersive_wake_->elevation_m(x_m, y_m);
  }
  return eta;
}

double ShipFleet::shown_elevation_m(const runtime::SurfaceSampler& water, double x_m, double y_m) const {
  return water.elevation_m(x_m, y_m) + bow_wave_elevation_m(x_m, y_m);
}

std::vector<BowWaveField> ShipFleet::bow_wave_fields() const {
  std::vector<BowWaveField> out;
  for (const auto& s : ships_) {
    if (s->bow_wave_ && s->bow_wave_->shown_weight() > 0.0) out.push_back(s->bow_wave_->field());
    if (s->dispersive_wake_ && s->dispersive_wake_->shown_weight() > 0.0) out.push_back(s->dispersive_wake_->field());
  }
  return out;
}

void ShipFleet::report_structure_contact(Ship& s, std::size_t index) {
  const BodyReport& r = s.body_.report();
  const int now = r.structure_contact_points > 0 ? r.structure : -1;
  const int before = s.status_.structure_contact;
  if (now == before) return;
  const HarbourObstacles* obstacles = seabed_ ? seabed_->obstacles() : nullptr;
  auto event_for = [&](int structure, bool began) {
    ContactEvent e;
    e.ship = s.name_;
    e.ship_index = index;
    e.began = began;
    e.structure = structure;
    const HarbourStructure h = obstacles != nullptr ? obstacles->describe(structure) : HarbourStructure{};
    e.wall = h.wall;
    e.porosity = h.porosity;
    e.description = h.describe();
    e.time_s = time_s_;
    if (began) {
      e.position_m = r.structure_contact_m;
      e.normal = r.structure_normal;
      e.closing_speed_m_s = r.structure_closing_speed_m_s;
      // An impact faster than a berthing ship ever meets a fender is a collision: the engine is
      // stopped as on grounding. A gentler touch (a tug pushing on a quay) keeps the orders.
      const bool collision = e.closing_speed_m_s > kBerthingSpeedLimit_m_s;
      if (collision) {
        s.orders_ = ShipOrders{};
        s.manual_ = ShipControls{};
      }
      events_.push_back(fmt::format("ship '{}' struck {} at ({:.1f}, {:.1f}) m, closing at {:.2f} m/s against its face "
                                    "(normal {:.2f}, {:.2f}){}",
                                    s.name_, e.description, e.position_m.x(), e.position_m.y(), e.closing_speed_m_s,
                                    e.normal.x(), e.normal.y(), collision ? "; engine stopped" : ""));
    } else {
      e.position_m = s.body_.state().position_m;
      events_.push_back(fmt::format("ship '{}' is clear of {}", s.name_, e.description));
    }
    contacts_.push_back(std::move(e));
  };
  if (before >= 0) event_for(before, false);
  if (now >= 0) event_for(now, true);
  s.status_.structure_contact = now;
}

std::vector<ContactEvent> ShipFleet::take_contacts() {
  std::vector<ContactEvent> out;
  out.swap(contacts_);
  return out;
}

std::vector<std::string> ShipFleet::take_events() {
  std::vector<std::string> out;
  out.swap(events_);
  return out;
}

}  // namespace nearshore::ships
