// libFuzzer target for the measured-spectrum readers (ctest label `fuzz`, a bounded run): a SWAN
// `.sp2` file through read_swan_spectrum, or an NDBC buoy's five realtime2 files through
// read_ndbc_spectrum, then what a bake first asks of the result (its checks, Hs, peak period and
// mean direction). The input is a raw SWAN file, or edits (fuzz_edits.hpp: cuts,
// numbers replaced by extreme ones, flipped bits) of small valid files made here. Every input must
// end in a spectrum or a nearshore::Error; anything else (crash, sanitizer report, another
// exception, a timeout, running out of memory) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "../../support/fuzz_edits.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/ocean/spectrum_files.hpp"

using namespace nearshore;
using namespace nearshore::ocean;

namespace {

// A SWAN 2-D file in the layout of SWAN's manual, appendix D: two locations (the first NODATA),
// two times, 4 frequencies, 4 nautical directions, VaDens with a FACTOR.
const char* const kSwanSeed =
    "SWAN   1                                Swan standard spectral file, version\n"
    "$   Data produced by SWAN version 41.45\n"
    "TIME                                    time-dependent data\n"
    "     1                                  time coding option\n"
    "LOCATIONS                               locations in x-y-space\n"
    "     2                                  number of locations\n"
    "    1000.00     2000.00\n"
    "    1500.00     2000.00\n"
    "AFREQ                                   absolute frequencies in Hz\n"
    "     4                                  number of frequencies\n"
    "    0.0500\n    0.0800\n    0.1200\n    0.2000\n"
    "NDIR                                    spectral nautical directions in degr\n"
    "     4                                  number of directions\n"
    "   45.0000\n  135.0000\n  225.0000\n  315.0000\n"
    "QUANT\n     1                                  number of quantities in table\n"
    "VaDens                                  variance densities in m2/Hz/degr\n"
    "m2/Hz/degr\n"
    "   -0.9900E+02                           exception value\n"
    "20261130.030000                         date and time\n"
    "NODATA\n"
    "FACTOR\n  1.000000E-04\n"
    "      1     20    300     10\n"
    "      5    200  99999    100\n"
    "      2     50   2000     20\n"
    "      0      3     40      1\n"
    "20261130.040000                         date and time\n"
    "ZERO\n"
    "ZERO\n";

// The five NDBC files of one buoy (separated by '|' here), two rows each, 3 frequencies.
const char* const kNdbcSeed =
    "#YY  MM DD hh mm Sep_Freq  < spec_1 (freq_1) spec_2 (freq_2) ... >\n"
    "2026 11 30 03 00 0.180 0.120 (0.0500) 2.500 (0.0800) 0.400 (0.1200)\n"
    "2026 11 30 02 00 9.999 0.000 (0.0500) 0.000 (0.0800) 0.000 (0.1200)\n"
    "|#YY  MM DD hh mm alpha1_1 (freq_1) ...\n"
    "2026 11 30 03 00 247.0 (0.0500) 250.0 (0.0800) 240.0 (0.1200)\n"
    "2026 11 30 02 00 999.0 (0.0500) 999.0 (0.0800) 999.0 (0.1200)\n"
    "|#YY  MM DD hh mm alpha2_1 (freq_1) ...\n"
    "2026 11 30 03 00 247.0 (0.0500) 249.0 (0.0800) 241.0 (0.1200)\n"
    "2026 11 30 02 00 999.0 (0.0500) 999.0 (0.0800) 999.0 (0.1200)\n"
    "|#YY  MM DD hh mm r1_1 (freq_1) ...\n"
    "2026 11 30 03 00 0.90 (0.0500) 0.85 (0.0800) 0.70 (0.1200)\n"
    "2026 11 30 02 00 999.00 (0.0500) 999.00 (0.0800) 999.00 (0.1200)\n"
    "|#YY  MM DD hh mm r2_1 (freq_1) ...\n"
    "2026 11 30 03 00 0.75 (0.0500) 0.66 (0.0800) 0.40 (0.1200)\n"
    "2026 11 30 02 00 999.00 (0.0500) 999.00 (0.0800) 999.00 (0.1200)\n";

const char* const kExtremes[] = {"0", "-1", "1e308", "1e-300", "inf", "nan", "2147483648", "-0.0", "999", "99999"};

void write(const std::string& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(text.data(), static_cast<std::streamsize>(text.size()));
}

// What a bake first asks of a spectrum it read (bake/src/case_wave_maker.cpp's spectrum_file key);
// sea_specification_from_sampled's spreading tables are left out: they cost 50 ms an input under
// the fuzzer's instrumentation and read nothing from the file that check_sampled_spectrum has not.
void use(const SampledDirectionalSpectrum& spectrum) {
  check_sampled_spectrum(spectrum);
  (void)significant_wave_height_m(spectrum);
  (void)peak_period_s(spectrum);
  (void)mean_direction_rad(spectrum);
}

// A seed that no longer reads (the readers moved on) would leave the fuzzer mutating errors only:
// stop with the message instead.
void check_seeds_read();

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  check_seeds_read();
  const int mode = data[0] % 3;
  const std::uint8_t selection = data[1];
  data += 2;
  size -= 2;
  try {
    if (mode < 2) {  // SWAN: raw bytes, or edits of the seed
      write("fuzz_input.sp2", mode == 0 ? std::string(reinterpret_cast<const char*>(data), size)
                                        : fuzzing::edited(kSwanSeed, data, size, kExtremes));
      SwanSpectrumSelection choice;
      choice.location_index = selection % 3;
      if (selection & 4) choice.time = (selection & 8) ? "20261130.040000" : "19990101.000000";
      use(read_swan_spectrum("fuzz_input.sp2", choice));
    } else {  // NDBC: edits of the five files, split at '|'
      const std::string joined = fuzzing::edited(kNdbcSeed, data, size, kExtremes);
      std::vector<std::string> parts(1);
      for (char c : joined) {
        if (c == '|' && parts.size() < 5)
          parts.emplace_back();
        else
          parts.back() += c;
      }
      parts.resize(5);
      const NdbcSpectrumFiles files{"fuzz_input.data_spec", "fuzz_input.swdir", "fuzz_input.swdir2", "fuzz_input.swr1",
                                    "fuzz_input.swr2"};
      write(files.spectral_density.string(), parts[0]);
      write(files.mean_direction.string(), parts[1]);
      write(files.principal_direction.string(), parts[2]);
      write(files.first_coefficient.string(), parts[3]);
      write(files.second_coefficient.string(), parts[4]);
      NdbcSpectrumSelection choice;
      choice.direction_count = 1 + selection % 90;
      if (selection & 128) choice.time = "2026 11 30 02 00";
      use(read_ndbc_spectrum(files, choice));
    }
  } catch (const Error&) {
  }
  return 0;
}

namespace {

std::vector<std::string> ndbc_seed_parts() {
  std::vector<std::string> parts(1);
  for (const char* c = kNdbcSeed; *c; ++c) {
    if (*c == '|')
      parts.emplace_back();
    else
      parts.back() += *c;
  }
  return parts;
}

void check_seeds_read() {
  static const bool checked = [] {
    try {
      write("fuzz_seed.sp2", kSwanSeed);
      SwanSpectrumSelection swan;
      swan.location_index = 1;
      use(read_swan_spectrum("fuzz_seed.sp2", swan));
      const std::vector<std::string> parts = ndbc_seed_parts();
      const NdbcSpectrumFiles files{"fuzz_seed.data_spec", "fuzz_seed.swdir", "fuzz_seed.swdir2", "fuzz_seed.swr1",
                                    "fuzz_seed.swr2"};
      write(files.spectral_density.string(), parts.at(0));
      write(files.mean_direction.string(), parts.at(1));
      write(files.principal_direction.string(), parts.at(2));
      write(files.first_coefficient.string(), parts.at(3));
      write(files.second_coefficient.string(), parts.at(4));
      use(read_ndbc_spectrum(files));
    } catch (const Error& error) {
      std::fprintf(stderr, "fuzz_spectrum_files: a seed no longer reads: %s\n", error.what());
      std::abort();
    }
    return true;
  }();
  (void)checked;
}

}  // namespace
