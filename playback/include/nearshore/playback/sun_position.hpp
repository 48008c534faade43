#pragma once
// Where the sun stands, seen from a place on the Earth at a UTC instant: the NOAA solar
// calculator's algorithm (NOAA Global Monitoring Laboratory, "General Solar Position
// Calculations", after Meeus, Astronomical Algorithms, 2nd ed. 1998, ch. 7, 22 and 25: the low
// accuracy solar coordinates, ~0.01 degree from 1950 to 2050) with its atmospheric refraction
// correction. GL-free: the sky model (sky_model.hpp) and a host's own lighting read it.
#include <string>

namespace nearshore::playback {

/// A calendar instant in Coordinated Universal Time (proleptic Gregorian calendar).
struct UtcTime {
  int year = 2026, month = 6, day = 21;  ///< month 1..12, day 1..31
  int hour = 12, minute = 0;             ///< 0..23, 0..59
  double second = 0.0;                   ///< 0..60

  /// Julian Day (days since 4713 BC January 1, 12h), Meeus eq. 7.1.
  double julian_day() const;
  /// "2026-06-21T12:00:00Z" (the trailing Z or "+00:00" optional; seconds optional).
  static UtcTime parse(const std::string& text);
  std::string to_string() const;
};

/// The sun seen from a place at an instant.
struct SunPosition {
  double azimuth_deg = 0.0;      ///< compass bearing: 0 north, 90 east, clockwise
  double elevation_deg = 0.0;    ///< apparent (refracted) height above the horizon
  double geometric_elevation_deg = 0.0;  ///< without atmospheric refraction
  double declination_deg = 0.0;  ///< apparent declination
  double right_ascension_deg = 0.0;  ///< apparent right ascension, 0..360
  double equation_of_time_min = 0.0;  ///< apparent minus mean solar time, minutes
};

/// NOAA/Meeus sun position at latitude (north positive) and longitude (east positive), degrees.
/// Throws nearshore::Error for a latitude outside [-90, 90] or a non-finite input.
SunPosition sun_position(double latitude_deg, double longitude_deg, const UtcTime& time);

}  // namespace nearshore::playback
