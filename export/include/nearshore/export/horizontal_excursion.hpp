#pragma once
// HorizontalExcursion: how far the water of a cell moves sideways as the waves pass, computed from
// what the frames carry, for the horizontal part of a displacement map (the "choppy" shift VFX
// tools apply so crests sharpen and troughs flatten, Tessendorf 2001 section 4.3).
//
// The frames hold the depth-integrated fluxes (P, Q) of seed 003 eq. (1)-(3) and the harbour grid
// the still-water depth d, so the depth-averaged velocity is
//     U = (P, Q) / h,   h = max(d + eta, kMinimumTotalDepth_m)                               (1)
// and the excursion is its time integral about the mean current:
//     xi(t_n) = X_n - Ubar t_n - mean_n(X_n - Ubar t_n),   X_n = trapezoidal sum of U dt    (2)
// with Ubar the time mean of U over the frames (the current and the return flow, which are not
// wave motion). For a linear wave eta = a cos(k x - w t) over depth d, P = (w / k) eta and (2)
// gives xi = -(a / (k d)) sin(k x - w t): the surface particle's excursion in shallow water. In
// deeper water the particles near the surface move kd coth(kd) times further than the depth
// average (1.31 x at kd = 1), so the shift is on the gentle side there.
//
// Two passes over the frames, in the same order: accumulate() every frame (Ubar and the mean of
// X), then excursion() every frame again (the same trapezoidal sum, now with the means known).
// Memory: a few rasters of doubles, whatever the number of frames.
#include <vector>

#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/raster.hpp"

namespace nearshore::exports {

/// (1): below 0.1 m of water (a swash film) the velocity is taken at 0.1 m, so a cell that is
/// drying does not throw the surface metres sideways.
inline constexpr double kMinimumTotalDepth_m = 0.1;

class HorizontalExcursion {
 public:
  /// frame_interval_s: time between the frames given, seconds (> 0).
  HorizontalExcursion(const HarbourGrid& harbour, double frame_interval_s);

  /// Pass 1: frame n (in time order, starting at 0).
  void accumulate(const Raster<float>& surface_elevation_m, const Raster<float>& flux_x_m2_s,
                  const Raster<float>& flux_y_m2_s);
  /// Ends pass 1; at least two frames must have been accumulated.
  void finish_accumulation();
  /// Pass 2: frame n again, in the same order; writes xi of (2) along x (east) and y (north),
  /// metres; land cells 0.
  void excursion(const Raster<float>& surface_elevation_m, const Raster<float>& flux_x_m2_s,
                 const Raster<float>& flux_y_m2_s, Raster<float>& excursion_x_m, Raster<float>& excursion_y_m);

 private:
  void integrate(const Raster<float>& surface_elevation_m, const Raster<float>& flux_x_m2_s,
                 const Raster<float>& flux_y_m2_s);
  const HarbourGrid& harbour_;
  double frame_interval_s_;
  int accumulated_frames_ = 0, step_ = 0;
  bool accumulating_ = true;
  // Per cell, x then y component: the running trapezoidal sum X_n, the previous frame's U, the sums
  // of U and of X_n over pass 1, then Ubar and the mean of X_n - Ubar t_n.
  std::vector<double> running_x_, running_y_, previous_u_, previous_v_, sum_u_, sum_v_, sum_running_x_,
      sum_running_y_, mean_u_, mean_v_, offset_x_, offset_y_;
};

/// How many water cells the shift folds over: where the Jacobian of the displaced positions
/// (x + xi_x, y + xi_y),  J = (1 + dxi_x/dx)(1 + dxi_y/dy) - (dxi_x/dy)(dxi_y/dx),  is <= 0, the
/// displaced surface overlaps itself (Tessendorf 2001, section 4.4). Central differences between
/// water cells, one-sided beside land and the grid's edges. Swash cells, where the run-up is longer
/// than a cell, are where it happens.
int folded_cell_count(const HarbourGrid& harbour, const Raster<float>& excursion_x_m, const Raster<float>& excursion_y_m);

}  // namespace nearshore::exports
