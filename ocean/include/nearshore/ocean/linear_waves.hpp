#pragma once
// Linear (Airy) wave theory shared by the bake (wave maker, deep-water FFT field, validation) and the
// loop tools (synthetic seas): the dispersion relation w^2 = g k tanh(k d) and the speeds it gives.
#include <functional>

namespace nearshore::ocean {

inline constexpr double kGravity_m_s2 = 9.81;

/// Linear dispersion w^2 = g k tanh(k d): the wavenumber k (rad/m) of angular frequency w at
/// still-water depth d (metres; d <= 0 or infinity = deep water, k = w^2/g). Newton iteration
/// from the Eckart/Fenton start, converged to 1e-12 relative.
double wavenumber_from_frequency(double angular_frequency_rad_s, double depth_m);
/// The inverse: w = sqrt(g k tanh(k d)).
double frequency_from_wavenumber(double wavenumber_rad_m, double depth_m);
/// Phase speed w/k and group speed dw/dk at depth d.
double phase_speed_m_s(double wavenumber_rad_m, double depth_m);
double group_speed_m_s(double wavenumber_rad_m, double depth_m);

/// Waves on a steady depth-uniform current (Doppler shift; e.g. Mei, "The applied dynamics of ocean
/// surface waves", sec. 3.6): a wave of absolute angular frequency w (the one a fixed gauge sees)
/// travelling along k on a current whose component along k is U (m/s, negative against the waves)
/// has w = sigma(k) + k U, sigma the intrinsic frequency of the still water. Returns the k > 0 of
/// the branch that travels along k (sigma > 0, group speed dsigma/dk + U > 0), found by bracketing
/// and bisection on `intrinsic_frequency` (any increasing sigma(k): Airy's, or a model's); 0 when
/// the current blocks the wave (an opposing U at least the largest speed the branch reaches).
double wavenumber_in_current(double angular_frequency_rad_s, double current_along_m_s,
                             const std::function<double(double wavenumber_rad_m)>& intrinsic_frequency);
/// The same with Airy's sigma(k) = sqrt(g k tanh(k d)): (w - k U)^2 = g k tanh(k d).
double wavenumber_in_current(double angular_frequency_rad_s, double depth_m, double current_along_m_s);

}  // namespace nearshore::ocean
