#include "nearshore/ships/ship_body.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>
#include <fmt/format.h>

#include "nearshore/core/error.hpp"

namespace nearshore::ships {
namespace {

constexpr double kPi = std::numbers::pi;
// Seabed contact (see ship_body.hpp): a sand bed 50 times stiffer than water's hydrostatic
// stiffness per unit area, damped over 0.1 s, Coulomb friction 0.4 regularised below 5 cm/s.
constexpr double kSeabedStiffnessRatio = 50.0;
constexpr double kSeabedDampingTime_s = 0.1;
constexpr double kSeabedFriction = 0.4;
constexpr double kFrictionVelocity_m_s = 0.05;
// Structures and land (ship_body.hpp): 10 times the bed's stiffness, a short damping time.
constexpr double kStructureStiffnessRatio = 500.0;
constexpr double kStructureDampingTime_s = 0.02;
constexpr double kStructureFriction = 0.4;
// The impact on a structure or the land (step 7 of substep): near-plastic along the face's normal,
// Coulomb friction along it. A ship that strikes a quay, a rubble mound or a bank does not bounce
// off: the closing energy goes into crushing (the bow, the fender, the rubble) and into the water's
// added mass, and what the hull springs back with is small against what it brought. Ship-collision
// mechanics takes the normal restitution as zero: Pedersen & Zhang (1998), "On impact mechanics in
// ship collisions", Marine Structures 11, 429-449, assume the contact points end the impact with
// a common normal velocity (e = 0), and the struck surface either sticks or slides against
// Coulomb friction mu; Zhang (1999, DTU thesis) applies the same to ships striking rigid walls and
// bridge piers, and PIANC WG 33 (2002, fender guidelines) counts a berthing ship's energy as
// absorbed by the fender and the hull, none of it returned as a rebound of the ship. So: e = 0, mu
// the contact's Coulomb coefficient (steel on concrete or rock, 0.4), and the penalty's push out of
// what penetration remains limited to a separation speed of at most kStructureSeparationSpeed_m_s,
// reached as depth / kStructureRelaxTime_s (the hull leaves the face as the depth closes, no faster:
// a penalty spring alone gives back the energy it stored, the rebound the previous e = 0.2 model
// showed as 0.6 m/s after a 3 m/s strike and 19 m of drift in 60 s).
constexpr double kStructureRestitution = 0.0;
// The least initial metacentric height of a default loading: IMO Intact Stability Code (2008),
// Part A 2.2.4, GM0 >= 0.15 m.
constexpr double kMinimumMetacentricHeight_m = 0.15;
constexpr double kStructureSeparationSpeed_m_s = 0.05;
constexpr double kStructureRelaxTime_s = 1.0;

// 1 / (effective mass) of a rigid body at arm r along unit direction d (world frame), with its
// world mass matrix and inertia tensor (Catto 2005; added masses included).
double inverse_effective_mass(const Eigen::LDLT<Eigen::Matrix3d>& mass, const Eigen::LDLT<Eigen::Matrix3d>& inertia,
                              const Eigen::Vector3d& r, const Eigen::Vector3d& d) {
  const Eigen::Vector3d linear = mass.solve(d);
  const Eigen::Vector3d angular = inertia.solve(r.cross(d));
  return d.dot(linear) + d.dot(angular.cross(r));
}

// Over one hull piece (a triangle, corners r_k relative to G in the world frame) with the
// pressure head f = eta - z linear over it (f_k at the corners): m0 = integral of f+ dA and
// m1 = integral of f+ r dA, exactly. Where f changes sign the wet part is the polygon cut off by
// f = 0; on each of its triangles f >= 0 is linear and
//   integral f dA = A (f_a + f_b + f_c) / 3,  integral f r dA = A / 12 (sum f_k r_k + sum f_k sum r_k).
void wet_moments(const Eigen::Vector3d r[3], const double f[3], double& m0, Eigen::Vector3d& m1) {
  m0 = 0.0;
  m1.setZero();
  if (f[0] <= 0.0 && f[1] <= 0.0 && f[2] <= 0.0) return;
  Eigen::Vector3d pr[4];
  double pf[4];
  int n = 0;
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    if (f[k] >= 0.0) {
      pr[n] = r[k];
      pf[n++] = f[k];
    }
    if ((f[k] > 0.0 && f[l] < 0.0) || (f[k] < 0.0 && f[l] > 0.0)) {
      const double t = f[k] / (f[k] - f[l]);
      pr[n] = r[k] + t * (r[l] - r[k]);
      pf[n++] = 0.0;
    }
  }
  for (int k = 1; k + 1 < n; ++k) {
    const double area = 0.5 * (pr[k] - pr[0]).cross(pr[k + 1] - pr[0]).norm();
    const double sum_f = pf[0] + pf[k] + pf[k + 1];
    m0 += area * sum_f / 3.0;
    m1 += area / 12.0 * (pf[0] * pr[0] + pf[k] * pr[k] + pf[k + 1] * pr[k + 1] + sum_f * (pr[0] + pr[k] + pr[k + 1]));
  }
}

struct Load {
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque_N_m = Eigen::Vector3d::Zero();
};

// Pressure load about G in still water (eta = 0) with G at world height z_g and orientation R,
// integrated piece by piece exactly as the body does.
Load still_water_pressure(const HullSamples& samples, const Eigen::Vector3d& g_body,
                          const Eigen::Matrix3d& rotation, double z_g, const WaterProperties& water) {
  Load load;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    Eigen::Vector3d r[3];
    double f[3];
    for (int k = 0; k < 3; ++k) {
      r[k] = rotation * (samples.corner_m[i][k] - g_body);
      f[k] = -(z_g + r[k].z());
    }
    double m0;
    Eigen::Vector3d m1;
    wet_moments(r, f, m0, m1);
    if (m0 <= 0.0) continue;
    const Eigen::Vector3d n = rotation * samples.normal[i];
    const double rho_g = water.density_kg_m3 * water.gravity_m_s2;
    load.force_N += -rho_g * m0 * n;
    load.torque_N_m += -rho_g * m1.cross(n);
  }
  return load;
}

// Area (m^2) of the hull's section by the plane x = x_m below the waterline z = waterline_z_m,
// exactly from the mesh: the plane cuts the closed oriented surface in closed loops, each
// triangle's piece of loop oriented along e_x x n, and Green's theorem gives the area as the
// integral of y dz around the part of the loops below the waterline (the waterline chord adds
// nothing: dz = 0 along it).
double section_area_m2(const HullMesh& mesh, double x_m, double waterline_z_m) {
  double sum = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices_m[t[0]], b = mesh.vertices_m[t[1]], c = mesh.vertices_m[t[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.squaredNorm() == 0.0) continue;
    Eigen::Vector2d ends[2];
    int count = 0;
    const Eigen::Vector3d v[3] = {a, b, c};
    for (int k = 0; k < 3 && count < 2; ++k) {
      const Eigen::Vector3d& p = v[k];
      const Eigen::Vector3d& q = v[(k + 1) % 3];
      const double dp = p.x() - x_m, dq = q.x() - x_m;
      if ((dp < 0.0 && dq >= 0.0) || (dp >= 0.0 && dq < 0.0)) {
        const Eigen::Vector3d r = p + (dp / (dp - dq)) * (q - p);
        ends[count++] = {r.y(), r.z()};
      }
    }
    if (count < 2) continue;
    Eigen::Vector2d p = ends[0], q = ends[1];
    if ((q - p).dot(Eigen::Vector2d(-n.z(), n.y())) < 0.0) std::swap(p, q);
    if (p.y() > waterline_z_m && q.y() > waterline_z_m) continue;
    // Clip to z <= waterline (the second coordinate is z).
    auto clip = [&](Eigen::Vector2d& out, const Eigen::Vector2d& other) {
      const double s = (waterline_z_m - other.y()) / (out.y() - other.y());
      out = other + s * (out - other);
    };
    if (p.y() > waterline_z_m) clip(p, q);
    if (q.y() > waterline_z_m) clip(q, p);
    sum += 0.5 * (p.x() + q.x()) * (q.y() - p.y());
  }
  return std::abs(sum);
}

}  // namespace

ShipParticulars particulars_for_hull(const std::string& ship_name, const HullMesh& mesh, const HullSamples& samples,
                                     const HullLoading& loading) {
  const WaterProperties& water = loading.water;
  const double rho = water.density_kg_m3, g = water.gravity_m_s2;
  if (samples.size() == 0)
    throw Error(ship_name, fmt::format("hull {} has no sample points", mesh.name), "give a hull with faces");
  const MeshMassProperties solid = mesh_mass_properties(mesh);
  ShipParticulars p;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = Eigen::Vector3d::Constant(-1e300);
  for (const auto& v : mesh.vertices_m) {
    low = low.cwiseMin(v);
    high = high.cwiseMax(v);
  }
  p.length_m = high.x() - low.x();
  p.beam_m = high.y() - low.y();
  p.depth_m = high.z() - low.z();
  p.hull_centre_m = 0.5 * (low + high);

  // 1. Mass and draft.
  const double whole_hull_kg = rho * solid.volume_m3;
  if (loading.mass_kg) {
    p.mass_kg = *loading.mass_kg;
  } else if (loading.draft_m) {
    if (!(*loading.draft_m > 0.0))
      throw Error(ship_name, fmt::format("draft_m = {} must be positive", *loading.draft_m), "give the draft in metres");
    p.mass_kg = rho * displaced_volume_m3(samples, low.z() + *loading.draft_m);
  } else {
    throw Error(ship_name, "has neither a mass nor a draft", "give mass_kg or draft_m");
  }
  if (!(p.mass_kg > 0.0) || !std::isfinite(p.mass_kg))
    throw Error(ship_name, fmt::format("mass_kg = {} must be a positive number", p.mass_kg), "give the displacement in kg");
  if (p.mass_kg >= whole_hull_kg)
    throw Error(ship_name,
                fmt::format("cannot float: its mass {:.4g} kg is more than the {:.4g} kg of water the whole hull {} "
                            "displaces ({:.4g} m^3)",
                            p.mass_kg, whole_hull_kg, mesh.name, solid.volume_m3),
                "give a smaller mass_kg (or a draft_m below the deck), or a bigger hull");
  const double volume = p.mass_kg / rho;
  const double waterline_z = waterline_for_volume_m(samples, volume);
  p.design_draft_m = waterline_z - low.z();

  // 2. Centre of gravity and inertia (the solid's, scaled to the mass, moved to G by parallel axes).
  //    A loaded ship floats at its design draft on an even keel and upright: G over the centre of
  //    buoyancy B of that waterline (a loading's trim is set by its ballast; the solid's centroid is
  //    not over B for a hull whose ends differ, and put the tug 0.7 deg down by the head at rest).
  //    KG: the solid's centroid unless given, but no higher than KM - 0.15 m, the least initial
  //    metacentric height GM0 the IMO Intact Stability Code (2008, Part A 2.2.4) allows: the solid
  //    centroid of a narrow hull with high sides is above its metacentre (the 20 x 3 m Wigley launch:
  //    KG 1.405 m, KM 1.396 m), and such a "ship" lolls 15-60 deg to whichever side a turn or a
  //    wave first pushes it (issue 42). KM = KB + BM, BM = I_wp / nabla, from the pieces' columns to
  //    the waterline (each wet piece's (z_w - z) (-n_z) A: volume, moments and waterplane).
  {
    double v = 0.0, mx = 0.0, my = 0.0, mz = 0.0, i_wp = 0.0, foot_y = 0.0, foot = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const Eigen::Vector3d& x = samples.position_m[i];
      if (x.z() >= waterline_z) continue;
      const double a = -samples.normal[i].z() * samples.area_m2[i];
      const double column = (waterline_z - x.z()) * a;
      v += column;
      mx += column * x.x();
      my += column * x.y();
      mz += column * 0.5 * (waterline_z + x.z());
      foot += a;
      foot_y += a * x.y();
      i_wp += a * x.y() * x.y();
    }
    p.centre_of_gravity_m = solid.centroid_m;
    if (v > 0.0 && foot > 0.0) {
      p.centre_of_gravity_m.x() = mx / v;
      p.centre_of_gravity_m.y() = my / v;
      const double y_f = foot_y / foot;  // the waterplane's centreline
      p.metacentre_height_m = mz / v + (i_wp - foot * y_f * y_f) / v - low.z();
      if (!loading.centre_of_gravity_height_m)
        p.centre_of_gravity_m.z() =
            std::min(solid.centroid_m.z(), low.z() + p.metacentre_height_m - kMinimumMetacentricHeight_m);
    }
  }
  if (loading.centre_of_gravity_height_m) p.centre_of_gravity_m.z() = *loading.centre_of_gravity_height_m;
  const Eigen::Vector3d d = p.centre_of_gravity_m - solid.centroid_m;
  p.inertia_kg_m2 = solid.inertia_per_density_m5 * (p.mass_kg / solid.volume_m3) +
                    p.mass_kg * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());

  // 3. Waterplane and wetted surface at the design draft.
  const double dz = 1e-3 * std::max(p.design_draft_m, 1e-3);
  const double waterplane_m2 =
      (displaced_volume_m3(samples, waterline_z + dz) - displaced_volume_m3(samples, waterline_z - dz)) / (2 * dz);
  double wetted = 0.0, lwl_low = 1e300, lwl_high = -1e300, bwl = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (samples.position_m[i].z() >= waterline_z) continue;
    wetted += samples.area_m2[i];
    lwl_low = std::min(lwl_low, samples.position_m[i].x());
    lwl_high = std::max(lwl_high, samples.position_m[i].x());
    bwl = std::max(bwl, 2.0 * std::abs(samples.position_m[i].y() - p.hull_centre_m.y()));
  }
  const double lwl = std::max(lwl_high - lwl_low, 1e-3), draft = std::max(p.design_draft_m, 1e-3);
  bwl = std::max(bwl, 1e-3);
  p.design_wetted_area_m2 = std::max(wetted, 1e-6);
  // Where the surge and sway drag act (ship_body.hpp): the wetted surface's centroid height, and the
  // centroid height of the underwater lateral area (the pieces' side projections |n_y| A).
  {
    double a = 0.0, az = 0.0, side = 0.0, side_z = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const Eigen::Vector3d& x = samples.position_m[i];
      if (x.z() >= waterline_z) continue;
      a += samples.area_m2[i];
      az += samples.area_m2[i] * x.z();
      const double s_y = std::abs(samples.normal[i].y()) * samples.area_m2[i];
      side += s_y;
      side_z += s_y * x.z();
    }
    p.surge_drag_z_m = a > 0.0 ? az / a : p.centre_of_gravity_m.z();
    p.sway_drag_z_m = side > 0.0 ? side_z / side : p.centre_of_gravity_m.z();
  }

  // 3b. Restricted water (restricted_water.hpp): Lpp as the waterline length, Cb on it, the
  //     midship section, the waterplane and its centroid (the x-moment of the displaced volume
  //     differenced across the waterline, as the waterplane area above).
  auto displaced_moment_x = [&](double z_w) {
    double m = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i)
      if (samples.position_m[i].z() < z_w)
        m += (z_w - samples.position_m[i].z()) * (-samples.normal[i].z()) * samples.area_m2[i] * samples.position_m[i].x();
    return m;
  };
  p.waterplane_area_m2 = std::max(waterplane_m2, 0.0);
  p.flotation_centre_x_m =
      waterplane_m2 > 0.0 ? (displaced_moment_x(waterline_z + dz) - displaced_moment_x(waterline_z - dz)) / (2 * dz) / waterplane_m2
                          : p.hull_centre_m.x();
  //     The waterline's length and breadth from the pieces' corners below it (the centroids above
  //     fall half a piece short of the ends).
  double pp_low = 1e300, pp_high = -1e300, beam_wl = 0.0;
  for (const auto& corners : samples.corner_m)
    for (const auto& c : corners) {
      if (c.z() > waterline_z) continue;
      pp_low = std::min(pp_low, c.x());
      pp_high = std::max(pp_high, c.x());
      beam_wl = std::max(beam_wl, 2.0 * std::abs(c.y() - p.hull_centre_m.y()));
    }
  const double lpp = std::max(pp_high - pp_low, 1e-3);
  beam_wl = std::max(beam_wl, 1e-3);
  p.squat.length_pp_m = lpp;
  p.squat.draft_m = draft;
  p.squat.displaced_volume_m3 = volume;
  p.squat.block_coefficient = volume / (lpp * beam_wl * draft);
  p.midship_area_m2 = section_area_m2(mesh, 0.5 * (pp_low + pp_high), waterline_z);

  // 4. Added masses: flat-plate strip values at the free surface (high-frequency limit).
  p.added_mass_kg = {0.05 * p.mass_kg, rho * kPi * draft * draft * lwl / 2.0, rho * kPi * bwl * bwl * lwl / 8.0};
  p.added_inertia_kg_m2 = {0.1 * p.inertia_kg_m2(0, 0), p.added_mass_kg.z() * lwl * lwl / 12.0,
                           p.added_mass_kg.y() * lwl * lwl / 12.0};

  // 5. Restoring stiffness from the same pressure integration the body uses (small heel and trim).
  const double z_g = p.centre_of_gravity_m.z() - waterline_z;
  const double angle = 0.01;
  // Restoring moment per radian about the upright pose (the upright pose may carry a trimming
  // moment of its own when G is not over the centre of buoyancy: difference it out).
  auto stiffness = [&](const Eigen::Vector3d& axis, int component) {
    const double upright = still_water_pressure(samples, p.centre_of_gravity_m, Eigen::Matrix3d::Identity(), z_g, water)
                               .torque_N_m[component];
    const double turned =
        still_water_pressure(samples, p.centre_of_gravity_m, Eigen::AngleAxisd(angle, axis).toRotationMatrix(), z_g, water)
            .torque_N_m[component];
    return std::max(-(turned - upright) / angle, 0.0);
  };
  const double roll_stiffness = stiffness(Eigen::Vector3d::UnitX(), 0);
  const double pitch_stiffness = stiffness(Eigen::Vector3d::UnitY(), 1);
  p.pitch_stiffness_N_m_rad = pitch_stiffness;
  const double heave_stiffness = rho * g * waterplane_m2;
  const double zeta = 0.05;  // radiation damping, fraction of critical
  // Surge, sway and yaw have no restoring force: a linear (laminar, low-speed) damping with a 120 s
  // time constant lets a ship that is left alone come to rest instead of coasting for ever.
  const double coasting_s = 120.0;
  p.linear_damping_N_s_m = {(p.mass_kg + p.added_mass_kg.x()) / coasting_s, (p.mass_kg + p.added_mass_kg.y()) / coasting_s,
                            2 * zeta * std::sqrt(heave_stiffness * (p.mass_kg + p.added_mass_kg.z()))};
  p.linear_damping_N_m_s = {
      2 * zeta * std::sqrt(roll_stiffness * (p.inertia_kg_m2(0, 0) + p.added_inertia_kg_m2.x())),
      2 * zeta * std::sqrt(pitch_stiffness * (p.inertia_kg_m2(1, 1) + p.added_inertia_kg_m2.y())),
      (p.inertia_kg_m2(2, 2) + p.added_inertia_kg_m2.z()) / coasting_s};

  // 6. Quadratic drag.
  const double surge = 0.5 * rho * p.design_wetted_area_m2 * 0.006;
  const double sway = 0.5 * rho * 1.0 * lwl * draft;
  const double heave = 0.5 * rho * 1.0 * std::max(waterplane_m2, 1e-6);
  const double l4 = std::pow(lwl, 4) / 32.0;
  p.quadratic_drag_N_s2_m2 = {surge, sway, heave};
  p.quadratic_drag_N_m_s2 = {0.5 * rho * 1.0 * lwl * std::pow(bwl, 4) / 32.0, heave / lwl * l4 * 1.0,
                             sway / lwl * l4};

  // 7. Engine and rudder.
  p.service_speed_m_s = loading.service_speed_m_s.value_or(0.25 * std::sqrt(g * lwl));
  p.max_thrust_N = (p.linear_damping_N_s_m.x() + surge * p.service_speed_m_s) * p.service_speed_m_s;
  p.max_astern_thrust_N = 0.6 * p.max_thrust_N;
  p.propeller_position_m = {lwl_low + 0.06 * lwl, p.hull_centre_m.y(), low.z() + 0.45 * draft};
  p.propeller_diameter_m = 0.6 * draft;
  p.rudder_area_m2 = 0.02 * lwl * draft;
  p.rudder_position_m = {lwl_low + 0.02 * lwl, p.hull_centre_m.y(), low.z() + 0.5 * draft};
  return p;
}

double ShipState::yaw_rad() const {
  const Eigen::Matrix3d r = orientation.toRotationMatrix();
  return std::atan2(r(1, 0), r(0, 0));
}
double ShipState::pitch_rad() const {
  const Eigen::Matrix3d r = orientation.toRotationMatrix();
  return -std::asin(std::clamp(r(2, 0), -1.0, 1.0));
}
double ShipState::roll_rad() const {
  const Eigen::Matrix3d r = orientation.toRotationMatrix();
  return std::atan2(r(2, 1), r(2, 2));
}
double ShipState::heading_deg() const {
  double h = 90.0 - yaw_rad() * 180.0 / kPi;
  h = std::fmod(h, 360.0);
  return h < 0.0 ? h + 360.0 : h;
}
double ShipState::forward_speed_m_s() const { return velocity_m_s.dot(orientation * Eigen::Vector3d::UnitX()); }

Eigen::Quaterniond orientation_from_euler(double yaw_rad, double pitch_rad, double roll_rad) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()));
}

// Reduced to one turn first (std::fmod is exact): any finite heading is a heading, and 1e308 deg
// times pi would overflow to infinity and make the orientation NaN (issue 44).
double yaw_from_heading_rad(double heading_deg) { return (90.0 - std::fmod(heading_deg, 360.0)) * kPi / 180.0; }

ShipBody::ShipBody(HullSamples samples, ShipParticulars particulars, ShipState initial)
    : samples_(std::move(samples)), particulars_(std::move(particulars)), state_(initial) {
  arm_m_.reserve(samples_.size());
  for (const auto& x : samples_.position_m) arm_m_.push_back(x - particulars_.centre_of_gravity_m);
  corner_arm_m_.reserve(samples_.size());
  for (const auto& c : samples_.corner_m)
    corner_arm_m_.push_back({c[0] - particulars_.centre_of_gravity_m, c[1] - particulars_.centre_of_gravity_m,
                             c[2] - particulars_.centre_of_gravity_m});
  query_points_.resize(samples_.size());
  elevations_m_.resize(samples_.size());
  world_arm_m_.resize(samples_.size());
  state_.orientation.normalize();
}

std::vector<Eigen::Vector3d> ShipBody::world_points_m() const {
  std::vector<Eigen::Vector3d> out;
  out.reserve(arm_m_.size());
  const Eigen::Matrix3d r = state_.orientation.toRotationMatrix();
  for (const auto& a : arm_m_) out.push_back(state_.position_m + r * a);
  return out;
}

Eigen::Vector3d ShipBody::to_world(const Eigen::Vector3d& body_point_m) const {
  return state_.position_m + state_.orientation * (body_point_m - particulars_.centre_of_gravity_m);
}

void ShipBody::step(const ShipEnvironment& environment, const ShipControls& controls, const ExternalLoad& external,
                    double dt_s) {
  if (!(dt_s > 0.0)) return;
  const int substeps = std::max(1, static_cast<int>(std::ceil(dt_s / max_substep_s - 1e-9)));
  // The closing speed of a strike is reported as the largest over the step's substeps: the impact
  // impulse stops the hull in the substep it strikes, and a report of the last substep alone missed
  // a strike in an earlier one (it read 0.07 m/s for a tug that struck at 3 m/s).
  double closing_m_s = 0.0;
  for (int s = 0; s < substeps; ++s) {
    substep(environment, controls, external, dt_s / substeps);
    closing_m_s = std::max(closing_m_s, report_.structure_closing_speed_m_s);
  }
  report_.structure_closing_speed_m_s = closing_m_s;
}

void ShipBody::substep(const ShipEnvironment& environment, const ShipControls& controls, const ExternalLoad& external,
                       double dt_s) {
  const WaterProperties& water = environment.water_properties;
  const Eigen::Matrix3d rotation = state_.orientation.toRotationMatrix();
  sample_water(environment, rotation);
  BodyReport report;
  Loads loads;
  double bottom_area_m2 = 0.0, bottom_area_depth_m3 = 0.0;
  add_pressure_and_seabed(environment, rotation, loads, report, bottom_area_m2, bottom_area_depth_m3);
  add_structure_contact(environment, loads, report);
  // 3. Gravity at G.
  loads.force.z() -= particulars_.mass_kg * water.gravity_m_s2;
  const WaterMotion motion = water_motion(environment, rotation, report);
  add_restricted_water_and_drag(motion, rotation, bottom_area_m2, bottom_area_depth_m3, water, loads, report);
  const double thrust = add_engine_and_rudder(controls, motion, rotation, water.density_kg_m3, dt_s, loads);
  loads.force += external.force_N;
  loads.torque += external.torque_N_m;
  integrate(loads, motion, rotation, report, dt_s);
  report.rudder_angle_rad = rudder_angle_rad_;
  report.thrust_N = thrust;
  report_ = report;
}

// 1. Where the hull points are and the water over them.
void ShipBody::sample_water(const ShipEnvironment& environment, const Eigen::Matrix3d& rotation) {
  const std::size_t n = arm_m_.size();
  for (std::size_t i = 0; i < n; ++i) {
    world_arm_m_[i] = rotation * arm_m_[i];
    query_points_[i] = {state_.position_m.x() + world_arm_m_[i].x(), state_.position_m.y() + world_arm_m_[i].y()};
  }
  if (environment.water != nullptr)
    environment.water->elevations_m(query_points_, elevations_m_);
  else
    std::fill(elevations_m_.begin(), elevations_m_.end(), 0.0);
  if (environment.extra_elevation_m)
    for (std::size_t i = 0; i < n; ++i) elevations_m_[i] += environment.extra_elevation_m(query_points_[i].x_m, query_points_[i].y_m);
}

// 2. Pressure (eq. 4.21-4.22) and seabed contact, point by point; the wet bottom's area and its
//    area-weighted depth for the restricted-water terms (step 4a).
void ShipBody::add_pressure_and_seabed(const ShipEnvironment& environment, const Eigen::Matrix3d& rotation, Loads& loads,
                                       BodyReport& report, double& bottom_area_m2, double& bottom_area_depth_m3) const {
  const double rho = environment.water_properties.density_kg_m3, g = environment.water_properties.gravity_m_s2;
  const double bed_stiffness = kSeabedStiffnessRatio * rho * g;
  for (std::size_t i = 0; i < arm_m_.size(); ++i) {
    const Eigen::Vector3d& arm = world_arm_m_[i];
    const double z = state_.position_m.z() + arm.z();
    // The piece's pressure head eta - z, linear over it (eta: the surface over its centroid).
    Eigen::Vector3d r[3];
    double f[3];
    for (int k = 0; k < 3; ++k) {
      r[k] = rotation * corner_arm_m_[i][k];
      f[k] = elevations_m_[i] - (state_.position_m.z() + r[k].z());
    }
    if (f[0] > 0.0 || f[1] > 0.0 || f[2] > 0.0) {
      double m0;
      Eigen::Vector3d m1;
      wet_moments(r, f, m0, m1);
      const Eigen::Vector3d normal = rotation * samples_.normal[i];
      const Eigen::Vector3d f_piece = -(rho * g * m0) * normal;
      loads.force += f_piece;
      loads.torque += -(rho * g) * m1.cross(normal);
      report.pressure_force_N += f_piece;
      if (elevations_m_[i] > z) {
        ++report.wet_points;
        report.wetted_area_m2 += samples_.area_m2[i];
      }
    }
    if (environment.seabed != nullptr) {
      const double bed_z = -environment.seabed->depth_m(query_points_[i].x_m, query_points_[i].y_m);
      // The depth under the hull's bottom for squat and the shallow-water resistance: the bed's
      // depth below still water, weighted by the wet bottom's horizontal projection.
      const double bottom = samples_.area_m2[i] * std::max(0.0, -(rotation * samples_.normal[i]).z());
      if (bottom > 0.0 && elevations_m_[i] > z && std::isfinite(bed_z)) {
        bottom_area_m2 += bottom;
        bottom_area_depth_m3 += bottom * -bed_z;
      }
      const double penetration = bed_z - z;
      if (penetration > 0.0) {
        const Eigen::Vector3d point_velocity = state_.velocity_m_s + state_.angular_velocity_rad_s.cross(arm);
        const double normal = std::max(
            0.0, bed_stiffness * samples_.area_m2[i] * (penetration - kSeabedDampingTime_s * point_velocity.z()));
        const Eigen::Vector2d slip(point_velocity.x(), point_velocity.y());
        const Eigen::Vector2d friction =
            -kSeabedFriction * normal * slip / std::sqrt(slip.squaredNorm() + kFrictionVelocity_m_s * kFrictionVelocity_m_s);
        const Eigen::Vector3d f(friction.x(), friction.y(), normal);
        loads.force += f;
        loads.torque += arm.cross(f);
        ++report.contact_points;
        report.max_penetration_m = std::max(report.max_penetration_m, penetration);
        report.contact_position_m += state_.position_m + arm;
      }
    }
  }
  if (report.contact_points > 0) report.contact_position_m /= report.contact_points;
}

// 2b. Structures and land: every hull point (wet or dry: a bow flare meets a quay above water)
//     inside a solid (phi < 0) and below its top. Skipped while the hull's centre is farther from
//     every face than half the hull's diagonal.
void ShipBody::add_structure_contact(const ShipEnvironment& environment, Loads& loads, BodyReport& report) const {
  const ShipParticulars& p = particulars_;
  const HarbourObstacles* obstacles = environment.seabed != nullptr ? environment.seabed->obstacles() : nullptr;
  if (obstacles == nullptr ||
      !(obstacles->signed_distance_m(state_.position_m.x(), state_.position_m.y()) < 0.5 * std::hypot(p.length_m, p.beam_m) + 1.0))
    return;
  const double face_stiffness =
      kStructureStiffnessRatio * environment.water_properties.density_kg_m3 * environment.water_properties.gravity_m_s2;
  for (std::size_t i = 0; i < arm_m_.size(); ++i) {
    const ObstacleSample o = obstacles->sample(query_points_[i].x_m, query_points_[i].y_m);
    if (!(o.signed_distance_m < 0.0) || o.normal.isZero()) continue;
    const Eigen::Vector3d& arm = world_arm_m_[i];
    const double z = state_.position_m.z() + arm.z();
    if (z > o.top_m) continue;
    const double depth = -o.signed_distance_m;
    const Eigen::Vector3d point_velocity = state_.velocity_m_s + state_.angular_velocity_rad_s.cross(arm);
    const Eigen::Vector3d normal(o.normal.x(), o.normal.y(), 0.0);
    const double outward = point_velocity.dot(normal);
    const double push = std::max(0.0, face_stiffness * samples_.area_m2[i] * (depth - kStructureDampingTime_s * outward));
    const Eigen::Vector3d slip = point_velocity - outward * normal;
    const Eigen::Vector3d f =
        push * normal - kStructureFriction * push * slip / std::sqrt(slip.squaredNorm() + kFrictionVelocity_m_s * kFrictionVelocity_m_s);
    loads.force += f;
    loads.torque += arm.cross(f);
    ++report.structure_contact_points;
    report.structure_force_N += push;
    report.structure_closing_speed_m_s = std::max(report.structure_closing_speed_m_s, -outward);
    if (depth > report.structure_penetration_m) {
      report.structure_penetration_m = depth;
      report.structure = o.structure;
      report.structure_contact_m = state_.position_m + arm;
      report.structure_normal = o.normal;
    }
  }
}

// 4. The hull's motion relative to the water (the current under G), in body axes, and how much of
//    the hull is wet (the drag, engine and rudder scale with it).
ShipBody::WaterMotion ShipBody::water_motion(const ShipEnvironment& environment, const Eigen::Matrix3d& rotation,
                                             const BodyReport& report) const {
  WaterMotion motion;
  motion.wet_fraction = std::min(1.0, report.wetted_area_m2 / particulars_.design_wetted_area_m2);
  motion.current_m_s = Eigen::Vector3d::Zero();
  if (environment.water != nullptr && motion.wet_fraction > 0.0) {
    const runtime::SurfaceState s = environment.water->state(state_.position_m.x(), state_.position_m.y());
    motion.current_m_s = {s.velocity_x_m_s, s.velocity_y_m_s, 0.0};
  }
  motion.velocity_m_s = rotation.transpose() * (state_.velocity_m_s - motion.current_m_s);
  motion.angular_velocity_rad_s = rotation.transpose() * state_.angular_velocity_rad_s;
  return motion;
}

// 4a. Restricted water (restricted_water.hpp) over the mean depth under the hull's bottom, then the
//     drag relative to the water, in body axes, scaled by the wetted fraction.
void ShipBody::add_restricted_water_and_drag(const WaterMotion& motion, const Eigen::Matrix3d& rotation, double bottom_area_m2,
                                             double bottom_area_depth_m3, const WaterProperties& water, Loads& loads,
                                             BodyReport& report) const {
  const ShipParticulars& p = particulars_;
  const double rho = water.density_kg_m3, g = water.gravity_m_s2;
  const Eigen::Vector3d& v_body = motion.velocity_m_s;
  const double wet_fraction = motion.wet_fraction;
  report.depth_under_hull_m = bottom_area_m2 > 0.0 ? bottom_area_depth_m3 / bottom_area_m2 : std::nan("");
  Eigen::Vector3d drag_velocity = v_body;  // surge at Lackenby's equivalent deep-water speed
  if (bottom_area_m2 > 0.0) {
    const double depth = report.depth_under_hull_m;
    if (p.midship_area_m2 > 0.0) {
      const double deep = deep_water_equivalent_speed_m_s(p.midship_area_m2, depth, p.squat.draft_m, v_body.x(), g);
      drag_velocity.x() = std::copysign(deep, v_body.x());
      report.deep_water_equivalent_speed_m_s = deep;
    }
    // Squat: the return flow's pressure deficit, as the loads the hull's hydrostatics balance at
    // Tuck's sinkage S_m (rho g A_wp S_m down at the centre of flotation, where it sinks without
    // trimming) and at the trim theta (a couple K_pitch theta, bow down for theta > 0: +y body).
    // Faded out as the hull leaves the water (no return flow round a hull in the air).
    report.squat = squat(p.squat, v_body.x(), depth, g);
    const double afloat = std::min(1.0, 2.0 * wet_fraction);
    if (afloat > 0.0 && (report.squat.midship_sinkage_m != 0.0 || report.squat.trim_rad != 0.0)) {
      const Eigen::Vector3d down =
          Eigen::Vector3d(0.0, 0.0, -afloat * rho * g * p.waterplane_area_m2 * report.squat.midship_sinkage_m);
      const Eigen::Vector3d flotation_arm =
          rotation * (Eigen::Vector3d(p.flotation_centre_x_m, p.centre_of_gravity_m.y(), p.centre_of_gravity_m.z()) -
                      p.centre_of_gravity_m);
      loads.force += down;
      loads.torque += flotation_arm.cross(down);
      loads.torque += rotation * Eigen::Vector3d(0.0, afloat * p.pitch_stiffness_N_m_rad * report.squat.trim_rad, 0.0);
    }
  }
  const Eigen::Vector3d& w_body = motion.angular_velocity_rad_s;
  const Eigen::Vector3d drag_body =
      -wet_fraction * (p.linear_damping_N_s_m.cwiseProduct(drag_velocity) +
                       p.quadratic_drag_N_s2_m2.cwiseProduct(drag_velocity.cwiseAbs()).cwiseProduct(drag_velocity));
  const Eigen::Vector3d drag_moment_body =
      -wet_fraction * (p.linear_damping_N_m_s.cwiseProduct(w_body) +
                       p.quadratic_drag_N_m_s2.cwiseProduct(w_body.cwiseAbs()).cwiseProduct(w_body));
  loads.force += rotation * drag_body;
  // The surge and sway drag at their heights (ship_body.hpp): their moments about G.
  auto drag_arm = [&](double z_m) {
    return Eigen::Vector3d(0.0, 0.0, std::isfinite(z_m) ? z_m - p.centre_of_gravity_m.z() : 0.0);
  };
  const Eigen::Vector3d drag_arm_surge = drag_arm(p.surge_drag_z_m), drag_arm_sway = drag_arm(p.sway_drag_z_m);
  const Eigen::Vector3d drag_lever_moment_body = drag_arm_surge.cross(Eigen::Vector3d(drag_body.x(), 0.0, 0.0)) +
                                                 drag_arm_sway.cross(Eigen::Vector3d(0.0, drag_body.y(), 0.0));
  loads.torque += rotation * (drag_moment_body + drag_lever_moment_body);
}

// 5. Engine (seed 002 eq. 3, F_e along the hull) and rudder, at their body points; the rudder
//    turns towards its order at its rate. Returns the thrust.
double ShipBody::add_engine_and_rudder(const ShipControls& controls, const WaterMotion& motion, const Eigen::Matrix3d& rotation,
                                       double density_kg_m3, double dt_s, Loads& loads) {
  const ShipParticulars& p = particulars_;
  const double rho = density_kg_m3, wet_fraction = motion.wet_fraction;
  const double order = std::clamp(controls.engine_order, -1.0, 1.0);
  const double thrust = wet_fraction * (order >= 0.0 ? order * p.max_thrust_N : order * p.max_astern_thrust_N);
  const Eigen::Vector3d thrust_world = rotation * Eigen::Vector3d(thrust, 0.0, 0.0);
  const Eigen::Vector3d propeller_arm = rotation * (p.propeller_position_m - p.centre_of_gravity_m);
  loads.force += thrust_world;
  loads.torque += propeller_arm.cross(thrust_world);

  const double rudder_order = std::clamp(controls.rudder_order_rad, -p.max_rudder_angle_rad, p.max_rudder_angle_rad);
  const double max_move = p.rudder_rate_rad_s * dt_s;
  rudder_angle_rad_ += std::clamp(rudder_order - rudder_angle_rad_, -max_move, max_move);
  const double forward = std::max(motion.velocity_m_s.x(), 0.0);
  const double slipstream = std::max(thrust, 0.0) * 8.0 / (kPi * rho * p.propeller_diameter_m * p.propeller_diameter_m);
  const double lift = wet_fraction * 0.5 * rho * p.rudder_area_m2 * p.rudder_lift_slope_per_rad * rudder_angle_rad_ *
                      (forward * forward + slipstream);
  const Eigen::Vector3d lift_world = rotation * Eigen::Vector3d(0.0, -lift, 0.0);
  const Eigen::Vector3d rudder_arm = rotation * (p.rudder_position_m - p.centre_of_gravity_m);
  loads.force += lift_world;
  loads.torque += rudder_arm.cross(lift_world);
  return thrust;
}

void ShipBody::integrate(const Loads& loads, const WaterMotion& motion, const Eigen::Matrix3d& rotation, const BodyReport& report,
                         double dt_s) {
  const ShipParticulars& p = particulars_;
  Eigen::Vector3d force = loads.force;
  const Eigen::Vector3d& torque = loads.torque;
  // 6. Semi-implicit Euler: Newton with the world-frame mass matrix, Euler's equations with the
  //    world-frame inertia tensor (eq. 4.19-4.20), then positions with the new velocities.
  const Eigen::Matrix3d mass_world =
      rotation * (p.mass_kg * Eigen::Matrix3d::Identity() + p.added_mass_kg.asDiagonal().toDenseMatrix()) *
      rotation.transpose();
  //    The added masses are the fluid's momentum A v_r (v_r relative to the water), carried in body
  //    axes: Kirchhoff's equations (Lamb 1932, Hydrodynamics section 124; Fossen 2011, Handbook of
  //    Marine Craft Hydrodynamics and Motion Control, the added-mass Coriolis matrix C_A) add
  //    A (w x v_r) - w x (A v_r) to the force (the first term undoes the part of M dv/dt that turns A
  //    with the body). Without it a turning ship needed (m + A_22) V^2 / R of lateral force instead
  //    of (m + A_11) V^2 / R, and so heeled twice the turning-heel estimate (issue 42). The Munk
  //    moment -v_r x (A v_r) that completes the pair is left out (ship_body.hpp): this body has no
  //    linear hull lift to balance its yaw, and with it the launch ran into a spin at 0.1 rad of rudder.
  {
    const Eigen::Vector3d v_r = state_.velocity_m_s - motion.current_m_s;
    const Eigen::Matrix3d added_world = rotation * p.added_mass_kg.asDiagonal().toDenseMatrix() * rotation.transpose();
    const Eigen::Vector3d& w_now = state_.angular_velocity_rad_s;
    force += added_world * w_now.cross(v_r) - w_now.cross(added_world * v_r);
  }
  state_.velocity_m_s += mass_world.ldlt().solve(force) * dt_s;
  const Eigen::Matrix3d inertia_world =
      rotation * (p.inertia_kg_m2 + p.added_inertia_kg_m2.asDiagonal().toDenseMatrix()) * rotation.transpose();
  const Eigen::Vector3d& w = state_.angular_velocity_rad_s;
  const Eigen::Vector3d angular_acceleration = inertia_world.ldlt().solve(torque - w.cross(inertia_world * w));
  state_.angular_velocity_rad_s += angular_acceleration * dt_s;
  // 7. An impact on a structure or the land: the penalty alone would let a fast hull through a thin
  //    breakwater (its depth inside is a cell or two) or bounce it back elastically, so at the
  //    deepest contact point one impulse with the rigid body's effective mass there (Catto,
  //    "Iterative dynamics with temporal coherence", GDC 2005; added masses included) sets the
  //    normal velocity: the closing velocity taken away (e = 0, kStructureRestitution), and an
  //    outward velocity the penalty gave beyond the separation speed taken back (never more than the
  //    penalty's own normal impulse of this step: contact only pushes). Then a friction impulse
  //    along the face of at most mu times the normal impulse: the slip stops (sticking) or is
  //    slowed by mu J_n (sliding), Pedersen & Zhang (1998).
  if (report.structure_contact_points > 0) {
    const Eigen::Vector3d r = report.structure_contact_m - state_.position_m;
    const Eigen::Vector3d normal(report.structure_normal.x(), report.structure_normal.y(), 0.0);
    const Eigen::LDLT<Eigen::Matrix3d> mass_solver(mass_world), inertia_solver(inertia_world);
    auto apply = [&](const Eigen::Vector3d& impulse) {
      const Eigen::Vector3d moment = r.cross(impulse);
      state_.velocity_m_s += mass_solver.solve(impulse);
      state_.angular_velocity_rad_s += inertia_solver.solve(moment);
    };
    auto point_velocity = [&]() -> Eigen::Vector3d { return state_.velocity_m_s + state_.angular_velocity_rad_s.cross(r); };
    const double outward = point_velocity().dot(normal);  // < 0: into the solid
    const double separation = std::min(report.structure_penetration_m / kStructureRelaxTime_s, kStructureSeparationSpeed_m_s);
    const double target = outward < 0.0 ? -kStructureRestitution * outward : std::min(outward, separation);
    double normal_impulse = (target - outward) / inverse_effective_mass(mass_solver, inertia_solver, r, normal);
    normal_impulse = std::max(normal_impulse, -report.structure_force_N * dt_s);
    apply(normal_impulse * normal);
    if (normal_impulse > 0.0) {
      const Eigen::Vector3d v = point_velocity();
      const Eigen::Vector3d slip = v - v.dot(normal) * normal;
      const double slip_m_s = slip.norm();
      if (slip_m_s > 1e-9) {
        const Eigen::Vector3d along = slip / slip_m_s;
        const double sticking = slip_m_s / inverse_effective_mass(mass_solver, inertia_solver, r, along);
        apply(-std::min(sticking, kStructureFriction * normal_impulse) * along);
      }
    }
  }
  state_.position_m += state_.velocity_m_s * dt_s;
  const double turn = state_.angular_velocity_rad_s.norm() * dt_s;
  if (turn > 0.0)
    state_.orientation =
        Eigen::Quaterniond(Eigen::AngleAxisd(turn, state_.angular_velocity_rad_s.normalized())) * state_.orientation;
  state_.orientation.normalize();
}

}  // namespace nearshore::ships
