// Spectra read from wave-model and buoy files (issue 46): each test WRITES a small file in the
// format from a synthetic JONSWAP (Hasselmann et al. 1973) with cos^2s spreading (Longuet-Higgins
// et al. 1963), reads it back and checks Hs, Tp and the mean direction against the spectrum it was
// written from; bad files must be refused naming the line.
#include "nearshore/ocean/spectrum_files.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "nearshore/core/error.hpp"
#include "spectrum_scratch.hpp"
#include "nearshore/ocean/sea_state_builder.hpp"
#include "nearshore/ocean/spectrum.hpp"

using namespace nearshore::ocean;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

// The synthetic sea: Hs 2 m, Tp 9 s (fp = 0.111 Hz, on no file frequency), gamma 3.3, travelling
// towards 23 degrees CCW from east (nautical: coming from 270 - 23 = 247 degrees), s = 15. An
// integer s makes cos^2s((theta - mean) / 2) a trigonometric polynomial of degree s, so sums over
// 36 (SWAN) or 72 (NDBC) equally spaced directions give its first harmonic, hence the mean
// direction, exactly: only the files' printed precision is left.
constexpr double kHs_m = 2.0, kTp_s = 9.0, kGamma = 3.3, kTravel_deg = 23.0, kSpreading_s = 15.0;

struct Sea {
  JonswapSpectrum spectrum{kHs_m, kTp_s, kGamma};
  CosineSquaredSpreading spreading{kTravel_deg * kDegree, kSpreading_s};
  /// E(f) in m2/Hz: S(w) dw/df.
  double density_m2_hz(double f) const { return 2.0 * kPi * spectrum.density_m2_s_rad(2.0 * kPi * f); }
};

fs::path scratch_directory() { return nearshore::ocean::testing::spectrum_scratch_directory(); }

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

// ---- SWAN .sp2 as SWAN's appendix D lays it out ----------------------------------------------

/// SWAN's usual frequencies: 0.04 Hz up by a factor 1.1 (its logarithmic grid), 35 of them (to 1.02 Hz).
std::vector<double> swan_frequencies_hz() {
  std::vector<double> f;
  for (int i = 0; i < 35; ++i) f.push_back(0.04 * std::pow(1.1, i));
  return f;
}

/// A SWAN 2-D file of the sea at two locations (the first ZERO, the second the sea) and one time,
/// in nautical directions 5, 15, ... 355 degrees, VaDens per degree.
std::string swan_file_text(const Sea& sea, bool energy_density = false) {
  const auto f = swan_frequencies_hz();
  std::string text =
      "SWAN   1                                Swan standard spectral file, version\n"
      "$   Data produced by SWAN version 41.45 (written by nearshore's test)\n"
      "$   Project: 'harbour'  ;  run number: '1'\n"
      "TIME                                    time-dependent data\n"
      "     1                                  time coding option\n"
      "LOCATIONS                               locations in x-y-space\n"
      "     2                                  number of locations\n"
      "    1000.00     2000.00\n"
      "    1500.00     2000.00\n"
      "AFREQ                                   absolute frequencies in Hz\n";
  text += fmt::format("{:6d}                                  number of frequencies\n", f.size());
  for (double v : f) text += fmt::format("{:10.4f}\n", v);
  text +=
      "NDIR                                    spectral nautical directions in degr\n"
      "    36                                  number of directions\n";
  std::vector<double> nautical_deg;
  for (int k = 0; k < 36; ++k) nautical_deg.push_back(5.0 + 10.0 * k);
  for (double d : nautical_deg) text += fmt::format("{:10.4f}\n", d);
  text += "QUANT\n     1                                  number of quantities in table\n";
  text += energy_density
              ? "EnDens                                  energy densities in J/m2/Hz/degr\nJ/m2/Hz/degr\n"
              : "VaDens                                  variance densities in m2/Hz/degr\nm2/Hz/degr\n";
  text += "   -0.9900E+02                           exception value\n";
  text += "20261130.030000                         date and time\n";
  text += "ZERO\n";
  // The matrix: E(f, theta) per degree, theta = travel direction of each nautical bin.
  const double to_file = (energy_density ? 1025.0 * 9.81 : 1.0) * kDegree;
  std::vector<double> values;
  double largest = 0.0;
  for (double fi : f)
    for (double d : nautical_deg) {
      const double travel = (270.0 - d) * kDegree;
      values.push_back(sea.density_m2_hz(fi) * sea.spreading.density_per_rad(travel, 0.0) * to_file);
      largest = std::max(largest, values.back());
    }
  const double factor = largest / 99999.0;  // SWAN scales its integers to at most 5 digits
  text += fmt::format("FACTOR\n  {:.6E}\n", factor);
  for (std::size_t i = 0; i < f.size(); ++i) {
    for (std::size_t k = 0; k < 36; ++k)
      text += fmt::format(" {:6d}", std::lround(values[i * 36 + k] / factor));
    text += "\n";
  }
  return text;
}

double components_mean_direction_rad(const SeaState& sea) {
  double c = 0.0, s = 0.0;
  for (const WaveComponent& w : sea.components) {
    c += w.amplitude_m * w.amplitude_m * std::cos(w.direction_rad);
    s += w.amplitude_m * w.amplitude_m * std::sin(w.direction_rad);
  }
  return std::atan2(s, c);
}

/// The trapezoid m0 of the exact JONSWAP on the file's frequencies: what a reader that loses
/// nothing must give back, up to the files' printed precision. Comparing with it separates the
/// reader from the file's own discretisation, which is checked against the exact Hs separately.
double trapezoid_hs_m(const Sea& sea, const std::vector<double>& f) {
  double m0 = 0.0;
  for (std::size_t i = 1; i < f.size(); ++i)
    m0 += 0.5 * (sea.density_m2_hz(f[i - 1]) + sea.density_m2_hz(f[i])) * (f[i] - f[i - 1]);
  return 4.0 * std::sqrt(m0);
}

}  // namespace

TEST(SwanSpectrumFile, RoundTripsAJonswapSea) {
  const Sea sea;
  const fs::path path = scratch_directory() / "harbour.sp2";
  write_text(path, swan_file_text(sea));

  SwanSpectrumSelection selection;
  selection.location_index = 1;
  const auto read = std::make_shared<SampledDirectionalSpectrum>(read_swan_spectrum(path, selection));
  ASSERT_EQ(read->frequencies_hz.size(), 35u);
  ASSERT_EQ(read->directions_rad.size(), 36u);

  // Hs: (a) against the trapezoid rule on the file's frequencies: the reader's only loss is the
  // integers' rounding (5 digits: <= 5e-6 of the peak per value, far under 0.1 %);
  const double hs_read = significant_wave_height_m(*read);
  EXPECT_NEAR(hs_read, trapezoid_hs_m(sea, read->frequencies_hz), 1e-3 * kHs_m);
  // (b) against the exact Hs: the trapezoid rule on the file's 10 % frequency steps. E and its
  // slope vanish at both ends of the band, so the Euler-Maclaurin end terms cancel and what is
  // left comes from the kink where JONSWAP's sigma jumps (0.07 -> 0.09) at fp; the band
  // (0.04-1.02 Hz) cuts < 0.1 % of m0. 0.5 % of Hs (measured: 0.05 %).
  EXPECT_NEAR(hs_read, kHs_m, 0.005 * kHs_m);
  // Tp: the peak file frequency is one of the two bracketing fp = 0.111 Hz, a factor 1.1 apart.
  EXPECT_NEAR(peak_period_s(*read), kTp_s, 0.1 * kTp_s);
  // Mean direction: exact on 36 directions for s = 15 (see the top); 0.1 degree covers rounding.
  EXPECT_NEAR(mean_direction_rad(*read) / kDegree, kTravel_deg, 0.1);

  // The builder: the cells tile the file's band and all but 1e-4 of its direction distribution, so
  // the components carry the file's Hs to the builder's quadrature of the bilinear interpolant
  // (0.5 % allows the 1e-4 and the 8-point rule on the kinks of the linear pieces); with a loop
  // period the frequencies are whole harmonics of 2 pi / T.
  DirectionalSeaSpecification spec = sea_specification_from_sampled(read);
  spec.frequency_count = 48;
  spec.direction_count = 24;
  spec.loop_period_s = 1200.0;
  spec.seed = 7;
  const SeaState components = build_sea_state(spec);
  EXPECT_NEAR(significant_wave_height_m(components), hs_read, 0.005 * hs_read);
  const double fundamental = 2.0 * kPi / spec.loop_period_s;
  for (const WaveComponent& c : components.components) {
    const double harmonic = c.angular_frequency_rad_s / fundamental;
    EXPECT_NEAR(harmonic, std::round(harmonic), 1e-9);
  }
  // Its mean direction: the direction cells are symmetric about the file's mean; 0.5 degree covers
  // the cells' quadrature.
  EXPECT_NEAR(components_mean_direction_rad(components) / kDegree, kTravel_deg, 0.5);
}

TEST(SwanSpectrumFile, EnergyDensityIsDividedByRhoG) {
  const Sea sea;
  const fs::path dir = scratch_directory();
  write_text(dir / "variance.sp2", swan_file_text(sea, false));
  write_text(dir / "energy.sp2", swan_file_text(sea, true));
  SwanSpectrumSelection selection;
  selection.location_index = 1;
  const double hs_variance = significant_wave_height_m(read_swan_spectrum(dir / "variance.sp2", selection));
  const double hs_energy = significant_wave_height_m(read_swan_spectrum(dir / "energy.sp2", selection));
  EXPECT_NEAR(hs_energy, hs_variance, 1e-4 * hs_variance);  // the same integers and rho g = 1025 x 9.81
}

namespace {

/// The message of the nearshore::Error that reading `text` as an .sp2 throws ("" when none).
std::string swan_error(const std::string& text, const std::string& name,
                       SwanSpectrumSelection selection = {1, "", 1025.0}) {
  const fs::path path = scratch_directory() / name;
  write_text(path, text);
  try {
    read_swan_spectrum(path, selection);
  } catch (const nearshore::Error& error) {
    return error.what();
  }
  return "";
}

std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// 1-based number of the line where `needle` first appears in `text`.
int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

}  // namespace

TEST(SwanSpectrumFile, BadFilesAreRefusedNamingTheLine) {
  const Sea sea;
  const std::string good = swan_file_text(sea);

  // A missing block: the frequencies cut out (AFREQ, its count and its 35 lines).
  {
    const auto from = good.find("AFREQ"), to = good.find("NDIR");
    std::string text = good;
    text.erase(from, to - from);
    const std::string message = swan_error(text, "no_afreq.sp2");
    EXPECT_NE(message.find(fmt::format("line {}", line_of(text, "NDIR"))), std::string::npos) << message;
    EXPECT_NE(message.find("AFREQ"), std::string::npos) << message;
  }
  // A wrong count: 36 frequencies announced, 35 listed, so the NDIR line is read as a frequency.
  {
    const std::string text =
        replace_once(good, "    35                                  number of frequencies",
                     "    36                                  number of frequencies");
    const std::string message = swan_error(text, "wrong_count.sp2");
    EXPECT_NE(message.find(fmt::format("line {}", line_of(text, "NDIR"))), std::string::npos) << message;
    EXPECT_NE(message.find("count"), std::string::npos) << message;
  }
  // A non-number in the matrix.
  {
    const auto factor_line = line_of(good, "FACTOR");
    std::string text = good;
    // The third matrix row (line FACTOR + 4): its first value made a word.
    std::size_t at = 0;
    for (int line = 1; line < factor_line + 4; ++line) at = text.find('\n', at) + 1;
    text.replace(text.find_first_not_of(' ', at), 1, "x");
    const std::string message = swan_error(text, "not_a_number.sp2");
    EXPECT_NE(message.find(fmt::format("line {}", factor_line + 4)), std::string::npos) << message;
    EXPECT_NE(message.find("row 3"), std::string::npos) << message;
  }
  // A row with a value too many.
  {
    const auto factor_line = line_of(good, "FACTOR");
    std::string text = good;
    std::size_t at = 0;
    for (int line = 1; line < factor_line + 3; ++line) at = text.find('\n', at) + 1;
    text.insert(text.find('\n', at), " 5");  // row 2, on line FACTOR + 3
    const std::string message = swan_error(text, "too_many.sp2");
    EXPECT_NE(message.find(fmt::format("line {}", factor_line + 3)), std::string::npos) << message;
    EXPECT_NE(message.find("more than 36"), std::string::npos) << message;
  }
  // The exception value (-99) in the matrix, a 1-D file, the ZERO location, a missing time, and
  // a file cut short.
  {
    const auto factor_line = line_of(good, "FACTOR");
    std::string text = good;
    std::size_t at = 0;
    for (int line = 1; line < factor_line + 2; ++line) at = text.find('\n', at) + 1;
    text.insert(at, "    -99");
    text.erase(text.find('\n', at) - 7, 7);  // keep 36 values: drop the row's last
    const std::string message = swan_error(text, "exception.sp2");
    EXPECT_NE(message.find(fmt::format("line {}", factor_line + 2)), std::string::npos) << message;
    EXPECT_NE(message.find("exception value"), std::string::npos) << message;
  }
  {
    const auto from = good.find("NDIR"), to = good.find("QUANT");
    std::string text = good;
    text.erase(from, to - from);
    EXPECT_NE(swan_error(text, "one_d.sp1").find("1-D"), std::string::npos);
  }
  EXPECT_NE(swan_error(good, "zero.sp2", {0, "", 1025.0}).find("no energy"), std::string::npos);
  EXPECT_NE(swan_error(good, "time.sp2", {1, "20270101.000000", 1025.0}).find("20261130.030000"),
            std::string::npos);
  EXPECT_NE(swan_error(good.substr(0, good.find("FACTOR") + 20), "short.sp2").find("ends"),
            std::string::npos);
  EXPECT_NE(swan_error("SWAN 1\nLONLAT\n", "header.sp2").find("after line 2"), std::string::npos);
  EXPECT_NE(swan_error("NOT SWAN\n", "not_swan.sp2").find("line 1"), std::string::npos);
}

// ---- NDBC's five realtime2 spectral files ------------------------------------------------------

namespace {

/// NDBC's 47 bands of its directional buoys (0.02-0.485 Hz; 0.005 Hz apart below 0.1 Hz, 0.01 Hz to
/// 0.35 Hz, then 0.02 Hz).
std::vector<double> ndbc_frequencies_hz() {
  std::vector<double> f = {0.0200};
  for (int i = 0; i < 13; ++i) f.push_back(0.0325 + 0.005 * i);
  for (int i = 0; i < 26; ++i) f.push_back(0.1000 + 0.01 * i);
  for (int i = 0; i < 7; ++i) f.push_back(0.3650 + 0.02 * i);
  return f;
}

/// Writes the five files with two rows each (the newest first, as NDBC lists them): the sea at
/// 2026 11 30 03 00 and a calm, missing-direction row an hour before.
NdbcSpectrumFiles write_ndbc_files(const Sea& sea, const fs::path& dir) {
  const auto f = ndbc_frequencies_hz();
  // cos^2s moments (Longuet-Higgins et al. 1963): r1 = s / (s + 1), r2 = s (s - 1) / ((s + 1)(s + 2)).
  const double s = kSpreading_s;
  const double r1 = s / (s + 1.0), r2 = s * (s - 1.0) / ((s + 1.0) * (s + 2.0));
  const double nautical_from_deg = 270.0 - kTravel_deg;  // 247
  auto file = [&](const std::string& header, bool separation, auto value, auto missing) {
    std::string text = "#YY  MM DD hh mm " + header + "\n";
    text += "2026 11 30 03 00";
    if (separation) text += " 0.180";
    for (double fi : f) text += fmt::format(" {} ({:.4f})", value(fi), fi);
    text += "\n2026 11 30 02 00";
    if (separation) text += " 9.999";
    for (double fi : f) text += fmt::format(" {} ({:.4f})", missing, fi);
    return text + "\n";
  };
  NdbcSpectrumFiles files{dir / "46087.data_spec", dir / "46087.swdir", dir / "46087.swdir2",
                          dir / "46087.swr1", dir / "46087.swr2"};
  write_text(files.spectral_density,
             file(
                 "Sep_Freq  < spec_1 (freq_1) spec_2 (freq_2) ... >", true,
                 [&](double fi) { return fmt::format("{:.3f}", sea.density_m2_hz(fi)); }, "0.000"));
  write_text(files.mean_direction,
             file(
                 "alpha1_1 (freq_1) ...", false,
                 [&](double) { return fmt::format("{:.1f}", nautical_from_deg); }, "999.0"));
  write_text(files.principal_direction,
             file(
                 "alpha2_1 (freq_1) ...", false,
                 [&](double) { return fmt::format("{:.1f}", nautical_from_deg); }, "999.0"));
  write_text(files.first_coefficient,
             file(
                 "r1_1 (freq_1) ...", false, [&](double) { return fmt::format("{:.2f}", r1); }, "999.00"));
  write_text(files.second_coefficient,
             file(
                 "r2_1 (freq_1) ...", false, [&](double) { return fmt::format("{:.2f}", r2); }, "999.00"));
  return files;
}

}  // namespace

TEST(NdbcSpectrumFiles, RoundTripsAJonswapSea) {
  const Sea sea;
  const NdbcSpectrumFiles files = write_ndbc_files(sea, scratch_directory());
  const auto read = std::make_shared<SampledDirectionalSpectrum>(read_ndbc_spectrum(files));
  ASSERT_EQ(read->frequencies_hz.size(), 47u);
  EXPECT_NE(read->source.find("2026 11 30 03 00"), std::string::npos);

  // Hs: (a) the reader keeps every band's density (the Fourier series is cut at zero and scaled
  // back to a unit integral), so against the trapezoid rule on the bands only the 3 printed
  // decimals are lost (<= 5e-4 m2/Hz per band x 0.47 Hz: < 0.1 % of m0);
  const double hs_read = significant_wave_height_m(*read);
  EXPECT_NEAR(hs_read, trapezoid_hs_m(sea, read->frequencies_hz), 1e-3 * kHs_m);
  // (b) against the exact Hs: the trapezoid rule on the bands (end terms cancel as for SWAN, the
  // sigma kink at fp remains) and the band's top at 0.485 Hz: the tail above holds ~5/4 (fp / f)^4
  // of m0 for a PM shape, 0.3 %, i.e. 0.15 % of Hs. 0.5 % of Hs (measured: 0.2 %).
  EXPECT_NEAR(hs_read, kHs_m, 0.005 * kHs_m);
  // Tp: one of the two bands bracketing fp = 0.111 Hz (0.11 and 0.12 Hz): within 0.01 / 0.11 = 9 %.
  EXPECT_NEAR(peak_period_s(*read), kTp_s, 0.09 * kTp_s);
  // Mean direction: alpha1 = alpha2 = 247.0 (printed to 0.1 degree), and the series (cut at zero)
  // is symmetric about it; sampled on 72 directions 5 degrees apart that do not straddle 23
  // degrees symmetrically, the cut arcs' edges move by up to half a step: 1 degree.
  EXPECT_NEAR(mean_direction_rad(*read) / kDegree, kTravel_deg, 1.0);

  DirectionalSeaSpecification spec = sea_specification_from_sampled(read);
  spec.frequency_count = 32;
  spec.direction_count = 24;
  spec.seed = 3;
  const SeaState components = build_sea_state(spec);
  EXPECT_NEAR(significant_wave_height_m(components), hs_read, 0.005 * hs_read);
  EXPECT_NEAR(components_mean_direction_rad(components) / kDegree, kTravel_deg, 1.5);
}

TEST(NdbcSpectrumFiles, BadFilesAreRefusedNamingTheLine) {
  const Sea sea;
  const fs::path dir = scratch_directory();
  auto error_of = [&](const NdbcSpectrumFiles& files, const NdbcSpectrumSelection& selection = {}) {
    try {
      read_ndbc_spectrum(files, selection);
    } catch (const nearshore::Error& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  NdbcSpectrumFiles files = write_ndbc_files(sea, dir);
  // The older row has no directions (999) where its density is 0: that is fine (calm) -> no energy.
  EXPECT_NE(error_of(files, {"2026 11 30 02 00", 72}).find("no energy"), std::string::npos);
  // A time none of the files holds.
  EXPECT_NE(error_of(files, {"2026 11 29 00 00", 72}).find("no row for time"), std::string::npos);

  // A non-number on line 2 of .swr1.
  {
    std::ifstream in(files.first_coefficient);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text = replace_once(text, " 0.94 (0.0200)", " abc (0.0200)");
    write_text(files.first_coefficient, text);
    const std::string message = error_of(files);
    EXPECT_NE(message.find("46087.swr1"), std::string::npos) << message;
    EXPECT_NE(message.find("line 2"), std::string::npos) << message;
    files = write_ndbc_files(sea, dir);
  }
  // A band too few in .swdir2: the frequencies differ.
  {
    std::ifstream in(files.principal_direction);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text = replace_once(text, " 247.0 (0.0200)", "");
    write_text(files.principal_direction, text);
    const std::string message = error_of(files);
    EXPECT_NE(message.find("46087.swdir2"), std::string::npos) << message;
    EXPECT_NE(message.find("46 bands"), std::string::npos) << message;
    files = write_ndbc_files(sea, dir);
  }
  // A missing direction (999.0) where there is energy.
  {
    std::ifstream in(files.mean_direction);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text = replace_once(text, " 247.0 (0.1100)", " 999.0 (0.1100)");
    write_text(files.mean_direction, text);
    const std::string message = error_of(files);
    EXPECT_NE(message.find("46087.swdir"), std::string::npos) << message;
    EXPECT_NE(message.find("0.11 Hz"), std::string::npos) << message;
    files = write_ndbc_files(sea, dir);
  }
  // A row that is not pairs.
  {
    write_text(files.spectral_density,
               "#YY  MM DD hh mm Sep_Freq ...\n2026 11 30 03 00 0.180 1.0 (0.05) 2.0\n");
    const std::string message = error_of(files);
    EXPECT_NE(message.find("line 2"), std::string::npos) << message;
    EXPECT_NE(message.find("pairs"), std::string::npos) << message;
  }
  // A file that does not exist.
  files = write_ndbc_files(sea, dir);
  files.second_coefficient = dir / "missing.swr2";
  EXPECT_NE(error_of(files).find("missing.swr2"), std::string::npos);
}
