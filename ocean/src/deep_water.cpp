#include "nearshore/ocean/deep_water.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstring>
#include <fstream>
#include <iterator>
#include <numbers>
#include <mutex>
#include <random>
#include <span>

#include <fftw3.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "nearshore/ocean/sea_state_builder.hpp"
#include "nearshore/core/error.hpp"
#include "fftw_planner.hpp"

namespace nearshore::ocean {

// A runtime builds a new field on one thread while another synthesises from its own.
std::mutex& detail::fftw_planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

namespace {

using detail::fftw_planner_mutex;

constexpr double kPi = std::numbers::pi;
const char* const kSubject = "deep-water specification";


/// The channels one synthesis fills, each the real field Re sum_k m(k) c_k e^{ik.x} of one
/// multiplier m(k) (see deep_water.hpp).
enum Channel : int {
  kElevation, kDisplacementX, kDisplacementY, kSlopeX, kSlopeY,
  kDisplacementXX, kDisplacementYY, kDisplacementXY, kFluxX, kFluxY, kChannelCount
};

/// m(k) = i^imaginary * real_multiplier(k). Every multiplier but the fluxes' has
/// conj(m(-k)) = m(k), so the channel's half spectrum is m(k) (c_k + conj(c_-k)) / 2; the fluxes'
/// are odd and real, conj(m(-k)) = -m(k): m(k) (c_k - conj(c_-k)) / 2.
bool is_imaginary(int channel) { return channel >= kDisplacementX && channel <= kSlopeY; }
bool is_odd_real(int channel) { return channel == kFluxX || channel == kFluxY; }

double real_multiplier(int channel, double kx, double ky, double w) {
  const double k = std::hypot(kx, ky);
  if (!(k > 0.0)) return 0.0;
  switch (channel) {
    case kElevation: return 1.0;
    case kDisplacementX: return kx / k;
    case kDisplacementY: return ky / k;
    case kSlopeX: return kx;
    case kSlopeY: return ky;
    case kDisplacementXX: return -kx * kx / k;
    case kDisplacementYY: return -ky * ky / k;
    case kDisplacementXY: return -kx * ky / k;
    case kFluxX: return w * kx / (k * k);
    case kFluxY: return w * ky / (k * k);
    default: return 0.0;
  }
}

std::vector<float>& channel_storage(DeepWaterFrame& frame, int channel) {
  switch (channel) {
    case kElevation: return frame.surface_elevation_m;
    case kDisplacementX: return frame.displacement_x_m;
    case kDisplacementY: return frame.displacement_y_m;
    case kSlopeX: return frame.slope_x;
    case kSlopeY: return frame.slope_y;
    case kDisplacementXX: return frame.displacement_xx;
    case kDisplacementYY: return frame.displacement_yy;
    case kDisplacementXY: return frame.displacement_xy;
    case kFluxX: return frame.flux_x_m2_s;
    default: return frame.flux_y_m2_s;
  }
}

/// Signed lattice index of FFT position p (0..N-1): 0, 1, ..., N/2, -N/2+1, ..., -1.
int signed_index(int p, int n) { return p <= n / 2 ? p : p - n; }

void check(const DeepWaterSpecification& spec) {
  if (!spec.spectrum) throw Error(kSubject, "has no wavenumber spectrum", "set .spectrum (e.g. beaufort_preset(6).spectrum)");
  if (spec.tile_lengths_m.empty())
    throw Error(kSubject, "has no cascades", "set .tile_lengths_m, e.g. cascade_tile_lengths_m(1000, 4)");
  for (std::size_t i = 0; i < spec.tile_lengths_m.size(); ++i) {
    const double length = spec.tile_lengths_m[i];
    if (!(length > 0.0) || !std::isfinite(length) || (i > 0 && !(length < spec.tile_lengths_m[i - 1])))
      throw Error(kSubject, fmt::format("tile length {} of cascade {} is not positive or not below the one before", length, i),
                  "give strictly decreasing tile lengths in metres, largest first");
  }
  const int n = spec.grid_size;
  if (n < 8 || n > 4096 || (n & (n - 1)) != 0)
    throw Error(kSubject, fmt::format("grid size {} is not a power of two in [8, 4096]", n), "use 64, 128, 256 or 512");
  if (!(spec.choppiness >= 0.0) || !std::isfinite(spec.choppiness))
    throw Error(kSubject, fmt::format("choppiness {} is negative or not finite", spec.choppiness), "use 0 to 2 (1 is usual)");
  if (!(spec.loop_period_s >= 0.0) || !std::isfinite(spec.loop_period_s))
    throw Error(kSubject, fmt::format("loop period {} s is negative or not finite", spec.loop_period_s),
                "give T_loop > 0 s, or 0 for no exact looping");
}

/// 4-point Gauss-Legendre on [-1, 1] (A&S 25.4): the cell integrals of seed 001 eq. 16.
constexpr std::array<double, 4> kCellNode = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                             0.8611363115940526};
constexpr std::array<double, 4> kCellWeight = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                               0.3478548451374538};

/// The integral of Psi over the lattice cell of (nx, m) (side dk, centred on (nx, m) dk), within
/// the band: 4 x 4 Gauss points, or 8 x 8 sub-cells of them where the band's edge crosses the
/// cell, so the clipped cells of neighbouring cascades add up to the spectrum's variance.
double cell_variance_m2(const WavenumberSpectrum& spectrum, int nx, int m, double dk, const CascadeBand& band) {
  const double x0 = (nx - 0.5) * dk, x1 = (nx + 0.5) * dk, y0 = (m - 0.5) * dk, y1 = (m + 0.5) * dk;
  const double near_x = std::max({x0, -x1, 0.0}), near_y = std::max({y0, -y1, 0.0});
  const double nearest = std::hypot(near_x, near_y);
  const double farthest = std::hypot(std::max(std::abs(x0), std::abs(x1)), std::max(std::abs(y0), std::abs(y1)));
  if (farthest <= band.min_wavenumber_rad_m || nearest >= band.max_wavenumber_rad_m) return 0.0;
  const bool inside = nearest >= band.min_wavenumber_rad_m && farthest < band.max_wavenumber_rad_m;
  const int subdivisions = inside ? 1 : 8;
  const double sub = dk / subdivisions;
  double variance = 0.0;
  for (int p = 0; p < subdivisions; ++p)
    for (int q = 0; q < subdivisions; ++q)
      for (std::size_t a = 0; a < kCellNode.size(); ++a)
        for (std::size_t b = 0; b < kCellNode.size(); ++b) {
          const double kx = x0 + (p + 0.5 + 0.5 * kCellNode[a]) * sub, ky = y0 + (q + 0.5 + 0.5 * kCellNode[b]) * sub;
          const double k = std::hypot(kx, ky);
          if (k < band.min_wavenumber_rad_m || k >= band.max_wavenumber_rad_m) continue;
          variance += kCellWeight[a] * kCellWeight[b] * 0.25 * sub * sub * spectrum.density_m4(kx, ky);
        }
  return variance;
}

struct Cascade {
  CascadeBand band;
  int n = 0;
  double spacing_rad_m = 0.0;        // 2 pi / L
  std::vector<float> amplitude_m;    // N*N, FFT order [row = ky index][column = kx index]
  std::vector<double> phase_rad;     // N*N
  std::vector<double> frequency_rad_s;  // N*N
  std::vector<long long> harmonic;   // N*N, w = harmonic * 2 pi / T_loop when looping
  double variance_m2 = 0.0, slope_variance = 0.0;
  DeepWaterFrame frame;
  // FFTW buffers: one input (N x (N/2+1) complex) and one output (N x N real) per channel.
  std::array<fftwf_complex*, kChannelCount> input{};
  std::array<float*, kChannelCount> output{};
  std::vector<std::complex<float>> coefficient;  // c_k(t), N*N
  // On the half spectrum N x (N/2+1): (c_k + conj(c_-k))/2, (c_k - conj(c_-k))/2, and each
  // channel's real multiplier (see real_multiplier), precomputed once.
  std::vector<std::complex<float>> even_part, odd_part;
  std::array<std::vector<float>, kChannelCount> multiplier;
};

}  // namespace

struct DeepWaterField::Impl {
  DeepWaterSpecification spec;
  std::vector<Cascade> cascades;
  fftwf_plan plan = nullptr;  // one N x N c2r plan, executed on every channel's arrays
  double recorded_unresolved_slope_variance = 0.0;  // a field rebuilt from a record has no spectrum

  // What both constructors share once every cascade's lattice (n, spacing, amplitudes, phases,
  // frequencies, harmonics) is set: the variances, the FFTW buffers, the channels' multipliers,
  // the frames' sizes and the one plan.
  void prepare_synthesis();
  // c_k = sum_i weight_i a_k e^{i(phi_k - w_k t_i)} of one cascade, then its even and odd parts.
  void mix_coefficients(Cascade& cascade, std::span<const TimedWeight> times) const;
};

void DeepWaterField::Impl::prepare_synthesis() {
  for (Cascade& cascade : cascades) {
    const int n = cascade.n;
    const double dk = cascade.spacing_rad_m;
    const std::size_t cells = static_cast<std::size_t>(n) * n;
    cascade.variance_m2 = cascade.slope_variance = 0.0;
    for (int row = 0; row < n; ++row)
      for (int column = 0; column < n; ++column) {
        const double a = cascade.amplitude_m[static_cast<std::size_t>(row) * n + column];
        const double k2 = (std::pow(signed_index(row, n), 2) + std::pow(signed_index(column, n), 2)) * dk * dk;
        cascade.variance_m2 += 0.5 * a * a;
        cascade.slope_variance += 0.5 * a * a * k2;
      }
    for (int channel = 0; channel < kChannelCount; ++channel) {
      cascade.input[channel] = fftwf_alloc_complex(static_cast<std::size_t>(n) * (n / 2 + 1));
      cascade.output[channel] = fftwf_alloc_real(cells);
    }
    cascade.coefficient.resize(cells);
    const std::size_t half_cells = static_cast<std::size_t>(n) * (n / 2 + 1);
    cascade.even_part.resize(half_cells);
    cascade.odd_part.resize(half_cells);
    for (int channel = 0; channel < kChannelCount; ++channel) {
      std::vector<float>& multiplier = cascade.multiplier[channel];
      multiplier.resize(half_cells);
      for (int row = 0; row < n; ++row)
        for (int column = 0; column <= n / 2; ++column)
          multiplier[static_cast<std::size_t>(row) * (n / 2 + 1) + column] = static_cast<float>(real_multiplier(
              channel, signed_index(column, n) * dk, signed_index(row, n) * dk,
              cascade.frequency_rad_s[static_cast<std::size_t>(row) * n + column]));
    }
    cascade.frame.grid_size = n;
    cascade.frame.tile_length_m = cascade.band.tile_length_m;
  }
  // One plan for all: same size, and fftwf_alloc_* gives every array the same alignment.
  const Cascade& first = cascades.front();
  const int n = first.n;
  {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    plan = fftwf_plan_dft_c2r_2d(n, n, first.input[0], first.output[0], FFTW_ESTIMATE);
  }
  if (!plan) throw Error(kSubject, fmt::format("FFTW could not plan a {0} x {0} transform", n), "use a smaller grid size");
}

std::vector<double> cascade_tile_lengths_m(double largest_tile_m, int count, double ratio) {
  if (!(largest_tile_m > 0.0) || count < 1 || !(ratio > 1.0))
    throw Error("cascade tile lengths", fmt::format("largest {} m, {} cascades, ratio {}", largest_tile_m, count, ratio),
                "give a largest tile > 0 m, at least 1 cascade and a ratio > 1");
  std::vector<double> lengths;
  for (int i = 0; i < count; ++i) lengths.push_back(largest_tile_m / std::pow(ratio, i));
  return lengths;
}

std::vector<double> cascade_tile_lengths_for_m(const WavenumberSpectrum& spectrum, int grid_size, int count,
                                               double shortest_wavelength_m) {
  if (grid_size < 8 || count < 1 || !(shortest_wavelength_m > 0.0))
    throw Error("cascade tile lengths", fmt::format("grid {} , {} cascades, shortest wavelength {} m", grid_size, count,
                                                    shortest_wavelength_m),
                "give a grid of at least 8, at least 1 cascade and a shortest wavelength > 0 m");
  const double largest = 10.0 * 2.0 * kPi / spectrum.peak_wavenumber_rad_m();
  if (count == 1) return {largest};
  const double smallest = shortest_wavelength_m * grid_size / 2.0;
  const double ratio = std::max(2.0, std::pow(largest / smallest, 1.0 / (count - 1)));
  return cascade_tile_lengths_m(largest, count, ratio);
}

double jacobian(double dxx, double dyy, double dxy, double lambda) {
  // seed 000 eq. (3.39)-(3.44); dD_x/dy = dD_y/dx because D is a gradient field.
  return (1.0 + lambda * dxx) * (1.0 + lambda * dyy) - (lambda * dxy) * (lambda * dxy);
}

FoamFeatures foam_features(double j, double threshold) {
  return {std::clamp(threshold - j, 0.0, 1.0), j};  // eq. (3.45), (3.47)
}

double turbulent_foam(double previous, double breaking, double dt_s, double decay_time_s) {
  const double alpha = decay_time_s > 0.0 ? std::exp(-dt_s / decay_time_s) : 0.0;
  return std::clamp(alpha * previous + breaking, 0.0, 1.0);
}

DeepWaterField::DeepWaterField(const DeepWaterSpecification& spec) : impl_(std::make_unique<Impl>()) {
  check(spec);
  impl_->spec = spec;
  const WavenumberSpectrum& spectrum = *spec.spectrum;
  const int n = spec.grid_size;
  const int count = static_cast<int>(spec.tile_lengths_m.size());
  const double fundamental_rad_s = spec.loop_period_s > 0.0 ? 2.0 * kPi / spec.loop_period_s : 0.0;
  std::mt19937_64 generator(spec.seed);

  impl_->cascades.resize(count);
  for (int i = 0; i < count; ++i) {
    Cascade& cascade = impl_->cascades[i];
    const double length = spec.tile_lengths_m[i];
    cascade.n = n;
    cascade.spacing_rad_m = 2.0 * kPi / length;
    // 1. The band: geometric means of the neighbours' lattice limits (see deep_water.hpp).
    auto boundary = [&](int coarse) {
      return std::sqrt(kPi * n / spec.tile_lengths_m[coarse] * 2.0 * kPi / spec.tile_lengths_m[coarse + 1]);
    };
    cascade.band = {length, i == 0 ? 0.0 : boundary(i - 1),
                    i + 1 == count ? (n / 2 - 1) * cascade.spacing_rad_m : boundary(i)};
    if (!(cascade.band.max_wavenumber_rad_m > cascade.band.min_wavenumber_rad_m))
      throw Error(kSubject, fmt::format("cascade {} (L = {} m) is left with an empty wavenumber band", i, length),
                  "use a smaller ratio between consecutive tile lengths or a larger grid size");

    // 2. Phases: one draw per lattice point in FFT order, whether or not it is in the band, so
    //    the phases of a cascade do not change when its band does.
    const std::size_t cells = static_cast<std::size_t>(n) * n;
    cascade.phase_rad.resize(cells);
    for (double& phase : cascade.phase_rad) phase = phase_from_draw_rad(generator());

    // 3. Amplitudes by the cell integral of Psi restricted to the band (seed 001 eq. 16), 4 x 4
    //    Gauss points per cell; frequencies from the dispersion relation, quantised when looping.
    cascade.amplitude_m.assign(cells, 0.0f);
    cascade.frequency_rad_s.assign(cells, 0.0);
    cascade.harmonic.assign(cells, -1);
    const double dk = cascade.spacing_rad_m;
    const CascadeBand band = cascade.band;
    std::vector<double> variance(cells, 0.0);
    tbb::parallel_for(0, n, [&](int row) {
      const int m = signed_index(row, n);
      for (int column = 0; column < n; ++column) {
        const int nx = signed_index(column, n);
        if (std::abs(m) == n / 2 || std::abs(nx) == n / 2 || (m == 0 && nx == 0)) continue;  // Nyquist and mean
        const std::size_t index = static_cast<std::size_t>(row) * n + column;
        variance[index] = cell_variance_m2(spectrum, nx, m, dk, band);
        const double w = frequency_from_wavenumber(std::hypot(nx * dk, m * dk), spec.still_water_depth_m);
        if (fundamental_rad_s > 0.0) {
          cascade.harmonic[index] = std::llround(w / fundamental_rad_s);
          cascade.frequency_rad_s[index] = static_cast<double>(cascade.harmonic[index]) * fundamental_rad_s;
        } else {
          cascade.frequency_rad_s[index] = w;
        }
      }
    });
    // Opposite wavevectors k and -k make a partly standing wave whose spatial variance swings
    // with time (the cross term a_k a_-k cos(2 w t - ...)). Each pair's variance goes to the one
    // that holds more of it (the down-wind one): the variance is kept exactly, and by Parseval
    // every frame's spatial variance is then sum a^2/2. Only cells cut by the cross-wind line
    // and spectra with an up-wind lobe (cos^2s, WindHalfPlane::kBothWays) have such pairs.
    for (int row = 0; row < n; ++row)
      for (int column = 0; column < n; ++column) {
        const std::size_t index = static_cast<std::size_t>(row) * n + column;
        const std::size_t mirror = static_cast<std::size_t>((n - row) % n) * n + (n - column) % n;
        if (index >= mirror) continue;
        double& own = variance[index];
        double& opposite = variance[mirror];
        if (own >= opposite) {
          own += opposite;
          opposite = 0.0;
        } else {
          opposite += own;
          own = 0.0;
        }
      }
    for (std::size_t index = 0; index < cells; ++index)
      cascade.amplitude_m[index] = static_cast<float>(std::sqrt(2.0 * std::max(variance[index], 0.0)));
  }
  // 4. Variances, FFTW buffers, multipliers and the plan (shared with a field rebuilt from a record).
  impl_->prepare_synthesis();
}

DeepWaterField::DeepWaterField(const RecordedDeepWater& recorded) : impl_(std::make_unique<Impl>()) {
  const char* const subject = "recorded deep-water field";
  const std::string fix = "rebuild it from the coefficient files of one bake (sequence/deep_water_section.hpp)";
  if (recorded.cascades.empty()) throw Error(subject, "has no cascades", fix);
  const int n = recorded.cascades.front().grid_size;
  if (n < 8 || n > 4096 || (n & (n - 1)) != 0)
    throw Error(subject, fmt::format("cascade 0 has a grid size {} that is not a power of two in [8, 4096]", n), fix);
  if (!(recorded.loop_period_s >= 0.0) || !std::isfinite(recorded.loop_period_s) || !(recorded.choppiness >= 0.0))
    throw Error(subject, fmt::format("loop period {} s or choppiness {} is negative or not finite",
                                     recorded.loop_period_s, recorded.choppiness), fix);
  DeepWaterSpecification& spec = impl_->spec;
  spec.grid_size = n;
  spec.still_water_depth_m = recorded.still_water_depth_m;
  spec.loop_period_s = recorded.loop_period_s;
  spec.choppiness = recorded.choppiness;
  spec.seed = recorded.seed;
  impl_->recorded_unresolved_slope_variance = recorded.unresolved_slope_variance;
  const std::size_t cells = static_cast<std::size_t>(n) * n;
  impl_->cascades.resize(recorded.cascades.size());
  for (std::size_t i = 0; i < recorded.cascades.size(); ++i) {
    const RecordedCascade& in = recorded.cascades[i];
    if (in.grid_size != n)
      throw Error(subject, fmt::format("cascade {} has N = {} but cascade 0 has N = {}", i, in.grid_size, n),
                  "give every cascade the same grid size (one FFT plan serves them all)");
    if (!(in.tile_length_m > 0.0) || !std::isfinite(in.tile_length_m) || in.amplitude_m.size() != cells ||
        in.phase_rad.size() != cells || in.angular_frequency_rad_s.size() != cells || in.harmonic.size() != cells)
      throw Error(subject, fmt::format("cascade {} has tile length {} m or arrays that are not {} x {}", i,
                                       in.tile_length_m, n, n), fix);
    Cascade& cascade = impl_->cascades[i];
    cascade.n = n;
    cascade.spacing_rad_m = 2.0 * kPi / in.tile_length_m;
    const double nyquist = (n / 2 - 1) * cascade.spacing_rad_m;
    const bool band_known = in.max_wavenumber_rad_m > in.min_wavenumber_rad_m;
    cascade.band = {in.tile_length_m, band_known ? in.min_wavenumber_rad_m : 0.0,
                    band_known ? in.max_wavenumber_rad_m : nyquist};
    cascade.amplitude_m = in.amplitude_m;
    cascade.phase_rad = in.phase_rad;
    cascade.frequency_rad_s = in.angular_frequency_rad_s;
    cascade.harmonic = in.harmonic;
    spec.tile_lengths_m.push_back(in.tile_length_m);
  }
  impl_->prepare_synthesis();
}

RecordedDeepWater DeepWaterField::record() const {
  RecordedDeepWater recorded;
  recorded.still_water_depth_m = impl_->spec.still_water_depth_m;
  recorded.loop_period_s = impl_->spec.loop_period_s;
  recorded.choppiness = impl_->spec.choppiness;
  recorded.seed = impl_->spec.seed;
  recorded.unresolved_slope_variance = unresolved_slope_variance();
  for (const Cascade& cascade : impl_->cascades)
    recorded.cascades.push_back({cascade.n, cascade.band.tile_length_m, cascade.band.min_wavenumber_rad_m,
                                 cascade.band.max_wavenumber_rad_m, cascade.amplitude_m, cascade.phase_rad,
                                 cascade.frequency_rad_s, cascade.harmonic});
  return recorded;
}

DeepWaterField::~DeepWaterField() {
  for (Cascade& cascade : impl_->cascades)
    for (int channel = 0; channel < kChannelCount; ++channel) {
      fftwf_free(cascade.input[channel]);
      fftwf_free(cascade.output[channel]);
    }
  if (impl_->plan) {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftwf_destroy_plan(impl_->plan);
  }
}

const DeepWaterSpecification& DeepWaterField::specification() const { return impl_->spec; }
int DeepWaterField::cascade_count() const { return static_cast<int>(impl_->cascades.size()); }
CascadeBand DeepWaterField::band(int cascade) const { return impl_->cascades.at(cascade).band; }
double DeepWaterField::cascade_variance_m2(int cascade) const { return impl_->cascades.at(cascade).variance_m2; }
double DeepWaterField::cascade_slope_variance(int cascade) const { return impl_->cascades.at(cascade).slope_variance; }
const DeepWaterFrame& DeepWaterField::frame(int cascade) const { return impl_->cascades.at(cascade).frame; }

double DeepWaterField::significant_wave_height_m() const {
  double variance = 0.0;
  for (const Cascade& cascade : impl_->cascades) variance += cascade.variance_m2;
  return 4.0 * std::sqrt(variance);
}

double DeepWaterField::unresolved_slope_variance() const {
  if (!impl_->spec.spectrum) return impl_->recorded_unresolved_slope_variance;
  const CascadeBand last = impl_->cascades.back().band;
  return impl_->spec.spectrum->moment_between(last.max_wavenumber_rad_m, impl_->spec.spectrum->highest_wavenumber_rad_m(), 2);
}

void DeepWaterField::Impl::mix_coefficients(Cascade& cascade, std::span<const TimedWeight> times) const {
  const int n = cascade.n;
  const int half = n / 2 + 1;
  const double loop_period_s = spec.loop_period_s;
  // 1. c_k = sum_i weight_i a e^{i(phi - w t_i)}. With a loop, w t = 2 pi frac(h t / T) exactly
  //    periodic in T (reduced in double before the float exponential).
  tbb::parallel_for(0, n, [&](int row) {
    for (int column = 0; column < n; ++column) {
      const std::size_t index = static_cast<std::size_t>(row) * n + column;
      const float a = cascade.amplitude_m[index];
      std::complex<float> sum = 0.0f;
      if (a != 0.0f)
        for (const TimedWeight& timed : times) {
          double advance_rad;
          if (loop_period_s > 0.0) {
            const double cycles = static_cast<double>(cascade.harmonic[index]) * timed.time_s / loop_period_s;
            advance_rad = 2.0 * kPi * (cycles - std::floor(cycles));
          } else {
            advance_rad = std::fmod(cascade.frequency_rad_s[index] * timed.time_s, 2.0 * kPi);
          }
          sum += static_cast<float>(timed.weight) *
                 std::polar(a, static_cast<float>(cascade.phase_rad[index] - advance_rad));
        }
      cascade.coefficient[index] = sum;
    }
  });
  // 2. The even and odd parts (c_k +- conj(c_-k)) / 2 on the half spectrum.
  tbb::parallel_for(0, n, [&](int row) {
    const int mirror_row = (n - row) % n;
    for (int column = 0; column < half; ++column) {
      const std::complex<float> own = cascade.coefficient[static_cast<std::size_t>(row) * n + column];
      const std::complex<float> opposite =
          std::conj(cascade.coefficient[static_cast<std::size_t>(mirror_row) * n + (n - column) % n]);
      const std::size_t j = static_cast<std::size_t>(row) * half + column;
      cascade.even_part[j] = 0.5f * (own + opposite);
      cascade.odd_part[j] = 0.5f * (own - opposite);
    }
  });
}

void DeepWaterField::synthesise(double time_s, bool with_flux) {
  const TimedWeight one{time_s, 1.0};
  synthesise(std::span<const TimedWeight>(&one, 1), with_flux);
}

void DeepWaterField::synthesise(std::span<const TimedWeight> times, bool with_flux) {
  std::vector<DeepWaterFrame> frames;
  frames.reserve(impl_->cascades.size());
  for (Cascade& cascade : impl_->cascades) frames.push_back(std::move(cascade.frame));
  synthesise_into(times, frames, with_flux);
  for (std::size_t i = 0; i < frames.size(); ++i) impl_->cascades[i].frame = std::move(frames[i]);
}

void DeepWaterField::synthesise_into(std::span<const TimedWeight> times, std::vector<DeepWaterFrame>& frames,
                                     bool with_flux) {
  const int channels = with_flux ? kChannelCount : kFluxX;
  frames.resize(impl_->cascades.size());
  for (std::size_t c = 0; c < impl_->cascades.size(); ++c) {
    Cascade& cascade = impl_->cascades[c];
    DeepWaterFrame& frame = frames[c];
    const int n = cascade.n;
    frame.grid_size = n;
    frame.tile_length_m = cascade.band.tile_length_m;
    impl_->mix_coefficients(cascade, times);
    // 3. Per channel: H_m = m(k) times the even (or, for the fluxes, odd) part, then c2r.
    tbb::parallel_for(0, channels, [&](int channel) {
      fftwf_complex* input = cascade.input[channel];
      const std::vector<std::complex<float>>& part = is_odd_real(channel) ? cascade.odd_part : cascade.even_part;
      const std::vector<float>& multiplier = cascade.multiplier[channel];
      const bool imaginary = is_imaginary(channel);
      const std::size_t half_cells = part.size();
      for (std::size_t j = 0; j < half_cells; ++j) {
        const float r = multiplier[j];
        if (imaginary) {  // i r (x + i y) = -r y + i r x
          input[j][0] = -r * part[j].imag();
          input[j][1] = r * part[j].real();
        } else {
          input[j][0] = r * part[j].real();
          input[j][1] = r * part[j].imag();
        }
      }
      fftwf_execute_dft_c2r(impl_->plan, input, cascade.output[channel]);
      std::vector<float>& storage = channel_storage(frame, channel);
      storage.assign(cascade.output[channel], cascade.output[channel] + static_cast<std::size_t>(n) * n);
    });
    if (!with_flux) {
      frame.flux_x_m2_s.clear();
      frame.flux_y_m2_s.clear();
    }
  }
}

SurfaceSample DeepWaterField::sample(double x_m, double y_m) const {
  SurfaceSample total;
  for (const Cascade& cascade : impl_->cascades) {
    const DeepWaterFrame& frame = cascade.frame;
    if (frame.surface_elevation_m.empty()) continue;
    const int n = frame.grid_size;
    const double u = x_m / frame.tile_length_m * n, v = y_m / frame.tile_length_m * n;
    const double u0 = std::floor(u), v0 = std::floor(v);
    const double fu = u - u0, fv = v - v0;
    auto wrap = [n](double p) { return static_cast<int>(((static_cast<long long>(p) % n) + n) % n); };
    const int c0 = wrap(u0), c1 = (c0 + 1) % n, r0 = wrap(v0), r1 = (r0 + 1) % n;
    auto bilinear = [&](const std::vector<float>& field) {
      auto at = [&](int r, int c) { return static_cast<double>(field[static_cast<std::size_t>(r) * n + c]); };
      return (1 - fv) * ((1 - fu) * at(r0, c0) + fu * at(r0, c1)) + fv * ((1 - fu) * at(r1, c0) + fu * at(r1, c1));
    };
    total.surface_elevation_m += bilinear(frame.surface_elevation_m);
    total.displacement_x_m += bilinear(frame.displacement_x_m);
    total.displacement_y_m += bilinear(frame.displacement_y_m);
    total.slope_x += bilinear(frame.slope_x);
    total.slope_y += bilinear(frame.slope_y);
    total.displacement_xx += bilinear(frame.displacement_xx);
    total.displacement_yy += bilinear(frame.displacement_yy);
    total.displacement_xy += bilinear(frame.displacement_xy);
  }
  return total;
}

FoamStatistics foam_statistics(const DeepWaterField& field, int sample_count, double threshold) {
  // R2 sequence (Roberts 2018): x_j = frac(j / phi2), y_j = frac(j / phi2^2), phi2 the plastic number.
  constexpr double plastic = 1.32471795724474602596;
  const double largest_tile_m = field.specification().tile_lengths_m.front();
  const double lambda = field.specification().choppiness;
  FoamStatistics statistics;
  long long breaking_count = 0;
  double breaking_sum = 0.0;
  for (int j = 1; j <= sample_count; ++j) {
    const double u = std::fmod(j / plastic, 1.0), v = std::fmod(j / (plastic * plastic), 1.0);
    const SurfaceSample s = field.sample(u * largest_tile_m, v * largest_tile_m);
    const double jac = jacobian(s.displacement_xx, s.displacement_yy, s.displacement_xy, lambda);
    const FoamFeatures foam = foam_features(jac, threshold);
    breaking_count += foam.breaking > 0.0;
    breaking_sum += foam.breaking;
    statistics.lowest_jacobian = std::min(statistics.lowest_jacobian, jac);
  }
  statistics.coverage = static_cast<double>(breaking_count) / std::max(sample_count, 1);
  statistics.mean_breaking = breaking_sum / std::max(sample_count, 1);
  return statistics;
}

std::vector<LatticeWave> DeepWaterField::lattice_waves(double min_amplitude_m) const {
  std::vector<LatticeWave> waves;
  for (const Cascade& cascade : impl_->cascades) {
    const int n = cascade.n;
    for (int row = 0; row < n; ++row)
      for (int column = 0; column < n; ++column) {
        const std::size_t index = static_cast<std::size_t>(row) * n + column;
        const double a = cascade.amplitude_m[index];
        if (a <= 0.0 || a < min_amplitude_m) continue;
        const double kx = signed_index(column, n) * cascade.spacing_rad_m, ky = signed_index(row, n) * cascade.spacing_rad_m;
        waves.push_back(
            {{a, cascade.frequency_rad_s[index], std::atan2(ky, kx), cascade.phase_rad[index]}, kx, ky});
      }
  }
  return waves;
}

SeaState DeepWaterField::wave_components(double min_amplitude_m) const {
  SeaState sea;
  sea.loop_period_s = impl_->spec.loop_period_s;
  sea.seed = impl_->spec.seed;
  for (const LatticeWave& lattice : lattice_waves(min_amplitude_m)) sea.components.push_back(lattice.wave);
  return sea;
}

double surface_elevation_m(const std::vector<LatticeWave>& waves, double x_m, double y_m, double time_s) {
  double eta = 0.0;
  for (const LatticeWave& lattice : waves) {
    const WaveComponent& c = lattice.wave;
    eta += c.amplitude_m * std::cos(lattice.wavenumber_x_rad_m * x_m + lattice.wavenumber_y_rad_m * y_m -
                                    c.angular_frequency_rad_s * time_s + c.phase_rad);
  }
  return eta;
}

CascadeLattice DeepWaterField::lattice(int cascade) const {
  const Cascade& c = impl_->cascades.at(static_cast<std::size_t>(cascade));
  return {c.n, c.band.tile_length_m, c.amplitude_m, c.phase_rad, c.frequency_rad_s, c.harmonic};
}

}  // namespace nearshore::ocean
