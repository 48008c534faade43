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
  auto g = [&](int i, int j) { return static_cast<double>(indicator_[static_cast<std::size_t>(j) * columns_ + i]); };
  const double g00 = g(i0, j0), g10 = g(i1, j0), g01 = g(i0, j1), g11 = g(i1, j1);
  const Eigen::Vector2d gradient(((1 - b) * (g10 - g00) + b * (g11 - g01)) / dx_,
                                 ((1 - a) * (g01 - g00) + a * (g11 - g10)) / dy_);
  const double norm = gradient.norm();
  if (norm > 1e-9) out.normal = gradient / norm;
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
