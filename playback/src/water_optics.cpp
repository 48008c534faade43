#include "nearshore/playback/water_optics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "nearshore/playback/sky_model.hpp"

namespace nearshore::playback {
namespace {
constexpr double kPi = std::numbers::pi;
// Pure water at 620, 520, 440 nm (seed 000 section 3.3.2): absorption a_w (Pope & Fry 1997),
// scattering b_w (Smith & Baker 1981), phytoplankton's normalised specific absorption a*_c
// (Prieur & Sathyendranath 1981).
constexpr double kWaterAbsorption[3] = {0.2755, 0.0409, 0.00635};
constexpr double kWaterScattering[3] = {0.0012, 0.0024, 0.0049};
constexpr double kChlorophyllSpecificAbsorption[3] = {0.260, 0.357, 0.944};
constexpr double kSedimentBackscatterRatio = 0.019;
}  // namespace

double water_phase_function(double cos_psi) {
  constexpr double p = 0.835;
  return 3.0 / (4.0 * kPi * (3.0 + p)) * (1.0 + p * cos_psi * cos_psi);
}

double particle_phase_function(double cos_psi, double g) {
  // Eq. (3.35) as Cornette & Shanks normalise it over the sphere, divided by 4 pi per steradian.
  return 3.0 * (1.0 - g * g) / (2.0 * (2.0 + g * g)) * (1.0 + cos_psi * cos_psi) /
         std::pow(1.0 + g * g - 2.0 * g * cos_psi, 1.5) / (4.0 * kPi);
}

double particle_backscatter_fraction(double g) {
  // Midpoint rule in mu = cos psi (the phase function is smooth in mu except near mu = 1, where
  // it peaks; 20000 intervals resolve a peak of width (1 - g) = 0.076).
  constexpr int kSteps = 20000;
  double total = 0.0, backward = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double mu = -1.0 + (i + 0.5) * 2.0 / kSteps;
    const double value = particle_phase_function(mu, g) * 2.0 * kPi * (2.0 / kSteps);
    total += value;
    if (mu < 0.0) backward += value;
  }
  return backward / total;
}

WaterOptics water_optics(const WaterConstituents& water) {
  const double chlorophyll = std::max(water.chlorophyll_mg_m3, 0.0);
  const double cdom_440 = water.cdom_absorption_440_per_m >= 0.0 ? water.cdom_absorption_440_per_m
                                                                  : 0.012 * std::pow(chlorophyll, 0.65);  // eq. (3.29)
  const double ntu = std::max(water.turbidity_ntu, 0.0);
  static const double particle_backscatter = particle_backscatter_fraction(kParticleAsymmetry);
  WaterOptics o;
  for (std::size_t c = 0; c < 3; ++c) {
    const double lambda = kBandWavelengthsNm[c];
    const double a_phytoplankton = 0.06 * kChlorophyllSpecificAbsorption[c] * std::pow(chlorophyll, 0.65);  // eq. (3.28)
    const double a_cdom = cdom_440 * std::exp(-0.014 * (lambda - 440.0));                                  // eq. (3.29)
    const double b_sediment = ntu * std::sqrt(550.0 / lambda);
    const double a_sediment = 0.08 * ntu * std::exp(-0.0123 * (lambda - 440.0));
    const double b_particles = 500.0 / lambda * 0.3 * std::pow(chlorophyll, 0.62);                          // eq. (3.31)
    o.absorption_per_m[c] = kWaterAbsorption[c] + a_phytoplankton + a_cdom + a_sediment;                    // eq. (3.27)
    o.scattering_per_m[c] = kWaterScattering[c] + b_particles + b_sediment;                                 // eq. (3.30)
    o.backscattering_per_m[c] =
        0.5 * kWaterScattering[c] + particle_backscatter * b_particles + kSedimentBackscatterRatio * b_sediment;
    o.diffuse_attenuation_per_m[c] = o.absorption_per_m[c] + o.backscattering_per_m[c];
    o.deep_reflectance[c] = 0.33 * o.backscattering_per_m[c] / o.diffuse_attenuation_per_m[c];
  }
  return o;
}

Radiance shallow_water_reflectance(const WaterOptics& o, const Radiance& seabed_albedo, double depth_m, double path_factor) {
  Radiance r{};
  for (std::size_t c = 0; c < 3; ++c) {
    const double seen = std::exp(-o.diffuse_attenuation_per_m[c] * path_factor * std::max(depth_m, 0.0));
    r[c] = o.deep_reflectance[c] * (1.0 - seen) + seabed_albedo[c] * seen;
  }
  return r;
}

}  // namespace nearshore::playback
