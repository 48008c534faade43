#include "nearshore/export/surface_statistics.hpp"

#include <cassert>
#include <cmath>

namespace nearshore::exports {

SurfaceStatistics::SurfaceStatistics(int columns, int rows)
    : columns_(columns),
      rows_(rows),
      mean_m_(static_cast<std::size_t>(columns) * rows, 0.0),
      sum_squared_deviation_m2_(mean_m_.size(), 0.0),
      breaking_sum_(mean_m_.size(), 0.0) {}

void SurfaceStatistics::add_frame(const Raster<float>& surface_elevation_m, const Raster<float>& breaking) {
  assert(surface_elevation_m.columns() == columns_ && surface_elevation_m.rows() == rows_);
  assert(breaking.columns() == columns_ && breaking.rows() == rows_);
  ++frame_count_;
  const double n = frame_count_;
  const float* eta = surface_elevation_m.data();
  const float* foam = breaking.data();
  for (std::size_t cell = 0; cell < mean_m_.size(); ++cell) {
    // Welford: the mean and the sum of squared deviations in one pass, without the cancellation of
    // sum(eta^2) - n mean^2 on a water level far from zero.
    const double delta = eta[cell] - mean_m_[cell];
    mean_m_[cell] += delta / n;
    sum_squared_deviation_m2_[cell] += delta * (eta[cell] - mean_m_[cell]);
    breaking_sum_[cell] += foam[cell];
  }
}

Raster<float> SurfaceStatistics::significant_wave_height_m() const {
  Raster<float> hs(columns_, rows_, 0.0f);
  if (frame_count_ == 0) return hs;
  for (std::size_t cell = 0; cell < mean_m_.size(); ++cell)
    hs.values()[cell] = static_cast<float>(4.0 * std::sqrt(sum_squared_deviation_m2_[cell] / frame_count_));
  return hs;
}

Raster<float> SurfaceStatistics::mean_surface_elevation_m() const {
  Raster<float> mean(columns_, rows_, 0.0f);
  for (std::size_t cell = 0; cell < mean_m_.size(); ++cell) mean.values()[cell] = static_cast<float>(mean_m_[cell]);
  return mean;
}

Raster<float> SurfaceStatistics::breaking_fraction() const {
  Raster<float> fraction(columns_, rows_, 0.0f);
  if (frame_count_ == 0) return fraction;
  for (std::size_t cell = 0; cell < mean_m_.size(); ++cell)
    fraction.values()[cell] = static_cast<float>(breaking_sum_[cell] / frame_count_);
  return fraction;
}

}  // namespace nearshore::exports
