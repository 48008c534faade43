#pragma once
// Readers for the laboratory data in ../shared/validation (read in place, never copied), and the
// statistics the comparisons use. Each reader states the column meanings of its case's README.
#include <filesystem>
#include <string>
#include <vector>

namespace nearshore::validation {

std::filesystem::path shared_validation_folder();  ///< NEARSHORE_SHARED_DIR/validation

// ---- Berkhoff, Booij & Radder (1982) ------------------------------------------------------------
/// One measured point: amplitude ratio A/A0 at a position given relative to the shoal centre.
struct BerkhoffPoint {
  int transect = 0;              ///< 1..8
  double downwave_m = 0.0;       ///< distance behind the shoal centre along the wave direction
  double transverse_m = 0.0;     ///< across the flume, 0 on the centreline (the paper's x)
  double amplitude_ratio = 0.0;  ///< A / A0, A0 = 23.2 mm
};
inline constexpr double kBerkhoffIncidentAmplitude_m = 0.0232;
/// All 208 points: transects 1-5 (section1..5.dat, 1, 3, 5, 7, 9 m behind the centre, column 1 the
/// transverse coordinate, column 2 the amplitude in mm) and 6-8 (section678.dat, at transverse
/// -2, 0, +2 m; column 1 = minus the downwave distance, columns 2-4 the amplitudes in mm).
std::vector<BerkhoffPoint> read_berkhoff_transects();

// ---- Mase & Kirby (1992) -----------------------------------------------------------------------
struct MaseKirbyGauge {
  std::string name;               ///< "h470" ... "h025"
  double still_water_depth_m = 0; ///< from the file name r2dNNN (NNN = depth in mm)
  double x_m = 0;                 ///< position in the flume: x = 10 m + 20 (0.47 m - d) (slope 1:20 from x = 10 m)
  std::vector<double> elevation_m;  ///< 20 Hz record, converted from cm
};
inline constexpr double kMaseKirbySampleInterval_s = 0.05;
std::vector<MaseKirbyGauge> read_mase_kirby_gauges();

// ---- Synolakis (1987) --------------------------------------------------------------------------
struct RunupMeasurement {
  double height_ratio = 0, runup_ratio = 0, depth_cm = 0;  ///< H/d, R/d, d
};
std::vector<RunupMeasurement> read_synolakis_runup();
/// The measured R/d at H/d = `height_ratio`: a least-squares power law R/d = a (H/d)^b through the
/// runs within a factor 1.2 of that H/d (the table scatters by about +-5 % between repeated runs).
double measured_runup_ratio(const std::vector<RunupMeasurement>& runs, double height_ratio);
/// Synolakis (1987) non-breaking run-up law R/d = 2.831 sqrt(cot beta) (H/d)^(5/4).
double synolakis_runup_law(double height_ratio, double cot_beta);
struct ProfileSnapshot {
  double dimensionless_time = 0;               ///< t sqrt(g/d)
  std::vector<double> offshore_distance_ratio;  ///< x/d from the initial shoreline, positive offshore
  std::vector<double> elevation_ratio;          ///< eta/d
};
/// profiles/Case0_0185_t30.txt ... for `case_name` "Case0_0185" or "Case0_3".
std::vector<ProfileSnapshot> read_synolakis_profiles(const std::string& case_name);

// ---- statistics --------------------------------------------------------------------------------
/// Mean of (max - min) over the whole periods of length `period_s` that fit in [start_s, end_s] of a
/// series sampled at `time_s`: the wave height "over whole periods" of a regular wave.
double mean_wave_height_m(const std::vector<double>& time_s, const std::vector<double>& elevation_m, double period_s,
                          double start_s, double end_s);
/// Hs = 4 sqrt(variance) and the mean of the samples with time in [start_s, end_s].
double significant_wave_height_m(const std::vector<double>& elevation_m, std::size_t first, std::size_t last);
double mean_level_m(const std::vector<double>& elevation_m, std::size_t first, std::size_t last);
double root_mean_square_error(const std::vector<double>& model, const std::vector<double>& data);
/// The series (`values` at increasing `time_s`) at time t, linear between samples; NaN outside them.
double sample_at(const std::vector<double>& time_s, const std::vector<double>& values, double t);

}  // namespace nearshore::validation
