#include "nearshore/ships/restricted_water.hpp"

#include <algorithm>
#include <cmath>

namespace nearshore::ships {

Squat squat(const SquatParticulars& ship, double speed_m_s, double depth_m, double gravity_m_s2) {
  Squat s;
  if (!(ship.length_pp_m > 0.0) || !(ship.draft_m > 0.0) || !(ship.displaced_volume_m3 > 0.0) ||
      !std::isfinite(depth_m) || !std::isfinite(speed_m_s))
    return s;
  // Depth no less than 1.1 T (restricted_water.hpp: the methods' lower bound; the bed takes over).
  const double h = std::max(depth_m, kRestrictedWaterMinDepthOverDraft * ship.draft_m);
  const double speed = std::abs(speed_m_s);
  s.depth_froude_number = speed / std::sqrt(gravity_m_s2 * h);
  const double fnh = std::min(s.depth_froude_number, kSquatMaxDepthFroudeNumber);
  const double shape = fnh * fnh / std::sqrt(1.0 - fnh * fnh);  // Tuck (1966)
  const double scale = ship.displaced_volume_m3 / (ship.length_pp_m * ship.length_pp_m);
  s.midship_sinkage_m = kTuckSinkageCoefficient * scale * shape;
  // Barrass: Cb > 0.7 squats at the bow, below at the stern, 0.7 on an even keel.
  const double cb = ship.block_coefficient;
  const double side = cb > kBarrassEvenKeelBlockCoefficient ? 1.0 : (cb < kBarrassEvenKeelBlockCoefficient ? -1.0 : 0.0);
  if (side == 0.0) {
    s.max_squat_m = s.midship_sinkage_m;
    return s;
  }
  s.max_squat_m = kIcorelsSquatCoefficient * scale * shape;
  // Bow down ahead for side > 0; astern the leading end is the stern, so the sign turns.
  const double direction = speed_m_s < 0.0 ? -1.0 : 1.0;
  s.trim_rad = side * direction * 2.0 * (s.max_squat_m - s.midship_sinkage_m) / ship.length_pp_m;
  return s;
}

double lackenby_speed_loss_fraction(double midship_area_m2, double depth_m, double draft_m, double deep_speed_m_s,
                                    double gravity_m_s2) {
  if (!(midship_area_m2 > 0.0) || !std::isfinite(depth_m)) return 0.0;
  const double h = std::max(depth_m, kRestrictedWaterMinDepthOverDraft * draft_m);
  if (!(h > 0.0)) return 0.0;
  const double blockage = std::max(midship_area_m2 / (h * h) - 0.05, 0.0);
  const double v2 = deep_speed_m_s * deep_speed_m_s;
  const double wave = v2 > 0.0 ? 1.0 - std::sqrt(std::tanh(gravity_m_s2 * h / v2)) : 0.0;
  return std::clamp(0.1242 * blockage + wave, 0.0, kLackenbyMaxSpeedLossFraction);
}

double deep_water_equivalent_speed_m_s(double midship_area_m2, double depth_m, double draft_m, double speed_m_s,
                                       double gravity_m_s2) {
  const double speed = std::abs(speed_m_s);
  if (speed == 0.0) return 0.0;
  // The fixed point of V_inf = V / (1 - f(V_inf)); f changes with V_inf only through the tanh
  // term, whose derivative is tiny below Fnh ~ 0.7, so a few iterations converge to round-off.
  double deep = speed;
  for (int k = 0; k < 8; ++k)
    deep = speed / (1.0 - lackenby_speed_loss_fraction(midship_area_m2, depth_m, draft_m, deep, gravity_m_s2));
  return deep;
}

}  // namespace nearshore::ships
