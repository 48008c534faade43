#pragma once
// SurfaceStatistics: the wave climate of each cell over a run of frames, what a harbour engineer
// maps (the `geotiff` export):
//   significant wave height  Hs = 4 sqrt(m0) over the frames (core/elevation_moments.hpp, the
//                            definition the bake's every-step map uses too), metres;
//   mean water level         the time mean of eta (set-up / set-down near breaking), metres;
//   breaking fraction        the time mean of the breaking indicator: the fraction of time the
//                            cell breaks where the indicator is 0 or 1, weighted by its strength
//                            where the solver writes values between.
// Accumulated frame by frame, so a sequence of any length takes the memory of three rasters of
// doubles.
#include <cstdint>
#include <vector>

#include "nearshore/core/elevation_moments.hpp"
#include "nearshore/core/raster.hpp"

namespace nearshore::exports {

class SurfaceStatistics {
 public:
  SurfaceStatistics(int columns, int rows);

  /// Adds one frame's fields (rasters of the constructor's size, row 0 south).
  void add_frame(const Raster<float>& surface_elevation_m, const Raster<float>& breaking);

  int frame_count() const { return static_cast<int>(moments_.sample_count()); }
  /// Hs = 4 standard deviations of eta over the frames added (population variance), metres.
  Raster<float> significant_wave_height_m() const;
  Raster<float> mean_surface_elevation_m() const;
  Raster<float> breaking_fraction() const;

 private:
  int columns_, rows_;
  ElevationMoments moments_;
  std::vector<double> breaking_sum_;
};

}  // namespace nearshore::exports
