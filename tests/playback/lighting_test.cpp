// The CPU reference of seed 003 eq. (12)-(16) against limits known without any code.
#include "nearshore/playback/lighting.hpp"

#include <gtest/gtest.h>

#include <cmath>

using nearshore::playback::Lighting;

TEST(Lighting, FresnelOfWaterAtNormalIncidenceIsTwoPercentAndOneAtGrazing) {
  // ((n - 1) / (n + 1))^2 = (0.333 / 2.333)^2 = 0.0204 for water.
  EXPECT_NEAR(nearshore::playback::fresnel_reflectance(1.0), 0.0204, 0.001);
  EXPECT_NEAR(nearshore::playback::fresnel_reflectance(0.0), 1.0, 1e-12);
}

TEST(Lighting, SunDirectionFollowsCompassBearing) {
  Lighting lighting;
  lighting.sun_azimuth_deg = 90;  // due east
  lighting.sun_elevation_deg = 30;
  const auto sun = lighting.sun_direction();
  EXPECT_NEAR(sun[0], std::cos(M_PI / 6), 1e-12);
  EXPECT_NEAR(sun[1], 0.0, 1e-12);
  EXPECT_NEAR(sun[2], 0.5, 1e-12);
}

TEST(Lighting, DeepWaterShowsTheWaterBodyAndShallowWaterTheSeabed) {
  Lighting lighting;
  lighting.sun_elevation_deg = 60;
  const nearshore::playback::Vector3 up = {0, 0, 1};
  const nearshore::playback::Vector3 to_eye = {0, 0.6, 0.8};
  const auto deep = nearshore::playback::shade_water(lighting, up, to_eye, 500.0, 0.0);
  const auto shallow = nearshore::playback::shade_water(lighting, up, to_eye, 0.05, 0.0);
  // eq. (14): over a deep seabed the transmitted light exp(-atten * path) vanishes, so red (most
  // absorbed) falls below blue; over 5 cm of water the sand (red > blue) shows through.
  EXPECT_LT(deep[0], deep[2]);
  EXPECT_GT(shallow[0], shallow[2]);
}

TEST(Lighting, FullFoamIsTheLitFoamColour) {
  Lighting lighting;
  const nearshore::playback::Vector3 up = {0, 0, 1};
  const auto foam = nearshore::playback::shade_water(lighting, up, up, 5.0, 1.0);
  const auto sun = lighting.sun_direction();
  for (int c = 0; c < 3; ++c) {
    const double irradiance = lighting.sun_radiance[c] * sun[2] + 0.6 * 0.5 * (lighting.sky_horizon[c] + lighting.sky_zenith[c]);
    EXPECT_NEAR(foam[c], lighting.foam_colour[c] * irradiance, 1e-9);
  }
}
