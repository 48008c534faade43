#include "nearshore/playback/surface_grids.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "nearshore/core/error.hpp"

namespace nearshore::playback {

std::string_view grid_kind_name(GridKind kind) {
  switch (kind) {
    case GridKind::radial: return "radial";
    case GridKind::quadtree: return "quadtree";
    case GridKind::projected: return "projected";
  }
  return "unknown";
}

GridKind grid_kind_from_name(std::string_view name) {
  for (GridKind kind : {GridKind::radial, GridKind::quadtree, GridKind::projected})
    if (grid_kind_name(kind) == name) return kind;
  throw Error("grid kind \"" + std::string(name) + "\"", "is not a grid the renderer has",
              "name one of radial, quadtree, projected");
}

// ---- radial ----------------------------------------------------------------------------------
RadialGrid build_radial_grid(const RadialGridSettings& s) {
  if (s.segment_count < 8 || s.segment_count > 65536 || !(s.inner_spacing_m > 0) ||
      !(s.outer_radius_m > 2 * s.inner_spacing_m))
    throw Error("RadialGridSettings", "segment_count " + std::to_string(s.segment_count) + ", inner_spacing_m " +
                                          std::to_string(s.inner_spacing_m) + ", outer_radius_m " +
                                          std::to_string(s.outer_radius_m),
                "give 8 <= segment_count <= 65536 and 0 < 2 inner_spacing_m < outer_radius_m");
  const int m = s.segment_count;
  const double growth = 2.0 * std::numbers::pi / m;
  // R_i = s ((1 + g)^i - 1) / g >= outer: the smallest such i is the last ring, placed at outer.
  const int last = static_cast<int>(std::ceil(std::log1p(s.outer_radius_m * growth / s.inner_spacing_m) / std::log1p(growth)));
  RadialGrid grid;
  grid.ring_count = last + 1;
  grid.segment_count = m;
  grid.polar.reserve(std::size_t(grid.ring_count) * m * 2);
  for (int i = 0; i <= last; ++i) {
    const double radius = i == last ? s.outer_radius_m : s.inner_spacing_m * std::expm1(i * std::log1p(growth)) / growth;
    for (int j = 0; j < m; ++j) {
      // eq. 2.20: angle 2 pi j / M + pi i / M (kept in [0, 2 pi) so float keeps its precision).
      const double angle = std::fmod(2.0 * std::numbers::pi * j / m + std::numbers::pi * (i % (2 * m)) / m,
                                     2.0 * std::numbers::pi);
      grid.polar.insert(grid.polar.end(), {float(radius), float(angle)});
    }
  }
  // Ring i + 1 is turned half a step ahead of ring i: vertex (i+1, j) lies between (i, j) and
  // (i, j+1), so each quad splits into the two triangles that share the edge (i, j+1)-(i+1, j).
  for (int i = 0; i < last; ++i)
    for (int j = 0; j < m; ++j) {
      const auto at = [m](int ring, int segment) { return std::uint32_t(ring * m + (segment % m)); };
      grid.triangles.insert(grid.triangles.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
      grid.triangles.insert(grid.triangles.end(), {at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)});
    }
  return grid;
}

// ---- quadtree --------------------------------------------------------------------------------
namespace {

struct Box {
  double x0, y0, x1, y1;
};

// 3-D distance from the eye to the nearest point of the box at still water (z = 0).
double nearest_distance_m(const Box& b, const Vector3& eye) {
  const double dx = std::max({b.x0 - eye[0], 0.0, eye[0] - b.x1});
  const double dy = std::max({b.y0 - eye[1], 0.0, eye[1] - b.y1});
  return std::sqrt(dx * dx + dy * dy + eye[2] * eye[2]);
}

// The box widened by the displacement bound, against the six frustum planes: outside when all
// eight corners are behind one plane.
bool in_frustum(const Box& b, double bound, const CameraView& view) {
  for (const auto& plane : view.frustum_planes) {
    bool any_inside = false;
    for (int corner = 0; corner < 8 && !any_inside; ++corner) {
      const double x = (corner & 1) ? b.x1 + bound : b.x0 - bound;
      const double y = (corner & 2) ? b.y1 + bound : b.y0 - bound;
      const double z = (corner & 4) ? bound : -bound;
      any_inside = plane[0] * x + plane[1] * y + plane[2] * z + plane[3] >= 0.0;
    }
    if (!any_inside) return false;
  }
  return true;
}

struct Selector {
  const QuadtreeSettings& settings;
  const CameraView& view;
  QuadtreeSelection& out;

  double node_size(int level) const { return 2.0 * out.levels[std::size_t(level)].patch_size_m; }
  void emit_patch(double x, double y, int level) {
    const double p = out.levels[std::size_t(level)].patch_size_m;
    if (in_frustum({x, y, x + p, y + p}, settings.displacement_bound_m, view)) out.patches.push_back({x, y, level});
  }
  // CDLOD's LODSelect for a node that must be drawn at `level` or finer.
  void select(double x, double y, int level) {
    const double s = node_size(level), p = 0.5 * s;
    if (!in_frustum({x, y, x + s, y + s}, settings.displacement_bound_m, view)) return;
    if (level == 0 || nearest_distance_m({x, y, x + s, y + s}, view.eye_m) > out.levels[std::size_t(level - 1)].range_m) {
      for (int q = 0; q < 4; ++q) emit_patch(x + (q & 1) * p, y + (q >> 1) * p, level);
      return;
    }
    const double finer_range = out.levels[std::size_t(level - 1)].range_m;
    for (int q = 0; q < 4; ++q) {
      const double cx = x + (q & 1) * p, cy = y + (q >> 1) * p;
      if (nearest_distance_m({cx, cy, cx + p, cy + p}, view.eye_m) <= finer_range)
        select(cx, cy, level - 1);  // the child is a level-(L-1) node
      else
        emit_patch(cx, cy, level);  // this quadrant stays at level L
    }
  }
};

}  // namespace

QuadtreeSelection select_quadtree(const QuadtreeSettings& s, const CameraView& view) {
  if (!(s.finest_spacing_m > 0) || s.patch_quads < 2 || s.patch_quads % 2 != 0 || s.patch_quads > 256 ||
      !(s.screen_error_px > 0) || !(s.reach_m > 0) || !(s.displacement_bound_m >= 0))
    throw Error("QuadtreeSettings",
                "finest_spacing_m " + std::to_string(s.finest_spacing_m) + ", patch_quads " +
                    std::to_string(s.patch_quads) + ", screen_error_px " + std::to_string(s.screen_error_px) +
                    ", reach_m " + std::to_string(s.reach_m),
                "give a positive spacing, error and reach and an even patch_quads in [2, 256]");
  QuadtreeSelection out;
  out.patch_quads = s.patch_quads;
  // A power-of-two spacing makes every vertex position a dyadic number, exact in float, so a
  // vertex two patches share comes out bit-identical from both.
  const double spacing0 = std::exp2(std::round(std::log2(s.finest_spacing_m)));
  const double node0 = 2.0 * s.patch_quads * spacing0;
  // range_L = spacing_L * focal / error (a level-L quad spans `error` pixels where the level
  // ends), at least 4 node sizes: then a level's region (within range_L plus a node's diagonal,
  // 1.354 range_L) ends before the next level starts to morph (0.7 range_{L+1} = 1.4 range_L),
  // and no two neighbouring patches are more than one level apart (docs/rendering.md).
  const double range0 = std::max(spacing0 * view.focal_length_px / s.screen_error_px, 4.0 * node0);
  const int top = std::clamp(static_cast<int>(std::ceil(std::log2(std::max(s.reach_m / range0, 1.0)))), 0, 40);
  for (int level = 0; level <= top; ++level) {
    QuadtreeLevel l;
    l.vertex_spacing_m = spacing0 * std::exp2(level);
    l.patch_size_m = l.vertex_spacing_m * s.patch_quads;
    l.range_m = range0 * std::exp2(level);
    // Fully morphed at 0.95 range: the coarser neighbour's edge lies beyond range_L, and the
    // margin covers float rounding of the GPU's distance.
    l.morph_start_m = 0.7 * l.range_m;
    l.morph_end_m = 0.95 * l.range_m;
    out.levels.push_back(l);
  }
  Selector selector{s, view, out};
  const double top_size = selector.node_size(top);
  const Vector3& eye = view.eye_m;
  const long long i0 = static_cast<long long>(std::floor((eye[0] - s.reach_m) / top_size));
  const long long i1 = static_cast<long long>(std::floor((eye[0] + s.reach_m) / top_size));
  const long long j0 = static_cast<long long>(std::floor((eye[1] - s.reach_m) / top_size));
  const long long j1 = static_cast<long long>(std::floor((eye[1] + s.reach_m) / top_size));
  for (long long j = j0; j <= j1; ++j)
    for (long long i = i0; i <= i1; ++i) {
      const double x = double(i) * top_size, y = double(j) * top_size;
      if (nearest_distance_m({x, y, x + top_size, y + top_size}, eye) <= s.reach_m) selector.select(x, y, top);
    }
  return out;
}

std::array<float, 2> quadtree_vertex(const QuadtreeSelection& selection, const QuadtreePatch& patch, int gx, int gy,
                                     const Vector3& eye_m) {
  // Written as shaders/water_quadtree.vert.glsl computes it, operation for operation, in float.
  const QuadtreeLevel& level = selection.levels[std::size_t(patch.level)];
  const float spacing = float(level.vertex_spacing_m);
  const float ox = float(patch.origin_x_m), oy = float(patch.origin_y_m);
  const float px = ox + float(gx) * spacing, py = oy + float(gy) * spacing;
  const float dx = px - float(eye_m[0]), dy = py - float(eye_m[1]), dz = float(eye_m[2]);
  const float distance = std::sqrt(dx * dx + dy * dy + dz * dz);
  const float morph = std::clamp((distance - float(level.morph_start_m)) / float(level.morph_end_m - level.morph_start_m),
                                 0.f, 1.f);
  // Odd vertices slide onto their even neighbour: at morph = 1 the patch is the coarser lattice.
  const float fx = float(gx % 2), fy = float(gy % 2);
  return {ox + (float(gx) - fx * morph) * spacing, oy + (float(gy) - fy * morph) * spacing};
}

// ---- projected -------------------------------------------------------------------------------
double curvature_drop_m(double rho, double r) {
  const double rho2 = rho * rho;
  return rho2 / (r + std::sqrt(std::max(r * r - rho2, 0.0)));
}

SpherePoint project_to_sphere(const CameraView& view, double ndc_x, double ndc_y, double r) {
  // Ray direction from the eye through the screen point (rotation only: no large numbers).
  const auto far_point = transform(inverse(view.rotation_projection), {ndc_x, ndc_y, 1.0, 1.0});
  double d[3] = {far_point[0] / far_point[3], far_point[1] / far_point[3], far_point[2] / far_point[3]};
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (double& c : d) c /= length;
  const double h = std::max(view.eye_m[2], 1e-3);
  // |o + t d - c|^2 = R^2 with o - c = (0, 0, R + h): t^2 + 2 t d_z (R + h) + h (2R + h) = 0;
  // the near root, in the form without cancellation.
  const double b = d[2] * (r + h), c = h * (2.0 * r + h);
  const double discriminant = b * b - c;
  SpherePoint out;
  double t = 0;
  if (d[2] < 0.0 && discriminant >= 0.0) {
    t = c / (-b + std::sqrt(discriminant));
  } else {
    // Above the horizon: the tangent ray at the same bearing.
    const double dip = horizon_dip_rad(h, r);
    double horizontal = std::hypot(d[0], d[1]);
    if (horizontal <= 0) {
      d[0] = view.forward[0];
      d[1] = view.forward[1];
      horizontal = std::hypot(d[0], d[1]);
    }
    d[0] = std::cos(dip) * d[0] / horizontal;
    d[1] = std::cos(dip) * d[1] / horizontal;
    d[2] = -std::sin(dip);
    t = horizon_distance_m(h, r);
    out.on_horizon = true;
  }
  out.x_m = view.eye_m[0] + t * d[0];
  out.y_m = view.eye_m[1] + t * d[1];
  out.z_m = h + t * d[2];
  return out;
}

ProjectedGridLayout layout_projected_grid(const ProjectedGridSettings& s, const CameraView& view) {
  if (!(s.vertex_spacing_px > 0) || !(s.earth_radius_m > 0) || !(s.margin_ndc >= 0))
    throw Error("ProjectedGridSettings", "vertex_spacing_px " + std::to_string(s.vertex_spacing_px) +
                                             ", earth_radius_m " + std::to_string(s.earth_radius_m),
                "give a positive spacing and radius and a margin >= 0");
  ProjectedGridLayout layout;
  const double edge = 1.0 + s.margin_ndc;
  layout.ndc_x0 = -edge;
  layout.ndc_x1 = edge;
  layout.ndc_y0 = -edge;
  // The horizon is the circle of points at the tangent distance, dip below the horizontal. Its
  // highest point across the screen's width tops the grid (sampled every 0.25 degree of bearing).
  const double h = std::max(view.eye_m[2], 1e-3);
  const double dip = horizon_dip_rad(h, s.earth_radius_m), distance = horizon_distance_m(h, s.earth_radius_m);
  double top = -1e30;
  bool seen = false;
  for (int k = 0; k < 1440; ++k) {
    const double bearing = 2.0 * std::numbers::pi * k / 1440;
    const std::array<double, 4> point = {distance * std::cos(dip) * std::cos(bearing),
                                         distance * std::cos(dip) * std::sin(bearing), -distance * std::sin(dip), 1.0};
    const auto clip = transform(view.rotation_projection, point);
    if (clip[3] <= 0) continue;  // behind the eye
    const double x = clip[0] / clip[3], y = clip[1] / clip[3];
    if (std::abs(x) > edge) continue;
    seen = true;
    top = std::max(top, y);
  }
  if (!seen) {
    // No horizon across the screen: all sea (looking down) or all sky (looking up).
    const SpherePoint centre = project_to_sphere(view, 0.0, 0.0, s.earth_radius_m);
    top = centre.on_horizon ? -1e30 : edge;
  }
  layout.ndc_y1 = std::min(top + s.margin_ndc, edge);
  if (layout.ndc_y1 <= layout.ndc_y0) return layout;  // no sea on screen: no vertices
  layout.columns = static_cast<int>(std::ceil((layout.ndc_x1 - layout.ndc_x0) * 0.5 * view.width_px / s.vertex_spacing_px)) + 1;
  layout.rows = static_cast<int>(std::ceil((layout.ndc_y1 - layout.ndc_y0) * 0.5 * view.height_px / s.vertex_spacing_px)) + 1;
  return layout;
}

}  // namespace nearshore::playback
