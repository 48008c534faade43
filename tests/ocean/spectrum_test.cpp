// Frequency spectra and directional spreading against their closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "nearshore/ocean/spectrum.hpp"
#include "nearshore/ocean/spectrum_quadrature.hpp"
#include "nearshore/ocean/wave_component.hpp"
#include "nearshore/core/error.hpp"

using namespace nearshore::ocean;

TEST(Spectrum, PiersonMoskowitzFromHsTpIntegratesToHs) {
  // m0 = alpha g^2 / (5 wp^4) is exact for the PM shape; the quadrature over [0.05, 200] wp
  // misses ~5/(4 200^4) of it, so 1e-6 relative is a fair bound.
  const PiersonMoskowitzSpectrum pm(2.5, 9.0);
  EXPECT_NEAR(pm.significant_wave_height_m(), 2.5, 2.5e-6);
  EXPECT_NEAR(pm.peak_angular_frequency_rad_s(), 2.0 * std::numbers::pi / 9.0, 1e-12);
}

TEST(Spectrum, PiersonMoskowitzFromWindMatchesClosedFormHs) {
  // seed 000 eq. (2.2): m0 = alpha U^4 / (5 * (4 beta / 5) g^2), Hs = 4 sqrt(m0) = 0.2092 U^2 / g.
  const double wind_m_s = 15.0;
  const auto pm = PiersonMoskowitzSpectrum::from_wind_speed(wind_m_s);
  const double expected_hs = 4.0 * std::sqrt(8.1e-3 / (4.0 * 0.74)) * wind_m_s * wind_m_s / kGravity_m_s2;
  EXPECT_NEAR(pm.significant_wave_height_m(), expected_hs, 1e-5 * expected_hs);
  EXPECT_NEAR(pm.peak_angular_frequency_rad_s(), 0.877 * kGravity_m_s2 / wind_m_s, 1e-3);
}

TEST(Spectrum, JonswapIsNormalisedToHsAndPeaksAtWp) {
  for (double gamma : {1.0, 3.3, 7.0}) {
    const JonswapSpectrum jonswap(3.0, 10.0, gamma);
    EXPECT_NEAR(jonswap.significant_wave_height_m(), 3.0, 1e-9);
    const double wp = jonswap.peak_angular_frequency_rad_s();
    EXPECT_GT(jonswap.density_m2_s_rad(wp), jonswap.density_m2_s_rad(0.97 * wp));
    EXPECT_GT(jonswap.density_m2_s_rad(wp), jonswap.density_m2_s_rad(1.03 * wp));
  }
  // gamma = 1 is the PM spectrum of the same Hs and Tp, point by point (the closed-form alpha
  // of PM against the numerically normalised alpha of JONSWAP: 1e-6 relative).
  const JonswapSpectrum flat(2.0, 8.0, 1.0);
  const PiersonMoskowitzSpectrum pm(2.0, 8.0);
  for (double w : {0.5, 0.785, 1.0, 2.0})
    EXPECT_NEAR(flat.density_m2_s_rad(w), pm.density_m2_s_rad(w), 1e-6 * pm.density_m2_s_rad(0.785));
  // A higher gamma concentrates the same variance: a higher peak.
  EXPECT_GT(JonswapSpectrum(2.0, 8.0, 3.3).density_m2_s_rad(2 * std::numbers::pi / 8), pm.density_m2_s_rad(2 * std::numbers::pi / 8));
}

TEST(Spectrum, JonswapFromWindAndFetchFollowsEquation23) {
  // U10 = 20 m/s, F = 100 km: alpha = 0.076 (gF/U^2)^-0.22, wp = 22 (g^2/(U F))^(1/3).
  const auto jonswap = JonswapSpectrum::from_wind_and_fetch(20.0, 1e5);
  const double g = kGravity_m_s2;
  EXPECT_NEAR(jonswap.phillips_constant(), 0.076 * std::pow(g * 1e5 / 400.0, -0.22), 1e-12);
  EXPECT_NEAR(jonswap.peak_angular_frequency_rad_s(), 22.0 * std::cbrt(g * g / (20.0 * 1e5)), 1e-12);
}

TEST(Spectrum, TmaFactorLimits) {
  // Deep water: 1. Shallow water (kd << 1): tanh^2(kd) / 2 ~ (kd)^2 / 2 = w^2 d / (2 g), to O((kd)^2).
  EXPECT_NEAR(tma_depth_factor(2.0, 1000.0), 1.0, 1e-12);
  const double w = 0.1, d = 2.0;
  const double kd = wavenumber_from_frequency(w, d) * d;
  ASSERT_LT(kd, 0.05);
  EXPECT_NEAR(tma_depth_factor(w, d), w * w * d / (2.0 * kGravity_m_s2), 2.0 * kd * kd * w * w * d / kGravity_m_s2);
  // TMA takes energy out: lower Hs than the deep-water spectrum it wraps.
  auto deep = std::make_shared<JonswapSpectrum>(2.0, 10.0, 3.3);
  const TmaSpectrum shallow(deep, 8.0);
  EXPECT_LT(shallow.significant_wave_height_m(), 0.95 * deep->significant_wave_height_m());
  EXPECT_NEAR(TmaSpectrum(deep, 5000.0).significant_wave_height_m(), 2.0, 1e-6);
}

TEST(Spectrum, CosineSquaredSpreadingIsNormalised) {
  // C(s) makes D integrate to 1 over the circle; 256 Gauss panels make the quadrature exact to 1e-10.
  for (double s : {1.0, 10.0, 75.0}) {
    const CosineSquaredSpreading spreading(0.7, s);
    const double total = integrate_gauss_legendre(
        [&](double theta) { return spreading.density_per_rad(theta, 1.0); }, 0.7 - std::numbers::pi, 0.7 + std::numbers::pi, 256);
    EXPECT_NEAR(total, 1.0, 1e-10) << "s = " << s;
    EXPECT_GT(spreading.density_per_rad(0.7, 1.0), spreading.density_per_rad(0.9, 1.0));
    // Narrower for larger s.
    EXPECT_LT(spreading.half_width_holding_rad(0.9, 1.0), std::numbers::pi);
  }
  EXPECT_GT(CosineSquaredSpreading(0.0, 5.0).half_width_holding_rad(0.9, 1.0),
            CosineSquaredSpreading(0.0, 50.0).half_width_holding_rad(0.9, 1.0));
}

TEST(Spectrum, BadParametersNameTheFix) {
  EXPECT_THROW(JonswapSpectrum(2.0, 0.0), nearshore::Error);
  EXPECT_THROW(JonswapSpectrum(2.0, 8.0, 0.5), nearshore::Error);
  EXPECT_THROW(PiersonMoskowitzSpectrum(-1.0, 8.0), nearshore::Error);
  EXPECT_THROW(CosineSquaredSpreading(0.0, 0.0), nearshore::Error);
  EXPECT_THROW(TmaSpectrum(nullptr, 5.0), nearshore::Error);
}
