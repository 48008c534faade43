#pragma once
// The linear dispersion of the equations the solver integrates (Madsen & Sorensen 1992 with
// B = dispersion_coefficient; seed 003 eq. (4)): what the wave maker and the deep-water coupling
// need to know about how the model carries a wave of a given frequency.
namespace nearshore::boussinesq {

/// Model wavenumber (rad/m) of the linear Madsen & Sorensen equations at still-water depth d:
///   w^2 = g d k^2 (1 + B (kd)^2) / (1 + (B + 1/3) (kd)^2).
/// Newton from the Airy wavenumber; 0 for w <= 0 or d <= 0.
double boussinesq_wavenumber(double angular_frequency_rad_s, double depth_m, double dispersion_coefficient);

/// The model wavenumber (rad/m) of a wave of absolute angular frequency w on a depth-uniform current
/// whose component along the wave is U (m/s, negative against it): the Doppler-shifted dispersion
/// relation (w - k U)^2 = g d k^2 (1 + B (kd)^2) / (1 + (B + 1/3) (kd)^2) of the equations on a
/// current (docs/solver.md, "Currents"); 0 when the current blocks the wave. U = 0 gives
/// boussinesq_wavenumber() to 1e-14.
double boussinesq_wavenumber_in_current(double angular_frequency_rad_s, double depth_m, double dispersion_coefficient,
                                        double current_along_m_s);

/// The largest k d the bake lets the equations carry: B = 1/15 is Madsen & Sorensen's (1992)
/// choice for k d up to about 3. What that costs is dispersion_phase_speed_error(3, B): +4.11 %
/// phase speed at a given frequency for B = 1/15 (+2.40 % at a given wavenumber).
inline constexpr double kLargestCarriedKd = 3.0;

/// Relative phase-speed error, at a given frequency, of a wave the model carries over still-water
/// depth `model_depth_m` against Airy theory over the true depth `true_depth_m`:
///   k_Airy(w, d_true) / k_model(w, d_model) - 1.
/// With d_model = d_true it is the error of the equations themselves; with d_model < d_true the
/// error of the effective-depth limit (docs/solver.md, "Effective depth").
double phase_speed_error(double angular_frequency_rad_s, double model_depth_m, double true_depth_m,
                         double dispersion_coefficient);

/// The tolerance the effective-depth limit is held to: the phase-speed error the equations have
/// at k d = kLargestCarriedKd (Airy k d), at a given frequency. 0.0411 for B = 1/15.
double carried_phase_speed_tolerance(double dispersion_coefficient);

/// The effective-depth limit for a carried band whose highest frequency is `w`: the depth at which
/// that wave has (Airy) k d = kLargestCarriedKd. Every shorter depth keeps the band inside the k d
/// the equations hold; a deeper bottom is not felt by it (tanh 3 = 0.995).
double effective_depth_limit_m(double highest_angular_frequency_rad_s);

/// The highest frequency a band starting at `lowest_angular_frequency_rad_s` may reach over water
/// as deep as `deepest_m`: without an effective-depth limit, the wave with k d = kLargestCarriedKd
/// at the deepest; with one, the limit may be no shallower than the depth at which the longest wave
/// of the band is still within carried_phase_speed_tolerance() of Airy over the deepest water
/// (it would feel the false bottom), and the band ends where k d = kLargestCarriedKd at that depth.
double highest_frequency_over_effective_depth_rad_s(double lowest_angular_frequency_rad_s, double deepest_m,
                                                   double dispersion_coefficient);

}  // namespace nearshore::boussinesq
