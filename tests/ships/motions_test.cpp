// issue 42's motions: a ship in a steady turn, at rest, and answering a speed order.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include <gtest/gtest.h>

#include "nearshore/ships/generic_hulls.hpp"
#include "nearshore/ships/ship_body.hpp"
#include "ships_test_support.hpp"

namespace nearshore::ships::motions {
namespace {

constexpr double kRho = 1025.0;
using ships::testing::kG;
constexpr double kDeg = 180.0 / std::numbers::pi;

struct Hydrostatics {
  double volume_m3, kb_m, bm_m;
};
// KB and BM = I_wp / nabla of the hull upright at body waterline z_w, from the pieces (not from the
// body's pressure integration): each wet piece's column to the waterline, (z_w - z) (-n_z) A,
// sums to the displaced volume and its moments; its footprint (-n_z) A sums to the waterplane.
Hydrostatics hydrostatics(const HullSamples& s, double z_w) {
  double v = 0, mz = 0, iy = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Eigen::Vector3d& x = s.position_m[i];
    if (x.z() >= z_w) continue;
    const double foot = -s.normal[i].z() * s.area_m2[i];
    v += (z_w - x.z()) * foot;
    mz += (z_w - x.z()) * foot * 0.5 * (z_w + x.z());
    iy += x.y() * x.y() * foot;
  }
  return {v, mz / v, iy / v};
}

TEST(ShipMotions, Probe) {
  for (int which = 0; which < 2; ++which) {
    const HullMesh hull = which == 0 ? wigley_hull(20, 3, 1.0, 2.5) : harbour_tug();
    HullSamples samples = sample_hull(hull, 2000);
    HullLoading loading;
    loading.draft_m = which == 0 ? 1.0 : 3.0;
    const ShipParticulars p = particulars_for_hull("probe", hull, samples, loading);
    const double keel = p.hull_centre_m.z() - 0.5 * p.depth_m;
    const Hydrostatics h = hydrostatics(samples, keel + p.design_draft_m);
    const double kg = p.centre_of_gravity_m.z() - keel;
    std::printf("%s: m %.0f kg T %.3f KG %.3f KB %.3f BM %.3f GM %.3f V_s %.2f\n", hull.name.c_str(), p.mass_kg,
                p.design_draft_m, kg, h.kb_m, h.bm_m, h.kb_m + h.bm_m - kg, p.service_speed_m_s);
    ShipState state;
    state.position_m = {0, 0, p.centre_of_gravity_m.z() - (keel + p.design_draft_m)};
    state.velocity_m_s = {p.service_speed_m_s, 0, 0};
    ShipBody body(samples, p, state);
    ShipEnvironment still;
    for (int k = 0; k < 150 * 30; ++k) {
      body.step(still, {1.0, std::atof(std::getenv("RUDDER"))}, {}, 1.0 / 30);
      const ShipState& s = body.state();
      if (k % 150 == 149)
        std::printf("t %5.1f V %.3f r %.4f R %.2f heel %.2f trim %.2f\n", (k + 1) / 30.0, s.velocity_m_s.norm(),
                    s.angular_velocity_rad_s.z(), s.velocity_m_s.norm() / std::abs(s.angular_velocity_rad_s.z()),
                    s.roll_rad() * kDeg, s.pitch_rad() * kDeg);
    }
  }
}

}  // namespace
}  // namespace nearshore::ships::motions
