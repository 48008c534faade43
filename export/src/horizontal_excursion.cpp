#include "nearshore/export/horizontal_excursion.hpp"

#include <algorithm>
#include <cassert>

namespace nearshore::exports {

HorizontalExcursion::HorizontalExcursion(const HarbourGrid& harbour, double frame_interval_s)
    : harbour_(harbour), frame_interval_s_(frame_interval_s) {
  assert(frame_interval_s > 0.0);
  const std::size_t cells = harbour.geometry.cell_count();
  for (auto* field : {&running_x_, &running_y_, &previous_u_, &previous_v_, &sum_u_, &sum_v_, &sum_running_x_,
                      &sum_running_y_, &mean_u_, &mean_v_, &offset_x_, &offset_y_})
    field->assign(cells, 0.0);
}

// One step of (2): U of this frame by (1), X_n += (U_{n-1} + U_n) dt / 2 (X_0 = 0).
void HorizontalExcursion::integrate(const Raster<float>& surface_elevation_m, const Raster<float>& flux_x_m2_s,
                                    const Raster<float>& flux_y_m2_s) {
  const float* eta = surface_elevation_m.data();
  const float* p = flux_x_m2_s.data();
  const float* q = flux_y_m2_s.data();
  const float* depth = harbour_.still_water_depth_m.data();
  const std::uint8_t* land = harbour_.land.data();
  const double half_step_s = 0.5 * frame_interval_s_;
  for (std::size_t cell = 0; cell < running_x_.size(); ++cell) {
    if (land[cell]) continue;
    const double total_depth_m = std::max(static_cast<double>(depth[cell]) + eta[cell], kMinimumTotalDepth_m);
    const double u = p[cell] / total_depth_m, v = q[cell] / total_depth_m;
    if (step_ > 0) {
      running_x_[cell] += half_step_s * (previous_u_[cell] + u);
      running_y_[cell] += half_step_s * (previous_v_[cell] + v);
    }
    previous_u_[cell] = u;
    previous_v_[cell] = v;
  }
}

void HorizontalExcursion::accumulate(const Raster<float>& surface_elevation_m, const Raster<float>& flux_x_m2_s,
                                     const Raster<float>& flux_y_m2_s) {
  assert(accumulating_);
  integrate(surface_elevation_m, flux_x_m2_s, flux_y_m2_s);
  for (std::size_t cell = 0; cell < running_x_.size(); ++cell) {
    sum_u_[cell] += previous_u_[cell];
    sum_v_[cell] += previous_v_[cell];
    sum_running_x_[cell] += running_x_[cell];
    sum_running_y_[cell] += running_y_[cell];
  }
  ++step_;
  accumulated_frames_ = step_;
}

void HorizontalExcursion::finish_accumulation() {
  assert(accumulating_ && accumulated_frames_ >= 2);
  const double n = accumulated_frames_;
  // mean_n(t_n) with t_n = n dt measured from the first frame.
  const double mean_time_s = 0.5 * (n - 1.0) * frame_interval_s_;
  for (std::size_t cell = 0; cell < running_x_.size(); ++cell) {
    mean_u_[cell] = sum_u_[cell] / n;
    mean_v_[cell] = sum_v_[cell] / n;
    offset_x_[cell] = sum_running_x_[cell] / n - mean_u_[cell] * mean_time_s;
    offset_y_[cell] = sum_running_y_[cell] / n - mean_v_[cell] * mean_time_s;
  }
  std::fill(running_x_.begin(), running_x_.end(), 0.0);
  std::fill(running_y_.begin(), running_y_.end(), 0.0);
  step_ = 0;
  accumulating_ = false;
}

void HorizontalExcursion::excursion(const Raster<float>& surface_elevation_m, const Raster<float>& flux_x_m2_s,
                                    const Raster<float>& flux_y_m2_s, Raster<float>& excursion_x_m,
                                    Raster<float>& excursion_y_m) {
  assert(!accumulating_ && step_ < accumulated_frames_);
  integrate(surface_elevation_m, flux_x_m2_s, flux_y_m2_s);
  const GridGeometry& g = harbour_.geometry;
  if (excursion_x_m.columns() != g.columns || excursion_x_m.rows() != g.rows) excursion_x_m = Raster<float>(g.columns, g.rows);
  if (excursion_y_m.columns() != g.columns || excursion_y_m.rows() != g.rows) excursion_y_m = Raster<float>(g.columns, g.rows);
  const double time_s = step_ * frame_interval_s_;
  const std::uint8_t* land = harbour_.land.data();
  for (std::size_t cell = 0; cell < running_x_.size(); ++cell) {
    if (land[cell]) {
      excursion_x_m.values()[cell] = 0.0f;
      excursion_y_m.values()[cell] = 0.0f;
      continue;
    }
    excursion_x_m.values()[cell] = static_cast<float>(running_x_[cell] - mean_u_[cell] * time_s - offset_x_[cell]);
    excursion_y_m.values()[cell] = static_cast<float>(running_y_[cell] - mean_v_[cell] * time_s - offset_y_[cell]);
  }
  ++step_;
}

namespace {

// d(field)/d(index) at (column, row) along (step_column, step_row), over water neighbours only.
double index_derivative(const HarbourGrid& harbour, const Raster<float>& field, int column, int row, int step_column,
                        int step_row) {
  const GridGeometry& g = harbour.geometry;
  auto water = [&](int c, int r) { return c >= 0 && c < g.columns && r >= 0 && r < g.rows && !harbour.land(c, r); };
  const bool after = water(column + step_column, row + step_row), before = water(column - step_column, row - step_row);
  if (after && before)
    return 0.5 * (field(column + step_column, row + step_row) - field(column - step_column, row - step_row));
  if (after) return field(column + step_column, row + step_row) - field(column, row);
  if (before) return field(column, row) - field(column - step_column, row - step_row);
  return 0.0;
}

}  // namespace

int folded_cell_count(const HarbourGrid& harbour, const Raster<float>& excursion_x_m, const Raster<float>& excursion_y_m) {
  const GridGeometry& g = harbour.geometry;
  const double dx = g.spacing_x_m(), dy = g.spacing_y_m();
  int folded = 0;
  for (int row = 0; row < g.rows; ++row)
    for (int column = 0; column < g.columns; ++column) {
      if (harbour.land(column, row)) continue;
      const double dxi_x_dx = index_derivative(harbour, excursion_x_m, column, row, 1, 0) / dx;
      const double dxi_x_dy = index_derivative(harbour, excursion_x_m, column, row, 0, 1) / dy;
      const double dxi_y_dx = index_derivative(harbour, excursion_y_m, column, row, 1, 0) / dx;
      const double dxi_y_dy = index_derivative(harbour, excursion_y_m, column, row, 0, 1) / dy;
      folded += (1.0 + dxi_x_dx) * (1.0 + dxi_y_dy) - dxi_x_dy * dxi_y_dx <= 0.0;
    }
  return folded;
}

}  // namespace nearshore::exports
