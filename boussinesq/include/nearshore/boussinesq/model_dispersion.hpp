#pragma once
// The linear dispersion of the equations the solver integrates (Madsen & Sorensen 1992 with
// B = dispersion_coefficient; seed 003 eq. (4)): what the wave maker and the deep-water coupling
// need to know about how the model carries a wave of a given frequency.
namespace nearshore::boussinesq {

/// Model wavenumber (rad/m) of the linear Madsen & Sorensen equations at still-water depth d:
///   w^2 = g d k^2 (1 + B (kd)^2) / (1 + (B + 1/3) (kd)^2).
/// Newton from the Airy wavenumber; 0 for w <= 0 or d <= 0.
double boussinesq_wavenumber(double angular_frequency_rad_s, double depth_m, double dispersion_coefficient);

}  // namespace nearshore::boussinesq
