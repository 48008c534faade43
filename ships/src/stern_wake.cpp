#include "nearshore/ships/stern_wake.hpp"

#include <algorithm>
#include <cmath>

namespace nearshore::ships {

SternWake::SternWake(SternWakeOptions options, std::uint64_t seed) : options_(options), random_(seed) {}

void SternWake::update(const ShipBody& body, double engine_order, double dt_s) {
  for (WakeDecal& d : decals_) {
    d.age_s += dt_s;
    d.width_m += 2.0 * d.spread_m_s * dt_s;
  }
  while (!decals_.empty() && decals_.front().age_s >= decals_.front().lifetime_s) decals_.pop_front();

  const ShipParticulars& p = body.particulars();
  // The stern: the aft end of the hull's box at the waterline (eq. 4.29-4.30 with our axes).
  const Eigen::Vector3d stern_body(p.hull_centre_m.x() - 0.5 * p.length_m, p.hull_centre_m.y(),
                                   p.hull_centre_m.z() - 0.5 * p.depth_m + p.design_draft_m);
  const Eigen::Vector3d stern = body.to_world(stern_body);
  const Eigen::Vector3d& v = body.state().velocity_m_s;
  const double speed = std::hypot(v.x(), v.y());
  if (!has_last_) {
    last_x_m_ = stern.x();
    last_y_m_ = stern.y();
    has_last_ = true;
    return;
  }
  const double moved = std::hypot(stern.x() - last_x_m_, stern.y() - last_y_m_);
  if (moved < std::max(p.beam_m, 1e-3) || speed < options_.min_speed_m_s) {
    if (speed < options_.min_speed_m_s) {  // keep the spacing from where the ship picks up speed again
      last_x_m_ = stern.x();
      last_y_m_ = stern.y();
    }
    return;
  }
  WakeDecal d;
  d.x_m = 0.5 * (stern.x() + last_x_m_);
  d.y_m = 0.5 * (stern.y() + last_y_m_);
  d.yaw_rad = std::atan2(stern.y() - last_y_m_, stern.x() - last_x_m_);
  d.width_m = p.beam_m;
  d.length_m = moved;
  d.lifetime_s = options_.lifetime_s;
  d.intensity = std::clamp(std::abs(engine_order), 0.3, 1.0);
  d.spread_m_s = options_.spread_rate * speed;
  d.variant = static_cast<int>(random_() % 4);
  decals_.push_back(d);
  while (static_cast<int>(decals_.size()) > options_.max_decals) decals_.pop_front();
  last_x_m_ = stern.x();
  last_y_m_ = stern.y();
}

CrestFoam::CrestFoam(CrestFoamOptions options, std::uint64_t seed) : options_(options), random_(seed) {}

void CrestFoam::update(const std::vector<BreakingCrest>& crests, double size_m, double yaw_rad, double weight,
                       double dt_s) {
  for (WakeDecal& d : decals_) d.age_s += dt_s;
  decals_.erase(std::remove_if(decals_.begin(), decals_.end(), [](const WakeDecal& d) { return d.age_s >= d.lifetime_s; }),
                decals_.end());
  if (weight <= 0.0 || crests.empty()) return;
  order_.assign(crests.begin(), crests.end());
  std::sort(order_.begin(), order_.end(), [](const BreakingCrest& a, const BreakingCrest& b) { return a.excess > b.excess; });
  int added = 0;
  const double young_s = 0.25 * options_.lifetime_s, near2 = 0.25 * size_m * size_m;
  for (const BreakingCrest& c : order_) {
    if (added >= options_.max_new_per_update) break;
    const bool covered = std::any_of(decals_.begin(), decals_.end(), [&](const WakeDecal& d) {
      return d.age_s < young_s && (d.x_m - c.x_m) * (d.x_m - c.x_m) + (d.y_m - c.y_m) * (d.y_m - c.y_m) < near2;
    });
    if (covered) continue;
    WakeDecal d;
    d.x_m = c.x_m;
    d.y_m = c.y_m;
    d.yaw_rad = yaw_rad;
    d.width_m = d.length_m = size_m;
    d.lifetime_s = options_.lifetime_s;
    d.intensity = std::min(1.0, 0.3 + 2.0 * c.excess) * std::clamp(weight, 0.0, 1.0);
    d.variant = static_cast<int>(random_() % 4);
    decals_.push_back(d);
    ++added;
  }
  while (static_cast<int>(decals_.size()) > options_.max_decals) decals_.pop_front();
}

}  // namespace nearshore::ships
