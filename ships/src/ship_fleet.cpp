#include "nearshore/ships/ship_fleet.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"

namespace nearshore::ships {
namespace {

constexpr double kPi = std::numbers::pi;

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

}  // namespace

Ship::Ship(std::string name, ShipBody body, ShipOrders orders, std::unique_ptr<BowWave> bow_wave, SternWake wake)
    : name_(std::move(name)),
      body_(std::move(body)),
      orders_(std::move(orders)),
      bow_wave_(std::move(bow_wave)),
      wake_(std::move(wake)) {}

ShipFleet::ShipFleet(FleetOptions options) : options_(options) {}

void ShipFleet::set_site(std::shared_ptr<const runtime::HarbourSite> site) {
  if (site)
    seabed_.emplace(std::move(site));
  else
    seabed_.reset();
}

void ShipFleet::set_seabed(Seabed seabed) { seabed_.emplace(std::move(seabed)); }

std::size_t ShipFleet::add_ship(const ShipDefinition& d) {
  const std::string subject = fmt::format("ship '{}'", d.name);
  if (d.hull_points < 16)
    throw Error(subject, fmt::format("hull_points = {} is too few", d.hull_points), "use at least a few hundred");
  if (!std::isfinite(d.x_m) || !std::isfinite(d.y_m) || !std::isfinite(d.heading_deg))
    throw Error(subject, "has a position or heading that is not a number", "give finite site metres and degrees");
  HullSamples samples = sample_hull(d.hull, d.hull_points);
  HullLoading loading = d.loading;
  loading.water = options_.water;
  ShipParticulars particulars = particulars_for_hull(subject, d.hull, samples, loading);

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
    const WakeLayerChoice& c = d.wake_layer;
    if (!(c.dispersive_below_froude > 0.0 && c.shallow_above_froude >= c.dispersive_below_froude && c.fade_s >= 0.0))
      throw Error(subject,
                  fmt::format("has wake_layer thresholds dispersive_below_froude = {}, shallow_above_froude = {}, "
                              "fade_s = {}",
                              c.dispersive_below_froude, c.shallow_above_froude, c.fade_s),
                  "use 0 < dispersive_below_froude <= shallow_above_froude and fade_s >= 0");
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
  const ShipOrders& o = ship.orders_;
  if (o.engine_order) c.engine_order = std::clamp(*o.engine_order, -1.0, 1.0);
  if (o.speed_m_s) {
    const double target = std::max(*o.speed_m_s, 0.0), service = std::max(p.service_speed_m_s, 1e-3);
    const double u = s.forward_speed_m_s();
    c.engine_order = std::clamp(target * target / (service * service) + 2.0 * (target - u) / service, -1.0, 1.0);
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
  if (!(dt_s > 0.0)) return;
  for (auto& s : ships_) apply_orders(*s);
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
  }
  for (auto& s : ships_) {
    update_bow_waves(*s, dt_s);
    s->wake_.update(s->body_, s->controls_.engine_order, dt_s);
    const BodyReport& r = s->body_.report();
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
  if (s.depth_froude_ < c.dispersive_below_froude) s.dispersive_chosen_ = true;
  if (s.depth_froude_ > c.shallow_above_froude) s.dispersive_chosen_ = false;
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

std::vector<std::string> ShipFleet::take_events() {
  std::vector<std::string> out;
  out.swap(events_);
  return out;
}

}  // namespace nearshore::ships
