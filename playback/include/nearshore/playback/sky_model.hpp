#pragma once
// The clear sky and the sunlight that reaches the sea, from the sun's position and the
// atmosphere's turbidity (GL-free; shaders/common.glsl evaluates the same formulas per pixel).
//
//  - Sky: Preetham, Shirley & Smits (1999), "A practical analytic model for daylight": the Perez
//    luminance distribution with Preetham's turbidity-linear coefficients, scaled by the zenith
//    luminance and chromaticity of seed 001 eq. (3)-(5) (Preetham's appendix A.2), then
//    xyY -> XYZ -> linear sRGB by seed 001 eq. (11)-(12).
//  - Sun: the extraterrestrial illuminance dimmed along the air mass by Rayleigh and aerosol
//    optical depths (Preetham appendix A.1's Angstrom turbidity), per colour band.
//  - Cloud: the CIE standard overcast sky (Moon & Spencer 1942; CIE S 011/E:2003 sky type 1),
//    L(theta) = L_z (1 + 2 cos theta) / 3, grey (D65), its zenith luminance from the horizontal
//    illuminance of an overcast day E_h = 0.3 + 21 sin(sun elevation) klx (Krochmann & Seidl 1974)
//    through E_h = 7 pi L_z / 9; the sun's beam hidden. A cloud cover c between 0 and 1 mixes the
//    two skies linearly (c of the overcast one, 1 - c of the clear one and of the sun's beam): a
//    simple stand-in for CIE's intermediate skies, exact at both ends.
//  - Twilight and night: the model is fitted for the sun above the horizon; below it, the sky of
//    a sun on the horizon is dimmed by a decade per 2.4 degrees of depression (a zenith luminance
//    of ~3 cd/m2 at civil dusk, sun 6 degrees down) to a floor of a moonless night, and the
//    sun's disc fades out as it sets. Nothing below the horizon produces NaN or a negative colour.
//
// Units: luminance in kcd/m2 (the unit of seed 001's Y_zenith), illuminance in klx, so a
// Lambertian surface of albedo A under illuminance E has radiance A E / pi in the same unit.
// Colours are linear sRGB triples whose Y (0.2126 R + 0.7152 G + 0.0722 B) is the luminance.
#include <array>

#include "nearshore/playback/vector3.hpp"

namespace nearshore::playback {

using Radiance = std::array<double, 3>;  ///< linear sRGB, kcd/m2 (luminance-weighted)

/// Perez et al. (1993) distribution coefficients A..E of one quantity (Y, x or y).
using PerezCoefficients = std::array<double, 5>;

/// The band centres the colour channels stand for (seed 000 section 3.3.2: red 620 nm, green
/// 520 nm, blue 440 nm); the sun's attenuation and the water's optics use them.
constexpr std::array<double, 3> kBandWavelengthsNm = {620.0, 520.0, 440.0};

struct SkyModel {
  Vector3 sun_direction = {0, 0, 1};    ///< unit, towards the sun (x east, y north, z up)
  double sun_zenith_rad = 0.0;          ///< theta_s the model was evaluated at (<= pi/2)
  double turbidity = 2.5;               ///< T, clamped to Preetham's fitted range [1.7, 10]
  PerezCoefficients perez_Y{}, perez_x{}, perez_y{};
  double zenith_luminance_kcd_m2 = 0.0; ///< Y_zenith (after the twilight factor)
  double zenith_x = 0.0, zenith_y = 0.0;
  /// The Perez denominators F(0, theta_s) of Y, x, y: the ratio formula, seed 001 eq. (7).
  double perez_zenith_Y = 1.0, perez_zenith_x = 1.0, perez_zenith_y = 1.0;
  double night_luminance_kcd_m2 = 1e-6; ///< floor: a moonless night sky (~1 mcd/m2)
  /// Illuminance of the sun's beam on a plane facing it, per colour band (klx), 0 once it set.
  Radiance sun_illuminance_klx = {0, 0, 0};
  double cloud_cover = 0.0;                       ///< c in [0, 1]: the overcast sky's share
  double overcast_zenith_luminance_kcd_m2 = 0.0;  ///< L_z of the CIE overcast sky
};

/// Seed 001 eq. (3): Y_zenith (kcd/m2) for turbidity T and sun zenith angle theta_s (rad);
/// Preetham (1999) appendix A.2. Defined for theta_s <= pi/2 (the twilight factor does the rest).
double preetham_zenith_luminance_kcd_m2(double turbidity, double sun_zenith_rad);
/// Seed 001 eq. (4)-(5): the zenith chromaticity x, y (Preetham's matrices).
double preetham_zenith_x(double turbidity, double sun_zenith_rad);
double preetham_zenith_y(double turbidity, double sun_zenith_rad);
/// Preetham's coefficients, linear in T (appendix A.2).
PerezCoefficients preetham_perez_Y(double turbidity);
PerezCoefficients preetham_perez_x(double turbidity);
PerezCoefficients preetham_perez_y(double turbidity);
/// Perez F(theta, gamma) = (1 + A e^(B / cos theta)) (1 + C e^(D gamma) + E cos^2 gamma).
double perez(const PerezCoefficients& c, double cos_theta, double gamma_rad);

/// Air mass of a path at zenith angle theta (Kasten 1966, as Preetham uses), capped at the horizon.
double relative_air_mass(double zenith_rad);
/// Fraction of the sun's beam reaching sea level per band: exp(-m (tau_Rayleigh + tau_aerosol)),
/// Rayleigh 0.008735 lambda^-4.08 (lambda in micrometres, Leckner 1978), aerosol beta lambda^-1.3
/// with Preetham's beta = 0.04608 T - 0.04586.
Radiance sun_transmittance(double turbidity, double zenith_rad);

/// Horizontal illuminance of an overcast sky (klx) for a sun at this elevation: 0.3 + 21 sin(e)
/// (Krochmann & Seidl 1974), dimmed below the horizon by a decade per 2.4 degrees as the clear sky is.
double overcast_horizontal_illuminance_klx(double sun_elevation_deg);
/// The sky for a sun at compass azimuth / apparent elevation (degrees), turbidity T and cloud cover c.
SkyModel make_sky(double sun_azimuth_deg, double sun_elevation_deg, double turbidity, double cloud_cover = 0.0);
/// Sky luminance and colour seen along a unit direction (z up). Below the horizon the horizon's
/// value (the sea's reflection of a grazing ray sees the sky's lowest band).
Radiance sky_radiance(const SkyModel& sky, const Vector3& direction);
/// Illuminance of the sky dome on a horizontal plane (klx per band): the cosine-weighted
/// integral of sky_radiance over the upper hemisphere (the ambient light of land, water, foam).
Radiance sky_illuminance_klx(const SkyModel& sky);
/// Linear sRGB from CIE xyY: seed 001 eq. (11)-(12).
Radiance xyY_to_linear_srgb(double x, double y, double Y);

}  // namespace nearshore::playback
