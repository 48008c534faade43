#pragma once
// Linear (Airy) wave theory shared by the bake (wave maker, deep-water FFT field, validation) and the
// loop tools (synthetic seas): the dispersion relation w^2 = g k tanh(k d) and the speeds it gives.
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

}  // namespace nearshore::ocean
