#include "nearshore/playback/sun_position.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <regex>

#include "nearshore/core/error.hpp"

namespace nearshore::playback {
namespace {
constexpr double kDegree = std::numbers::pi / 180.0;
double sin_deg(double a) { return std::sin(a * kDegree); }
double cos_deg(double a) { return std::cos(a * kDegree); }
double wrap_360(double a) { return a - 360.0 * std::floor(a / 360.0); }

// Atmospheric refraction (degrees) at a geometric elevation e (degrees): the NOAA calculator's
// piecewise fit (Bennett-type above 5 degrees, a polynomial near the horizon, and the
// below-horizon branch), for 1010 hPa and 10 degrees C.
double refraction_deg(double e) {
  if (e > 85.0) return 0.0;
  const double t = std::tan(e * kDegree);
  double arcseconds = 0.0;
  if (e > 5.0)
    arcseconds = 58.1 / t - 0.07 / (t * t * t) + 0.000086 / std::pow(t, 5);
  else if (e > -0.575)
    arcseconds = 1735.0 + e * (-518.2 + e * (103.4 + e * (-12.79 + e * 0.711)));
  else
    arcseconds = -20.774 / t;
  return arcseconds / 3600.0;
}
}  // namespace

double UtcTime::julian_day() const {
  // Meeus eq. 7.1 with the Gregorian correction B = 2 - A + A/4.
  int y = year, m = month;
  if (m <= 2) {
    y -= 1;
    m += 12;
  }
  const int a = y / 100;
  const int b = 2 - a + a / 4;
  const double day_fraction = (hour + (minute + second / 60.0) / 60.0) / 24.0;
  return std::floor(365.25 * (y + 4716)) + std::floor(30.6001 * (m + 1)) + day + day_fraction + b - 1524.5;
}

UtcTime UtcTime::parse(const std::string& text) {
  static const std::regex pattern(R"((\d{4})-(\d{2})-(\d{2})[T ](\d{2}):(\d{2})(?::(\d{2}(?:\.\d*)?))?(Z|\+00:00)?)");
  std::smatch match;
  if (!std::regex_match(text, match, pattern))
    throw Error("UTC time \"" + text + "\"", "is not an ISO 8601 date and time",
                "write it as YYYY-MM-DDThh:mm[:ss]Z, e.g. 2026-06-21T12:00:00Z");
  UtcTime t;
  t.year = std::stoi(match[1]);
  t.month = std::stoi(match[2]);
  t.day = std::stoi(match[3]);
  t.hour = std::stoi(match[4]);
  t.minute = std::stoi(match[5]);
  t.second = match[6].matched ? std::stod(match[6]) : 0.0;
  if (t.month < 1 || t.month > 12 || t.day < 1 || t.day > 31 || t.hour > 23 || t.minute > 59 || t.second >= 61.0)
    throw Error("UTC time \"" + text + "\"", "has a month, day, hour, minute or second out of range",
                "give a real date and a time of day from 00:00:00 to 23:59:59");
  return t;
}

std::string UtcTime::to_string() const {
  char text[40];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02.0fZ", year, month, day, hour, minute, second);
  return text;
}

SunPosition sun_position(double latitude_deg, double longitude_deg, const UtcTime& time) {
  if (!std::isfinite(latitude_deg) || !std::isfinite(longitude_deg) || std::abs(latitude_deg) > 90.0)
    throw Error("sun position", "latitude " + std::to_string(latitude_deg) + ", longitude " + std::to_string(longitude_deg),
                "give a latitude in [-90, 90] degrees (north positive) and a finite longitude (east positive)");
  // 1. Julian centuries from J2000.0. UTC stands in for Terrestrial Time: the ~70 s between them
  //    move the sun by 0.001 degree, far inside the algorithm's own 0.01 degree.
  const double T = (time.julian_day() - 2451545.0) / 36525.0;
  // 2. The sun's geometric mean longitude and mean anomaly, the eccentricity of the Earth's
  //    orbit and the equation of the centre (Meeus ch. 25, eq. 25.2-25.4).
  const double L0 = wrap_360(280.46646 + T * (36000.76983 + T * 0.0003032));
  const double M = 357.52911 + T * (35999.05029 - 0.0001537 * T);
  const double e = 0.016708634 - T * (0.000042037 + 0.0000001267 * T);
  const double C = sin_deg(M) * (1.914602 - T * (0.004817 + 0.000014 * T)) + sin_deg(2 * M) * (0.019993 - 0.000101 * T) +
                   sin_deg(3 * M) * 0.000289;
  // 3. Apparent longitude (nutation and aberration), obliquity of the ecliptic (eq. 22.2, 25.8).
  const double omega = 125.04 - 1934.136 * T;
  const double lambda = L0 + C - 0.00569 - 0.00478 * sin_deg(omega);
  const double epsilon0 = 23.0 + (26.0 + (21.448 - T * (46.815 + T * (0.00059 - T * 0.001813))) / 60.0) / 60.0;
  const double epsilon = epsilon0 + 0.00256 * cos_deg(omega);
  // 4. Apparent right ascension and declination (eq. 25.6, 25.7).
  SunPosition sun;
  sun.right_ascension_deg = wrap_360(std::atan2(cos_deg(epsilon) * sin_deg(lambda), cos_deg(lambda)) / kDegree);
  sun.declination_deg = std::asin(sin_deg(epsilon) * sin_deg(lambda)) / kDegree;
  // 5. Equation of time (Meeus eq. 28.3, Smart's series), minutes.
  const double y = std::pow(std::tan(epsilon / 2.0 * kDegree), 2);
  sun.equation_of_time_min = 4.0 / kDegree *
                             (y * sin_deg(2 * L0) - 2 * e * sin_deg(M) + 4 * e * y * sin_deg(M) * cos_deg(2 * L0) -
                              0.5 * y * y * sin_deg(4 * L0) - 1.25 * e * e * sin_deg(2 * M));
  // 6. True solar time, hour angle, and the local horizontal coordinates.
  const double utc_minutes = time.hour * 60.0 + time.minute + time.second / 60.0;
  const double true_solar_minutes = utc_minutes + sun.equation_of_time_min + 4.0 * longitude_deg;
  const double hour_angle = true_solar_minutes / 4.0 - 180.0;
  const double phi = latitude_deg, delta = sun.declination_deg;
  const double cos_zenith = std::clamp(sin_deg(phi) * sin_deg(delta) + cos_deg(phi) * cos_deg(delta) * cos_deg(hour_angle), -1.0, 1.0);
  sun.geometric_elevation_deg = 90.0 - std::acos(cos_zenith) / kDegree;
  // Azimuth from north, clockwise: atan2 of the east and north components of the sun's direction.
  const double east = -cos_deg(delta) * sin_deg(hour_angle);
  const double north = sin_deg(delta) * cos_deg(phi) - cos_deg(delta) * sin_deg(phi) * cos_deg(hour_angle);
  sun.azimuth_deg = wrap_360(std::atan2(east, north) / kDegree);
  sun.elevation_deg = sun.geometric_elevation_deg + refraction_deg(sun.geometric_elevation_deg);
  return sun;
}

}  // namespace nearshore::playback
