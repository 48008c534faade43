#pragma once
// Reflection at the sea surface: Fresnel for water and the Bruneton, Neyret & Holzschuch (2010)
// "Real-time realistic ocean lighting" BRDF, seed 000 eq. (3.12)-(3.24): a Gaussian distribution
// of facet slopes whose variance is what the drawn normals cannot show (the spectrum's tail
// beyond the finest grid, and whatever the mesh filters out with distance), Smith shadowing.
// Isotropic: sigma_x^2 = sigma_y^2 = slope_variance_per_axis (eq. 3.14 then gives sigma_v^2 the
// same). GL-free; shaders/common.glsl has the same functions in GLSL.
#include "nearshore/playback/vector3.hpp"

namespace nearshore::playback {

/// Refractive index of sea water for visible light.
constexpr double kWaterRefractiveIndex = 1.333;

/// ((n - 1) / (n + 1))^2: the reflectance at normal incidence, 0.0204 for water.
double fresnel_reflectance_at_normal_incidence(double refractive_index = kWaterRefractiveIndex);
/// Schlick's approximation, seed 000 eq. (3.21): R + (1 - R)(1 - cos)^5, with R from n = 1.333.
double fresnel_reflectance(double cos_incidence);
/// The exact unpolarised Fresnel reflectance of an air-water interface (the reference Schlick's
/// approximation is checked against).
double fresnel_reflectance_exact(double cos_incidence, double refractive_index = kWaterRefractiveIndex);

/// erfc(x) as Bruneton (2010) approximates it: 2 e^(-x^2) / (2.319 x + sqrt(4 + 1.52 x^2)), x >= 0.
double erfc_approximation(double x);
/// Smith's shadowing term Lambda(a), eq. (3.17), with a = cos theta / sqrt(2 sigma^2 sin^2 theta)
/// (eq. 3.18), for a direction at cos theta from the mean normal.
double smith_lambda(double cos_theta, double slope_variance_per_axis);
/// Cox & Munk (1954) mean square slope of a clean sea in wind U (m/s at 12.5 m), both axes summed:
/// 0.003 + 0.00512 U. The fallback when the spectrum's unresolved variance is not known.
double cox_munk_slope_variance(double wind_speed_m_s);
/// The share of that mean square slope along the wind: Cox & Munk's (1954) clean-sea regressions
/// sigma_u^2 = 3.16e-3 U and sigma_c^2 = 0.003 + 1.92e-3 U with the intercept (the slope of the
/// calm sea, no direction) shared by both axes: (0.0015 + 3.16e-3 U) / (0.003 + 5.08e-3 U); 1/2
/// without wind, 0.61 at 10 m/s (their 0.59 with the intercept crosswind).
double cox_munk_upwind_share(double wind_speed_m_s);

/// The BRDF (1/sr) of a surface with mean normal n for unit vectors v (to the eye) and l (to the
/// light): p(zeta_h) F(v.h) / (4 h_z^4 cos theta_v cos theta_l (1 + Lambda_v + Lambda_l)), eq. (3.20).
/// 0 when v or l is below the mean surface.
double ocean_brdf(const Vector3& normal, const Vector3& to_eye, const Vector3& to_light,
                  double slope_variance_per_axis);
/// Bruneton's mean Fresnel reflectance of the sky seen in a rough surface, eq. (3.24):
/// R + (1 - R) (1 - cos theta_v)^(5 exp(-2.69 sigma_v)) / (1 + 22.7 sigma_v^1.5) (the exponent as in
/// Bruneton's paper; the seed's typesetting lost it).
double mean_fresnel_reflectance(double cos_view, double slope_variance_per_axis);

}  // namespace nearshore::playback
