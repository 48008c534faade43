#pragma once
// The spectrum of a surface-elevation record (a gauge of a bake, a wave buoy, a runtime query at
// one point over time) and the sea-state parameters read from it (issue 45: "Hs, Tp and the mean
// periods at a gauge").
//
// Estimate: Welch's averaged periodogram (Welch 1967): the record cut into segments of `segment`
// samples overlapping by half, each with its mean removed (a set-up or a tide is not a wave) and
// a periodic Hann window w_j = (1 - cos(2 pi j / N)) / 2, then
//   S(f_k) = c_k dt / sum_j w_j^2 |sum_j w_j x_j exp(-2 pi i j k / N)|^2,   f_k = k / (N dt),
// averaged over the segments, c_k = 2 for 0 < f_k < the Nyquist frequency and 1 at 0 and at it:
// a one-sided variance density in m^2/Hz whose sum S df is the record's variance (Parseval, with
// the window's power divided out).
//
// Parameters (the IAHR/PIANC list of sea-state parameters, 1986; the names SWAN and WAVEWATCH III
// print), from the moments m_n = sum_k f_k^n S(f_k) df over the band [min, max] (default: the first
// bin above 0 to the Nyquist frequency):
//   Hm0  = 4 sqrt(m0)            significant wave height, spectral (m)
//   Tm01 = m0 / m1               mean period (s)
//   Tm02 = sqrt(m0 / m2)         mean zero-crossing period (s)
//   Tp   = 1 / f_p               peak period: f_p the largest bin's frequency, refined by the
//                                parabola through the logarithms of it and its two neighbours
//                                (half a bin at most)
// Thread-safe; FFTW plans are made under the ocean library's planner lock.
#include <span>
#include <vector>

namespace nearshore::ocean {

struct RecordSpectrumOptions {
  /// Samples per Welch segment; 0: the largest power of two not above a quarter of the record (about
  /// seven half-overlapping segments), at least 16. A longer segment resolves finer frequencies
  /// (df = 1 / (segment dt)) with fewer segments to average.
  int segment_samples = 0;
  double min_frequency_hz = 0.0;  ///< moments and peak from here (0: the first bin above 0)
  double max_frequency_hz = 0.0;  ///< to here (0: the Nyquist frequency, 1 / (2 dt))
};

struct RecordSpectrum {
  std::vector<double> frequency_hz;            ///< f_k = k df, k = 0 .. N/2
  std::vector<double> variance_density_m2_hz;  ///< S(f_k), one-sided
  double frequency_resolution_hz = 0.0;        ///< df = 1 / (N dt)
  int segment_samples = 0;                     ///< N
  int segment_count = 0;
  double significant_height_hm0_m = 0.0;
  double peak_period_s = 0.0;
  double mean_period_tm01_s = 0.0;
  double zero_crossing_period_tm02_s = 0.0;
};

/// The directions of a sea at one point from its elevation and its horizontal flux (or velocity)
/// recorded together: the PUV method (a pressure gauge and a current meter, or a gauge of a bake
/// with its P and Q). Welch's cross-spectra (the same segments and window as record_spectrum) of
/// eta with the flux's components give the first-order directional Fourier coefficients of the
/// directional spectrum D(f, theta) (Longuet-Higgins, Cartwright & Smith 1963; Kuik, van Vledder &
/// Holthuijsen 1988, J. Phys. Oceanogr. 18, eq. 2-6):
///   a1(f) = C_eu(f) / sqrt(S_ee(f) (S_uu(f) + S_vv(f))),   b1(f) = C_ev(f) / sqrt(S_ee (S_uu + S_vv))
/// with C the co-spectrum (the real part of the cross-spectrum). Linear waves travelling towards
/// theta carry u = G(f) eta cos(theta), v = G(f) eta sin(theta) in phase with eta, so a1 = cos(theta),
/// b1 = sin(theta) whatever the transfer G (a flux or a velocity, any depth). Then
///   direction(f) = atan2(b1, a1),   spread(f) = sqrt(2 (1 - sqrt(a1^2 + b1^2)))   (radians)
/// and over the band (the moments' band of record_spectrum), weighting by S_ee:
///   mean direction = atan2(sum b1 S_ee, sum a1 S_ee),  spread from the weighted a1, b1 alike;
///   peak direction = direction(f) at the peak bin.
/// Directions are those the waves travel TOWARDS, degrees counter-clockwise from the +x axis (east
/// of the grid), in (-180, 180]: the convention of the case files' direction_deg (docs/commands/
/// bake.md). Where the flux or the elevation holds no variance at a bin, its direction is NaN.
struct DirectionalRecordSpectrum {
  RecordSpectrum elevation;              ///< record_spectrum of the elevation alone, bit for bit
  std::vector<double> a1, b1;            ///< per bin of elevation.frequency_hz
  std::vector<double> direction_deg;     ///< per bin: atan2(b1, a1), travel, counter-clockwise from east
  std::vector<double> spread_deg;        ///< per bin: Kuik's circular spread
  double peak_direction_deg = 0.0;       ///< at the peak bin (the largest S_ee in the band)
  double mean_direction_deg = 0.0;       ///< over the band, S_ee-weighted
  double directional_spread_deg = 0.0;   ///< over the band, S_ee-weighted
};

/// Welch's spectrum of `elevation_m` sampled every `sample_interval_s` and its parameters. Throws
/// nearshore::Error naming the parameter when the record is shorter than 16 samples or longer
/// than 2^30, the interval
/// is not positive and finite, a sample is not finite, or the band holds no bin.
RecordSpectrum record_spectrum(std::span<const double> elevation_m, double sample_interval_s,
                               const RecordSpectrumOptions& options = {});

/// record_spectrum of `elevation_m` and the directions of the sea from `flux_x` and `flux_y` (east
/// and north components of a depth-integrated flux in m^2/s or of a velocity in m/s, sampled with
/// the elevation). Throws nearshore::Error as record_spectrum does, and naming flux_x or flux_y when
/// their lengths differ from the elevation's or a sample is not finite.
DirectionalRecordSpectrum directional_record_spectrum(std::span<const double> elevation_m, std::span<const double> flux_x,
                                                      std::span<const double> flux_y, double sample_interval_s,
                                                      const RecordSpectrumOptions& options = {});

}  // namespace nearshore::ocean
