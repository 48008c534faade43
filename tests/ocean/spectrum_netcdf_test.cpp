// Spectra from wave models' NetCDF output (issue 46, ocean/netcdf/spectrum_netcdf.hpp): each layout
// written by the test with the netCDF C API as the model writes it, and read back into the JONSWAP
// it came from.
#include "nearshore/ocean/spectrum_netcdf.hpp"

#include <gtest/gtest.h>
#include <netcdf.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"
#include "spectrum_scratch.hpp"
#include "nearshore/ocean/spectrum.hpp"

using namespace nearshore::ocean;
namespace fs = std::filesystem;

// A named namespace: the test sources are compiled as one unity file, whose anonymous namespace
// the other spectrum tests already fill with the same names.
namespace spectrum_netcdf_test {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

// The synthetic sea of tests/ocean/spectrum_files_test.cpp: JONSWAP Hs 2 m, Tp 9 s, gamma 3.3,
// travelling towards 23 degrees CCW from east, cos^2s with s = 15 (an integer s: its first
// harmonic, hence the mean direction, is summed exactly over 36 equally spaced directions).
constexpr double kHs_m = 2.0, kTp_s = 9.0, kTravel_deg = 23.0;

fs::path scratch_file(const std::string& name) { return nearshore::ocean::testing::spectrum_scratch_directory() / name; }

void check(int status) { ASSERT_EQ(status, NC_NOERR) << nc_strerror(status); }

// SWAN's frequencies (0.04 Hz up by 1.1, 35) and 36 directions 10 degrees apart.
struct Layout {
  std::vector<double> frequencies_hz, directions_deg;
};
Layout layout() {
  Layout l;
  for (int i = 0; i < 35; ++i) l.frequencies_hz.push_back(0.04 * std::pow(1.1, i));
  for (int k = 0; k < 36; ++k) l.directions_deg.push_back(5.0 + 10.0 * k);
  return l;
}

// Writes a file of 2 times and 3 locations; the sea at (time 2, location 2), zeros elsewhere.
// ww3: efth(time, station, frequency, direction) "m2 s rad-1", direction "to", nautical. swan:
// density(time, points, frequency, direction) "m2/Hz/degr", direction "from", nautical.
fs::path write_file(bool ww3) {
  const JonswapSpectrum spectrum(kHs_m, kTp_s, 3.3);
  const CosineSquaredSpreading spreading(kTravel_deg * kDegree, 15.0);
  const Layout l = layout();
  const fs::path path = scratch_file(ww3 ? "ww3_spec.nc" : "swan_spec.nc");
  int nc = 0, dims[4] = {}, time = 0, location = 0, frequency = 0, direction = 0, density = 0;
  check(nc_create(path.c_str(), NC_CLOBBER | NC_NETCDF4, &nc));
  check(nc_def_dim(nc, "time", 2, &dims[0]));
  check(nc_def_dim(nc, ww3 ? "station" : "points", 3, &dims[1]));
  check(nc_def_dim(nc, "frequency", l.frequencies_hz.size(), &dims[2]));
  check(nc_def_dim(nc, "direction", l.directions_deg.size(), &dims[3]));
  check(nc_def_var(nc, "time", NC_DOUBLE, 1, &dims[0], &time));
  check(nc_def_var(nc, ww3 ? "station" : "points", NC_INT, 1, &dims[1], &location));
  check(nc_def_var(nc, "frequency", NC_FLOAT, 1, &dims[2], &frequency));
  check(nc_def_var(nc, "direction", NC_FLOAT, 1, &dims[3], &direction));
  const std::string direction_name = ww3 ? "sea_surface_wave_to_direction" : "sea_surface_wave_from_direction";
  check(nc_put_att_text(nc, direction, "standard_name", direction_name.size(), direction_name.c_str()));
  check(nc_put_att_text(nc, frequency, "units", 3, "s-1"));
  check(nc_put_att_text(nc, direction, "units", 6, "degree"));
  check(nc_def_var(nc, ww3 ? "efth" : "density", NC_FLOAT, 4, dims, &density));
  const std::string units = ww3 ? "m2 s rad-1" : "m2/Hz/degr";
  check(nc_put_att_text(nc, density, "units", units.size(), units.c_str()));
  const float fill = 9.96921e36f;
  check(nc_put_att_float(nc, density, "_FillValue", NC_FLOAT, 1, &fill));
  check(nc_enddef(nc));
  std::vector<float> f(l.frequencies_hz.begin(), l.frequencies_hz.end()), d(l.directions_deg.begin(), l.directions_deg.end());
  check(nc_put_var_float(nc, frequency, f.data()));
  check(nc_put_var_float(nc, direction, d.data()));
  const double times[2] = {0.0, 3600.0};
  check(nc_put_var_double(nc, time, times));
  const int stations[3] = {1, 2, 3};
  check(nc_put_var_int(nc, location, stations));
  std::vector<float> values(2 * 3 * f.size() * d.size(), 0.0f);
  for (std::size_t i = 0; i < f.size(); ++i)
    for (std::size_t k = 0; k < d.size(); ++k) {
      // The file's direction to the direction of travel (CCW from east).
      const double travel_rad = (ww3 ? 90.0 - l.directions_deg[k] : 270.0 - l.directions_deg[k]) * kDegree;
      const double per_rad = 2.0 * kPi * spectrum.density_m2_s_rad(2.0 * kPi * l.frequencies_hz[i]) *
                             spreading.density_per_rad(travel_rad, 0.0);
      values[((1 * 3 + 1) * f.size() + i) * d.size() + k] = static_cast<float>(ww3 ? per_rad : per_rad * kDegree);
    }
  check(nc_put_var_float(nc, density, values.data()));
  check(nc_close(nc));
  return path;
}

// Hs within 1 % (the file's 10 % frequency steps; tests/ocean/spectrum_files_test.cpp has the same
// bound for the .sp2), Tp the file frequency nearest the peak (within the 10 % step), the mean
// direction within 0.1 degree (exact for s = 15 over 36 directions, float values).
void expect_the_sea(const SampledDirectionalSpectrum& s) {
  std::printf("%s: Hs %.4f m, Tp %.3f s, mean direction %.3f deg\n", s.source.c_str(), significant_wave_height_m(s),
              peak_period_s(s), mean_direction_rad(s) / kDegree);
  EXPECT_NEAR(significant_wave_height_m(s), kHs_m, 0.01 * kHs_m) << s.source;
  EXPECT_NEAR(peak_period_s(s), kTp_s, 0.1 * kTp_s) << s.source;
  EXPECT_NEAR(mean_direction_rad(s) / kDegree, kTravel_deg, 0.1) << s.source;
}

}  // namespace spectrum_netcdf_test

using spectrum_netcdf_test::expect_the_sea;
using spectrum_netcdf_test::scratch_file;
using spectrum_netcdf_test::write_file;

TEST(NetcdfSpectrum, Wavewatch3PointOutputRoundTripsAJonswap) {
  const fs::path file = write_file(true);
  expect_the_sea(read_netcdf_spectrum(file, {NetcdfSpectrumLayout::kWavewatch3, 1, 1}));
}

TEST(NetcdfSpectrum, SwanNetcdfRoundTripsAJonswap) {
  const fs::path file = write_file(false);
  expect_the_sea(read_netcdf_spectrum(file, {NetcdfSpectrumLayout::kSwan, 1, 1}));
}

TEST(NetcdfSpectrum, ErrorsNameTheFileTheVariableAndTheFix) {
  const fs::path ww3 = write_file(true);
  const auto expect_error = [](const auto& read, std::vector<std::string> fragments) {
    try {
      read();
      ADD_FAILURE() << "no error for " << fragments.front();
    } catch (const nearshore::Error& error) {
      const std::string message = error.what();
      for (const std::string& fragment : fragments) EXPECT_NE(message.find(fragment), std::string::npos) << message;
      EXPECT_FALSE(error.fix().empty()) << message;
    }
  };
  // The SWAN layout asked of a WW3 file: no `energy` variable (nor `density`).
  expect_error([&] { return read_netcdf_spectrum(ww3, {NetcdfSpectrumLayout::kSwan, 0, 0}); }, {ww3.string(), "`energy`"});
  // A station beyond the file's three.
  expect_error([&] { return read_netcdf_spectrum(ww3, {NetcdfSpectrumLayout::kWavewatch3, 3, 0}); },
               {ww3.string(), "3 locations", "`station`", "spectrum_location"});
  // The zeros of (time 1, location 1): no energy.
  expect_error([&] { return read_netcdf_spectrum(ww3, {NetcdfSpectrumLayout::kWavewatch3, 0, 0}); }, {ww3.string()});
  // Not NetCDF at all.
  const fs::path text = scratch_file("not.nc");
  { std::FILE* f = std::fopen(text.c_str(), "w"); std::fputs("SWAN   1\n", f); std::fclose(f); }
  expect_error([&] { return read_netcdf_spectrum(text, {}); }, {text.string(), "NetCDF"});
}
