#pragma once
// SurfaceStatistics: the wave climate of each cell over a run of frames, what a harbour engineer
// maps (the `geotiff` export):
//   significant wave height  Hs = 4 sqrt(m0) over the frames (core/elevation_moments.hpp, the
//                            definition the bake's every-step map uses too), metres;
//   mean water level         the time mean of eta (set-up / set-down near breaking), metres;
//   breaking fraction        the time mean of the breaking indicator: the fraction of time the
//                            cell breaks where the indicator is 0 or 1, weighted by its strength
//                            where the solver writes values between;
//   wet fraction             the fraction of the frames in which the cell held water (total depth
//                            d + eta above the bake's dry depth). Below 1 the cell is the
//                            shoreline's swash: the bake pins eta at -d while a cell is dry, so
//                            4 sqrt(m0) there measures the moving shoreline, not a wave height.
// Accumulated frame by frame, so a sequence of any length takes the memory of three rasters of
// doubles.
#include <cstdint>
#include <vector>

#include "nearshore/core/elevation_moments.hpp"
#include "nearshore/core/raster.hpp"

namespace nearshore::exports {

class SurfaceStatistics {
 public:
  /// Without the depth: every cell counts as wet in every frame (wet_fraction 1).
  SurfaceStatistics(int columns, int rows);
  /// With the still-water depth (row 0 south, m, positive down) and the wet/dry threshold
  /// (the bake's solver dry_depth_m): each frame also counts the cells holding water.
  SurfaceStatistics(const Raster<float>& still_water_depth_m, double dry_depth_m);

  /// Adds one frame's fields (rasters of the constructor's size, row 0 south).
  void add_frame(const Raster<float>& surface_elevation_m, const Raster<float>& breaking);

  int frame_count() const { return static_cast<int>(moments_.sample_count()); }
  /// Hs = 4 standard deviations of eta over the frames added (population variance), metres.
  Raster<float> significant_wave_height_m() const;
  Raster<float> mean_surface_elevation_m() const;
  Raster<float> breaking_fraction() const;
  /// The fraction of the frames added in which the cell held water, d + eta > dry depth (1 without
  /// a depth, and where no frame was added).
  Raster<float> wet_fraction() const;

 private:
  int columns_, rows_;
  ElevationMoments moments_;
  std::vector<double> breaking_sum_;
  std::vector<float> still_water_depth_m_;  // empty: no wet test
  double dry_depth_m_ = 0.0;
  std::vector<std::uint32_t> wet_frames_;
};

}  // namespace nearshore::exports
