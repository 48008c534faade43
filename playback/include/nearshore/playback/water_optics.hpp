#pragma once
// The colour of sea water from what is in it: inherent optical properties (IOPs) per colour band,
// seed 000 section 3.3.2 eq. (3.27)-(3.37), and the apparent ones a renderer needs (diffuse
// attenuation, the reflectance of deep water). GL-free; the renderer sends WaterOptics to the
// shaders as uniforms and shaders/common.glsl shade_water uses it exactly as lighting.cpp does.
//
//   a(l)   = a_w + a_phytoplankton + a_CDOM + a_sediment        eq. (3.27)-(3.29)
//   b(l)   = b_w + b_particles + b_sediment                     eq. (3.30)-(3.31)
//   b_b(l) = 1/2 b_w + B_p b_particles + B_s b_sediment         backscattering; B_p from eq. (3.35)
//   K(l)   = a + b_b                                             diffuse attenuation (Gordon 1989, per unit path)
//   R_inf  = 0.33 b_b / (a + b_b)                                deep water's irradiance reflectance
//                                                               (Gordon, Brown & Jacobs 1975; Morel & Prieur 1977)
// and over a seabed of albedo A at depth H seen along a path factor m = 1/mu_d + 1/mu_v
// (Maritorena, Morel & Gentili 1994, the shallow-water reflectance seed 000 eq. 3.25 blends by
// the transparency alpha(l) of eq. 3.37, here per band):
//   R(H) = R_inf (1 - e^(-K m H)) + A e^(-K m H)
#include <array>

namespace nearshore::playback {

using Radiance = std::array<double, 3>;  ///< per colour band (red 620, green 520, blue 440 nm)

/// What is in the water.
struct WaterConstituents {
  double chlorophyll_mg_m3 = 0.3;          ///< C of eq. (3.26)-(3.31), uniform with depth (C_0; no deep maximum)
  /// Absorption of coloured dissolved organic matter at 440 nm (1/m); its spectrum falls as
  /// e^(-0.014 (lambda - 440)) (eq. 3.29). Negative: from the chlorophyll, 0.012 C^0.65 (eq. 3.29).
  double cdom_absorption_440_per_m = -1.0;
  /// Suspended mineral sediment as the turbidity a harbour's instruments read (nephelometric
  /// turbidity units). Its scattering is b(550) = 1 NTU^-1 m^-1 (turbidity in NTU and the
  /// scattering coefficient in 1/m are about equal, Kirk 2011 ch. 3.6), spectrally flat-ish
  /// (550 / lambda)^0.5; backscattering ratio 0.019 (Petzold's San Diego harbour, 1972);
  /// absorption 0.08 b(550) at 440 nm falling as e^(-0.0123 (lambda - 440)) (Babin et al. 2003).
  double turbidity_ntu = 0.5;
};

/// Per-band properties (1/m except the reflectance).
struct WaterOptics {
  Radiance absorption_per_m{}, scattering_per_m{}, backscattering_per_m{};
  Radiance diffuse_attenuation_per_m{};  ///< K = a + b_b
  Radiance deep_reflectance{};           ///< R_inf
};

/// Eq. (3.34): Rayleigh-like scattering of water molecules, polarisation factor p = 0.835 (1/sr).
double water_phase_function(double cos_psi);
/// Eq. (3.35): Cornette & Shanks (1992) for particles, asymmetry g (1/sr, integrates to 1).
double particle_phase_function(double cos_psi, double g);
/// Fraction of eq. (3.35)'s scattering into the backward hemisphere (numerical integral).
double particle_backscatter_fraction(double g);
/// Mean cosine of ocean particle scattering (Petzold's average phase function, Mobley 1994).
constexpr double kParticleAsymmetry = 0.924;

/// Eq. (3.27)-(3.31) with the constituents above.
WaterOptics water_optics(const WaterConstituents& water);
/// R(H) above for a seabed of albedo A at depth H (m) and path factor m (1/mu_d + 1/mu_v).
Radiance shallow_water_reflectance(const WaterOptics& optics, const Radiance& seabed_albedo, double depth_m,
                                   double path_factor);

}  // namespace nearshore::playback
