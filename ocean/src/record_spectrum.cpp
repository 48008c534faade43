// Welch's spectrum of an elevation record and its sea-state parameters (record_spectrum.hpp).
#include "nearshore/ocean/record_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include <fftw3.h>
#include <fmt/format.h>

#include "fftw_planner.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::ocean {
namespace {

const char* const kSubject = "record spectrum";

// One r2c plan over one segment's buffers; made and destroyed under the planner lock.
class SegmentTransform {
 public:
  explicit SegmentTransform(int samples)
      : input_(fftwf_alloc_real(samples)), output_(fftwf_alloc_complex(samples / 2 + 1)) {
    const std::lock_guard lock(detail::fftw_planner_mutex());
    plan_ = fftwf_plan_dft_r2c_1d(samples, input_, output_, FFTW_ESTIMATE);
  }
  ~SegmentTransform() {
    {
      const std::lock_guard lock(detail::fftw_planner_mutex());
      fftwf_destroy_plan(plan_);
    }
    fftwf_free(input_);
    fftwf_free(output_);
  }
  SegmentTransform(const SegmentTransform&) = delete;
  SegmentTransform& operator=(const SegmentTransform&) = delete;
  float* input() { return input_; }
  const fftwf_complex* run() {
    fftwf_execute(plan_);
    return output_;
  }

 private:
  float* input_;
  fftwf_complex* output_;
  fftwf_plan plan_ = nullptr;
};

}  // namespace

RecordSpectrum record_spectrum(std::span<const double> elevation_m, double sample_interval_s,
                               const RecordSpectrumOptions& options) {
  if (elevation_m.size() < 16)
    throw Error(kSubject, fmt::format("elevation_m holds {} samples", elevation_m.size()),
                "give a record of at least 16 samples (a spectrum needs several waves: minutes of a sea)");
  if (elevation_m.size() > (std::size_t{1} << 30))
    throw Error(kSubject, fmt::format("elevation_m holds {} samples", elevation_m.size()),
                "give at most 2^30 samples (cut the record into parts and take each part's spectrum)");
  const int n = static_cast<int>(elevation_m.size());
  if (!(sample_interval_s > 0.0) || !std::isfinite(sample_interval_s))
    throw Error(kSubject, fmt::format("sample_interval_s is {}", sample_interval_s), "give the record's positive sample interval");
  for (int j = 0; j < n; ++j)
    if (!std::isfinite(elevation_m[j]))
      throw Error(kSubject, fmt::format("elevation_m[{}] is {}", j, elevation_m[j]),
                  "remove or fill the gap (a spectrum needs evenly spaced finite samples)");
  int N = options.segment_samples;
  if (N == 0) {
    N = 16;
    while (2 * N <= n / 4) N *= 2;
  }
  if (N < 16 || N > n)
    throw Error(kSubject, fmt::format("segment_samples is {} for a record of {} samples", options.segment_samples, n),
                "give 0 (a quarter of the record) or 16 to the record's length");

  RecordSpectrum spectrum;
  spectrum.segment_samples = N;
  spectrum.frequency_resolution_hz = 1.0 / (N * sample_interval_s);
  const int bins = N / 2 + 1;
  std::vector<double> window(N), sum(bins, 0.0);
  double window_power = 0.0;
  for (int j = 0; j < N; ++j) {
    window[j] = 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * j / N));
    window_power += window[j] * window[j];
  }
  // Half-overlapping segments; the last one ends at the record's end, so no sample is left out.
  const int hop = std::max(1, N / 2);
  const int segments = 1 + (n - N + hop - 1) / hop;
  SegmentTransform transform(N);
  for (int s = 0; s < segments; ++s) {
    const int first = std::min(s * hop, n - N);
    double mean = 0.0;
    for (int j = 0; j < N; ++j) mean += elevation_m[first + j];
    mean /= N;
    float* input = transform.input();
    for (int j = 0; j < N; ++j) input[j] = static_cast<float>(window[j] * (elevation_m[first + j] - mean));
    const fftwf_complex* output = transform.run();
    for (int k = 0; k < bins; ++k) sum[k] += double(output[k][0]) * output[k][0] + double(output[k][1]) * output[k][1];
  }
  spectrum.segment_count = segments;
  spectrum.frequency_hz.resize(bins);
  spectrum.variance_density_m2_hz.resize(bins);
  for (int k = 0; k < bins; ++k) {
    const double one_sided = (k == 0 || 2 * k == N) ? 1.0 : 2.0;
    spectrum.frequency_hz[k] = k * spectrum.frequency_resolution_hz;
    spectrum.variance_density_m2_hz[k] = one_sided * sample_interval_s / window_power * sum[k] / segments;
  }

  // The band of the moments and the peak.
  const double df = spectrum.frequency_resolution_hz, nyquist_hz = 0.5 / sample_interval_s;
  const double low_hz = options.min_frequency_hz > 0.0 ? options.min_frequency_hz : df;
  const double high_hz = options.max_frequency_hz > 0.0 ? std::min(options.max_frequency_hz, nyquist_hz) : nyquist_hz;
  const int k_low = std::max(1, static_cast<int>(std::ceil(low_hz / df - 1e-9)));
  const int k_high = std::min(bins - 1, static_cast<int>(std::floor(high_hz / df + 1e-9)));
  if (!(k_low <= k_high))
    throw Error(kSubject,
                fmt::format("the band {} to {} Hz holds no bin of {} Hz (min_frequency_hz, max_frequency_hz)", low_hz,
                            high_hz, df),
                "widen the band or lengthen segment_samples");
  double m0 = 0.0, m1 = 0.0, m2 = 0.0;
  int peak = k_low;
  for (int k = k_low; k <= k_high; ++k) {
    const double f = spectrum.frequency_hz[k], S = spectrum.variance_density_m2_hz[k];
    m0 += S * df;
    m1 += f * S * df;
    m2 += f * f * S * df;
    if (S > spectrum.variance_density_m2_hz[peak]) peak = k;
  }
  spectrum.significant_height_hm0_m = 4.0 * std::sqrt(m0);
  if (m0 > 0.0) {
    spectrum.mean_period_tm01_s = m0 / m1;
    spectrum.zero_crossing_period_tm02_s = std::sqrt(m0 / m2);
    // The parabola through the logarithms of the peak bin and its neighbours (inside the band): its
    // vertex. A Hann window's main lobe is close to a Gaussian, whose logarithm is a parabola, so the
    // vertex of log S finds a regular wave's frequency to a few hundredths of a bin, where the
    // parabola through S itself is off by a tenth (Gasior & Gonzalez 2004, CERN-AB-2004-023).
    double offset = 0.0;
    if (peak > k_low && peak < k_high) {
      const double below = spectrum.variance_density_m2_hz[peak - 1], at = spectrum.variance_density_m2_hz[peak],
                   above = spectrum.variance_density_m2_hz[peak + 1];
      if (below > 0.0 && above > 0.0) {
        const double log_below = std::log(below), log_at = std::log(at), log_above = std::log(above);
        const double curvature = log_below - 2.0 * log_at + log_above;
        if (curvature < 0.0) offset = std::clamp(0.5 * (log_below - log_above) / curvature, -0.5, 0.5);
      }
    }
    spectrum.peak_period_s = 1.0 / ((peak + offset) * df);
  }
  return spectrum;
}

}  // namespace nearshore::ocean
