#pragma once
// The deep-water FFT field (Tessendorf 1999; seed 000 section 3.1; seed 001 section 2): outside
// the harbour the sea is statistically uniform, and a few periodic tiles synthesised by inverse
// FFT show it. Issue 5.
//
// Convention (the same as WaveComponent, so the harbour's wave maker and this field are the
// same waves): on each cascade's lattice k = (n, m) 2 pi / L, |n|, |m| < N/2,
//   eta(x, t)   = sum_k a_k cos(k . x - w_k t + phi_k) = Re sum_k c_k(t) e^{i k.x},  c_k = a_k e^{i(phi_k - w_k t)}
//   D(x, t)     = Re sum_k i (k/|k|) c_k e^{i k.x}       choppy displacement, x -> x + lambda D
//                 (seed 000 eq. 3.5-3.6 with the sign that sharpens crests, as Gerstner waves do:
//                  the literal -i of eq. 3.6 with lambda > 0 would sharpen troughs)
//   grad eta    = Re sum_k i k c_k e^{i k.x}
//   dD_a/dx_b   = -Re sum_k (k_a k_b / |k|) c_k e^{i k.x}
//   J           = (1 + lambda dDx/dx)(1 + lambda dDy/dy) - (lambda dDx/dy)^2     (eq. 3.39-3.44; the
//                 seed's kappa = eps / L_i^2 converts its texture units, ours are metres already)
//   flux P, Q   = Re sum_k (w_k / |k|) (k/|k|) c_k e^{i k.x}   (depth-integrated linear velocity, m^2/s)
// a_k = sqrt(2 * integral of Psi over the lattice cell of k, within the cascade's band) (seed 001
// eq. 16); phi_k uniform from std::mt19937_64(seed); w_k from w^2 = g k tanh(k d), rounded to the
// nearest whole multiple of 2 pi / T_loop when looping, so eta(t + T_loop) = eta(t) exactly.
//
// Cascades (seed 000 eq. 3.7): tiles of decreasing length L_0 > L_1 > ...; cascade i keeps the
// wavenumbers |k| in [k_i, k_{i+1}) and no other, so no variance is counted twice. The boundary
// k_{i+1} is the geometric mean of cascade i's Nyquist wavenumber pi N / L_i and cascade i+1's
// fundamental 2 pi / L_{i+1}: equal margins, in octaves, from both lattices' limits. The last
// cascade ends at (N/2 - 1) 2 pi / L; the slope variance beyond it is reported for the lighting
// (Bruneton et al. 2010).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <vector>

#include "nearshore/ocean/spectrum_wavenumber.hpp"
#include "nearshore/ocean/wave_component.hpp"

namespace nearshore::ocean {

struct DeepWaterSpecification {
  std::shared_ptr<const WavenumberSpectrum> spectrum;  ///< required
  std::vector<double> tile_lengths_m;  ///< one per cascade, strictly decreasing (cascade_tile_lengths_m)
  int grid_size = 256;                 ///< N: samples per tile side, a power of two in [8, 4096]
  double still_water_depth_m = 0.0;    ///< <= 0: deep water; else finite-depth dispersion (the harbour's offshore depth)
  double loop_period_s = 0.0;          ///< T_loop (s); 0 = no exact looping
  double choppiness = 1.0;             ///< lambda of eq. 3.5 (dimensionless, 0 = no horizontal displacement)
  std::uint64_t seed = 1;              ///< phases (recorded in every output)
};

/// L_i = L_0 / ratio^i (seed 000 eq. 3.7 with b = L_{count-1} and ratio 2). A non-integer ratio
/// (e.g. 3.7) hides the tiling better: the tiles' repeats then never line up.
std::vector<double> cascade_tile_lengths_m(double largest_tile_m, int count, double ratio = 4.0);

/// Tile lengths that fit a spectrum: the largest tile holds 10 peak wavelengths (so the peak sits
/// 10 lattice steps from the origin and the energy below half a step is negligible), the last
/// cascade's Nyquist wavelength 2 L / N is `shortest_wavelength_m`, and the ratio between
/// consecutive tiles is constant (at least 2; with fewer octaves to cover, the shortest
/// resolved wave is shorter than asked).
std::vector<double> cascade_tile_lengths_for_m(const WavenumberSpectrum& spectrum, int grid_size, int count,
                                               double shortest_wavelength_m);

/// The wavenumber band of one cascade (rad/m).
struct CascadeBand {
  double tile_length_m = 0.0;
  double min_wavenumber_rad_m = 0.0;  ///< inclusive
  double max_wavenumber_rad_m = 0.0;  ///< exclusive
};

/// One cascade at one time: N x N samples, row-major, row j at y = j L / N (row 0 south),
/// column i at x = i L / N (column 0 west); the tile repeats with period L in x and y.
struct DeepWaterFrame {
  int grid_size = 0;
  double tile_length_m = 0.0;
  std::vector<float> surface_elevation_m;      ///< eta
  std::vector<float> displacement_x_m;         ///< D_x (multiply by lambda for the choppy offset)
  std::vector<float> displacement_y_m;         ///< D_y
  std::vector<float> slope_x, slope_y;         ///< d eta / dx, d eta / dy
  std::vector<float> displacement_xx;          ///< dD_x/dx
  std::vector<float> displacement_yy;          ///< dD_y/dy
  std::vector<float> displacement_xy;          ///< dD_x/dy = dD_y/dx
  std::vector<float> flux_x_m2_s, flux_y_m2_s; ///< only with `with_flux` (the baked tile set)
};

/// Foam features from the Jacobian, seed 000 eq. (3.45)-(3.47): f_b = clamp(J_b - J, 0, 1).
/// The seed's J_b = -0.2 belongs to its J in texture units (kappa = eps / L_i^2, eq. 3.40) and a
/// tuned eps. Here D is in metres and lambda = 1 is the physical (Gerstner) displacement, under
/// which a single wave has J = 1 - a k cos(phase): it breaks at the Stokes limit a k = 0.443, i.e.
/// J_b = 0.557 (kStokesBreakingJacobian, the default). Measured over the Beaufort presets this
/// gives a coverage rising from 0.011 % (force 1) to 1.5 % (force 12); J_b = -0.2 at lambda = 1
/// gives none at all. Both are parameters.
inline constexpr double kStokesBreakingJacobian = 1.0 - 0.443;
struct FoamFeatures {
  double breaking = 0.0;      ///< f_b = clamp(J_b - J, 0, 1)
  double stretching = 1.0;    ///< f_s = J
};
double jacobian(double displacement_xx, double displacement_yy, double displacement_xy, double choppiness);
FoamFeatures foam_features(double jacobian_value, double breaking_threshold = kStokesBreakingJacobian);
/// f_t after one step of dt (s): f_t = exp(-dt / decay_time) f_t_previous + f_b, clamped to [0, 1].
/// Seed 000 eq. (3.46) writes f_t^t = alpha f_b^{t-1} + f_b^t; the recursive form keeps the
/// decaying trail behind a crest for longer than one frame, with alpha = exp(-dt / decay_time).
double turbulent_foam(double previous_turbulent, double breaking, double dt_s, double decay_time_s);

class DeepWaterField;

/// Foam statistics of the last synthesised frame, over `sample_count` points of the largest
/// tile placed on a 2-D Kronecker (R2) low-discrepancy sequence, so they never alias with the
/// smaller tiles' periods. J uses the field's choppiness.
struct FoamStatistics {
  double coverage = 0.0;       ///< fraction of the surface with f_b > 0 (J < breaking_threshold)
  double mean_breaking = 0.0;  ///< mean f_b
  double lowest_jacobian = 1.0;
};
FoamStatistics foam_statistics(const DeepWaterField& field, int sample_count,
                               double breaking_threshold = kStokesBreakingJacobian);

/// All cascades summed at a point, each sampled bilinearly from its periodic tile.
struct SurfaceSample {
  double surface_elevation_m = 0.0, displacement_x_m = 0.0, displacement_y_m = 0.0;
  double slope_x = 0.0, slope_y = 0.0;
  double displacement_xx = 0.0, displacement_yy = 0.0, displacement_xy = 0.0;
};

/// eta(x, t) = sum a cos(k . x - w t + phi) over `waves` (m), by direct summation at one point of
/// the field's frame: the field itself, exactly, without the FFT's bilinear sampling. For tests,
/// gauges and the coherence measurement; a frame of the runtime uses the FFT.
double surface_elevation_m(const std::vector<LatticeWave>& waves, double x_m, double y_m, double time_s);

/// One cascade's lattice coefficients (views into the field, valid while it lives).
struct CascadeLattice {
  int grid_size = 0;                               ///< N
  double tile_length_m = 0.0;                      ///< L
  std::span<const float> amplitude_m;              ///< a_k
  std::span<const double> phase_rad;               ///< phi_k
  std::span<const double> angular_frequency_rad_s; ///< w_k (loop-quantised when looping)
  std::span<const long long> harmonic;             ///< w_k = harmonic 2 pi / T_loop when looping, else -1
};

/// One time of a weighted synthesis: DeepWaterField::synthesise(times) makes sum_i weight_i
/// field(time_i). The synthesis is linear in the coefficients c_k(t), so the sum is formed in the
/// spectral domain (sum_i weight_i c_k(t_i)) and costs ONE inverse FFT per channel, whatever the
/// number of times: how the runtime crossfades the deep water across a loop's jump exactly as the
/// harbour frames are crossfaded (runtime/deep_water_source.hpp, docs/runtime.md).
struct TimedWeight {
  double time_s = 0.0;  ///< the field's time (s)
  double weight = 1.0;  ///< dimensionless
};

/// One cascade's lattice as recorded (the bake's deep_water_cascade_<i>.bin, read through
/// sequence/deep_water_section.hpp, or DeepWaterField::record()): N x N coefficients in FFT order
/// (row = ky index, column = kx index, indices above N/2 negative).
struct RecordedCascade {
  int grid_size = 0;                  ///< N
  double tile_length_m = 0.0;         ///< L
  double min_wavenumber_rad_m = 0.0;  ///< the band (inclusive), for band(); 0 and 0: unknown
  double max_wavenumber_rad_m = 0.0;  ///< (exclusive)
  std::vector<float> amplitude_m;     ///< a_k (m)
  std::vector<double> phase_rad;      ///< phi_k
  std::vector<double> angular_frequency_rad_s;  ///< w_k (rad/s)
  std::vector<long long> harmonic;    ///< w_k = harmonic 2 pi / T_loop when looping, else -1
};

/// A whole field as recorded: with it DeepWaterField rebuilds the same lattice waves (same
/// amplitudes, phases and frequencies, hence the same surface) without the spectrum, in
/// milliseconds instead of the seconds the spectrum's cell integrals take.
struct RecordedDeepWater {
  std::vector<RecordedCascade> cascades;  ///< largest tile first, every one of the same N
  double still_water_depth_m = 0.0;       ///< <= 0: deep (recorded for the fluxes' depth)
  double loop_period_s = 0.0;             ///< T_loop (s), 0 = none: the harmonics are used when > 0
  double choppiness = 1.0;                ///< lambda
  std::uint64_t seed = 0;                 ///< the phases' seed, for the record
  double unresolved_slope_variance = 0.0; ///< what unresolved_slope_variance() returns
};

class DeepWaterField {
 public:
  /// Integrates the spectrum over every lattice cell (the long part: N^2 cells per cascade) and
  /// plans the FFTs. Throws nearshore::Error naming the field at fault.
  explicit DeepWaterField(const DeepWaterSpecification& specification);
  /// Rebuilds a field from its recorded lattices (no spectrum: specification().spectrum is null).
  /// Throws nearshore::Error naming the cascade for an empty record, a grid size that is not a
  /// power of two in [8, 4096] or differs between cascades, or arrays that are not N x N.
  explicit DeepWaterField(const RecordedDeepWater& recorded);
  ~DeepWaterField();
  DeepWaterField(const DeepWaterField&) = delete;
  DeepWaterField& operator=(const DeepWaterField&) = delete;

  const DeepWaterSpecification& specification() const;
  int cascade_count() const;
  CascadeBand band(int cascade) const;
  /// sum a^2/2 of the cascade's components (m^2); by Parseval also the spatial variance of eta.
  double cascade_variance_m2(int cascade) const;
  /// sum a^2 k^2 / 2 of the cascade (the mean square slope it resolves).
  double cascade_slope_variance(int cascade) const;
  /// 4 sqrt(sum of the cascades' variances) (m).
  double significant_wave_height_m() const;
  /// integral of k^2 S(k) above the last cascade's band: the mean square slope the lattices do
  /// not resolve, for the lighting's roughness (Bruneton et al. 2010).
  double unresolved_slope_variance() const;

  /// Fills frame(i) of every cascade at time t (s). with_flux adds the fluxes (2 more FFTs).
  void synthesise(double time_s, bool with_flux = false);
  /// Fills frame(i) of every cascade with sum_i weight_i field(time_i) (see TimedWeight): one
  /// inverse FFT per channel and cascade however many times are mixed. An empty span gives zeros.
  void synthesise(std::span<const TimedWeight> times, bool with_flux = false);
  /// The same into `frames` (resized to cascade_count(); their vectors' memory is reused), leaving
  /// frame(i) untouched: what a runtime keeping its own ring of frames calls.
  void synthesise_into(std::span<const TimedWeight> times, std::vector<DeepWaterFrame>& frames,
                       bool with_flux = false);
  const DeepWaterFrame& frame(int cascade) const;
  /// The sum of all cascades at (x, y) (m) from the last synthesise().
  SurfaceSample sample(double x_m, double y_m) const;

  /// The field's components as WaveComponents (direction = the wavevector's, frequency = the
  /// possibly loop-quantised w_k), amplitude >= min_amplitude_m, for the harbour wave maker:
  /// at the offshore edge the baked waves and this field are then the same waves.
  SeaState wave_components(double min_amplitude_m = 0.0) const;
  /// The same components with their lattice wavevectors, cascade by cascade in FFT order.
  std::vector<LatticeWave> lattice_waves(double min_amplitude_m = 0.0) const;

  /// Cascade `cascade`'s lattice coefficients, N x N in FFT order (row = ky index, column = kx
  /// index, indices above N/2 negative): what the bake writes beside the frames for the runtime
  /// (sequence/deep_water_section.hpp) and what a runtime field is rebuilt from.
  CascadeLattice lattice(int cascade) const;
  /// Every cascade's lattice and the field's constants, copied: DeepWaterField(record()) is the
  /// same field (a second instance for another thread, or one to keep without the spectrum).
  RecordedDeepWater record() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nearshore::ocean
