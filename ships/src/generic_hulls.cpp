#include "nearshore/ships/generic_hulls.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"
#include "nearshore/ships/ship_limits.hpp"

namespace nearshore::ships {
namespace {

constexpr double kPi = std::numbers::pi;

// A half section: points (y >= 0, z) from the keel centre (t = 0) round the starboard... here the
// PORT side (y > 0) up to the deck centre (t = 1). The full ring mirrors it.
using HalfSection = std::function<std::vector<Eigen::Vector2d>(double x_m)>;

// Lofts rings at stations xs (aft to fore) into a closed surface with a fan cap at each end.
// Every ring has the same point count. Orientation is fixed at the end by the signed volume.
HullMesh loft(const std::string& name, const std::vector<double>& stations_m, const HalfSection& half) {
  HullMesh mesh;
  mesh.name = name;
  std::size_t ring_size = 0;
  std::vector<int> ring_start;
  for (double x : stations_m) {
    const std::vector<Eigen::Vector2d> h = half(x);  // h.front(): keel centre, h.back(): deck centre
    // Ring: keel centre, port side up, deck centre, starboard side down (mirror, without the ends).
    std::vector<Eigen::Vector2d> ring = h;
    for (std::size_t k = h.size() - 2; k >= 1; --k) ring.emplace_back(-h[k].x(), h[k].y());
    if (ring_size == 0) ring_size = ring.size();
    if (ring.size() != ring_size) throw Error(name, "sections of different sizes", "internal: fix the generator");
    ring_start.push_back(static_cast<int>(mesh.vertices_m.size()));
    for (const auto& p : ring) mesh.vertices_m.emplace_back(x, p.x(), p.y());
  }
  const int m = static_cast<int>(ring_size);
  for (std::size_t s = 0; s + 1 < stations_m.size(); ++s)
    for (int k = 0; k < m; ++k) {
      const int a = ring_start[s] + k, b = ring_start[s] + (k + 1) % m;
      const int c = ring_start[s + 1] + k, d = ring_start[s + 1] + (k + 1) % m;
      mesh.triangles.push_back({a, c, d});
      mesh.triangles.push_back({a, d, b});
    }
  // End caps: fans from the ring's centroid (one new vertex each).
  for (int end = 0; end < 2; ++end) {
    const int start = end == 0 ? ring_start.front() : ring_start.back();
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int k = 0; k < m; ++k) centre += mesh.vertices_m[start + k];
    centre /= m;
    const int c = static_cast<int>(mesh.vertices_m.size());
    mesh.vertices_m.push_back(centre);
    for (int k = 0; k < m; ++k) {
      const int a = start + k, b = start + (k + 1) % m;
      // The sides use ring edges k+1 -> k at the first station and k -> k+1 at the last: the caps
      // use each in the other direction.
      if (end == 0)
        mesh.triangles.push_back({c, a, b});
      else
        mesh.triangles.push_back({c, b, a});
    }
  }
  if (mesh_mass_properties(mesh).volume_m3 < 0.0)
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

void require_positive(const std::string& what, double value, const std::string& parameter) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw Error(what, fmt::format("{} = {} must be a positive number of metres", parameter, value),
                "give a positive size");
}

}  // namespace

HullMesh box_barge(double length_m, double beam_m, double depth_m) {
  const std::string name = fmt::format("box barge {} x {} x {} m", length_m, beam_m, depth_m);
  require_positive(name, length_m, "length_m");
  require_positive(name, beam_m, "beam_m");
  require_positive(name, depth_m, "depth_m");
  HullMesh mesh;
  mesh.name = name;
  const double hx = 0.5 * length_m, hy = 0.5 * beam_m;
  for (int k = 0; k < 8; ++k)
    mesh.vertices_m.emplace_back((k & 1) ? hx : -hx, (k & 2) ? hy : -hy, (k & 4) ? depth_m : 0.0);
  // Faces counter-clockwise seen from outside (vertex index bits: x, y, z).
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}

HullMesh wigley_hull(double length_m, double beam_m, double draft_m, double depth_m, int sections, int levels) {
  const std::string name = fmt::format("Wigley hull {} x {} x {} m (depth {} m)", length_m, beam_m, draft_m, depth_m);
  require_positive(name, length_m, "length_m");
  require_positive(name, beam_m, "beam_m");
  require_positive(name, draft_m, "draft_m");
  if (!(depth_m > draft_m)) throw Error(name, "depth_m must exceed draft_m", "give a freeboard above the waterline");
  if (sections < 3 || levels < 2) throw Error(name, "needs at least 3 sections and 2 levels", "use the defaults");
  // The ends x = +-L/2 have zero breadth: keep a sliver (1e-3 of the beam) so the end rings stay
  // proper polygons and the caps close them with (nearly) zero area.
  std::vector<double> stations;
  for (int s = 0; s < sections; ++s) stations.push_back(-0.5 * length_m + length_m * s / (sections - 1));
  auto half = [=](double x) {
    const double f = std::max(1.0 - std::pow(2.0 * x / length_m, 2), 1e-3);
    std::vector<Eigen::Vector2d> h;
    h.emplace_back(0.0, 0.0);
    // Below the waterline: z from the keel up, cosine-spaced (finer near the keel's curvature).
    for (int k = 1; k <= levels; ++k) {
      const double z = draft_m * (1.0 - std::cos(0.5 * kPi * k / levels));
      const double zeta = (draft_m - z) / draft_m;
      h.emplace_back(std::max(0.5 * beam_m * f * (1.0 - zeta * zeta), 1e-4 * beam_m), z);
    }
    h.emplace_back(0.5 * beam_m * f, depth_m);  // wall side up to the deck
    h.emplace_back(0.0, depth_m);               // deck centre
    return h;
  };
  return loft(name, stations, half);
}

HullMesh harbour_tug(double length_m, double beam_m, double depth_m) {
  const std::string name = fmt::format("harbour tug {} x {} x {} m", length_m, beam_m, depth_m);
  require_positive(name, length_m, "length_m");
  require_positive(name, beam_m, "beam_m");
  require_positive(name, depth_m, "depth_m");
  const double bow_start = 0.1 * length_m;     // waterline closes forward of here
  const double rise_start = 0.25 * length_m;   // keel rises forward of here
  const double bilge_m = 0.25 * beam_m;
  std::vector<double> stations;
  const int sections = 33;
  for (int s = 0; s < sections; ++s) {
    const double u = static_cast<double>(s) / (sections - 1);
    stations.push_back(-0.5 * length_m + length_m * (0.5 - 0.5 * std::cos(kPi * u)));  // finer at the ends
  }
  auto half = [=](double x) {
    double b = 0.5 * beam_m;
    if (x < 0.0) b *= 0.85 + 0.15 * (1.0 - std::pow(2.0 * x / length_m, 2));          // transom 85 % wide
    if (x > bow_start) b *= std::sqrt(std::max(1.0 - std::pow((x - bow_start) / (0.5 * length_m - bow_start), 2), 0.0));
    b = std::max(b, 0.01 * beam_m);
    double keel = 0.0;
    if (x > rise_start) keel = 0.6 * depth_m * std::pow((x - rise_start) / (0.5 * length_m - rise_start), 2);
    const double radius = std::min(bilge_m, std::min(b, 0.8 * (depth_m - keel)));
    std::vector<Eigen::Vector2d> h;
    h.emplace_back(0.0, keel);
    h.emplace_back(0.5 * (b - radius), keel);
    for (int k = 0; k <= 6; ++k) {  // bilge quarter circle
      const double a = -0.5 * kPi + 0.5 * kPi * k / 6.0;
      h.emplace_back(b - radius + radius * std::cos(a), keel + radius + radius * std::sin(a));
    }
    for (int k = 1; k <= 4; ++k) {  // side up to the deck
      const double z0 = keel + radius;
      h.emplace_back(b, z0 + (depth_m - z0) * k / 4.0);
    }
    h.emplace_back(0.5 * b, depth_m);
    h.emplace_back(0.0, depth_m);
    return h;
  };
  return loft(name, stations, half);
}

std::optional<HullMesh> generic_hull(const std::string& name, const GenericHullDimensions& dimensions) {
  // Each dimension 0 (the hull's default) or within its range (ship_limits.hpp): a 1e9 m hull
  // would be lofted and cut into pieces before anything else could refuse it.
  const std::string subject = fmt::format("generic hull '{}'", name);
  const std::pair<const char*, const ParameterRange*> checks[] = {
      {"length_m", &limits::kLength}, {"beam_m", &limits::kBeam}, {"depth_m", &limits::kDepth}, {"draft_m", &limits::kDraft}};
  const double values[] = {dimensions.length_m, dimensions.beam_m, dimensions.depth_m, dimensions.draft_m};
  for (int k = 0; k < 4; ++k)
    if (values[k] != 0.0) require_in_range(subject, checks[k].first, values[k], *checks[k].second);
  auto or_default = [](double value, double fallback) { return value > 0.0 ? value : fallback; };
  if (name == "box_barge")
    return box_barge(or_default(dimensions.length_m, 20.0), or_default(dimensions.beam_m, 8.0),
                     or_default(dimensions.depth_m, 3.0));
  if (name == "wigley") {
    const double draft = or_default(dimensions.draft_m, 1.25);
    return wigley_hull(or_default(dimensions.length_m, 20.0), or_default(dimensions.beam_m, 2.0), draft,
                       or_default(dimensions.depth_m, 2.0 * draft));
  }
  if (name == "tug")
    return harbour_tug(or_default(dimensions.length_m, 24.0), or_default(dimensions.beam_m, 9.0),
                       or_default(dimensions.depth_m, 4.5));
  return std::nullopt;
}

}  // namespace nearshore::ships
