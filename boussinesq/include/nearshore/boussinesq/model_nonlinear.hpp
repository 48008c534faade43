#pragma once
// The weakly nonlinear properties of the equations the solver integrates, in constant depth, and the
// potential-flow references they are judged against (issue 19; docs/validation.md "Nonlinear
// checks"). What the continuous equations do is what the discrete solver must follow; where the
// equations themselves depart from Stokes is a property of the model, not an error of the scheme.
//
// The 1-D equations on a flat bed (seed 003 eq. 1-2, 4 with d_x = 0, n = 1, no friction):
//   eta_t + P_x = 0
//   P_t + (P^2/h)_x + g h eta_x - (B + 1/3) D^2 P_xxt - B g D^3 eta_xxx = 0,   h = d + eta
// with D = d (seed 003 and Madsen & Sorensen 1992: the dispersive terms use the still-water depth)
// or D = h (DispersionDepth::kTotal: the dispersive terms on the total depth, the usual first step
// toward full nonlinearity).
//
// Equations::kFullyNonlinear (docs/solver.md, "Fully nonlinear dispersion"): the same linear terms,
// with the dispersive terms of the Serre-Green-Naghdi equations (fully nonlinear at O(mu^2)) and the
// Madsen & Sorensen (1992) enhancement applied to the whole shallow-water momentum residual S on the
// local total depth:
//   P_t + (P^2/h)_x + g h eta_x - (1/3) [h^3 (u_xt + u u_xx - u_x^2)]_x - B h^2 S_xx = 0,
//   u = P/h,  S = P_t + (P^2/h)_x + g h eta_x.
// Linearised it is the seed's equation; its bound second harmonic equals Stokes' to O((kd)^2) for
// B = 1/15 (fully_nonlinear_second_harmonic_m).
#include <vector>

namespace nearshore::boussinesq {

/// Which nonlinear terms the momentum equations carry (SolverParameters::equations).
enum class Equations {
  kWeaklyNonlinear,  ///< seed 003 eq. (1)-(7): nonlinear only in the shallow-water terms (Madsen & Sorensen 1992)
  kFullyNonlinear,   ///< the Serre-Green-Naghdi dispersive terms plus the enhancement on h (above)
};

/// Which depth multiplies the dispersive terms of eq. (4)-(5) (SolverParameters::dispersion_depth).
enum class DispersionDepth {
  kStillWater,  ///< d: seed 003 eq. (4)-(5), Madsen & Sorensen (1992) (default)
  kTotal,       ///< h = d + eta: nonlinear dispersive terms (docs/solver.md, "Dispersion depth")
};

/// Amplitude (m) of the bound second harmonic of a regular wave eta = a cos(k x - w t) + a2 cos 2(...)
/// in depth d by Stokes' second-order theory (potential flow):
///   a2 = (k a^2 / 4) cosh(kd) (2 + cosh 2kd) / sinh^3(kd).
double stokes_second_harmonic_m(double amplitude_m, double wavenumber_rad_m, double depth_m);

/// The same for the continuous Boussinesq equations above (second-order Stokes-type expansion of the
/// equations themselves, derived in docs/validation.md "Nonlinear checks"): with c0 the model's
/// linear phase speed at k,
///   a2 = a^2 [ (c0^2/d + g/2) - s k^2 (2 d (B+1/3) c0^2 - 3 B g d^2) / 2 ] / (6 (g d - c0^2)),
/// s = 0 for DispersionDepth::kStillWater, 1 for kTotal. Reduces to Stokes' 3 a^2 / (4 k^2 d^3) for
/// k d -> 0.
double boussinesq_second_harmonic_m(double amplitude_m, double wavenumber_rad_m, double depth_m,
                                    double dispersion_coefficient, DispersionDepth depth_kind);

/// The bound second harmonic of the fully nonlinear equations (Equations::kFullyNonlinear), from the
/// second-order expansion of the equations above (docs/validation.md "Nonlinear checks"), x = k d:
///   a2 = a^2 (9 + (45 B + 3) x^2 + (36 B^2 + 8 B) x^4) / (12 k^2 d^3)
/// = Stokes' 3 a^2 / (4 k^2 d^3) (1 + (5 B + 1/3) x^2 + ...): for B = 1/15 the O(x^2) term is Stokes'
/// 2/3 exactly.
double fully_nonlinear_second_harmonic_m(double amplitude_m, double wavenumber_rad_m, double depth_m,
                                         double dispersion_coefficient);

/// Relative frequency (= phase speed) increase w/w0 - 1 of a regular wave of first-harmonic
/// amplitude a by Stokes' third-order theory, with the mean water level at rest and NO MEAN MASS
/// FLUX (Stokes' second definition of celerity, what a closed flume imposes):
///   (ka)^2 [ (9 - 10 s^2 + 9 s^4) / (16 s^4) - 1 / (2 s kd) ],   s = tanh kd
/// (Fenton 1985's first-definition term (2 + 7 S^2)/(4 (1 - S)^2) minus the Doppler shift of the
/// return current that cancels the Stokes drift, g a^2 / (2 c d)).
double stokes_frequency_increase(double amplitude_m, double wavenumber_rad_m, double depth_m);

/// A steady periodic wave of the continuous equations (no mean mass flux, mean level at rest):
/// eta = sum_n harmonics_m[n-1] cos(n theta), P = phase_speed * eta, theta = k x - c k t.
struct SteadyWave {
  double phase_speed_m_s = 0.0;
  std::vector<double> harmonics_m;  ///< amplitude of cos(n theta), n = 1..N (harmonics_m[0] = a)
};

/// Solves the continuous equations for the steady wave of first-harmonic amplitude a at wavenumber
/// k, exactly to the truncation of `harmonic_count` Fourier modes (Galerkin on sin(n theta) of the
/// momentum residual, Newton, continued in amplitude from the linear wave). This is the reference
/// for the discrete solver's amplitude dispersion and bound harmonics at every order the equations
/// carry. Throws nearshore::Error when Newton does not converge (a wave beyond the equations' reach).
/// The last 256 solves are kept process-wide (thread-safe): the same arguments, bit for bit, return
/// the same wave without solving again (a bake asks for its wave maker's wave many times).
SteadyWave boussinesq_steady_wave(double amplitude_m, double wavenumber_rad_m, double depth_m,
                                  double dispersion_coefficient, DispersionDepth depth_kind, int harmonic_count = 8,
                                  Equations equations = Equations::kWeaklyNonlinear);

}  // namespace nearshore::boussinesq
