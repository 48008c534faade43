#include "nearshore/export/surface_statistics.hpp"

#include <cassert>
#include <cmath>

namespace nearshore::exports {

SurfaceStatistics::SurfaceStatistics(int columns, int rows)
    : columns_(columns), rows_(rows), moments_(static_cast<std::size_t>(columns) * rows), breaking_sum_(moments_.cell_count(), 0.0) {}

SurfaceStatistics::SurfaceStatistics(const Raster<float>& still_water_depth_m, double dry_depth_m)
    : SurfaceStatistics(still_water_depth_m.columns(), still_water_depth_m.rows()) {
  still_water_depth_m_ = still_water_depth_m.values();
  dry_depth_m_ = dry_depth_m;
  wet_frames_.assign(still_water_depth_m_.size(), 0);
}

void SurfaceStatistics::add_frame(const Raster<float>& surface_elevation_m, const Raster<float>& breaking) {
  assert(surface_elevation_m.columns() == columns_ && surface_elevation_m.rows() == rows_);
  assert(breaking.columns() == columns_ && breaking.rows() == rows_);
  const float* eta = surface_elevation_m.data();
  const float* foam = breaking.data();
  for (std::size_t cell = 0; cell < breaking_sum_.size(); ++cell) {
    moments_.add(cell, eta[cell]);
    breaking_sum_[cell] += foam[cell];
  }
  // The solver's test (d + eta > dry depth is wet), on the frame's float eta.
  for (std::size_t cell = 0; cell < wet_frames_.size(); ++cell)
    wet_frames_[cell] += static_cast<double>(still_water_depth_m_[cell]) + eta[cell] > dry_depth_m_ ? 1u : 0u;
  moments_.end_sample();
}

Raster<float> SurfaceStatistics::significant_wave_height_m() const {
  Raster<float> hs(columns_, rows_, 0.0f);
  for (std::size_t cell = 0; cell < breaking_sum_.size(); ++cell) hs.values()[cell] = static_cast<float>(moments_.significant_wave_height_m(cell));
  return hs;
}

Raster<float> SurfaceStatistics::mean_surface_elevation_m() const {
  Raster<float> mean(columns_, rows_, 0.0f);
  for (std::size_t cell = 0; cell < breaking_sum_.size(); ++cell) mean.values()[cell] = static_cast<float>(moments_.mean_m(cell));
  return mean;
}

Raster<float> SurfaceStatistics::breaking_fraction() const {
  Raster<float> fraction(columns_, rows_, 0.0f);
  if (moments_.sample_count() == 0) return fraction;
  for (std::size_t cell = 0; cell < breaking_sum_.size(); ++cell)
    fraction.values()[cell] = static_cast<float>(breaking_sum_[cell] / static_cast<double>(moments_.sample_count()));
  return fraction;
}

Raster<float> SurfaceStatistics::wet_fraction() const {
  Raster<float> fraction(columns_, rows_, 1.0f);
  if (wet_frames_.empty() || moments_.sample_count() == 0) return fraction;
  for (std::size_t cell = 0; cell < wet_frames_.size(); ++cell)
    fraction.values()[cell] = static_cast<float>(static_cast<double>(wet_frames_[cell]) / static_cast<double>(moments_.sample_count()));
  return fraction;
}

}  // namespace nearshore::exports
