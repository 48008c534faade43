// Welch's spectrum of an elevation record and its sea-state parameters (record_spectrum.hpp).
#include "nearshore/ocean/record_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <numbers>
#include <utility>

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

void check_samples(std::span<const double> record, const char* name) {
  for (std::size_t j = 0; j < record.size(); ++j)
    if (!std::isfinite(record[j]))
      throw Error(kSubject, fmt::format("{}[{}] is {}", name, j, record[j]),
                  "remove or fill the gap (a spectrum needs evenly spaced finite samples)");
}

// The segment length N (options.segment_samples, 0: the largest power of two not above a quarter).
int checked_segment_samples(std::span<const double> elevation_m, double sample_interval_s,
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
  check_samples(elevation_m, "elevation_m");
  int N = options.segment_samples;
  if (N == 0) {
    N = 16;
    while (2 * N <= n / 4) N *= 2;
  }
  if (N < 16 || N > n)
    throw Error(kSubject, fmt::format("segment_samples is {} for a record of {} samples", options.segment_samples, n),
                "give 0 (a quarter of the record) or 16 to the record's length");
  return N;
}

// Welch's sums over the segments, per bin: |E|^2 of the elevation and, with a flux, |U|^2, |V|^2
// and the co-spectra Re(conj(E) U), Re(conj(E) V) (all of the windowed, mean-removed segments).
struct WelchSums {
  int segments = 0;
  double window_power = 0.0;
  std::vector<double> ee, uu, vv, eu, ev;
};

WelchSums welch_sums(std::span<const double> elevation_m, std::span<const double> flux_x,
                     std::span<const double> flux_y, int N) {
  const int n = static_cast<int>(elevation_m.size());
  const bool directional = !flux_x.empty();
  const int bins = N / 2 + 1;
  WelchSums sums;
  sums.ee.assign(bins, 0.0);
  if (directional) sums.uu = sums.vv = sums.eu = sums.ev = sums.ee;
  std::vector<double> window(N);
  for (int j = 0; j < N; ++j) {
    window[j] = 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * j / N));
    sums.window_power += window[j] * window[j];
  }
  // Half-overlapping segments; the last one ends at the record's end, so no sample is left out.
  const int hop = std::max(1, N / 2);
  sums.segments = 1 + (n - N + hop - 1) / hop;
  SegmentTransform transform(N);
  std::vector<std::complex<double>> e(bins), u(bins);
  const auto transformed = [&](std::span<const double> record, int first, std::vector<std::complex<double>>& out) {
    double mean = 0.0;
    for (int j = 0; j < N; ++j) mean += record[first + j];
    mean /= N;
    float* input = transform.input();
    for (int j = 0; j < N; ++j) input[j] = static_cast<float>(window[j] * (record[first + j] - mean));
    const fftwf_complex* output = transform.run();
    for (int k = 0; k < bins; ++k) out[k] = {output[k][0], output[k][1]};
  };
  for (int s = 0; s < sums.segments; ++s) {
    const int first = std::min(s * hop, n - N);
    transformed(elevation_m, first, e);
    for (int k = 0; k < bins; ++k) sums.ee[k] += e[k].real() * e[k].real() + e[k].imag() * e[k].imag();
    if (!directional) continue;
    transformed(flux_x, first, u);
    for (int k = 0; k < bins; ++k) {
      sums.uu[k] += std::norm(u[k]);
      sums.eu[k] += (std::conj(e[k]) * u[k]).real();
    }
    transformed(flux_y, first, u);
    for (int k = 0; k < bins; ++k) {
      sums.vv[k] += std::norm(u[k]);
      sums.ev[k] += (std::conj(e[k]) * u[k]).real();
    }
  }
  return sums;
}

// The spectrum from the sums and its parameters over the band; `band` gets the band's bins and the
// peak bin.
struct Band {
  int low = 0, high = 0, peak = 0;
};

RecordSpectrum elevation_spectrum(const WelchSums& sums, int N, double sample_interval_s,
                                  const RecordSpectrumOptions& options, Band& band) {
  RecordSpectrum spectrum;
  spectrum.segment_samples = N;
  spectrum.segment_count = sums.segments;
  spectrum.frequency_resolution_hz = 1.0 / (N * sample_interval_s);
  const int bins = N / 2 + 1;
  spectrum.frequency_hz.resize(bins);
  spectrum.variance_density_m2_hz.resize(bins);
  for (int k = 0; k < bins; ++k) {
    const double one_sided = (k == 0 || 2 * k == N) ? 1.0 : 2.0;
    spectrum.frequency_hz[k] = k * spectrum.frequency_resolution_hz;
    spectrum.variance_density_m2_hz[k] = one_sided * sample_interval_s / sums.window_power * sums.ee[k] / sums.segments;
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
  band = {k_low, k_high, peak};
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

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

// Kuik et al. (1988) eq. 6: the circular spread of first-order coefficients, degrees.
double spread_deg(double a1, double b1) {
  return degrees(std::sqrt(std::max(0.0, 2.0 * (1.0 - std::sqrt(a1 * a1 + b1 * b1)))));
}

}  // namespace

RecordSpectrum record_spectrum(std::span<const double> elevation_m, double sample_interval_s,
                               const RecordSpectrumOptions& options) {
  const int N = checked_segment_samples(elevation_m, sample_interval_s, options);
  Band band;
  return elevation_spectrum(welch_sums(elevation_m, {}, {}, N), N, sample_interval_s, options, band);
}

DirectionalRecordSpectrum directional_record_spectrum(std::span<const double> elevation_m, std::span<const double> flux_x,
                                                      std::span<const double> flux_y, double sample_interval_s,
                                                      const RecordSpectrumOptions& options) {
  const int N = checked_segment_samples(elevation_m, sample_interval_s, options);
  for (const auto& [record, name] : {std::pair{flux_x, "flux_x"}, std::pair{flux_y, "flux_y"}}) {
    if (record.size() != elevation_m.size())
      throw Error(kSubject, fmt::format("{} holds {} samples and elevation_m {}", name, record.size(), elevation_m.size()),
                  "give the flux (or velocity) sampled with the elevation, one sample of each per time");
    check_samples(record, name);
  }
  const WelchSums sums = welch_sums(elevation_m, flux_x, flux_y, N);
  DirectionalRecordSpectrum out;
  Band band;
  out.elevation = elevation_spectrum(sums, N, sample_interval_s, options, band);
  const std::size_t bins = sums.ee.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.a1.assign(bins, nan);
  out.b1.assign(bins, nan);
  out.direction_deg.assign(bins, nan);
  out.spread_deg.assign(bins, nan);
  // The band's sums of a1 S and b1 S: a1 S_ee = C_eu sqrt(S_ee / (S_uu + S_vv)) (the common factors
  // of the Welch normalisation cancel in a1 and b1, so the raw sums serve).
  double a1_weighted = 0.0, b1_weighted = 0.0, weight = 0.0;
  for (std::size_t k = 0; k < bins; ++k) {
    const double denominator = std::sqrt(sums.ee[k] * (sums.uu[k] + sums.vv[k]));
    if (!(denominator > 0.0)) continue;
    out.a1[k] = sums.eu[k] / denominator;
    out.b1[k] = sums.ev[k] / denominator;
    out.direction_deg[k] = degrees(std::atan2(out.b1[k], out.a1[k]));
    out.spread_deg[k] = spread_deg(out.a1[k], out.b1[k]);
    if (static_cast<int>(k) >= band.low && static_cast<int>(k) <= band.high) {
      const double S = out.elevation.variance_density_m2_hz[k];
      a1_weighted += out.a1[k] * S;
      b1_weighted += out.b1[k] * S;
      weight += S;
    }
  }
  out.peak_direction_deg = out.direction_deg[band.peak];
  if (weight > 0.0) {
    out.mean_direction_deg = degrees(std::atan2(b1_weighted, a1_weighted));
    out.directional_spread_deg = spread_deg(a1_weighted / weight, b1_weighted / weight);
  } else {
    out.mean_direction_deg = out.directional_spread_deg = nan;
  }
  return out;
}

}  // namespace nearshore::ocean
