#include "nearshore/playback/site_terrain.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace nearshore::playback {

namespace {

using Point = std::array<double, 2>;

// Bilinear between cell centres, clamped to the outer centres (GL_LINEAR with GL_CLAMP_TO_EDGE:
// what the water's shaders read from the same raster).
template <class T, class Value>
double cell_bilinear(const Raster<T>& field, const GridGeometry& g, double x_m, double y_m, Value value) {
  const double u = std::clamp(x_m / g.spacing_x_m() - 0.5, 0.0, double(field.columns() - 1));
  const double v = std::clamp(y_m / g.spacing_y_m() - 0.5, 0.0, double(field.rows() - 1));
  const int i0 = std::min(int(u), field.columns() - 1), j0 = std::min(int(v), field.rows() - 1);
  const int i1 = std::min(i0 + 1, field.columns() - 1), j1 = std::min(j0 + 1, field.rows() - 1);
  const double a = u - i0, b = v - j0;
  const double south = (1 - a) * value(field(i0, j0)) + a * value(field(i1, j0));
  const double north = (1 - a) * value(field(i0, j1)) + a * value(field(i1, j1));
  return (1 - b) * south + b * north;
}

double smoothstep(double edge0, double edge1, double x) {
  if (edge1 <= edge0) return x < edge0 ? 0.0 : 1.0;
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// Vertex positions along one axis of the lattice: the site's edge, the cell centres (every
// `stride`-th, each interval cut into `subdivisions`), the far edge; then the skirt beyond both
// edges in steps growing geometrically from the lattice's own to `skirt_m`, no longer than
// `fine_step_m` while within `fine_before_m` (before 0) or `fine_after_m` (beyond the far edge):
// the surroundings' cells, where the skirt follows their ground.
std::vector<double> axis_positions(int cells, double spacing_m, int stride, int subdivisions, double skirt_m,
                                   double fine_before_m = 0.0, double fine_after_m = 0.0, double fine_step_m = 0.0) {
  const double length = cells * spacing_m;
  std::vector<double> inner{0.0};
  std::vector<int> centres;
  for (int i = 0; i < cells; i += stride) centres.push_back(i);
  if (centres.back() != cells - 1) centres.push_back(cells - 1);
  for (std::size_t k = 0; k < centres.size(); ++k) {
    const double c = (centres[k] + 0.5) * spacing_m;
    if (k > 0) {
      const double previous = (centres[k - 1] + 0.5) * spacing_m;
      for (int s = 1; s < subdivisions; ++s) inner.push_back(previous + (c - previous) * s / subdivisions);
    }
    inner.push_back(c);
  }
  inner.push_back(length);
  // The skirt: 24 steps from one lattice step to skirt_m, each the last times a constant ratio.
  const int steps = 24;
  const double first = spacing_m * stride / subdivisions;
  double ratio = 1.3;  // solve first (ratio^steps - 1) / (ratio - 1) = skirt_m by bisection
  double lo = 1.0001, hi = 3.0;
  for (int it = 0; it < 60; ++it) {
    ratio = 0.5 * (lo + hi);
    (first * (std::pow(ratio, steps) - 1) / (ratio - 1) < skirt_m ? lo : hi) = ratio;
  }
  // Outwards from an edge: without fine steps the 24 geometric ones; with them, each step the
  // last times the ratio but at most fine_step_m within the fine reach, until skirt_m.
  const auto outward = [&](double fine_m) {
    std::vector<double> out;
    double step = first, reach = 0;
    if (!(fine_m > 0 && fine_step_m > 0)) {
      for (int s = 0; s < steps; ++s) out.push_back(reach += step), step *= ratio;
      return out;
    }
    while (reach < skirt_m * (1 - 1e-9) && out.size() < 4096) {
      if (reach < fine_m) step = std::min(step, fine_step_m);
      out.push_back(reach = std::min(reach + step, skirt_m));
      step *= ratio;
    }
    return out;
  };
  const std::vector<double> before = outward(fine_before_m), after = outward(fine_after_m);
  std::vector<double> positions;
  for (auto it = before.rbegin(); it != before.rend(); ++it) positions.push_back(-*it);
  positions.insert(positions.end(), inner.begin(), inner.end());
  for (double d : after) positions.push_back(length + d);
  return positions;
}

// The point of a W x H site's edge at arc length s counter-clockwise from the south-west corner,
// and the inverse for a point on the edge.
Point perimeter_point(double width_m, double height_m, double s) {
  const double perimeter = 2 * (width_m + height_m);
  s = std::fmod(std::fmod(s, perimeter) + perimeter, perimeter);
  if (s < width_m) return {s, 0.0};
  if ((s -= width_m) < height_m) return {width_m, s};
  if ((s -= height_m) < width_m) return {width_m - s, height_m};
  return {0.0, height_m - (s - width_m)};
}
double perimeter_position(double width_m, double height_m, const Point& q) {
  if (q[1] <= 0) return q[0];
  if (q[0] >= width_m) return width_m + q[1];
  if (q[1] >= height_m) return width_m + height_m + (width_m - q[0]);
  return 2 * width_m + height_m + (height_m - q[1]);
}

// Beyond the grid (shaders/surface.glsl skirt_ground_m is the twin of the elevation): the edge's
// ground averaged along the edge (round its corners) over +-`beyond` of the nearest edge point, at
// most a quarter of the site's shorter side (the further out, the smoother the coast it
// continues); land (that average above still water) stays at that height out to the skirt's end
// (the land goes on to the horizon: the sea is not drawn over it, surface.glsl); water deepens to
// the open sea's depth over the site's extent (as still_water_depth_at in surface.glsl); the two
// blended by the average from 1 m under to 1 m over still water, so a coast crossing the edge
// continues without a step. inland_m: the edge's distance inland plus, on land, the way beyond.
struct SkirtProfile {
  double elevation_m = 0.0, inland_m = 0.0;
};
double inland_of(const HarbourGrid& harbour, double x, double y);
SkirtProfile skirt_profile(const HarbourGrid& harbour, const SurroundingGround& surroundings, double open_sea_depth_m,
                           double x, double y, bool with_inland) {
  const double width_m = harbour.geometry.width_m(), height_m = harbour.geometry.height_m();
  const Point q{std::clamp(x, 0.0, width_m), std::clamp(y, 0.0, height_m)};
  const double beyond = std::hypot(x - q[0], y - q[1]);
  const double s0 = perimeter_position(width_m, height_m, q), reach = std::min(beyond, 0.25 * std::min(width_m, height_m));
  double elevation = 0, inland_sum = 0;
  const int taps = 9;
  for (int t = 0; t < taps; ++t) {
    const Point e = perimeter_point(width_m, height_m, s0 + reach * (2.0 * t / (taps - 1) - 1.0));
    elevation += ground_elevation_m(harbour, e[0], e[1]) / taps;
    if (with_inland) inland_sum += inland_of(harbour, e[0], e[1]) / taps;
  }
  const double drop = elevation + open_sea_depth_m;
  const double as_water = elevation - drop * smoothstep(0.0, std::max(width_m, height_m), beyond);
  const double edge_rule = as_water + (elevation - as_water) * smoothstep(-1.0, 1.0, elevation);
  // The surroundings where they have data (SurroundingGround): w times the elevation and w read
  // bilinearly (GL_LINEAR, clamped to the outer cells, whose w is 0), turned to from the edge's rule.
  double ground = edge_rule;
  if (!surroundings.empty()) {
    const auto same = [](float v) { return double(v); };
    const double w = cell_bilinear(surroundings.weight, surroundings.cells, x - surroundings.cells.origin_x_m,
                                   y - surroundings.cells.origin_y_m, same);
    const double t = w * smoothstep(0.0, surroundings.edge_blend_m, beyond);
    if (t > 0.0) {
      const double weighted = cell_bilinear(surroundings.weighted_elevation_m, surroundings.cells,
                                            x - surroundings.cells.origin_x_m, y - surroundings.cells.origin_y_m, same);
      ground = edge_rule + (weighted / w - edge_rule) * t;
    }
  }
  return {ground, inland_sum + smoothstep(-1.0, 1.0, ground) * beyond};
}

// Distance inland of the still-water line: minus the coast distance channel, bilinear; where
// that is missing or infinite (a grid whose channel says "no coast"), far inland on ground
// above still water and far offshore below it.
double inland_of(const HarbourGrid& harbour, double x, double y) {
  const double far = ground_elevation_m(harbour, x, y) > 0 ? 1e4 : -1e4;
  if (harbour.coast_distance_m.columns() != harbour.geometry.columns ||
      harbour.coast_distance_m.rows() != harbour.geometry.rows)
    return far;
  const double d = cell_bilinear(harbour.coast_distance_m, harbour.geometry, x, y, [](float c) {
    return std::isfinite(c) ? std::clamp(double(c), -1e4, 1e4) : std::numeric_limits<double>::quiet_NaN();
  });
  return std::isfinite(d) ? -d : far;
}

struct Builder {
  const HarbourGrid& harbour;
  const SurroundingGround& surroundings;
  const TerrainOptions& options;
  double width_m, height_m, skirt_m;
  bool cell_structures;  // structures known only by porous cells
  TerrainMesh mesh;

  std::uint32_t vertex(double x, double y, double z, double inland, TerrainMaterial material) {
    mesh.vertices.insert(mesh.vertices.end(),
                         {float(x), float(y), float(z), float(inland), float(static_cast<int>(material))});
    return std::uint32_t(mesh.vertices.size() / TerrainMesh::kFloatsPerVertex - 1);
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) { mesh.indices.insert(mesh.indices.end(), {a, b, c}); }
  void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) { triangle(a, b, c), triangle(a, c, d); }

  double ground(double x, double y) const { return ground_elevation_m(harbour, x, y); }
  // Distance inland of the still-water line: minus the coast distance channel, bilinear; where
  // that is missing or infinite (a grid whose channel says "no coast"), far inland on ground
  // above still water and far offshore below it.
  double inland(double x, double y) const { return inland_of(harbour, x, y); }
  double structure_indicator(double x, double y) const {
    return cell_bilinear(harbour.porosity, harbour.geometry, x, y, [](float n) { return n < 0.99f ? 1.0 : 0.0; });
  }

  // Beyond the grid: the skirt's rule (skirt_profile below).
  void skirt_point(double x, double y, double& z, double& land_inland) const {
    const SkirtProfile profile = skirt_profile(harbour, surroundings, options.open_sea_depth_m, x, y, true);
    z = profile.elevation_m;
    land_inland = profile.inland_m;
  }

  void ground_lattice() {
    const GridGeometry& g = harbour.geometry;
    const long long cells = (long long)g.columns * g.rows;
    const double budget = double(options.max_lattice_vertices) * options.max_lattice_vertices;
    int stride = 1, subdivisions = 1;
    if (cells > budget)
      stride = int(std::ceil(std::sqrt(double(cells) / budget)));
    else
      subdivisions = std::clamp(int(std::sqrt(budget / double(cells))), 1, 2);
    // Within the surroundings' box the skirt's steps are at most their cells.
    double west = 0, east = 0, south = 0, north = 0, fine_step = 0;
    if (!surroundings.empty()) {
      const GridGeometry& s = surroundings.cells;
      west = -s.origin_x_m, east = s.origin_x_m + s.width_m() - width_m;
      south = -s.origin_y_m, north = s.origin_y_m + s.height_m() - height_m;
      fine_step = s.smaller_spacing_m();
    }
    const std::vector<double> xs =
        axis_positions(g.columns, g.spacing_x_m(), stride, subdivisions, skirt_m, west, east, fine_step);
    const std::vector<double> ys =
        axis_positions(g.rows, g.spacing_y_m(), stride, subdivisions, skirt_m, south, north, fine_step);
    const int nx = int(xs.size()), ny = int(ys.size());
    std::vector<double> z(std::size_t(nx) * ny);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double x = xs[std::size_t(i)], y = ys[std::size_t(j)];
        double elevation = 0, land_inland = 0;
        TerrainMaterial material = TerrainMaterial::ground;
        if (x >= 0 && x <= width_m && y >= 0 && y <= height_m) {
          elevation = ground(x, y);
          land_inland = inland(x, y);
          if (cell_structures) {  // the porous cells' smooth half-level outline raised to the crest
            const double m = structure_indicator(x, y);
            const double raised = std::max(elevation, options.cell_structure_crest_m);
            elevation += (raised - elevation) * smoothstep(0.3, 0.7, m);
            if (m > 0.5) material = TerrainMaterial::rubble;
          }
        } else {
          skirt_point(x, y, elevation, land_inland);
        }
        z[std::size_t(j) * nx + i] = elevation;
        vertex(x, y, elevation, land_inland, material);
      }
    mesh.ground_vertex_count = std::size_t(nx) * ny;
    // Each quad cut along the diagonal whose ends differ less: the split follows the ground's
    // ridges and valleys rather than crossing them.
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i) {
        const std::uint32_t a = std::uint32_t(j * nx + i), b = a + 1, c = a + std::uint32_t(nx), d = c + 1;
        if (std::abs(z[a] - z[d]) <= std::abs(z[b] - z[c]))
          triangle(a, b, d), triangle(a, d, c);
        else
          triangle(a, b, c), triangle(b, d, c);
      }
  }

  // A polyline's or ring's vertices offset sideways by the miter of their two edges (unit normal
  // over the cosine of the half angle, at most 3 times the offset at sharp turns).
  static std::vector<Point> miters(const std::vector<Point>& p, bool closed) {
    const std::size_t n = p.size();
    std::vector<Point> out(n);
    auto normal = [&](std::size_t a, std::size_t b) {
      const double dx = p[b][0] - p[a][0], dy = p[b][1] - p[a][1], l = std::hypot(dx, dy);
      return Point{-dy / l, dx / l};  // left of a -> b
    };
    for (std::size_t k = 0; k < n; ++k) {
      const bool has_previous = closed || k > 0, has_next = closed || k + 1 < n;
      const Point before = has_previous ? normal((k + n - 1) % n, k) : normal(k, k + 1);
      const Point after = has_next ? normal(k, (k + 1) % n) : before;
      Point m{before[0] + after[0], before[1] + after[1]};
      const double l = std::hypot(m[0], m[1]);
      if (l < 1e-9) m = after; else m = {m[0] / l, m[1] / l};
      const double cosine = std::max(m[0] * after[0] + m[1] * after[1], 1.0 / 3.0);
      out[k] = {m[0] / cosine, m[1] / cosine};
    }
    return out;
  }

  std::vector<Point> site_points(const StructureLine& line) const {
    std::vector<Point> points;
    for (const auto& v : line) {
      const Point p{v[0] - harbour.geometry.origin_x_m, v[1] - harbour.geometry.origin_y_m};
      if (points.empty() || std::hypot(p[0] - points.back()[0], p[1] - points.back()[1]) > 1e-3) points.push_back(p);
    }
    return points;
  }

  // The toe's elevation under a crest point: the ground there, 0.3 m down so the faces meet it.
  double toe_m(const Point& p) const {
    return ground(std::clamp(p[0], 0.0, width_m), std::clamp(p[1], 0.0, height_m)) - 0.3;
  }

  // A centre line `crest_width_m` wide: the crest, two faces down to the bed (sloped at
  // side_slope, or vertical), and a head at each end sloped the same way.
  void line_structure(const CoastalStructure& s, const std::vector<Point>& p, TerrainMaterial material) {
    const std::size_t n = p.size();
    const std::vector<Point> m = miters(p, false);
    const double half = 0.5 * s.crest_width_m, crest = s.crest_elevation_m;
    std::vector<std::uint32_t> crest_left(n), crest_right(n), toe_left(n), toe_right(n);
    for (std::size_t k = 0; k < n; ++k) {
      const double toe = std::min(toe_m(p[k]), crest - 0.5), run = s.side_slope * (crest - toe);
      Point along{0, 0};  // the heads' toe reaches beyond the ends by the same run
      if (k == 0 || k + 1 == n) {
        const Point& a = p[k == 0 ? 0 : n - 2];
        const Point& b = p[k == 0 ? 1 : n - 1];
        const double l = std::hypot(b[0] - a[0], b[1] - a[1]), sign = k == 0 ? -1.0 : 1.0;
        along = {sign * run * (b[0] - a[0]) / l, sign * run * (b[1] - a[1]) / l};
      }
      const double inner = half, outer = half + run;
      crest_left[k] = vertex(p[k][0] + m[k][0] * inner, p[k][1] + m[k][1] * inner, crest, 0, material);
      crest_right[k] = vertex(p[k][0] - m[k][0] * inner, p[k][1] - m[k][1] * inner, crest, 0, material);
      toe_left[k] = vertex(p[k][0] + m[k][0] * outer + along[0], p[k][1] + m[k][1] * outer + along[1], toe, 0, material);
      toe_right[k] = vertex(p[k][0] - m[k][0] * outer + along[0], p[k][1] - m[k][1] * outer + along[1], toe, 0, material);
    }
    for (std::size_t k = 0; k + 1 < n; ++k) {
      quad(crest_left[k], crest_right[k], crest_right[k + 1], crest_left[k + 1]);
      quad(toe_left[k], crest_left[k], crest_left[k + 1], toe_left[k + 1]);
      quad(crest_right[k], toe_right[k], toe_right[k + 1], crest_right[k + 1]);
    }
    quad(crest_left[0], toe_left[0], toe_right[0], crest_right[0]);
    quad(crest_left[n - 1], crest_right[n - 1], toe_right[n - 1], toe_left[n - 1]);
  }

  // Ear clipping of a simple counter-clockwise ring (O(n^2), chart outlines are short); a ring
  // it cannot finish (self-crossing) ends as a fan of what is left.
  static std::vector<std::array<std::size_t, 3>> triangulate(const std::vector<Point>& ring) {
    std::vector<std::size_t> left(ring.size());
    for (std::size_t k = 0; k < ring.size(); ++k) left[k] = k;
    std::vector<std::array<std::size_t, 3>> triangles;
    auto cross = [&](std::size_t a, std::size_t b, std::size_t c) {
      return (ring[b][0] - ring[a][0]) * (ring[c][1] - ring[a][1]) - (ring[b][1] - ring[a][1]) * (ring[c][0] - ring[a][0]);
    };
    while (left.size() > 3) {
      bool clipped = false;
      for (std::size_t k = 0; k < left.size() && !clipped; ++k) {
        const std::size_t a = left[(k + left.size() - 1) % left.size()], b = left[k], c = left[(k + 1) % left.size()];
        if (cross(a, b, c) <= 0) continue;  // reflex
        bool empty = true;
        for (std::size_t q : left)
          if (q != a && q != b && q != c && cross(a, b, q) >= 0 && cross(b, c, q) >= 0 && cross(c, a, q) >= 0) {
            empty = false;
            break;
          }
        if (!empty) continue;
        triangles.push_back({a, b, c});
        left.erase(left.begin() + std::ptrdiff_t(k));
        clipped = true;
      }
      if (!clipped) break;
    }
    for (std::size_t k = 1; k + 1 < left.size(); ++k) triangles.push_back({left[0], left[k], left[k + 1]});
    return triangles;
  }

  // A polygon's outer ring: its top at the crest, walls down to the bed (sloped outwards at
  // side_slope, or vertical). Holes (inner rings) are not cut out of the top.
  void polygon_structure(const CoastalStructure& s, std::vector<Point> ring, TerrainMaterial material) {
    if (ring.size() > 3 && std::hypot(ring.front()[0] - ring.back()[0], ring.front()[1] - ring.back()[1]) < 1e-3)
      ring.pop_back();
    if (ring.size() < 3) return;
    double area = 0;
    for (std::size_t k = 0; k < ring.size(); ++k) {
      const Point& a = ring[k];
      const Point& b = ring[(k + 1) % ring.size()];
      area += a[0] * b[1] - b[0] * a[1];
    }
    if (area < 0) std::reverse(ring.begin(), ring.end());
    const std::size_t n = ring.size();
    const std::vector<Point> m = miters(ring, true);  // left of a counter-clockwise ring: inwards
    const double crest = s.crest_elevation_m;
    std::vector<std::uint32_t> top(n), wall_top(n), wall_toe(n);
    for (std::size_t k = 0; k < n; ++k) {
      const double toe = std::min(toe_m(ring[k]), crest - 0.5), run = s.side_slope * (crest - toe);
      top[k] = vertex(ring[k][0], ring[k][1], crest, 0, material);
      wall_top[k] = vertex(ring[k][0], ring[k][1], crest, 0, material);
      wall_toe[k] = vertex(ring[k][0] - m[k][0] * run, ring[k][1] - m[k][1] * run, toe, 0, material);
    }
    for (const auto& t : triangulate(ring)) triangle(top[t[0]], top[t[1]], top[t[2]]);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t l = (k + 1) % n;
      quad(wall_toe[k], wall_toe[l], wall_top[l], wall_top[k]);
    }
  }

  void structures() {
    for (const CoastalStructure& s : harbour.structures) {
      const TerrainMaterial material = s.side_slope > 0 ? TerrainMaterial::rubble : TerrainMaterial::concrete;
      for (const StructureLine& line : s.lines) {
        const std::vector<Point> p = site_points(line);
        if (p.size() >= 2 && s.crest_width_m > 0) line_structure(s, p, material);
      }
      for (const auto& rings : s.polygons)
        if (!rings.empty()) polygon_structure(s, site_points(rings.front()), material);
    }
  }

  // Distance from q to the segment a-b.
  static double segment_distance(const Point& q, const Point& a, const Point& b) {
    const double dx = b[0] - a[0], dy = b[1] - a[1], l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? std::clamp(((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / l2, 0.0, 1.0) : 0.0;
    return std::hypot(q[0] - a[0] - t * dx, q[1] - a[1] - t * dy);
  }

  // The structures' outline at still water on texels of a quarter cell (at least 0.5 m, at most
  // 4096 a side); from the porous cells, at the cells, when the grid carries no geometry.
  void dry_mask() {
    const GridGeometry& g = harbour.geometry;
    if (cell_structures) {
      mesh.structure_mask = Raster<float>(g.columns, g.rows, 0.f);
      for (int j = 0; j < g.rows; ++j)
        for (int i = 0; i < g.columns; ++i) mesh.structure_mask(i, j) = harbour.porosity(i, j) < 0.99f ? 1.f : 0.f;
      return;
    }
    const double texel = std::max(0.25 * g.smaller_spacing_m(), 0.5);
    const int columns = std::clamp(int(std::ceil(width_m / texel)), 1, 4096);
    const int rows = std::clamp(int(std::ceil(height_m / texel)), 1, 4096);
    const double tx = width_m / columns, ty = height_m / rows;
    mesh.structure_mask = Raster<float>(columns, rows, 0.f);
    auto for_texels_near = [&](double x0, double y0, double x1, double y1, auto inside) {
      const int i0 = std::max(int(std::floor(x0 / tx)), 0), i1 = std::min(int(std::ceil(x1 / tx)), columns - 1);
      const int j0 = std::max(int(std::floor(y0 / ty)), 0), j1 = std::min(int(std::ceil(y1 / ty)), rows - 1);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
          if (inside(Point{(i + 0.5) * tx, (j + 0.5) * ty})) mesh.structure_mask(i, j) = 1.f;
    };
    for (const CoastalStructure& s : harbour.structures) {
      if (s.crest_elevation_m <= 0) continue;  // awash: the water covers it
      const double reach = s.side_slope * s.crest_elevation_m;  // the faces' run above still water
      for (const StructureLine& line : s.lines) {
        const std::vector<Point> p = site_points(line);
        const double r = 0.5 * s.crest_width_m + reach;
        for (std::size_t k = 0; k + 1 < p.size(); ++k)
          for_texels_near(std::min(p[k][0], p[k + 1][0]) - r, std::min(p[k][1], p[k + 1][1]) - r,
                          std::max(p[k][0], p[k + 1][0]) + r, std::max(p[k][1], p[k + 1][1]) + r,
                          [&](const Point& q) { return segment_distance(q, p[k], p[k + 1]) <= r; });
      }
      for (const auto& rings : s.polygons) {
        if (rings.empty()) continue;
        const std::vector<Point> ring = site_points(rings.front());
        if (ring.size() < 3) continue;
        double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
        for (const Point& q : ring) x0 = std::min(x0, q[0]), y0 = std::min(y0, q[1]), x1 = std::max(x1, q[0]), y1 = std::max(y1, q[1]);
        for_texels_near(x0 - reach, y0 - reach, x1 + reach, y1 + reach, [&](const Point& q) {
          bool inside = false;
          double nearest = 1e300;
          for (std::size_t k = 0, l = ring.size() - 1; k < ring.size(); l = k++) {
            const Point &a = ring[k], &b = ring[l];
            if ((a[1] > q[1]) != (b[1] > q[1]) && q[0] < (b[0] - a[0]) * (q[1] - a[1]) / (b[1] - a[1]) + a[0])
              inside = !inside;
            nearest = std::min(nearest, segment_distance(q, a, b));
          }
          return inside || nearest <= reach;
        });
      }
    }
  }
};

}  // namespace

double ground_elevation_m(const HarbourGrid& harbour, double x_m, double y_m) {
  return -cell_bilinear(harbour.still_water_depth_m, harbour.geometry, x_m, y_m, [](float d) { return double(d); });
}

SurroundingGround surrounding_ground(const HarbourGrid& harbour) {
  const Surroundings& outer = harbour.surroundings;
  SurroundingGround ground;
  if (outer.empty()) return ground;
  ground.cells = outer.geometry;
  ground.cells.origin_x_m -= harbour.geometry.origin_x_m;  // into the site frame
  ground.cells.origin_y_m -= harbour.geometry.origin_y_m;
  ground.edge_blend_m = 2.0 * std::max(outer.geometry.spacing_x_m(), outer.geometry.spacing_y_m());
  const int columns = outer.geometry.columns, rows = outer.geometry.rows;
  // Cells (8-connected steps) to the nearest cell without data, the box's outside counting as
  // such, up to kSurroundingsFadeCells + 1: a few sweeps of d = min(d, neighbour + 1).
  const int far = kSurroundingsFadeCells + 1;
  Raster<int> steps(columns, rows, far);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i)
      if (!std::isfinite(outer.still_water_depth_m(i, j))) steps(i, j) = 0;
  for (int sweep = 0; sweep < far; ++sweep) {
    Raster<int> next = steps;
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < columns; ++i)
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int ii = i + di, jj = j + dj;
            const int neighbour = ii < 0 || jj < 0 || ii >= columns || jj >= rows ? 0 : steps(ii, jj);
            next(i, j) = std::min(next(i, j), neighbour + 1);
          }
    steps = std::move(next);
  }
  ground.weight = Raster<float>(columns, rows, 0.f);
  ground.weighted_elevation_m = Raster<float>(columns, rows, 0.f);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      if (steps(i, j) == 0) continue;  // no data
      const float w = float(smoothstep(1.0, 1.0 + kSurroundingsFadeCells, steps(i, j)));
      ground.weight(i, j) = w;
      ground.weighted_elevation_m(i, j) = -w * outer.still_water_depth_m(i, j);
    }
  return ground;
}

double skirt_ground_m(const HarbourGrid& harbour, const SurroundingGround& surroundings, double open_sea_depth_m,
                      double x_m, double y_m) {
  return skirt_profile(harbour, surroundings, open_sea_depth_m, x_m, y_m, false).elevation_m;
}

TerrainMesh build_site_terrain(const HarbourGrid& harbour, const TerrainOptions& options) {
  const GridGeometry& g = harbour.geometry;
  const double width = g.width_m(), height = g.height_m();
  const double skirt = options.skirt_width_m > 0 ? options.skirt_width_m : std::max(kDefaultSkirtWidthM, std::max(width, height));
  bool geometry = false;
  for (const CoastalStructure& s : harbour.structures) geometry = geometry || !s.lines.empty() || !s.polygons.empty();
  const SurroundingGround surroundings = surrounding_ground(harbour);
  Builder builder{harbour, surroundings, options, width, height, skirt, !geometry, {}};
  builder.mesh.skirt_width_m = skirt;
  builder.mesh.surroundings = surroundings;
  builder.ground_lattice();
  builder.structures();
  builder.dry_mask();
  return std::move(builder.mesh);
}

}  // namespace nearshore::playback
