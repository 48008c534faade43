#include "nearshore/ships/harbour_obstacles.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace nearshore::ships {
namespace {

// The Boussinesq solver's wall threshold (boussinesq_solver.hpp kWallPorosity): below it a cell is
// a solid vertical wall there too. Repeated here because the ships link no part of the bake side.
constexpr double kWallPorosity = 0.05;

}  // namespace

std::string HarbourStructure::describe() const {
  if (id == 0) return "the land";
  return fmt::format("structure {} ({}, porosity {:.2f}, {} cells about ({:.1f}, {:.1f}) m)", id,
                     wall ? "a quay wall" : "a rubble-mound breakwater", porosity, cells, centre_m.x(), centre_m.y());
}

HarbourObstacles::HarbourObstacles(const HarbourGrid& grid, HarbourObstacleOptions options) : options_(options) {
  columns_ = grid.still_water_depth_m.columns();
  rows_ = grid.still_water_depth_m.rows();
  dx_ = grid.geometry.spacing_x_m();
  dy_ = grid.geometry.spacing_y_m();
  options_.band_cells = std::clamp(options_.band_cells, 2, 64);
  options_.smoothing_passes = std::clamp(options_.smoothing_passes, 0, options_.band_cells);
  const std::size_t n = static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_);
  const bool has_land = grid.land.columns() == columns_ && grid.land.rows() == rows_;
  const bool has_porosity = grid.porosity.columns() == columns_ && grid.porosity.rows() == rows_;
  auto index = [&](int i, int j) { return static_cast<std::size_t>(j) * columns_ + i; };
  auto is_land = [&](int i, int j) { return has_land && grid.land(i, j) != kWaterCell; };
  auto is_structure = [&](int i, int j) { return !is_land(i, j) && has_porosity && grid.porosity(i, j) < 1.0f; };

  // 1. Labels: land 0, structures 1, 2, ... by 8-connected flood fill.
  label_.assign(n, -1);
  top_.assign(n, 0.0f);
  std::vector<std::pair<int, int>> stack;
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      if (is_land(i, j)) {
        label_[index(i, j)] = 0;
        top_[index(i, j)] = std::max(-grid.still_water_depth_m(i, j), 0.0f);
        any_ = true;
      }
    }
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      if (!is_structure(i, j) || label_[index(i, j)] >= 0) continue;
      any_ = true;
      HarbourStructure s;
      s.id = static_cast<int>(structures_.size()) + 1;
      s.porosity = 1.0;
      stack.assign(1, {i, j});
      label_[index(i, j)] = s.id;
      while (!stack.empty()) {
        const auto [ci, cj] = stack.back();
        stack.pop_back();
        ++s.cells;
        s.porosity = std::min(s.porosity, static_cast<double>(grid.porosity(ci, cj)));
        s.centre_m += Eigen::Vector2d((ci + 0.5) * dx_, (cj + 0.5) * dy_);
        top_[index(ci, cj)] = static_cast<float>(std::max(options_.structure_crest_m, -static_cast<double>(grid.still_water_depth_m(ci, cj))));
        // 8-connected: a breakwater rasterised along a diagonal touches itself at corners.
        const int neighbours[8][2] = {{ci + 1, cj},     {ci - 1, cj},     {ci, cj + 1},     {ci, cj - 1},
                                      {ci + 1, cj + 1}, {ci - 1, cj - 1}, {ci - 1, cj + 1}, {ci + 1, cj - 1}};
        for (const auto& q : neighbours)
          if (q[0] >= 0 && q[1] >= 0 && q[0] < columns_ && q[1] < rows_ && is_structure(q[0], q[1]) &&
              label_[index(q[0], q[1])] < 0) {
            label_[index(q[0], q[1])] = s.id;
            stack.push_back({q[0], q[1]});
          }
      }
      s.centre_m /= s.cells;
      s.wall = s.porosity < kWallPorosity;
      structures_.push_back(s);
    }
  if (!any_) return;

  // 2. Distance from each cell centre to the nearest centre of the other kind, within the band:
  //    every cell with a neighbour of the other kind stamps its window.
  const int band = options_.band_cells;
  const double far_m = band * std::max(dx_, dy_);
  std::vector<float> distance(n, static_cast<float>(far_m));
  owner_.assign(n, -1);
  auto solid = [&](int i, int j) { return label_[index(i, j)] >= 0; };
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      const bool here = solid(i, j);
      if (here) owner_[index(i, j)] = static_cast<std::int32_t>(index(i, j));
      bool boundary = false;
      for (int dj = -1; dj <= 1 && !boundary; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int qi = i + di, qj = j + dj;
          if (qi >= 0 && qj >= 0 && qi < columns_ && qj < rows_ && solid(qi, qj) != here) {
            boundary = true;
            break;
          }
        }
      if (!boundary) continue;
      for (int qj = std::max(j - band, 0); qj <= std::min(j + band, rows_ - 1); ++qj)
        for (int qi = std::max(i - band, 0); qi <= std::min(i + band, columns_ - 1); ++qi) {
          if (solid(qi, qj) == here) continue;
          const float d = static_cast<float>(std::hypot((qi - i) * dx_, (qj - j) * dy_));
          const std::size_t q = index(qi, qj);
          if (d < distance[q]) {
            distance[q] = d;
            if (here) owner_[q] = static_cast<std::int32_t>(index(i, j));  // water cell q: its nearest solid
          }
        }
    }
  // phi: the face lies half a cell from a centre whose neighbour is of the other kind.
  const double half = 0.5 * std::min(dx_, dy_);
  phi_.resize(n);
  for (std::size_t c = 0; c < n; ++c) {
    const double d = distance[c] >= far_m ? far_m : distance[c] - half;
    phi_[c] = static_cast<float>(label_[c] >= 0 ? -d : d);
  }
  // 3. Binomial passes in x and y (edges clamped): two over phi, six over the +-1 indicator whose
  //    gradient gives the normal.
  std::vector<float> tmp(n);
  auto smooth = [&](std::vector<float>& field, int passes) {
    for (int pass = 0; pass < passes; ++pass) {
      for (int j = 0; j < rows_; ++j)
        for (int i = 0; i < columns_; ++i)
          tmp[index(i, j)] = 0.25f * (field[index(std::max(i - 1, 0), j)] + 2.0f * field[index(i, j)] +
                                      field[index(std::min(i + 1, columns_ - 1), j)]);
      for (int j = 0; j < rows_; ++j)
        for (int i = 0; i < columns_; ++i)
          field[index(i, j)] = 0.25f * (tmp[index(i, std::max(j - 1, 0))] + 2.0f * tmp[index(i, j)] +
                                        tmp[index(i, std::min(j + 1, rows_ - 1))]);
    }
  };
  smooth(phi_, 2);
  indicator_.resize(n);
  for (std::size_t c = 0; c < n; ++c) indicator_[c] = label_[c] >= 0 ? -1.0f : 1.0f;
  smooth(indicator_, options_.smoothing_passes);
  fit_normals(distance);
}

void HarbourObstacles::fit_normals(const std::vector<float>& distance) {
  // 4. The fitted normal near the faces (step 3 of the header). The boundary edges: between cell
  //    (i, j) and its east or north neighbour where one is solid and the other water, at the
  //    edge's midpoint, with the outward (solid -> water) unit normal of the edge; bucketed by
  //    (i, j) so that a window of cells finds its edges.
  const std::size_t n = static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_);
  auto index = [&](int i, int j) { return static_cast<std::size_t>(j) * columns_ + i; };
  auto solid = [&](int i, int j) { return label_[index(i, j)] >= 0; };
  struct Edge {
    Eigen::Vector2d mid_m;
    Eigen::Vector2d outward;
  };
  std::vector<Edge> edges;
  std::vector<std::uint32_t> first(n + 1, 0);
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      first[index(i, j)] = static_cast<std::uint32_t>(edges.size());
      const bool here = solid(i, j);
      const double sign = here ? 1.0 : -1.0;
      if (i + 1 < columns_ && solid(i + 1, j) != here)
        edges.push_back({{(i + 1) * dx_, (j + 0.5) * dy_}, {sign, 0.0}});
      if (j + 1 < rows_ && solid(i, j + 1) != here)
        edges.push_back({{(i + 0.5) * dx_, (j + 1) * dy_}, {0.0, sign}});
    }
  first[n] = static_cast<std::uint32_t>(edges.size());
  fitted_normal_.assign(n, Eigen::Vector2f::Zero());
  const double cell_m = std::max(dx_, dy_);
  const double near_m = options_.normal_fit_cells * cell_m;
  const double radius_m = std::max(options_.normal_fit_radius_cells, 1.0) * std::sqrt(dx_ * dy_);
  std::vector<std::pair<Eigen::Vector2d, double>> picked;  // one fit's midpoints and weights
  // Every edge within `reach_m` of `centre`, by the cells whose edges can lie there.
  auto for_edges_near = [&](const Eigen::Vector2d& centre, double reach_m, auto&& visit) {
    const int i0 = std::max(static_cast<int>(std::floor((centre.x() - reach_m) / dx_)) - 1, 0);
    const int i1 = std::min(static_cast<int>(std::floor((centre.x() + reach_m) / dx_)) + 1, columns_ - 1);
    const int j0 = std::max(static_cast<int>(std::floor((centre.y() - reach_m) / dy_)) - 1, 0);
    const int j1 = std::min(static_cast<int>(std::floor((centre.y() + reach_m) / dy_)) + 1, rows_ - 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        for (std::uint32_t e = first[index(i, j)]; e < first[index(i, j) + 1]; ++e) visit(edges[e]);
  };
  for (int j = 0; j < rows_; ++j)
    for (int i = 0; i < columns_; ++i) {
      const std::size_t c = index(i, j);
      if (distance[c] > near_m) continue;
      // The nearest boundary edge (the face this cell belongs to).
      const Eigen::Vector2d centre((i + 0.5) * dx_, (j + 0.5) * dy_);
      const Edge* nearest = nullptr;
      double nearest_m2 = 1e300;
      for_edges_near(centre, distance[c] + cell_m, [&](const Edge& e) {
        const double d2 = (e.mid_m - centre).squaredNorm();
        if (d2 < nearest_m2) {
          nearest_m2 = d2;
          nearest = &e;
        }
      });
      if (nearest == nullptr) continue;
      // Weighted total least squares over the edges within the radius on this side of the solid:
      // first the weighted mean outward normal of the edges that do not face against the nearest
      // one (`side`), then only the edges that face along it, which leaves out the far side of a
      // thin pier or breakwater (its risers are perpendicular to the nearest tread, and would pull
      // the line across the structure). Weights: a Gaussian of standard deviation R / 2, cut at R.
      const double inverse_two_variance = 2.0 / (radius_m * radius_m);
      Eigen::Vector2d side = Eigen::Vector2d::Zero();
      for_edges_near(nearest->mid_m, radius_m, [&](const Edge& e) {
        const double r2 = (e.mid_m - nearest->mid_m).squaredNorm();
        if (r2 < radius_m * radius_m && e.outward.dot(nearest->outward) >= 0.0)
          side += std::exp(-r2 * inverse_two_variance) * e.outward;
      });
      double weight_sum = 0.0;
      Eigen::Vector2d mean = Eigen::Vector2d::Zero(), outward_sum = Eigen::Vector2d::Zero();
      picked.clear();
      for_edges_near(nearest->mid_m, radius_m, [&](const Edge& e) {
        const double r2 = (e.mid_m - nearest->mid_m).squaredNorm();
        if (r2 >= radius_m * radius_m || !(e.outward.dot(side) > 0.0)) return;
        const double w = std::exp(-r2 * inverse_two_variance);
        picked.emplace_back(e.mid_m, w);
        weight_sum += w;
        mean += w * e.mid_m;
        outward_sum += w * e.outward;
      });
      if (picked.empty()) continue;
      mean /= weight_sum;
      double cxx = 0.0, cyy = 0.0, cxy = 0.0;
      for (const auto& [m, w] : picked) {
        const Eigen::Vector2d d = m - mean;
        cxx += w * d.x() * d.x();
        cyy += w * d.y() * d.y();
        cxy += w * d.x() * d.y();
      }
      // The principal axis of the covariance is the line's direction (angle theta); the normal is
      // perpendicular. Where the points spread about equally both ways (a structure of a cell or
      // two, a tight corner) the line is undefined and the edges' mean outward normal stands in.
      const double spread = std::hypot(cxx - cyy, 2.0 * cxy);
      Eigen::Vector2d normal;
      if (picked.size() >= 3 && spread > 0.3 * (cxx + cyy)) {
        const double theta = 0.5 * std::atan2(2.0 * cxy, cxx - cyy);
        normal = Eigen::Vector2d(-std::sin(theta), std::cos(theta));
        const Eigen::Vector2d side = outward_sum.squaredNorm() > 1e-12 ? outward_sum : nearest->outward;
        if (normal.dot(side) < 0.0) normal = -normal;
      } else {
        normal = outward_sum.squaredNorm() > 1e-12 ? outward_sum.normalized() : nearest->outward;
      }
      fitted_normal_[c] = normal.cast<float>();
    }
}

double HarbourObstacles::signed_distance_m(double x_m, double y_m) const {
  return any_ ? sample(x_m, y_m).signed_distance_m : 1e30;
}

ObstacleSample HarbourObstacles::sample(double x_m, double y_m) const {
  ObstacleSample out;
  if (!any_ || std::isnan(x_m) || std::isnan(y_m)) {
    out.signed_distance_m = 1e30;
    return out;
  }
  // Bilinear between cell centres, clamped at the edges (the seabed's rule, seabed.hpp).
  const double u = std::clamp(x_m / dx_ - 0.5, 0.0, static_cast<double>(columns_ - 1));
  const double v = std::clamp(y_m / dy_ - 0.5, 0.0, static_cast<double>(rows_ - 1));
  const int i0 = std::min(static_cast<int>(u), std::max(columns_ - 2, 0));
  const int j0 = std::min(static_cast<int>(v), std::max(rows_ - 2, 0));
  const int i1 = std::min(i0 + 1, columns_ - 1), j1 = std::min(j0 + 1, rows_ - 1);
  const double a = columns_ > 1 ? u - i0 : 0.0, b = rows_ > 1 ? v - j0 : 0.0;
  auto at = [&](int i, int j) { return static_cast<double>(phi_[static_cast<std::size_t>(j) * columns_ + i]); };
  const double f00 = at(i0, j0), f10 = at(i1, j0), f01 = at(i0, j1), f11 = at(i1, j1);
  out.signed_distance_m = (1 - b) * ((1 - a) * f00 + a * f10) + b * ((1 - a) * f01 + a * f11);
  // The normal from the smoothed indicator: over a kernel of 1.7 cells the cells' staircase along a
  // straight face averages out, so its gradient is the face's normal (phi's own gradient keeps the
  // staircase's ripple near the face).
  // Near a face: the fitted normals of the four cells (step 4 of the constructor), blended.
  auto fitted = [&](int i, int j) { return fitted_normal_[static_cast<std::size_t>(j) * columns_ + i].cast<double>(); };
  const Eigen::Vector2d n00 = fitted(i0, j0), n10 = fitted(i1, j0), n01 = fitted(i0, j1), n11 = fitted(i1, j1);
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();
  if (!n00.isZero() && !n10.isZero() && !n01.isZero() && !n11.isZero())
    normal = (1 - b) * ((1 - a) * n00 + a * n10) + b * ((1 - a) * n01 + a * n11);
  if (normal.norm() < 1e-6) {
    auto g = [&](int i, int j) { return static_cast<double>(indicator_[static_cast<std::size_t>(j) * columns_ + i]); };
    const double g00 = g(i0, j0), g10 = g(i1, j0), g01 = g(i0, j1), g11 = g(i1, j1);
    normal = Eigen::Vector2d(((1 - b) * (g10 - g00) + b * (g11 - g01)) / dx_, ((1 - a) * (g01 - g00) + a * (g11 - g10)) / dy_);
  }
  const double norm = normal.norm();
  if (norm > 1e-9) out.normal = normal / norm;
  const int ci = std::clamp(static_cast<int>(std::lround(u)), 0, columns_ - 1);
  const int cj = std::clamp(static_cast<int>(std::lround(v)), 0, rows_ - 1);
  const std::int32_t owner = owner_[static_cast<std::size_t>(cj) * columns_ + ci];
  if (owner >= 0) {
    out.structure = label_[static_cast<std::size_t>(owner)];
    out.top_m = top_[static_cast<std::size_t>(owner)];
  }
  return out;
}

HarbourStructure HarbourObstacles::describe(int id) const {
  if (id == 0) return HarbourStructure{};
  if (id < 1 || id > static_cast<int>(structures_.size())) throw std::out_of_range("no such structure");
  return structures_[static_cast<std::size_t>(id - 1)];
}

}  // namespace nearshore::ships
