#pragma once
// ElevationMoments: the time mean and variance of the surface elevation in each cell over a run of
// samples (the bake's every solver step, or a sequence's frames), and the significant wave height
// from them: Hs = 4 sqrt(m0), m0 the variance of eta about its time mean (the spectral Hm0;
// Holthuijsen 2007, "Waves in Oceanic and Coastal Waters", 4.2.2); a sinusoid of amplitude a has
// 2 sqrt(2) a. The one owner of that definition: the bake's wave_statistics.tif, `export --to
// geotiff` and the agitation maps all read it here.
//
// Sums of eta and eta^2 in double precision: eta is measured from still water, so |mean| is small
// next to the standard deviation and sum(eta^2)/n - mean^2 loses no significant digit (a 1e-16
// relative rounding of values near Hs^2). The sums are the state a bake's checkpoint saves.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace nearshore {

class ElevationMoments {
 public:
  explicit ElevationMoments(std::size_t cells) : sum_m_(cells, 0.0), sum_squares_m2_(cells, 0.0) {}

  /// One cell's sample; call for every cell of a sample (threads may share the cells out), then
  /// end_sample() once.
  void add(std::size_t cell, double surface_elevation_m) {
    sum_m_[cell] += surface_elevation_m;
    sum_squares_m2_[cell] += surface_elevation_m * surface_elevation_m;
  }
  void end_sample() { ++sample_count_; }

  long sample_count() const { return sample_count_; }
  std::size_t cell_count() const { return sum_m_.size(); }
  /// Time mean of eta, metres (0 before any sample).
  double mean_m(std::size_t cell) const { return sample_count_ > 0 ? sum_m_[cell] / static_cast<double>(sample_count_) : 0.0; }
  /// 4 sqrt(population variance of eta), metres (0 before any sample).
  double significant_wave_height_m(std::size_t cell) const {
    if (sample_count_ == 0) return 0.0;
    const double mean = mean_m(cell);
    return 4.0 * std::sqrt(std::max(0.0, sum_squares_m2_[cell] / static_cast<double>(sample_count_) - mean * mean));
  }

  /// The state, for a checkpoint (the bake's WaveStatistics saves and loads it).
  std::vector<double>& sums_m() { return sum_m_; }
  std::vector<double>& sums_of_squares_m2() { return sum_squares_m2_; }
  const std::vector<double>& sums_m() const { return sum_m_; }
  const std::vector<double>& sums_of_squares_m2() const { return sum_squares_m2_; }
  void set_sample_count(long count) { sample_count_ = count; }

 private:
  std::vector<double> sum_m_, sum_squares_m2_;
  long sample_count_ = 0;
};

}  // namespace nearshore
