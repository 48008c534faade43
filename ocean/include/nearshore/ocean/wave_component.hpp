#pragma once
// WaveComponent: one linear wave of a sea state. The deep-water FFT field (deep_water) and the
// Boussinesq wave maker (boussinesq) are driven by the SAME list of components, so at the offshore
// edge of a harbour the baked waves and the FFT field are the same waves (issue 5, coherence).
//   surface elevation  eta(x, y, t) = sum_i a_i cos(k_i (x cos th_i + y sin th_i) - w_i t + phi_i)
// with k_i from the linear dispersion relation w^2 = g k tanh(k d) at the depth d where it is used.
#include <cstdint>
#include <vector>

#include "nearshore/ocean/linear_waves.hpp"

namespace nearshore::ocean {

struct WaveComponent {
  double amplitude_m = 0.0;              ///< a_i (half the height)
  double angular_frequency_rad_s = 0.0;  ///< w_i
  double direction_rad = 0.0;            ///< th_i, direction of travel, counter-clockwise from +x (east)
  double phase_rad = 0.0;                ///< phi_i
};

/// A component with its wavevector: a deep-water field's lattice wave (the WaveComponent alone
/// cannot give k back when the field loops: w is then the harmonic of 2 pi / T_loop nearest w(|k|))
/// or a synthetic sea's plane wave at a known depth.
struct LatticeWave {
  WaveComponent wave;               ///< a, w (possibly loop-quantised), direction of k, phi
  double wavenumber_x_rad_m = 0.0;  ///< k_x = n 2 pi / L
  double wavenumber_y_rad_m = 0.0;  ///< k_y = m 2 pi / L
};

/// A sea state as the solver and the runtime see it: its components, and if it loops, the period
/// every component completes a whole number of cycles in (0 = not periodic).
struct SeaState {
  std::vector<WaveComponent> components;
  double loop_period_s = 0.0;
  std::uint64_t seed = 0;  ///< the seed the phases were drawn from (recorded in every output)
};

}  // namespace nearshore::ocean
