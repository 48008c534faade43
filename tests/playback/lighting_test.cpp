// The CPU twins of the lighting (no GPU): each model against published numbers or limits known
// without any code. The shaders are compared with these twins on Mesa (lighting_render_test.cpp).
#include "nearshore/playback/lighting.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "nearshore/core/error.hpp"

namespace playback = nearshore::playback;
using playback::Lighting;
using playback::Radiance;
using playback::UtcTime;

namespace {
double luminance(const Radiance& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }
}  // namespace

// ---- sun position -------------------------------------------------------------------------
TEST(SunPosition, JulianDayOfMeeusExample7a) {
  // Meeus, Astronomical Algorithms (1998), example 7.a: 1957 October 4.81 = JD 2436116.31.
  UtcTime t{1957, 10, 4, 19, 26, 24.0};  // 0.81 day = 19 h 26 min 24 s
  EXPECT_NEAR(t.julian_day(), 2436116.31, 1e-6);
}

TEST(SunPosition, ApparentRightAscensionAndDeclinationOfMeeusExample25a) {
  // Meeus example 25.a, 1992 October 13.0 TD: apparent alpha = 13h 13m 31.4s = 198.38083 degrees,
  // delta = -7 deg 47' 06" = -7.78507 degrees. The low-accuracy method claims 0.01 degree.
  const auto sun = playback::sun_position(0.0, 0.0, UtcTime{1992, 10, 13, 0, 0, 0.0});
  EXPECT_NEAR(sun.right_ascension_deg, 198.38083, 0.01);
  EXPECT_NEAR(sun.declination_deg, -7.78507, 0.01);
}

TEST(SunPosition, ZenithAndAzimuthOfTheNrelSpaExampleWithinATenthOfADegree) {
  // Reda & Andreas (2004), Solar Position Algorithm for Solar Radiation Applications, NREL/TP-560-
  // 34302, the worked example: 2003 October 17, 12:30:30 local time (UTC-7) at 39.742476 N,
  // 105.1786 W: topocentric zenith 50.11162 degrees (refracted, 820 hPa, 11 C), azimuth 194.34024.
  // NOAA's algorithm and refraction (1010 hPa) agree to ~0.01 degree; the issue asks 0.1.
  const auto sun = playback::sun_position(39.742476, -105.1786, UtcTime{2003, 10, 17, 19, 30, 30.0});
  EXPECT_NEAR(90.0 - sun.elevation_deg, 50.11162, 0.1);
  EXPECT_NEAR(sun.azimuth_deg, 194.34024, 0.1);
}

TEST(SunPosition, RisesInTheEastAndSetsInTheWest) {
  // Equinox on the equator: the sun rises due east near 06:00 local solar time and sets due west.
  const auto morning = playback::sun_position(0.0, 0.0, UtcTime{2026, 3, 20, 7, 0, 0.0});
  const auto evening = playback::sun_position(0.0, 0.0, UtcTime{2026, 3, 20, 17, 0, 0.0});
  EXPECT_NEAR(morning.azimuth_deg, 90.0, 1.0);
  EXPECT_NEAR(evening.azimuth_deg, 270.0, 1.0);
  // 15 degrees per hour after 06:00 local solar time, which on 20 March is 06:07.5 UTC at 0 E
  // (equation of time -7.5 min): 13.1 degrees at 07:00 UTC.
  EXPECT_NEAR(morning.geometric_elevation_deg, 13.1, 0.5);
}

TEST(SunPosition, ParsesIsoUtcAndRejectsNonsense) {
  const UtcTime t = UtcTime::parse("2026-06-21T18:45:30Z");
  EXPECT_EQ(t.year, 2026);
  EXPECT_EQ(t.hour, 18);
  EXPECT_EQ(t.minute, 45);
  EXPECT_DOUBLE_EQ(t.second, 30.0);
  EXPECT_EQ(UtcTime::parse("2026-06-21T18:45").minute, 45);
  EXPECT_THROW(UtcTime::parse("21/06/2026"), nearshore::Error);
  EXPECT_THROW(UtcTime::parse("2026-13-01T00:00Z"), nearshore::Error);
  EXPECT_THROW(playback::sun_position(95.0, 0.0, t), nearshore::Error);
}

// ---- sky ------------------------------------------------------------------------------------
TEST(SkyModel, ZenithLuminanceAndChromaticityAreSeed001Formulas) {
  for (double turbidity : {2.0, 3.0, 6.0})
    for (double elevation : {5.0, 30.0, 60.0}) {
      const double theta_s = (90.0 - elevation) * std::numbers::pi / 180.0;
      // seed 001 eq. (3), written out here again
      const double chi = (4.0 / 9.0 - turbidity / 120.0) * (std::numbers::pi - 2.0 * theta_s);
      const double y_zenith = (4.0453 * turbidity - 4.9710) * std::tan(chi) - 0.2155 * turbidity + 2.4192;
      const auto sky = playback::make_sky(180.0, elevation, turbidity);
      EXPECT_NEAR(sky.zenith_luminance_kcd_m2, y_zenith, 1e-9);
      // Straight up the Perez ratio is 1: the sky's colour there has luminance Y_zenith (up to
      // clipping of out-of-gamut negative components, none for these skies).
      const Radiance up = playback::sky_radiance(sky, {0, 0, 1});
      EXPECT_NEAR(luminance(up), y_zenith, 1e-3 * y_zenith) << "T " << turbidity << " elevation " << elevation;
      // Blue sky: zenith x, y below the white point (0.3127, 0.329), blue above red.
      EXPECT_LT(sky.zenith_x, 0.3127);
      EXPECT_GT(up[2], up[0]);
    }
}

TEST(SkyModel, BrightestNearTheSunAndTheSunReddensAtSunset) {
  const auto sky = playback::make_sky(180.0, 30.0, 3.0);
  const Radiance near_sun = playback::sky_radiance(sky, {0.0, -std::cos(0.6), std::sin(0.6)});
  const Radiance opposite = playback::sky_radiance(sky, {0.0, std::cos(0.6), std::sin(0.6)});
  EXPECT_GT(luminance(near_sun), 2.0 * luminance(opposite));
  const auto noon = playback::make_sky(180.0, 60.0, 3.0), sunset = playback::make_sky(270.0, 2.0, 3.0);
  const auto& n = noon.sun_illuminance_klx;
  const auto& s = sunset.sun_illuminance_klx;
  EXPECT_GT(s[0] / s[2], 2.0 * n[0] / n[2]);  // warmer
  EXPECT_LT(luminance(s), 0.3 * luminance(n));
}

TEST(SkyModel, DaylightIlluminanceIsOfTheMeasuredOrder) {
  // Clear sky, sun 60 degrees up: global horizontal illuminance ~90-110 klx of which diffuse
  // ~10-20 % (IES handbook; Darula & Kittler). The Preetham sky is known to run bright, so the
  // bounds are wide: 50-150 klx, diffuse 5-40 %.
  const auto sky = playback::make_sky(180.0, 60.0, 2.5);
  const double diffuse = luminance(playback::sky_illuminance_klx(sky));
  const double direct = luminance(sky.sun_illuminance_klx) * std::sin(60.0 * std::numbers::pi / 180.0);
  EXPECT_GT(direct + diffuse, 50.0);
  EXPECT_LT(direct + diffuse, 150.0);
  EXPECT_GT(diffuse / (direct + diffuse), 0.05);
  EXPECT_LT(diffuse / (direct + diffuse), 0.40);
}

TEST(SkyModel, TwilightAndNightFadeWithoutNaN) {
  double previous = 1e30;
  for (double elevation = 20.0; elevation >= -30.0; elevation -= 0.5) {
    const auto sky = playback::make_sky(250.0, elevation, 3.0);
    for (double z : {-0.5, 0.0, 0.01, 0.3, 1.0}) {
      const Radiance c = playback::sky_radiance(sky, {std::sqrt(1 - z * z), 0.0, z});
      for (double v : c) {
        EXPECT_TRUE(std::isfinite(v)) << "elevation " << elevation;
        EXPECT_GE(v, 0.0);
      }
    }
    for (double v : sky.sun_illuminance_klx) EXPECT_TRUE(std::isfinite(v) && v >= 0.0);
    const double zenith = luminance(playback::sky_radiance(sky, {0, 0, 1}));
    EXPECT_LE(zenith, previous * (1 + 1e-9) + 1e-12) << "elevation " << elevation;
    previous = zenith;
  }
  EXPECT_EQ(luminance(playback::make_sky(250.0, -2.0, 3.0).sun_illuminance_klx), 0.0);  // set
  EXPECT_LT(previous, 1e-5);  // night
}

// ---- Fresnel and the BRDF ---------------------------------------------------------------------
TEST(OceanBrdf, FresnelOfWaterAtNormalIncidenceIsTwoPercentAndOneAtGrazing) {
  // ((n - 1) / (n + 1))^2 = (0.333 / 2.333)^2 = 0.0204 for water.
  EXPECT_NEAR(playback::fresnel_reflectance_at_normal_incidence(), 0.0204, 0.0001);
  EXPECT_NEAR(playback::fresnel_reflectance_exact(1.0), 0.0204, 0.0001);
  EXPECT_NEAR(playback::fresnel_reflectance(1.0), 0.0204, 0.0001);
  EXPECT_NEAR(playback::fresnel_reflectance(0.0), 1.0, 1e-12);
  EXPECT_NEAR(playback::fresnel_reflectance_exact(0.0), 1.0, 1e-12);
  // Schlick's approximation stays within 0.01 of Fresnel's equations up to 60 degrees incidence,
  // and within 0.06 beyond (its known worst, 0.059 near 84 degrees).
  for (double c = 0.0; c <= 1.0; c += 0.01)
    EXPECT_NEAR(playback::fresnel_reflectance(c), playback::fresnel_reflectance_exact(c), c >= 0.5 ? 0.01 : 0.06) << "cos " << c;
}

TEST(OceanBrdf, BrunetonErfcApproximationIsWithinHalfAPercent) {
  for (double x = 0.0; x <= 4.0; x += 0.01)
    EXPECT_NEAR(playback::erfc_approximation(x) / std::erfc(x), 1.0, 0.005) << "x " << x;
}

TEST(OceanBrdf, DirectionalAlbedoIsAtMostOne) {
  // Energy: integral over the hemisphere of brdf(v, l) cos(theta_l) <= 1 for every view, by the
  // midpoint rule on 0.2 x 0.4 degree cells (the lobe of the smallest variance is ~6 degrees
  // wide, so the quadrature error is far below the 1 % allowed).
  const playback::Vector3 n = {0, 0, 1};
  for (double variance : {0.003, 0.02, 0.1})
    for (double view_deg : {0.0, 30.0, 60.0, 80.0, 88.0}) {
      const playback::Vector3 v = {std::sin(view_deg * std::numbers::pi / 180), 0.0, std::cos(view_deg * std::numbers::pi / 180)};
      constexpr int kTheta = 450, kPhi = 900;
      const double d_theta = 0.5 * std::numbers::pi / kTheta, d_phi = 2 * std::numbers::pi / kPhi;
      double albedo = 0.0;
      for (int i = 0; i < kTheta; ++i) {
        const double theta = (i + 0.5) * d_theta;
        const double weight = std::cos(theta) * std::sin(theta) * d_theta * d_phi;
        for (int j = 0; j < kPhi; ++j) {
          const double phi = (j + 0.5) * d_phi;
          const playback::Vector3 l = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
          albedo += playback::ocean_brdf(n, v, l, variance) * weight;
        }
      }
      EXPECT_LE(albedo, 1.01) << "variance " << variance << " view " << view_deg;
      // and it is the Fresnel reflectance for a near-mirror seen from above
      if (variance == 0.003 && view_deg == 0.0) {
        EXPECT_NEAR(albedo, 0.0204, 0.002);
      }
      EXPECT_GT(albedo, 0.01);
    }
}

TEST(OceanBrdf, MeanFresnelGoesFromTwoPercentToOneAndRoughnessLowersGrazingReflection) {
  EXPECT_NEAR(playback::mean_fresnel_reflectance(1.0, 0.01), 0.0204, 1e-4);
  EXPECT_NEAR(playback::mean_fresnel_reflectance(0.0, 1e-8), 1.0, 1e-3);
  EXPECT_LT(playback::mean_fresnel_reflectance(0.1, 0.05), playback::mean_fresnel_reflectance(0.1, 0.001));
}

// ---- water colour from IOPs ----------------------------------------------------------------
TEST(WaterOptics, ChlorophyllMakesTheSeaGreenerAndCdomBrowner) {
  playback::WaterConstituents clear;
  clear.chlorophyll_mg_m3 = 0.05;
  clear.cdom_absorption_440_per_m = 0.005;
  clear.turbidity_ntu = 0.0;
  auto share = [](const Radiance& r, int c) { return r[std::size_t(c)] / (r[0] + r[1] + r[2]); };
  const Radiance clear_r = playback::water_optics(clear).deep_reflectance;
  EXPECT_GT(share(clear_r, 2), 0.6);  // clear ocean water is blue
  auto green = clear;
  green.chlorophyll_mg_m3 = 5.0;  // a bloom
  const Radiance green_r = playback::water_optics(green).deep_reflectance;
  EXPECT_GT(share(green_r, 1), share(clear_r, 1) + 0.1);
  EXPECT_GT(green_r[1], green_r[2]);
  auto brown = clear;
  brown.cdom_absorption_440_per_m = 1.0;  // a river plume
  brown.turbidity_ntu = 5.0;
  const Radiance brown_r = playback::water_optics(brown).deep_reflectance;
  EXPECT_LT(share(brown_r, 2), share(clear_r, 2) - 0.3);
  EXPECT_GT(brown_r[0] / brown_r[2], 5.0 * clear_r[0] / clear_r[2]);  // red over blue: towards brown
  EXPECT_GT(brown_r[0], brown_r[2]);
}

TEST(WaterOptics, TurbidWaterHidesTheSeabedSoonerAndDeepWaterShowsNone) {
  playback::WaterConstituents clear, turbid;
  clear.turbidity_ntu = 0.2;
  turbid.turbidity_ntu = 10.0;
  const Radiance sand = {0.55, 0.50, 0.38};
  const auto clear_o = playback::water_optics(clear), turbid_o = playback::water_optics(turbid);
  for (int c = 0; c < 3; ++c) EXPECT_GT(turbid_o.diffuse_attenuation_per_m[std::size_t(c)], clear_o.diffuse_attenuation_per_m[std::size_t(c)]);
  const Radiance at_zero = playback::shallow_water_reflectance(clear_o, sand, 0.0, 2.25);
  const Radiance deep = playback::shallow_water_reflectance(clear_o, sand, 1000.0, 2.25);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_NEAR(at_zero[c], sand[c], 1e-12);
    EXPECT_NEAR(deep[c], clear_o.deep_reflectance[c], 1e-9);
  }
  // The share of the seabed in what comes back from 3 m: (R - R_inf) / (A - R_inf).
  auto seabed_share = [&](const playback::WaterOptics& o, int c) {
    const Radiance r = playback::shallow_water_reflectance(o, sand, 3.0, 2.25);
    return (r[std::size_t(c)] - o.deep_reflectance[std::size_t(c)]) / (sand[std::size_t(c)] - o.deep_reflectance[std::size_t(c)]);
  };
  for (int c = 0; c < 3; ++c) EXPECT_GT(seabed_share(clear_o, c), 3.0 * seabed_share(turbid_o, c)) << "band " << c;
  EXPECT_GT(seabed_share(clear_o, 1), 0.5);  // 3 m of clear water: the sand shows
  EXPECT_LT(seabed_share(turbid_o, 1), 0.1);  // 10 NTU: it does not
}

TEST(WaterOptics, PhaseFunctionsIntegrateToOneAndParticlesScatterForward) {
  for (double g : {0.0, 0.5, 0.924}) {
    double total_p = 0.0, total_w = 0.0;
    constexpr int kSteps = 20000;
    for (int i = 0; i < kSteps; ++i) {
      const double mu = -1.0 + (i + 0.5) * 2.0 / kSteps;
      total_p += playback::particle_phase_function(mu, g) * 2 * std::numbers::pi * 2.0 / kSteps;
      total_w += playback::water_phase_function(mu) * 2 * std::numbers::pi * 2.0 / kSteps;
    }
    EXPECT_NEAR(total_w, 1.0, 1e-6);
    // Cornette-Shanks is normalised to 1 only approximately for g > 0 (it is a fit): 3 %.
    EXPECT_NEAR(total_p, 1.0, 0.03) << "g " << g;
  }
  // Petzold's measured backscattering ratios lie between 0.01 and 0.03 (Mobley 1994, table 3.10).
  const double back = playback::particle_backscatter_fraction(playback::kParticleAsymmetry);
  EXPECT_GT(back, 0.005);
  EXPECT_LT(back, 0.04);
}

// ---- the sea surface put together --------------------------------------------------------
TEST(Lighting, DeepWaterShowsTheWaterBodyAndShallowWaterTheSeabed) {
  Lighting lighting;
  lighting.sun_elevation_deg = 60;
  const auto frame = playback::prepare_lighting(lighting);
  playback::SurfacePoint deep, shallow;
  deep.to_eye = shallow.to_eye = {0, -0.6, 0.8};  // looking north, away from the sun (azimuth 200)
  deep.water_depth_m = 500.0;
  shallow.water_depth_m = 0.3;
  const Radiance d = playback::shade_water(frame, deep), s = playback::shade_water(frame, shallow);
  EXPECT_LT(d[0], d[2]);  // blue water
  EXPECT_GT(s[0], s[2]);  // sand through 30 cm of clear water
  EXPECT_GT(luminance(s), 2.0 * luminance(d));
}

TEST(Lighting, GlitterPeaksWhereTheSunIsMirrored) {
  Lighting lighting;
  lighting.sun_azimuth_deg = 180.0;  // south
  lighting.sun_elevation_deg = 20.0;
  lighting.sub_grid_slope_variance = 0.01;
  const auto frame = playback::prepare_lighting(lighting);
  const double e = 20.0 * std::numbers::pi / 180.0;
  playback::SurfacePoint towards_sun, away;
  towards_sun.to_eye = {0.0, std::cos(e), std::sin(e)};  // eye to the north, looking south
  away.to_eye = {0.0, -std::cos(e), std::sin(e)};
  EXPECT_GT(luminance(playback::shade_water(frame, towards_sun)), 20.0 * luminance(playback::shade_water(frame, away)));
}

TEST(Lighting, FullFoamIsTheLitFoamColourAndNothingIsNaNAtNight) {
  Lighting lighting;
  const auto frame = playback::prepare_lighting(lighting);
  playback::SurfacePoint foam;
  foam.foam = 1.0;
  const Radiance lit = playback::shade_water(frame, foam);
  const Radiance expected = playback::shade_lambertian(frame, {0, 0, 1}, lighting.foam_albedo);
  for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(lit[c], expected[c], 1e-9);
  for (double elevation : {-1.0, -10.0, -40.0}) {
    lighting.sun_elevation_deg = elevation;
    const auto night = playback::prepare_lighting(lighting);
    playback::SurfacePoint p;
    p.crest_thinness = 1.0;
    p.to_eye = {0.0, 0.99, std::sqrt(1 - 0.99 * 0.99)};
    for (double v : playback::to_display(night, playback::shade_water(night, p))) EXPECT_TRUE(std::isfinite(v));
    EXPECT_TRUE(std::isfinite(night.exposure));
  }
}

TEST(Lighting, SetSunForPlaceAndTimeUsesTheEphemeris) {
  Lighting lighting;
  lighting.set_sun_for(38.905, 121.695, UtcTime{2026, 6, 21, 4, 0, 0.0});  // Dalian, local noon ~12:00 CST
  EXPECT_NEAR(lighting.sun_elevation_deg, 90.0 - 38.905 + 23.44, 1.0);
  EXPECT_NEAR(lighting.sun_azimuth_deg, 180.0, 8.0);
}

// ---- display -------------------------------------------------------------------------------
TEST(Lighting, ExposureMapsLuminanceAndKeepsChromaticity) {
  Lighting lighting;
  const playback::LightingFrame frame = playback::prepare_lighting(lighting);
  const auto linear = [](const Radiance& display) {
    Radiance out;
    for (std::size_t c = 0; c < 3; ++c) out[c] = std::pow(display[c], 2.2);
    return out;
  };
  // A colour well inside the display: Y maps to 1 - exp(-k Y), the channels keep their ratios.
  const Radiance teal = {0.2 / frame.exposure, 0.5 / frame.exposure, 0.6 / frame.exposure};
  const Radiance shown = linear(playback::to_display(frame, teal));
  EXPECT_NEAR(luminance(shown), 1.0 - std::exp(-frame.exposure * luminance(teal)), 1e-12);
  EXPECT_NEAR(shown[0] / shown[2], teal[0] / teal[2], 1e-12);
  EXPECT_NEAR(shown[1] / shown[2], teal[1] / teal[2], 1e-12);
  // A bright saturated blue whose blue channel would pass 1: the blue is 1, the luminance still
  // the curve's, and the red/green ratio (the hue) unchanged by the move towards grey.
  const Radiance blue = {0.3 / frame.exposure, 0.6 / frame.exposure, 6.0 / frame.exposure};
  const Radiance bright = linear(playback::to_display(frame, blue));
  EXPECT_NEAR(bright[2], 1.0, 1e-12);
  EXPECT_NEAR(luminance(bright), 1.0 - std::exp(-frame.exposure * luminance(blue)), 1e-12);
  EXPECT_LT(bright[0], bright[1]);
  EXPECT_EQ(playback::to_display(frame, {0, 0, 0}), (Radiance{0, 0, 0}));
}

TEST(Lighting, TheNoonSkyIsDisplayedBlueNotGrey) {
  // The Preetham sky at noon (sun 74 degrees up, Dalian in June) 30 degrees above the horizon,
  // away from the sun: its linear colour is blue (B > R); once displayed it stays as blue as it
  // is: the displayed B / R equals the linear one to the power 1/2.2 (the hue survives the
  // exposure), where a curve per channel (the old 1 - exp(-k L) of each) pulled it towards grey.
  Lighting lighting;
  lighting.sun_azimuth_deg = 180.0;
  lighting.sun_elevation_deg = 74.0;
  const playback::LightingFrame frame = playback::prepare_lighting(lighting);
  const double e = 30.0 * std::numbers::pi / 180.0;
  const Radiance sky = playback::sky_radiance(frame.sky, {0.0, std::cos(e), std::sin(e)});
  ASSERT_GT(sky[2], 1.2 * sky[0]);
  const Radiance shown = playback::to_display(frame, sky);
  EXPECT_NEAR(shown[2] / shown[0], std::pow(sky[2] / sky[0], 1.0 / 2.2), 1e-9);
  double per_channel[3];
  for (std::size_t c = 0; c < 3; ++c) per_channel[c] = std::pow(1.0 - std::exp(-frame.exposure * sky[c]), 1.0 / 2.2);
  EXPECT_GT(shown[2] / shown[0], per_channel[2] / per_channel[0]);
}

// ---- detail normals ------------------------------------------------------------------------
TEST(Lighting, ParallaxOffsetIsWhereTheEyeRayMeetsTheRelief) {
  // Seed 004 eq. (5) against geometry: an eye 10 m up at the origin; the eye ray through the
  // drawn point B = (bx, by, 0) meets the plane z = h where the ray's parameter gives z = h, i.e.
  // at B + (E - B) h / 10 horizontally. The offset must be exactly that while the view is steeper
  // than the limit, and along the view but no longer than the limit's beyond it.
  const playback::Vector3 eye = {0.0, 0.0, 10.0};
  // straight down, 38, 15 and 2 degrees above the water (the last flatter than the limit)
  for (const auto& [bx, by] : {std::pair{0.0, 0.0}, std::pair{5.0, 12.0}, std::pair{-30.0, 20.0}, std::pair{0.0, 290.0}}) {
    for (double h : {0.4, -0.25}) {
      const double length = std::sqrt(bx * bx + by * by + 100.0);
      const playback::Vector3 to_eye = {(eye[0] - bx) / length, (eye[1] - by) / length, eye[2] / length};
      const auto offset = playback::parallax_offset_m(to_eye, h);
      if (to_eye[2] >= playback::kParallaxMinViewCosine) {
        EXPECT_NEAR(offset[0], (eye[0] - bx) * h / 10.0, 1e-12) << bx << ", " << by;
        EXPECT_NEAR(offset[1], (eye[1] - by) * h / 10.0, 1e-12) << bx << ", " << by;
      } else {
        EXPECT_LT(std::hypot(offset[0], offset[1]), std::abs(h) / playback::kParallaxMinViewCosine + 1e-12);
      }
    }
  }
  // Grazing (2 degrees): the lookup moves along the view by h / 0.12, not h / tan(2 degrees).
  const double g = 2.0 * std::numbers::pi / 180.0;
  const auto grazing = playback::parallax_offset_m({0.0, -std::cos(g), std::sin(g)}, 0.3);
  EXPECT_NEAR(grazing[1], -std::cos(g) * 0.3 / playback::kParallaxMinViewCosine, 1e-12);
  EXPECT_EQ(grazing[0], 0.0);
}

TEST(Lighting, DetailNormalsFadeWithFootprintAndTheirReliefWhereTheGridCannotDrawIt) {
  const double texel = 0.5;
  EXPECT_EQ(playback::detail_normal_weight(texel, 0.4), 1.0);   // a pixel within a texel keeps it all
  EXPECT_EQ(playback::detail_normal_weight(texel, 2.0), 0.0);   // four texels a pixel: into the variance
  EXPECT_NEAR(playback::detail_normal_weight(texel, 1.25), 0.5, 1e-12);
  // The grid's vertices every kMeshVertexSpacingPx pixels: at most a texel apart, the grid draws the
  // cascade's relief (no parallax); four texels apart, none of it.
  EXPECT_EQ(playback::unresolved_relief_weight(texel, texel / playback::kMeshVertexSpacingPx), 0.0);
  EXPECT_EQ(playback::unresolved_relief_weight(texel, 4.0 * texel / playback::kMeshVertexSpacingPx), 1.0);
  double previous = 0.0;
  for (double footprint = 0.05; footprint < 3.0; footprint += 0.05) {
    const double w = playback::unresolved_relief_weight(texel, footprint);
    EXPECT_GE(w, previous);
    previous = w;
  }
}

namespace {
double luminance_of(const Radiance& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }
}  // namespace

TEST(Weather, OvercastSkyIsTheCieSkyOfKrochmannsIlluminance) {
  // CIE standard overcast sky: zenith three times the horizon, the same in every azimuth, grey;
  // its dome gives the horizontal illuminance of Krochmann & Seidl (1974), 0.3 + 21 sin(e) klx
  // (the midpoint rule of sky_illuminance_klx: within 1 %). No sun beam under full cloud.
  for (const double elevation : {10.0, 35.0, 60.0}) {
    const playback::SkyModel sky = playback::make_sky(200.0, elevation, 4.0, 1.0);
    const double zenith = luminance_of(playback::sky_radiance(sky, {0, 0, 1}));
    const Radiance north = playback::sky_radiance(sky, {0, 1, 0}), south = playback::sky_radiance(sky, {0, -1, 0});
    EXPECT_NEAR(zenith / luminance_of(north), 3.0, 1e-9);
    EXPECT_NEAR(luminance_of(north), luminance_of(south), 1e-12);
    EXPECT_NEAR(north[0], north[2], 1e-12) << "grey";
    const double expected_klx = 0.3 + 21.0 * std::sin(elevation * std::numbers::pi / 180.0);
    EXPECT_NEAR(luminance_of(playback::sky_illuminance_klx(sky)), expected_klx, 0.01 * expected_klx) << elevation;
    EXPECT_EQ(luminance_of(sky.sun_illuminance_klx), 0.0);
  }
  // Half cover: half of each sky and half of the sun's beam.
  const playback::SkyModel clear = playback::make_sky(200.0, 35.0, 4.0, 0.0), half = playback::make_sky(200.0, 35.0, 4.0, 0.5),
                           full = playback::make_sky(200.0, 35.0, 4.0, 1.0);
  const playback::Vector3 direction = {0.3, 0.5, 0.81};
  EXPECT_NEAR(luminance_of(playback::sky_radiance(half, direction)),
              0.5 * (luminance_of(playback::sky_radiance(clear, direction)) + luminance_of(playback::sky_radiance(full, direction))), 1e-9);
  EXPECT_NEAR(luminance_of(half.sun_illuminance_klx), 0.5 * luminance_of(clear.sun_illuminance_klx), 1e-9);
}

TEST(Weather, FogFollowsKoschmiederAndTheWmoVisibility) {
  Lighting lighting;
  playback::apply_weather(lighting, "fog");
  const playback::LightingFrame frame = playback::prepare_lighting(lighting);
  const double visibility = lighting.visibility_m, top = lighting.fog_top_m;
  // A black object at the visibility, seen horizontally inside the layer, keeps 5 % contrast
  // against the fog behind it (the WMO's meteorological optical range).
  const playback::Vector3 eye = {0, 0, 20}, object = {visibility, 0, 20};
  const Radiance seen = playback::through_air(frame, {0, 0, 0}, eye, object);
  const Radiance fog = playback::fog_radiance(frame, {1, 0, 0});
  EXPECT_NEAR(1.0 - luminance_of(seen) / luminance_of(fog), 0.05, 1e-9);
  // From above the layer (an aircraft at 3 x the top) straight down: only the layer's depth counts.
  EXPECT_NEAR(playback::fog_transmittance(frame, {0, 0, 3 * top}, {0, 0, 0}), std::exp(-frame.fog_extinction_per_m * top), 1e-12);
  EXPECT_EQ(playback::fog_transmittance(frame, {0, 0, 3 * top}, {500, 0, 2 * top}), 1.0) << "both above the layer";
  // The sky at the zenith from the sea: dimmed by the layer's whole depth, from its top: not at all.
  const Radiance zenith = playback::sky_radiance(frame.sky, {0, 0, 1});
  const double t = std::exp(-frame.fog_extinction_per_m * top);
  const Radiance from_sea = playback::sky_seen(frame, {0, 0, 0}, {0, 0, 1});
  EXPECT_NEAR(luminance_of(from_sea), t * luminance_of(zenith) + (1 - t) * luminance_of(playback::fog_radiance(frame, {0, 0, 1})), 1e-9);
  EXPECT_NEAR(luminance_of(playback::sky_seen(frame, {0, 0, top}, {0, 0, 1})), luminance_of(zenith), 1e-12);
  // Clear air changes nothing.
  const playback::LightingFrame clear = playback::prepare_lighting(Lighting{});
  EXPECT_EQ(playback::through_air(clear, {1, 2, 3}, eye, object), (Radiance{1, 2, 3}));
}

TEST(Weather, PresetsByNameAndAnUnknownNameListsThem) {
  Lighting lighting;
  playback::apply_weather(lighting, "mist");
  EXPECT_EQ(lighting.cloud_cover, 1.0);
  EXPECT_GE(lighting.visibility_m, 1000.0);  // WMO: mist 1-5 km
  EXPECT_LE(lighting.visibility_m, 5000.0);
  playback::apply_weather(lighting, "fog");
  EXPECT_LT(lighting.visibility_m, 1000.0);  // WMO: fog below 1 km
  try {
    playback::apply_weather(lighting, "drizzle");
    FAIL() << "an unknown weather was accepted";
  } catch (const nearshore::Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("drizzle"), std::string::npos);
    for (const char* name : {"clear", "hazy", "overcast", "mist", "fog"}) EXPECT_NE(message.find(name), std::string::npos) << name;
  }
}

TEST(Lighting, GlitterFacetsFollowCoxAndMunksEllipseAlongTheWind) {
  // The facet-slope density integrates to 1 and its second moments along and across the wind are
  // the frame's upwind and crosswind variances (plus the isotropic extra): at 10 m/s the total
  // 0.0542 splits 0.0333 / 0.0209 (Cox & Munk's own fits 0.0316 and 0.0222, the calm sea's 0.003
  // all crosswind), whatever way the wind blows.
  Lighting lighting;
  lighting.wind_speed_m_s = 10.0;
  lighting.wind_direction_rad = 0.7;
  const playback::LightingFrame frame = playback::prepare_lighting(lighting);
  EXPECT_NEAR(frame.slope_variance_upwind, playback::cox_munk_slope_variance(10.0) * (0.0015 + 0.0316) / (0.003 + 0.0508), 1e-12);
  EXPECT_NEAR(frame.slope_variance_upwind + frame.slope_variance_crosswind, playback::cox_munk_slope_variance(10.0), 1e-12);
  EXPECT_GT(frame.slope_variance_upwind / frame.slope_variance_crosswind, 1.4);
  const double extra = 0.002, step = 0.002;
  double mass = 0, along2 = 0, across2 = 0;
  for (double a = -1.0; a <= 1.0; a += step)
    for (double c = -1.0; c <= 1.0; c += step) {
      const double p = playback::facet_slope_density(frame, a, c, extra) * step * step;
      mass += p, along2 += p * a * a, across2 += p * c * c;
    }
  EXPECT_NEAR(mass, 1.0, 1e-3);
  EXPECT_NEAR(along2, frame.slope_variance_upwind + extra, 1e-4);
  EXPECT_NEAR(across2, frame.slope_variance_crosswind + extra, 1e-4);
  // Smith's and the mean Fresnel's roughness: the upwind variance looking along the wind, the
  // crosswind one across it, the mean straight down.
  const playback::Vector3 downwind = {std::cos(0.7), std::sin(0.7), 0.3}, crosswind = {-std::sin(0.7), std::cos(0.7), 0.3};
  EXPECT_NEAR(playback::slope_variance_along(frame, downwind, 0.0), frame.slope_variance_upwind, 1e-12);
  EXPECT_NEAR(playback::slope_variance_along(frame, crosswind, 0.0), frame.slope_variance_crosswind, 1e-12);
  EXPECT_NEAR(playback::slope_variance_along(frame, {0, 0, 1}, 0.0), frame.slope_variance_per_axis, 1e-12);
}

TEST(Lighting, TheRefractedSceneIsTheFlatSeabedTermForTermAndItsProbeFollowsSnell) {
  // Screen-space refraction (docs/lighting.md step 5): the opaque scene's seabed, drawn in air
  // as L = A t E_air / pi (shade_lambertian facing up), found d below the surface along the
  // refracted view (path d / cos theta_w) gives the procedural seabed's radiance exactly.
  Lighting lighting;
  lighting.water.turbidity_ntu = 2.0;
  const playback::LightingFrame frame = playback::prepare_lighting(lighting);
  const double s = std::sin(0.6), c = std::cos(0.6);  // a view 34 degrees from the vertical
  for (const double depth : {0.5, 3.0, 12.0}) {
    playback::SurfacePoint procedural;
    procedural.to_eye = {s, 0.0, c};
    procedural.water_depth_m = depth;
    procedural.seabed_albedo_scale = 1.13;
    playback::SurfacePoint refracted = procedural;
    const Radiance albedo = {frame.seabed_albedo[0] * 1.13, frame.seabed_albedo[1] * 1.13, frame.seabed_albedo[2] * 1.13};
    refracted.refracted_scene = playback::shade_lambertian(frame, {0, 0, 1}, albedo);
    refracted.refracted_scene_coverage = 1.0;
    const double cos_w = std::sqrt(1.0 - s * s / (1.333 * 1.333));
    refracted.refracted_depth_m = depth;
    refracted.refracted_path_m = depth / cos_w;
    const Radiance a = playback::shade_water(frame, procedural), b = playback::shade_water(frame, refracted);
    for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(b[k], a[k], 1e-12 * a[k]) << "depth " << depth << " band " << k;
  }
  // The probe: d below the point, displaced away from the eye by d tan(theta_w) (Snell); with the
  // depth the scene shows, it is where the refracted ray meets that depth.
  const auto probe = playback::refraction_probe_m({10.0, 20.0, 0.5}, {0, 0, 1}, {-s, 0, c}, 4.0);
  EXPECT_NEAR(probe[2], 0.5 - 4.0, 1e-12);
  EXPECT_NEAR(probe[0], 10.0 + 4.0 * std::tan(std::asin(s / 1.333)), 1e-9);
  EXPECT_NEAR(probe[1], 20.0, 1e-12);
  // What a submerged object keeps: exp(-K (d / 0.8 + path)) per band; nothing lost at the surface.
  const Radiance kept = playback::submerged_transmittance(frame, 2.0, 3.0);
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(kept[k], std::exp(-frame.water.diffuse_attenuation_per_m[k] * (2.0 / 0.8 + 3.0)), 1e-15);
  EXPECT_EQ(playback::submerged_transmittance(frame, 0.0, 0.0)[1], 1.0);
  // from_display undoes to_display (the 8-bit scene copy's colour back to radiance).
  for (const Radiance& radiance : {Radiance{0.02, 0.03, 0.05}, Radiance{1.0, 0.8, 0.5}, Radiance{3.0, 3.1, 2.5}}) {
    const Radiance back = playback::from_display(frame, playback::to_display(frame, radiance));
    for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(back[k], radiance[k], 1e-9 * radiance[k]);
  }
}

TEST(Lighting, StructuresFoamFromTheAirEntrainmentOnsetAlongTheirFace) {
  // structure_foam: the water's speed along the face is |rate| / sin(alpha) on a 1:1.5 rubble slope
  // (sin 0.555), the rising rate on a vertical wall; foam from the onset (1 m/s), white at twice it,
  // fading linearly to nothing a band off the face.
  const playback::LightingFrame frame = playback::prepare_lighting(Lighting{});
  EXPECT_NEAR(playback::kRubbleMoundFaceSine, std::sin(std::atan(1.0 / 1.5)), 1e-15);
  const double s = playback::kRubbleMoundFaceSine;
  EXPECT_EQ(playback::structure_foam(frame, 0.99 * s, s, 0.0, 8.0), 0.0);   // 0.99 m/s up the slope
  EXPECT_NEAR(playback::structure_foam(frame, 1.5 * s, s, 0.0, 8.0), 0.5, 1e-12);
  EXPECT_NEAR(playback::structure_foam(frame, -1.5 * s, s, 0.0, 8.0), 0.5, 1e-12);  // the down-rush too
  EXPECT_EQ(playback::structure_foam(frame, 3.0, s, 0.0, 8.0), 1.0);
  EXPECT_NEAR(playback::structure_foam(frame, 3.0, s, 6.0, 8.0), 0.25, 1e-12);
  EXPECT_EQ(playback::structure_foam(frame, 3.0, s, 8.0, 8.0), 0.0);
  // A vertical wall: the same rate foams less (no slope to run up), and falling water not at all.
  EXPECT_NEAR(playback::structure_foam(frame, 1.5, 1.0, 0.0, 8.0), 0.5, 1e-12);
  EXPECT_EQ(playback::structure_foam(frame, 0.9, 1.0, 0.0, 8.0), 0.0);
  EXPECT_GT(playback::structure_foam(frame, 0.9, s, 0.0, 8.0), 0.0);
  EXPECT_EQ(playback::structure_foam(frame, -3.0, 1.0, 0.0, 8.0), 0.0);
  // Off: an infinite onset.
  Lighting off;
  off.structure_foam_onset_m_s = std::numeric_limits<double>::infinity();
  EXPECT_EQ(playback::structure_foam(playback::prepare_lighting(off), 30.0, s, 0.0, 8.0), 0.0);
}

TEST(Lighting, TheSeabedIsSeenWhereTheRefractedViewMeetsItAndItsTextureAveragesOne) {
  // Snell: a view 45 degrees from the vertical refracts to asin(sin 45 / 1.333) = 32.0 degrees, so
  // a seabed 4 m down is met tan(32.0) x 4 = 2.50 m beyond the point, away from the eye; straight
  // down it is met right below.
  const double s = std::sqrt(0.5);
  const auto bottom = playback::refracted_seabed_point(10.0, 20.0, {0, 0, 1}, {-s, 0, s}, 4.0);
  EXPECT_NEAR(bottom[0], 10.0 + 4.0 * std::tan(std::asin(s / 1.333)), 1e-3);
  EXPECT_NEAR(bottom[1], 20.0, 1e-12);
  const auto below = playback::refracted_seabed_point(10.0, 20.0, {0, 0, 1}, {0, 0, 1}, 4.0);
  EXPECT_NEAR(below[0], 10.0, 1e-12);
  // The texture keeps the seabed's mean albedo (mean 1 over a wide area, within 2 %) and stays in
  // 0.7 .. 1.3.
  double sum = 0, lowest = 2, highest = 0;
  int count = 0;
  for (double x = 0; x < 2000; x += 1.7)
    for (double y = 0; y < 2000; y += 1.9) {
      const double t = playback::seabed_texture(x, y);
      sum += t, ++count, lowest = std::min(lowest, t), highest = std::max(highest, t);
    }
  EXPECT_NEAR(sum / count, 1.0, 0.02);
  EXPECT_GE(lowest, 0.7);
  EXPECT_LE(highest, 1.3);
}
